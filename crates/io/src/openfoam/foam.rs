//! One OpenFOAM file: its `FoamFile` header (format, class, arch) and the
//! lists and entries after it, in ASCII or binary. A list is `N ( ... )`,
//! `N { value }` (N copies) or, in binary files, `N (` followed by the raw
//! bytes of its N items and `)`. Labels are 32- or 64-bit and scalars 32-
//! or 64-bit as the header's `arch` says ("LSB;label=32;scalar=64", the
//! default); `MSB` files are byte-swapped. Comments (`//`, `/* */`) are
//! skipped. Every count is checked against the bytes left before anything
//! is allocated.

use super::OpenFoamError;

/// A file's bytes and what its header says.
pub(super) struct FoamFile<'a> {
    pub bytes: &'a [u8],
    pub name: String,
    pub binary: bool,
    pub class: String,
    pub label64: bool,
    pub scalar32: bool,
    pub big_endian: bool,
    /// Where the header ends.
    pub body: usize,
}

impl<'a> FoamFile<'a> {
    pub fn parse(bytes: &'a [u8], name: &str) -> Result<FoamFile<'a>, OpenFoamError> {
        let mut file = FoamFile {
            bytes,
            name: name.into(),
            binary: false,
            class: String::new(),
            label64: false,
            scalar32: false,
            big_endian: false,
            body: 0,
        };
        let mut at = 0;
        let word = file.word(&mut at);
        if word != "FoamFile" {
            return Err(file.invalid(at, "no FoamFile header".into()));
        }
        file.skip_space(&mut at);
        if bytes.get(at) != Some(&b'{') {
            return Err(file.invalid(at, "the FoamFile header has no '{'".into()));
        }
        at += 1;
        loop {
            file.skip_space(&mut at);
            match bytes.get(at) {
                Some(b'}') => {
                    at += 1;
                    break;
                }
                None => return Err(file.invalid(at, "the FoamFile header is not closed".into())),
                _ => {}
            }
            let key = file.word(&mut at);
            if key.is_empty() {
                return Err(file.invalid(at, "a header entry has no name".into()));
            }
            let value = file.entry_value(&mut at)?;
            match key.as_str() {
                "format" => file.binary = value == "binary",
                "class" => file.class = value,
                "arch" => {
                    for part in value.split(';') {
                        match part.trim() {
                            "MSB" => file.big_endian = true,
                            "label=64" => file.label64 = true,
                            "scalar=32" => file.scalar32 = true,
                            _ => {}
                        }
                    }
                }
                _ => {}
            }
        }
        file.body = at;
        Ok(file)
    }

    pub fn invalid(&self, at: usize, message: String) -> OpenFoamError {
        OpenFoamError::Invalid {
            file: self.name.clone(),
            at,
            message,
        }
    }

    /// Skips white space and comments.
    pub fn skip_space(&self, at: &mut usize) {
        let b = self.bytes;
        while *at < b.len() {
            if b[*at].is_ascii_whitespace() {
                *at += 1;
            } else if b[*at..].starts_with(b"//") {
                while *at < b.len() && b[*at] != b'\n' {
                    *at += 1;
                }
            } else if b[*at..].starts_with(b"/*") {
                *at = find(b, *at + 2, b"*/").map_or(b.len(), |end| end + 2);
            } else {
                break;
            }
        }
    }

    /// The next word (letters, digits, `_.:<>-+` and quotes' contents).
    pub fn word(&self, at: &mut usize) -> String {
        self.skip_space(at);
        let b = self.bytes;
        if b.get(*at) == Some(&b'"') {
            let end = find(b, *at + 1, b"\"").unwrap_or(b.len());
            let w = String::from_utf8_lossy(&b[*at + 1..end]).into_owned();
            *at = (end + 1).min(b.len());
            return w;
        }
        let start = *at;
        while *at < b.len() && (b[*at].is_ascii_alphanumeric() || b"_.:<>-+#".contains(&b[*at])) {
            *at += 1;
        }
        String::from_utf8_lossy(&b[start..*at]).into_owned()
    }

    /// The value of a `key value;` entry, up to the `;`.
    fn entry_value(&self, at: &mut usize) -> Result<String, OpenFoamError> {
        self.skip_space(at);
        // A quoted value may hold ';' ("LSB;label=32;scalar=64").
        let from = if self.bytes.get(*at) == Some(&b'"') {
            find(self.bytes, *at + 1, b"\"").map_or(*at, |q| q + 1)
        } else {
            *at
        };
        let end = find(self.bytes, from, b";")
            .ok_or_else(|| self.invalid(*at, "an entry has no ';'".into()))?;
        let value = String::from_utf8_lossy(&self.bytes[*at..end])
            .trim()
            .trim_matches('"')
            .to_string();
        *at = end + 1;
        Ok(value)
    }

    /// Moves past the keyword `key` (a whole word) at the top level of the
    /// body; `false` when there is none.
    pub fn seek_keyword(&self, at: &mut usize, key: &str) -> bool {
        let mut pos = self.body;
        while pos < self.bytes.len() {
            self.skip_space(&mut pos);
            let w = self.word(&mut pos);
            if w == key {
                *at = pos;
                return true;
            }
            if w.is_empty() {
                // Skip a delimiter or a block we do not read.
                match self.bytes.get(pos) {
                    Some(b'{') => pos = self.matching(pos, b'{', b'}'),
                    Some(b'(') => pos = self.matching(pos, b'(', b')'),
                    Some(_) => pos += 1,
                    None => break,
                }
            }
        }
        false
    }

    /// The position after the bracket that closes the one at `at`.
    fn matching(&self, mut at: usize, open: u8, close: u8) -> usize {
        let mut depth = 0usize;
        while at < self.bytes.len() {
            let b = self.bytes[at];
            if b == open {
                depth += 1;
            } else if b == close {
                depth -= 1;
                if depth == 0 {
                    return at + 1;
                }
            }
            at += 1;
        }
        at
    }

    /// A non-negative count.
    pub fn count(&self, at: &mut usize, what: &str) -> Result<usize, OpenFoamError> {
        let start = *at;
        let w = self.word(at);
        w.parse::<usize>()
            .map_err(|_| self.invalid(start, format!("{what}: expected a count, found \"{w}\"")))
    }

    fn expect(&self, at: &mut usize, byte: u8, what: &str) -> Result<(), OpenFoamError> {
        self.skip_space(at);
        if self.bytes.get(*at) == Some(&byte) {
            *at += 1;
            Ok(())
        } else {
            Err(self.invalid(*at, format!("{what}: expected '{}'", byte as char)))
        }
    }

    /// A list of `n` items of `width` numbers each (1 for labels and
    /// scalars, 3 for vectors), as f64; `integer` items are labels.
    pub fn numbers(
        &self,
        at: &mut usize,
        width: usize,
        integer: bool,
        what: &str,
    ) -> Result<Vec<f64>, OpenFoamError> {
        let n = self.count(at, what)?;
        self.skip_space(at);
        let size = if integer {
            if self.label64 { 8 } else { 4 }
        } else if self.scalar32 {
            4
        } else {
            8
        };
        match self.bytes.get(*at) {
            Some(b'{') => {
                *at += 1;
                let one = self.ascii_item(at, width, what)?;
                self.expect(at, b'}', what)?;
                // N copies of one value: the memory they take, not the
                // file's length, bounds N.
                let bytes = (n as u64).saturating_mul(8 * width as u64);
                crate::preflight::check(&self.name, || format!("{what} ({n} copies)"), bytes)?;
                Ok(one.iter().copied().cycle().take(n * width).collect())
            }
            Some(b'(') if self.binary && n > 0 => {
                *at += 1;
                let bytes = n
                    .checked_mul(width * size)
                    .filter(|&len| len <= self.bytes.len() - *at)
                    .ok_or_else(|| self.truncated(*at, n, what))?;
                let raw = &self.bytes[*at..*at + bytes];
                *at += bytes;
                self.expect(at, b')', what)?;
                Ok(raw
                    .chunks_exact(size)
                    .map(|c| self.decode(c, integer))
                    .collect())
            }
            Some(b'(') => {
                *at += 1;
                // Each item takes at least two bytes in ASCII.
                self.fits(*at, n, 2 * width, what)?;
                let mut out = Vec::with_capacity(n * width);
                for _ in 0..n {
                    out.extend(self.ascii_item(at, width, what)?);
                }
                self.expect(at, b')', what)?;
                Ok(out)
            }
            _ => Err(self.invalid(*at, format!("{what}: expected '(' or '{{' after the count"))),
        }
    }

    /// One ASCII item: a number, or `(x y z)` for a vector.
    pub fn ascii_item(
        &self,
        at: &mut usize,
        width: usize,
        what: &str,
    ) -> Result<Vec<f64>, OpenFoamError> {
        if width == 1 {
            return Ok(vec![self.number(at, what)?]);
        }
        self.expect(at, b'(', what)?;
        let mut v = Vec::with_capacity(width);
        for _ in 0..width {
            v.push(self.number(at, what)?);
        }
        self.expect(at, b')', what)?;
        Ok(v)
    }

    pub fn number(&self, at: &mut usize, what: &str) -> Result<f64, OpenFoamError> {
        let start = *at;
        let w = self.word(at);
        w.parse::<f64>()
            .map_err(|_| self.invalid(start, format!("{what}: expected a number, found \"{w}\"")))
    }

    /// The faces of a `faceList` (ASCII: `k(a b c ...)` each) or a
    /// `faceCompactList` (two lists: offsets, then the labels).
    pub fn faces(&self, at: &mut usize) -> Result<(Vec<usize>, Vec<i64>), OpenFoamError> {
        if self.class == "faceCompactList" || self.binary {
            if self.class != "faceCompactList" {
                return Err(self.invalid(
                    *at,
                    format!(
                        "binary faces of class \"{}\" (expected faceCompactList)",
                        self.class
                    ),
                ));
            }
            let offsets = self.numbers(at, 1, true, "face offsets")?;
            let labels = self.numbers(at, 1, true, "face labels")?;
            let mut starts = Vec::with_capacity(offsets.len());
            let mut last = 0usize;
            for &o in &offsets {
                let o = o as usize;
                if o < last || o > labels.len() {
                    return Err(self.invalid(*at, format!("face offset {o} out of order")));
                }
                starts.push(o);
                last = o;
            }
            if starts.last() != Some(&labels.len()) || starts.first() != Some(&0) {
                return Err(self.invalid(*at, "the face offsets do not span the labels".into()));
            }
            return Ok((starts, labels.into_iter().map(|l| l as i64).collect()));
        }
        let n = self.count(at, "faces")?;
        self.expect(at, b'(', "faces")?;
        self.fits(*at, n, 8, "faces")?;
        let mut starts = Vec::with_capacity(n + 1);
        let mut labels = Vec::new();
        starts.push(0);
        for _ in 0..n {
            let k = self.count(at, "face size")?;
            self.expect(at, b'(', "face")?;
            self.fits(*at, k, 2, "face")?;
            for _ in 0..k {
                let v = self.number(at, "face label")?;
                labels.push(v as i64);
            }
            self.expect(at, b')', "face")?;
            starts.push(labels.len());
        }
        self.expect(at, b')', "faces")?;
        Ok((starts, labels))
    }

    fn decode(&self, c: &[u8], integer: bool) -> f64 {
        let mut b = [0u8; 8];
        b[..c.len()].copy_from_slice(c);
        if self.big_endian {
            b[..c.len()].reverse();
        }
        match (integer, c.len()) {
            (true, 4) => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            (true, _) => i64::from_le_bytes(b) as f64,
            (false, 4) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            (false, _) => f64::from_le_bytes(b),
        }
    }

    /// `n` items of at least `bytes` each must fit in what is left.
    fn fits(&self, at: usize, n: usize, bytes: usize, what: &str) -> Result<(), OpenFoamError> {
        match n.checked_mul(bytes) {
            Some(len) if len <= self.bytes.len().saturating_sub(at) => Ok(()),
            _ => Err(self.truncated(at, n, what)),
        }
    }

    fn truncated(&self, at: usize, n: usize, what: &str) -> OpenFoamError {
        OpenFoamError::Truncated {
            file: self.name.clone(),
            what: format!("{what} ({n} items from byte {at})"),
            found: self.bytes.len() as u64,
        }
    }
}

fn find(bytes: &[u8], from: usize, needle: &[u8]) -> Option<usize> {
    bytes
        .get(from..)?
        .windows(needle.len())
        .position(|w| w == needle)
        .map(|p| p + from)
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "FoamFile { version 2.0; format ascii; class vectorField; }\n";

    #[test]
    fn ascii_lists_and_uniform_lists() {
        let text = format!("{HEADER}// a comment\n2 ( (0 1 2) /* x */ (3 4 5e-1) )\n3{{7}}");
        let f = FoamFile::parse(text.as_bytes(), "t").unwrap();
        let mut at = f.body;
        assert_eq!(
            f.numbers(&mut at, 3, false, "p").unwrap(),
            vec![0., 1., 2., 3., 4., 0.5]
        );
        assert_eq!(f.numbers(&mut at, 1, true, "l").unwrap(), vec![7., 7., 7.]);
    }

    #[test]
    fn binary_lists_by_the_arch() {
        let mut bytes =
            b"FoamFile { format binary; class labelList; arch \"LSB;label=64;scalar=32\"; }\n2("
                .to_vec();
        bytes.extend(5i64.to_le_bytes());
        bytes.extend((-1i64).to_le_bytes());
        bytes.extend(b")\n1(");
        bytes.extend(1.5f32.to_le_bytes());
        bytes.extend(b")");
        let f = FoamFile::parse(&bytes, "t").unwrap();
        let mut at = f.body;
        assert_eq!(f.numbers(&mut at, 1, true, "l").unwrap(), vec![5., -1.]);
        assert_eq!(f.numbers(&mut at, 1, false, "s").unwrap(), vec![1.5]);
        // A count the bytes cannot hold.
        let mut short = bytes[..f.body].to_vec();
        short.extend(b"1000000(");
        let f = FoamFile::parse(&short, "t").unwrap();
        let mut at = f.body;
        assert!(matches!(
            f.numbers(&mut at, 1, true, "l"),
            Err(OpenFoamError::Truncated { .. })
        ));
    }

    #[test]
    fn faces_ascii_and_compact() {
        let text = "FoamFile { format ascii; class faceList; }\n2(4(0 1 2 3) 3(4 5 6))";
        let f = FoamFile::parse(text.as_bytes(), "t").unwrap();
        let mut at = f.body;
        assert_eq!(
            f.faces(&mut at).unwrap(),
            (vec![0, 4, 7], vec![0, 1, 2, 3, 4, 5, 6])
        );
        let text = "FoamFile { format ascii; class faceCompactList; }\n3(0 4 7) 7(0 1 2 3 4 5 6)";
        let f = FoamFile::parse(text.as_bytes(), "t").unwrap();
        let mut at = f.body;
        assert_eq!(
            f.faces(&mut at).unwrap(),
            (vec![0, 4, 7], vec![0, 1, 2, 3, 4, 5, 6])
        );
    }
}
