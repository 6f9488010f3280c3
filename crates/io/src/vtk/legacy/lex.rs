//! A cursor over a legacy VTK file: whitespace-separated keywords and ASCII
//! values, with line counting, and raw big-endian blocks for BINARY files.

use crate::vtk::VtkError;
use crate::vtk::numeric::{Scalar, decode_f64, decode_i64, parse_f64, parse_i64};

pub(super) struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// 1-based line of `pos` (in BINARY files, newline bytes inside binary
    /// blocks are counted too, so lines after a block are approximate).
    line: usize,
    pub file: &'a str,
    pub binary: bool,
}

impl<'a> Cursor<'a> {
    pub fn new(bytes: &'a [u8], file: &'a str) -> Self {
        Cursor {
            bytes,
            pos: 0,
            line: 1,
            file,
            binary: false,
        }
    }

    pub fn line(&self) -> usize {
        self.line
    }

    pub fn syntax(&self, message: impl Into<String>) -> VtkError {
        VtkError::Syntax {
            file: self.file.into(),
            line: self.line,
            message: message.into(),
        }
    }

    fn skip_whitespace(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    fn token_end(&self, start: usize) -> usize {
        self.bytes[start..]
            .iter()
            .position(u8::is_ascii_whitespace)
            .map_or(self.bytes.len(), |n| start + n)
    }

    /// The next whitespace-separated token, or `None` at the end.
    pub fn token(&mut self) -> Option<&'a [u8]> {
        self.skip_whitespace();
        if self.pos >= self.bytes.len() {
            return None;
        }
        let start = self.pos;
        self.pos = self.token_end(start);
        Some(&self.bytes[start..self.pos])
    }

    /// The next token as text; `what` names what was expected, for the
    /// error at the end of the file or on non-UTF-8 bytes.
    pub fn word(&mut self, what: &str) -> Result<&'a str, VtkError> {
        match self.token() {
            None => Err(self.syntax(format!("expected {what}, found the end of the file"))),
            Some(t) => std::str::from_utf8(t)
                .map_err(|_| self.syntax(format!("expected {what}, found non-text bytes"))),
        }
    }

    /// A count or size: a non-negative integer.
    pub fn count(&mut self, what: &str) -> Result<usize, VtkError> {
        let w = self.word(what)?;
        w.parse().map_err(|_| {
            self.syntax(format!(
                "expected {what} (a non-negative integer), found \"{w}\""
            ))
        })
    }

    /// The next token if it is on the current line (optional trailing
    /// parameters such as the component count of SCALARS).
    pub fn line_word(&mut self) -> Option<&'a str> {
        let mut p = self.pos;
        while p < self.bytes.len() && matches!(self.bytes[p], b' ' | b'\t' | b'\r') {
            p += 1;
        }
        if p >= self.bytes.len() || self.bytes[p].is_ascii_whitespace() {
            return None;
        }
        let end = self.token_end(p);
        let word = std::str::from_utf8(&self.bytes[p..end]).ok()?;
        self.pos = end;
        Some(word)
    }

    /// Whether the next token is `keyword` (ASCII case-insensitive), without
    /// consuming anything.
    pub fn next_is(&self, keyword: &str) -> bool {
        let mut p = self.pos;
        while p < self.bytes.len() && self.bytes[p].is_ascii_whitespace() {
            p += 1;
        }
        let end = self.token_end(p);
        self.bytes[p..end].eq_ignore_ascii_case(keyword.as_bytes())
    }

    /// The rest of the current line, consuming its newline.
    pub fn rest_of_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        match self.bytes[start..].iter().position(|&b| b == b'\n') {
            Some(n) => {
                self.pos = start + n + 1;
                self.line += 1;
                &self.bytes[start..start + n]
            }
            None => {
                self.pos = self.bytes.len();
                &self.bytes[start..]
            }
        }
    }

    /// The current line (without its newline), not consumed.
    pub fn peek_line(&self) -> &'a [u8] {
        let rest = &self.bytes[self.pos..];
        &rest[..rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len())]
    }

    /// Whether every byte has been read.
    pub fn at_eof(&self) -> bool {
        self.pos >= self.bytes.len()
    }

    /// A binary block of `count` elements of `ty`: VTK starts it on the line
    /// after its keyword line.
    fn block(&mut self, ty: Scalar, count: usize, section: &str) -> Result<&'a [u8], VtkError> {
        self.rest_of_line();
        let available = self.bytes.len() - self.pos;
        let need = count.checked_mul(ty.size()).filter(|&n| n <= available);
        let Some(need) = need else {
            return Err(VtkError::Truncated {
                file: self.file.into(),
                section: section.into(),
                expected: count,
                found: available / ty.size(),
                unit: "values",
            });
        };
        let block = &self.bytes[self.pos..self.pos + need];
        self.line += block.iter().filter(|&&b| b == b'\n').count();
        self.pos += need;
        Ok(block)
    }

    fn truncated(&self, section: &str, expected: usize, found: usize) -> VtkError {
        VtkError::Truncated {
            file: self.file.into(),
            section: section.into(),
            expected,
            found,
            unit: "values",
        }
    }

    /// `count` values of `ty` as f64 (ASCII tokens or a big-endian block).
    pub fn floats(
        &mut self,
        ty: Scalar,
        count: usize,
        section: &str,
    ) -> Result<Vec<f64>, VtkError> {
        if self.binary {
            let block = self.block(ty, count, section)?;
            return Ok(decode_f64(ty, block, true));
        }
        let mut out = Vec::with_capacity(count.min(self.bytes.len() / 2));
        for i in 0..count {
            let Some(t) = self.token() else {
                return Err(self.truncated(section, count, i));
            };
            let v = std::str::from_utf8(t).ok().and_then(|s| parse_f64(ty, s));
            let Some(v) = v else {
                return Err(self.syntax(format!(
                    "{section}: value {i}: \"{}\" is not a {}",
                    String::from_utf8_lossy(t),
                    ty.vtu_name()
                )));
            };
            out.push(v);
        }
        Ok(out)
    }

    /// `count` integers of integer type `ty`.
    pub fn ints(&mut self, ty: Scalar, count: usize, section: &str) -> Result<Vec<i64>, VtkError> {
        if ty.is_float() {
            return Err(self.syntax(format!(
                "{section}: indices must have an integer type, found {}",
                ty.vtu_name()
            )));
        }
        if self.binary {
            let block = self.block(ty, count, section)?;
            return decode_i64(ty, block, true)
                .map_err(|i| self.syntax(format!("{section}: value {i} does not fit in 64 bits")));
        }
        let mut out = Vec::with_capacity(count.min(self.bytes.len() / 2));
        for i in 0..count {
            let Some(t) = self.token() else {
                return Err(self.truncated(section, count, i));
            };
            let v = std::str::from_utf8(t).ok().and_then(|s| parse_i64(ty, s));
            let Some(v) = v else {
                return Err(self.syntax(format!(
                    "{section}: value {i}: \"{}\" is not a {}",
                    String::from_utf8_lossy(t),
                    ty.vtu_name()
                )));
            };
            out.push(v);
        }
        Ok(out)
    }
}

/// Legacy names encode spaces and other special characters as `%XX`.
pub(super) fn decode_name(raw: &str) -> String {
    let b = raw.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = b
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok());
        match (b[i], hex.and_then(|h| u8::from_str_radix(h, 16).ok())) {
            (b'%', Some(v)) => {
                out.push(v);
                i += 3;
            }
            (c, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::decode_name;

    #[test]
    fn names_decode_percent_escapes() {
        assert_eq!(decode_name("a%20b%25"), "a b%");
        assert_eq!(decode_name("p%2"), "p%2");
        assert_eq!(decode_name("plain"), "plain");
    }
}
