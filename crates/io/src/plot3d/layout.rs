//! Byte layout of PLOT3D binary files: byte order, optional grid count,
//! optional Fortran record markers, optional IBLANK, decided from the
//! header and the file size.
//!
//! Single-grid 3-D files only. A grid (xyz) file is `ni nj nk`, then all x,
//! all y, all z (32-bit floats), optionally an IBLANK int per point; a
//! solution (q) file is `ni nj nk`, four floats (fsmach alpha re time), then
//! five arrays (density, x/y/z momentum, stagnation energy). Either may
//! start with a grid count of 1, and either may wrap each of those parts in
//! Fortran record markers (a 32-bit byte count before and after).

use crate::IoError;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Endian {
    Big,
    Little,
}

impl Endian {
    fn name(self) -> &'static str {
        match self {
            Endian::Big => "big-endian",
            Endian::Little => "little-endian",
        }
    }

    pub(crate) fn i32_at(self, bytes: &[u8], offset: usize) -> Option<i32> {
        let b: [u8; 4] = bytes.get(offset..offset + 4)?.try_into().ok()?;
        Some(match self {
            Endian::Big => i32::from_be_bytes(b),
            Endian::Little => i32::from_le_bytes(b),
        })
    }

    /// `count` 32-bit floats from `offset`; the caller checked the length.
    pub(crate) fn f32s(self, bytes: &[u8], offset: usize, count: usize) -> Vec<f32> {
        let slice = &bytes[offset..offset + 4 * count];
        let conv = match self {
            Endian::Big => f32::from_be_bytes,
            Endian::Little => f32::from_le_bytes,
        };
        slice
            .chunks_exact(4)
            .map(|c| conv([c[0], c[1], c[2], c[3]]))
            .collect()
    }

    /// `count` 32-bit ints from `offset`; the caller checked the length.
    pub(crate) fn i32s(self, bytes: &[u8], offset: usize, count: usize) -> Vec<i32> {
        (0..count)
            .map(|i| self.i32_at(bytes, offset + 4 * i).unwrap_or(0))
            .collect()
    }
}

/// Which file of the pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Grid,
    Solution,
}

impl Kind {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Kind::Grid => "grid",
            Kind::Solution => "solution",
        }
    }
}

/// Where the arrays of a file are.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    pub endian: Endian,
    pub dims: [usize; 3],
    /// Byte offset of the first array value (x, or density).
    pub data: usize,
    /// Grid files: whether an IBLANK array follows z.
    pub iblank: bool,
    /// Solution files: byte offset of the four floats fsmach alpha re time.
    pub conditions: usize,
    /// Bytes after the last array (tolerated, reported).
    pub trailing: usize,
    /// Human description, e.g. "big-endian, IBLANK".
    pub description: String,
}

/// Header forms: `(prefix ints before the dims, record markers)`.
const FORMS: [(usize, bool); 4] = [(0, false), (0, true), (1, false), (1, true)];

/// The largest point count: indices are `u32`.
const MAX_POINTS: usize = u32::MAX as usize;

/// Decides the layout of a PLOT3D file, or says why it fits none.
pub(crate) fn detect(bytes: &[u8], file: &str, kind: Kind) -> Result<Layout, IoError> {
    let header_err = |message: String| IoError::Plot3dHeader {
        file: file.to_string(),
        what: kind.name(),
        message,
    };
    if bytes.len() < 12 {
        return Err(header_err(format!(
            "the file has {} bytes; the header alone needs 12",
            bytes.len()
        )));
    }
    let mut fitting: Vec<Layout> = Vec::new();
    // The smallest-size candidate that does not fit: the file is most
    // likely that layout, truncated.
    let mut short: Option<(usize, Layout)> = None;
    for endian in [Endian::Big, Endian::Little] {
        for (prefix, records) in FORMS {
            let Some(candidate) = header(bytes, endian, prefix, records) else {
                continue;
            };
            for (layout, needed) in sizes(bytes, candidate, kind) {
                if needed <= bytes.len() {
                    fitting.push(layout);
                } else if short.as_ref().is_none_or(|(n, _)| needed < *n) {
                    short = Some((needed, layout));
                }
            }
        }
    }
    // Prefer an exact fit, then the least trailing data; ties keep the
    // order above (big-endian, plain single grid first).
    if let Some(best) = fitting.into_iter().min_by_key(|l| l.trailing) {
        return Ok(best);
    }
    if let Some((expected, layout)) = short {
        let [ni, nj, nk] = layout.dims;
        return Err(IoError::Plot3dTruncated {
            file: file.to_string(),
            what: kind.name(),
            ni,
            nj,
            nk,
            layout: layout.description,
            expected,
            found: bytes.len(),
        });
    }
    let be: Vec<i32> = (0..3)
        .filter_map(|i| Endian::Big.i32_at(bytes, 4 * i))
        .collect();
    let le: Vec<i32> = (0..3)
        .filter_map(|i| Endian::Little.i32_at(bytes, 4 * i))
        .collect();
    Err(header_err(format!(
        "no valid single-grid header: the first ints read {be:?} big-endian and {le:?} \
         little-endian; ni, nj, nk must each be at least 2 and their product at most {MAX_POINTS}"
    )))
}

/// The dims and data offset of one header form, when its fields are
/// plausible: markers where the form has them, a grid count of 1, each
/// dimension at least 2 and the point count within `u32`.
fn header(bytes: &[u8], endian: Endian, prefix: usize, records: bool) -> Option<Layout> {
    let int = |offset: usize| endian.i32_at(bytes, offset);
    let mut at = 0;
    if prefix == 1 {
        if records {
            (int(0)? == 4 && int(8)? == 4).then_some(())?;
            (int(4)? == 1).then_some(())?;
            at = 12;
        } else {
            (int(0)? == 1).then_some(())?;
            at = 4;
        }
    }
    if records {
        (int(at)? == 12 && int(at + 16)? == 12).then_some(())?;
        at += 4;
    }
    let mut dims = [0usize; 3];
    for (d, dim) in dims.iter_mut().enumerate() {
        let v = int(at + 4 * d)?;
        *dim = usize::try_from(v).ok().filter(|&v| v >= 2)?;
    }
    let points = dims.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d))?;
    (points <= MAX_POINTS).then_some(())?;
    at += 12 + if records { 4 } else { 0 };
    let mut description = endian.name().to_string();
    if prefix == 1 {
        description += ", grid count";
    }
    if records {
        description += ", Fortran records";
    }
    Some(Layout {
        endian,
        dims,
        data: at,
        iblank: false,
        conditions: 0,
        trailing: 0,
        description,
    })
}

/// The variants of a header's layout (with and without IBLANK for a grid)
/// and the file size each needs.
fn sizes(bytes: &[u8], mut layout: Layout, kind: Kind) -> Vec<(Layout, usize)> {
    let n: usize = layout.dims.iter().product();
    let records = layout.description.contains("records");
    let marker = if records { 4 } else { 0 };
    let int = |offset: usize| layout.endian.i32_at(bytes, offset);
    let mut out = Vec::new();
    match kind {
        Kind::Grid => {
            for iblank in [false, true] {
                let body = if iblank { 16 * n } else { 12 * n };
                let mut l = layout.clone();
                l.data = layout.data + marker;
                l.iblank = iblank;
                if iblank {
                    l.description += ", IBLANK";
                }
                let needed = l.data + body + marker;
                if records && bytes.len() >= needed {
                    // The record length says which variant it is.
                    let ok = int(layout.data) == i32::try_from(body).ok()
                        && int(needed - 4) == i32::try_from(body).ok();
                    if !ok {
                        continue;
                    }
                }
                if !records && bytes.len() >= needed && !plain_iblank_fits(bytes, &l, n, needed) {
                    continue;
                }
                l.trailing = bytes.len().saturating_sub(needed);
                out.push((l, needed));
            }
        }
        Kind::Solution => {
            layout.conditions = layout.data + marker;
            let after_conditions = layout.conditions + 16 + marker;
            if records
                && bytes.len() >= after_conditions
                && (int(layout.data) != Some(16) || int(after_conditions - 4) != Some(16))
            {
                return out;
            }
            layout.data = after_conditions + marker;
            let needed = layout.data + 20 * n + marker;
            layout.trailing = bytes.len().saturating_sub(needed);
            out.push((layout, needed));
        }
    }
    out
}

/// Whether a plain (unmarked) grid layout is believable as to IBLANK. IBLANK
/// values are small ints (0 blanked, 1 normal, negative: another grid's
/// number) while float coordinates read as ints are huge, so: with IBLANK,
/// the would-be values must all be small; without, bytes after z that read
/// as small ints with some non-zero are a truncated IBLANK array, not
/// trailing padding.
fn plain_iblank_fits(bytes: &[u8], l: &Layout, n: usize, needed: usize) -> bool {
    let small = |v: i32| v.unsigned_abs() <= 1000;
    let start = l.data + 12 * n;
    let int = |i: usize| l.endian.i32_at(bytes, start + 4 * i);
    if l.iblank {
        (0..n).all(|i| int(i).is_some_and(small))
    } else {
        let count = n.min((bytes.len() - needed) / 4);
        let values: Vec<i32> = (0..count).filter_map(int).collect();
        !(count > 0 && values.iter().all(|&v| small(v)) && values.iter().any(|&v| v != 0))
    }
}
