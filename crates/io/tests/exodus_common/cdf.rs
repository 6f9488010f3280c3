//! A minimal netCDF classic writer (CDF-1, CDF-2 and CDF-5), written from
//! the "NetCDF Classic and 64-bit Offset Format" specification (netCDF
//! User's Guide, "File Format Specification") and its CDF-5 extension:
//! big-endian header `magic numrecs dim_list gatt_list var_list`, then the
//! fixed-size variables one after the other and the record variables
//! interleaved record by record, every block padded to 4 bytes.

/// The on-disk version: CDF-1 (32-bit offsets), CDF-2 (64-bit offsets),
/// CDF-5 (64-bit offsets, counts and sizes; 64-bit integer type).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Version {
    Cdf1 = 1,
    Cdf2 = 2,
    Cdf5 = 5,
}

const NC_DIMENSION: u32 = 0x0A;
const NC_VARIABLE: u32 = 0x0B;
const NC_ATTRIBUTE: u32 = 0x0C;

/// The external types this writer uses (nc_type codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Type {
    Char = 2,
    Int = 4,
    Float = 5,
    Double = 6,
    Int64 = 10,
}

impl Type {
    fn size(self) -> usize {
        match self {
            Type::Char => 1,
            Type::Int | Type::Float => 4,
            Type::Double | Type::Int64 => 8,
        }
    }
}

/// Values of a variable or attribute, stored big-endian.
#[derive(Debug, Clone)]
pub enum Values {
    Chars(Vec<u8>),
    Ints(Vec<i32>),
    Floats(Vec<f32>),
    Doubles(Vec<f64>),
    Int64s(Vec<i64>),
}

impl Values {
    fn kind(&self) -> Type {
        match self {
            Values::Chars(_) => Type::Char,
            Values::Ints(_) => Type::Int,
            Values::Floats(_) => Type::Float,
            Values::Doubles(_) => Type::Double,
            Values::Int64s(_) => Type::Int64,
        }
    }

    fn len(&self) -> usize {
        match self {
            Values::Chars(v) => v.len(),
            Values::Ints(v) => v.len(),
            Values::Floats(v) => v.len(),
            Values::Doubles(v) => v.len(),
            Values::Int64s(v) => v.len(),
        }
    }

    fn bytes(&self) -> Vec<u8> {
        match self {
            Values::Chars(v) => v.clone(),
            Values::Ints(v) => v.iter().flat_map(|x| x.to_be_bytes()).collect(),
            Values::Floats(v) => v.iter().flat_map(|x| x.to_be_bytes()).collect(),
            Values::Doubles(v) => v.iter().flat_map(|x| x.to_be_bytes()).collect(),
            Values::Int64s(v) => v.iter().flat_map(|x| x.to_be_bytes()).collect(),
        }
    }
}

struct Var {
    name: String,
    dims: Vec<usize>,
    attrs: Vec<(String, Values)>,
    values: Values,
}

/// A netCDF classic dataset being built.
pub struct Cdf {
    version: Version,
    dims: Vec<(String, usize)>,
    /// Index of the unlimited (record) dimension and the number of records.
    record_dim: Option<usize>,
    vars: Vec<Var>,
}

fn pad4(bytes: &mut Vec<u8>) {
    while !bytes.len().is_multiple_of(4) {
        bytes.push(0);
    }
}

impl Cdf {
    pub fn new(version: Version) -> Self {
        Cdf {
            version,
            dims: Vec::new(),
            record_dim: None,
            vars: Vec::new(),
        }
    }

    /// Defines a fixed-size dimension; returns its id.
    pub fn dim(&mut self, name: &str, len: usize) -> usize {
        self.dims.push((name.into(), len));
        self.dims.len() - 1
    }

    /// Defines the unlimited dimension with `records` records.
    pub fn record_dim(&mut self, name: &str, records: usize) -> usize {
        let id = self.dim(name, records);
        self.record_dim = Some(id);
        id
    }

    /// Defines a variable over `dims` (the record dimension first, if it
    /// is one) with all its values in row-major order.
    pub fn var(&mut self, name: &str, dims: &[usize], values: Values) -> &mut Self {
        self.vars.push(Var {
            name: name.into(),
            dims: dims.to_vec(),
            attrs: Vec::new(),
            values,
        });
        self
    }

    /// Adds an attribute to the variable defined last.
    pub fn attr(&mut self, name: &str, values: Values) -> &mut Self {
        let var = self.vars.last_mut().expect("a variable first");
        var.attrs.push((name.into(), values));
        self
    }

    fn is_record(&self, var: &Var) -> bool {
        self.record_dim.is_some() && var.dims.first() == self.record_dim.as_ref()
    }

    /// Values per record (record variables) or in all (the others).
    fn slab_len(&self, var: &Var) -> usize {
        let skip = usize::from(self.is_record(var));
        var.dims[skip..].iter().map(|&d| self.dims[d].1).product()
    }

    fn wide(&self) -> bool {
        self.version == Version::Cdf5
    }

    /// NON_NEG: 4 bytes, 8 in CDF-5.
    fn count(&self, out: &mut Vec<u8>, n: usize) {
        if self.wide() {
            out.extend((n as u64).to_be_bytes());
        } else {
            out.extend((n as u32).to_be_bytes());
        }
    }

    fn name(&self, out: &mut Vec<u8>, name: &str) {
        self.count(out, name.len());
        out.extend(name.as_bytes());
        pad4(out);
    }

    fn attrs(&self, out: &mut Vec<u8>, attrs: &[(String, Values)]) {
        if attrs.is_empty() {
            out.extend(0u32.to_be_bytes());
            self.count(out, 0);
            return;
        }
        out.extend(NC_ATTRIBUTE.to_be_bytes());
        self.count(out, attrs.len());
        for (name, values) in attrs {
            self.name(out, name);
            out.extend((values.kind() as u32).to_be_bytes());
            self.count(out, values.len());
            out.extend(values.bytes());
            pad4(out);
        }
    }

    /// The file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        // Every variable's padded size per record (or in all).
        let vsize: Vec<usize> = self
            .vars
            .iter()
            .map(|v| (self.slab_len(v) * v.values.kind().size()).div_ceil(4) * 4)
            .collect();
        let header = |begins: &[u64]| {
            let mut out = b"CDF".to_vec();
            out.push(self.version as u8);
            self.count(&mut out, self.record_dim.map_or(0, |d| self.dims[d].1));
            out.extend(NC_DIMENSION.to_be_bytes());
            self.count(&mut out, self.dims.len());
            for (i, (name, len)) in self.dims.iter().enumerate() {
                self.name(&mut out, name);
                let stored = if Some(i) == self.record_dim { 0 } else { *len };
                self.count(&mut out, stored);
            }
            self.attrs(&mut out, &[]);
            out.extend(NC_VARIABLE.to_be_bytes());
            self.count(&mut out, self.vars.len());
            for (v, var) in self.vars.iter().enumerate() {
                self.name(&mut out, &var.name);
                self.count(&mut out, var.dims.len());
                for &d in &var.dims {
                    self.count(&mut out, d);
                }
                self.attrs(&mut out, &var.attrs);
                out.extend((var.values.kind() as u32).to_be_bytes());
                self.count(&mut out, vsize[v]);
                if self.version == Version::Cdf1 {
                    out.extend((begins[v] as u32).to_be_bytes());
                } else {
                    out.extend(begins[v].to_be_bytes());
                }
            }
            out
        };
        // The header's length does not depend on the offsets' values.
        let start = header(&vec![0; self.vars.len()]).len();
        let mut begins = vec![0u64; self.vars.len()];
        let mut at = start;
        for (v, var) in self.vars.iter().enumerate() {
            if !self.is_record(var) {
                begins[v] = at as u64;
                at += vsize[v];
            }
        }
        let mut record_at = at;
        for (v, var) in self.vars.iter().enumerate() {
            if self.is_record(var) {
                begins[v] = record_at as u64;
                record_at += vsize[v];
            }
        }
        let mut out = header(&begins);
        for var in self.vars.iter().filter(|v| !self.is_record(v)) {
            out.extend(var.values.bytes());
            pad4(&mut out);
        }
        let records = self.record_dim.map_or(0, |d| self.dims[d].1);
        for r in 0..records {
            for var in self.vars.iter().filter(|v| self.is_record(v)) {
                let size = self.slab_len(var) * var.values.kind().size();
                out.extend(&var.values.bytes()[r * size..(r + 1) * size]);
                pad4(&mut out);
            }
        }
        out
    }
}
