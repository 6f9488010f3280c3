//! Both layouts (`A`: hexadecimal text; `B`: integers) in both byte
//! orders, written here by the layout the module describes; the
//! `A` layout is also read from files CGNS's own `hdf2adf` wrote
//! (`tests/cgns.rs`).

use super::*;

struct Writer {
    ascii: bool,
    little: bool,
    out: Vec<u8>,
}

impl Writer {
    fn int(&self, v: u64, n: usize) -> Vec<u8> {
        let mut b: Vec<u8> = (0..n).map(|i| (v >> (8 * i)) as u8).collect();
        if !self.little {
            b.reverse();
        }
        b
    }

    fn pointer(&self, at: u64) -> Vec<u8> {
        if self.ascii {
            format!("{:08X}{:04X}", at / BLOCK, at % BLOCK).into_bytes()
        } else {
            [self.int(at / BLOCK, 8), self.int(at % BLOCK, 4)].concat()
        }
    }

    /// A chunk: tag, pointer to its end tag, content, end tag.
    fn chunk(&mut self, tag: &[u8], content: &[u8], end_tag: &[u8]) -> u64 {
        let at = self.out.len() as u64;
        let end = at + 16 + content.len() as u64;
        let p = self.pointer(end);
        self.out.extend([tag, &p, content, end_tag].concat());
        at
    }

    fn node(
        &mut self,
        name: &str,
        label: &str,
        data_type: &str,
        dims: &[u64],
        data: (u64, u64),
        children: &[(&str, u64)],
    ) -> u64 {
        let table = if children.is_empty() {
            0
        } else {
            let entries: Vec<u8> = children
                .iter()
                .flat_map(|(n, at)| [format!("{n:32}").into_bytes(), self.pointer(*at)].concat())
                .collect();
            self.chunk(b"SNTb", &entries, b"snTE")
        };
        let mut h = b"NoDe".to_vec();
        h.extend(
            format!(
                "{name:32}{label:32}{:08X}{:08X}",
                children.len(),
                children.len()
            )
            .bytes(),
        );
        h.extend(self.pointer(table));
        h.extend(format!("{data_type:32}{:02X}", dims.len()).bytes());
        for i in 0..12 {
            let d = dims.get(i).copied().unwrap_or(0);
            h.extend(if self.ascii {
                format!("{d:08X}").into_bytes()
            } else {
                self.int(d, 8)
            });
        }
        h.extend(format!("{:04X}", data.0).bytes());
        h.extend(self.pointer(data.1));
        h.extend(b"TaiL");
        let at = self.out.len() as u64;
        self.out.extend(h);
        at
    }
}

/// A root with a real array split over two chunks, an integer matrix,
/// and a link to the array.
fn file(ascii: bool, little: bool) -> Vec<u8> {
    let mut w = Writer {
        ascii,
        little,
        out: vec![0; FILE_HEADER + 80],
    };
    let reals: Vec<u8> = [1.5f64, -2.0, 1e300]
        .iter()
        .flat_map(|v| w.int(v.to_bits(), 8))
        .collect();
    let first = w.chunk(b"DaTa", &reals[..8], b"dEnD");
    let second = w.chunk(b"DaTa", &reals[8..], b"dEnD");
    let entries = [
        w.pointer(first),
        w.pointer(first + 24),
        w.pointer(second),
        w.pointer(second + 32),
    ]
    .concat();
    let table = w.chunk(b"DCtb", &entries, b"dcTE");
    let a = w.node("A", "DataArray_t", "R8", &[3], (2, table), &[]);
    let ints: Vec<u8> = [1i32, -2, 3, 4]
        .iter()
        .flat_map(|&v| w.int(u64::from(v as u32), 4))
        .collect();
    let data = w.chunk(b"DaTa", &ints, b"dEnD");
    let b = w.node("B", "IndexArray_t", "I4", &[2, 2], (1, data), &[]);
    let target = w.chunk(b"DaTa", b" |/A", b"dEnD");
    let link = w.node("L", "DataArray_t", "LK", &[4], (1, target), &[]);
    let root = w.node(
        "ADF MotherNode",
        "Root Node of ADF File",
        "MT",
        &[],
        (0, 0),
        &[("A", a), ("B", b), ("L", link)],
    );
    let last = w.out.len() as u64 - 1;
    let mut h = b"\xc0\xa8\xa3\xa9ADF Database Version ".to_vec();
    h.extend(if ascii { b"A02011>" } else { b"B02012>" });
    h.extend(format!("AdF0{:28}AdF1{:28}AdF2", "", "").bytes());
    h.extend([if little { b'L' } else { b'B' }, b'B']);
    h.extend(b"AdF3010204080408080808080808AdF4");
    h.extend(
        [
            w.pointer(root),
            w.pointer(last),
            w.pointer(186),
            w.pointer(0),
        ]
        .concat(),
    );
    h.extend(b"AdF5");
    assert_eq!(h.len(), FILE_HEADER);
    w.out[..FILE_HEADER].copy_from_slice(&h);
    w.out
}

#[test]
fn both_layouts_in_both_byte_orders_read_the_same_tree() {
    let dir = std::env::temp_dir().join(format!("tetray-adf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (ascii, little) in [(true, true), (true, false), (false, true), (false, false)] {
        let path = dir.join(format!("t-{ascii}-{little}.adf"));
        std::fs::write(&path, file(ascii, little)).unwrap();
        let adf = Adf::open(&path).unwrap_or_else(|e| panic!("{ascii} {little}: {e}"));
        assert_eq!(adf.children("/").unwrap(), ["A", "B", "L"]);
        assert_eq!(adf.label("/B").as_deref(), Some("IndexArray_t"));
        assert_eq!(adf.data_f64("/A").unwrap(), [1.5, -2.0, 1e300]);
        assert_eq!(adf.data_i64("/B").unwrap(), [1, -2, 3, 4]);
        // The link reads as its target.
        assert_eq!(adf.data_f64("/L").unwrap(), [1.5, -2.0, 1e300]);
        // Cut before its last byte: refused.
        let bytes = file(ascii, little);
        std::fs::write(&path, &bytes[..bytes.len() - 1]).unwrap();
        let Err(e) = Adf::open(&path) else {
            panic!("a cut file read");
        };
        assert!(e.to_string().contains("end of file"), "{e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
