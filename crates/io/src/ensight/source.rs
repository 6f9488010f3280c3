//! Reading an EnSight Gold data file, ASCII or C binary, item by item: a
//! text line (in C binary, an 80-byte string), integers and floats (in C
//! binary, 32-bit, little- or big-endian as the first count says; in
//! ASCII, numbers separated by white space or run together in fixed
//! 12-character fields). Every count is checked against the bytes left.

use super::EnSightError;

pub(super) struct Source<'a> {
    pub bytes: &'a [u8],
    pub at: usize,
    /// Where reading stops (the end of a time step's block).
    pub end: usize,
    pub binary: bool,
    pub big_endian: bool,
    pub name: String,
    /// ASCII numbers split from a line and not yet taken.
    pending: Vec<String>,
}

impl<'a> Source<'a> {
    /// The file's bytes; `C Binary` first means binary (Fortran binary is
    /// refused).
    pub fn new(bytes: &'a [u8], name: &str) -> Result<Source<'a>, EnSightError> {
        let mut s = Source {
            bytes,
            at: 0,
            end: bytes.len(),
            binary: false,
            big_endian: false,
            name: name.into(),
            pending: Vec::new(),
        };
        let head = String::from_utf8_lossy(&bytes[..bytes.len().min(80)]).to_lowercase();
        if head.starts_with("c binary") {
            s.binary = true;
            s.at = 80;
        } else if head.starts_with("fortran binary") {
            return Err(
                s.invalid("Fortran binary EnSight files are not read (C binary and ASCII are)")
            );
        }
        Ok(s)
    }

    pub fn invalid(&self, message: &str) -> EnSightError {
        EnSightError::Invalid {
            file: self.name.clone(),
            at: self.at,
            message: message.into(),
        }
    }

    pub fn at_end(&mut self) -> bool {
        if self.binary {
            self.at + 80 > self.end
        } else {
            self.pending.is_empty()
                && self.bytes[self.at.min(self.end)..self.end]
                    .iter()
                    .all(|b| b.is_ascii_whitespace() || *b == 0)
        }
    }

    /// The next text line (trimmed), or an 80-byte string.
    pub fn line(&mut self) -> Result<String, EnSightError> {
        self.pending.clear();
        if self.binary {
            if self.at + 80 > self.end {
                return Err(self.invalid("the file ends where a text line belongs"));
            }
            let raw = &self.bytes[self.at..self.at + 80];
            self.at += 80;
            let text = raw.split(|&b| b == 0).next().unwrap_or_default();
            return Ok(String::from_utf8_lossy(text).trim().to_string());
        }
        // Skip blank lines.
        while self.at < self.end && (self.bytes[self.at] == b'\n' || self.bytes[self.at] == b'\r') {
            self.at += 1;
        }
        if self.at >= self.end {
            return Err(self.invalid("the file ends where a text line belongs"));
        }
        let start = self.at;
        while self.at < self.end && self.bytes[self.at] != b'\n' {
            self.at += 1;
        }
        let text = String::from_utf8_lossy(&self.bytes[start..self.at])
            .trim()
            .to_string();
        Ok(text)
    }

    /// The next line, left unread.
    pub fn peek_line(&mut self) -> Option<String> {
        let (at, pending) = (self.at, self.pending.clone());
        let line = self.line().ok();
        self.at = at;
        self.pending = pending;
        line
    }

    pub fn ints(&mut self, n: usize, what: &str) -> Result<Vec<i64>, EnSightError> {
        self.fits(n, what)?;
        if self.binary {
            return Ok(self.words(n, i32::from_le_bytes, i32::from_be_bytes, i64::from));
        }
        let mut out = Vec::with_capacity(n);
        while out.len() < n {
            let token = self.token(what)?;
            out.push(
                token
                    .parse::<i64>()
                    .map_err(|_| self.invalid(&format!("{what}: \"{token}\" is not an integer")))?,
            );
        }
        Ok(out)
    }

    /// One count; in C binary it also tells the byte order (a count read
    /// the wrong way round is huge or negative).
    pub fn count(&mut self, what: &str) -> Result<usize, EnSightError> {
        if self.binary && self.at + 4 <= self.end {
            let b: [u8; 4] = self.bytes[self.at..self.at + 4]
                .try_into()
                .expect("4 bytes");
            let (le, be) = (i32::from_le_bytes(b), i32::from_be_bytes(b));
            let plausible = |v: i32| (0..=1 << 30).contains(&v);
            if !plausible(le) && plausible(be) {
                self.big_endian = true;
            } else if plausible(le) {
                self.big_endian = false;
            }
        }
        let v = self.ints(1, what)?[0];
        usize::try_from(v).map_err(|_| self.invalid(&format!("{what}: count {v} is negative")))
    }

    pub fn floats(&mut self, n: usize, what: &str) -> Result<Vec<f64>, EnSightError> {
        self.fits(n, what)?;
        if self.binary {
            return Ok(self.words(n, f32::from_le_bytes, f32::from_be_bytes, f64::from));
        }
        let mut out = Vec::with_capacity(n);
        while out.len() < n {
            let token = self.token(what)?;
            match parse_float(&token) {
                Some(v) => out.push(v),
                // Fixed-width fields run together ("-1.0e+00-2.0e+00").
                None if token.len() > 12 && token.len() % 12 == 0 => {
                    for field in token.as_bytes().chunks(12) {
                        let text = String::from_utf8_lossy(field);
                        out.push(parse_float(text.trim()).ok_or_else(|| {
                            self.invalid(&format!("{what}: \"{token}\" is not a number"))
                        })?);
                    }
                }
                None => {
                    return Err(self.invalid(&format!("{what}: \"{token}\" is not a number")));
                }
            }
        }
        out.truncate(n);
        Ok(out)
    }

    /// `n` binary 4-byte values (already checked to fit), decoded in the
    /// file's byte order and widened.
    fn words<T, U>(
        &mut self,
        n: usize,
        le: fn([u8; 4]) -> T,
        be: fn([u8; 4]) -> T,
        widen: fn(T) -> U,
    ) -> Vec<U> {
        let raw = &self.bytes[self.at..self.at + 4 * n];
        self.at += 4 * n;
        let decode = if self.big_endian { be } else { le };
        raw.chunks_exact(4)
            .map(|c| widen(decode([c[0], c[1], c[2], c[3]])))
            .collect()
    }

    fn token(&mut self, what: &str) -> Result<String, EnSightError> {
        loop {
            if !self.pending.is_empty() {
                return Ok(self.pending.remove(0));
            }
            let line = self
                .line()
                .map_err(|_| self.invalid(&format!("{what}: the file ends early")))?;
            self.pending = line.split_whitespace().map(str::to_string).collect();
        }
    }

    /// `n` items (4 bytes each in binary, at least 2 in ASCII) must fit.
    fn fits(&self, n: usize, what: &str) -> Result<(), EnSightError> {
        let left = self.end.saturating_sub(self.at);
        let room = if self.binary {
            n.checked_mul(4).is_some_and(|bytes| bytes <= left)
        } else {
            // The last number may end the file without a separator.
            let pending: usize = self.pending.iter().map(|p| p.len() + 1).sum();
            n.checked_mul(2)
                .is_some_and(|bytes| bytes <= left + pending + 1)
        };
        if room {
            Ok(())
        } else {
            Err(EnSightError::Truncated {
                file: self.name.clone(),
                what: format!("{what} ({n} values)"),
                found: self.bytes.len() as u64,
            })
        }
    }

    /// Limits reading to time step `step` (0-based) of a file holding
    /// several between `BEGIN TIME STEP` and `END TIME STEP`; a file
    /// without them is one step.
    pub fn select_step(&mut self, step: usize) -> Result<(), EnSightError> {
        let marker = b"BEGIN TIME STEP";
        let starts: Vec<usize> = self
            .bytes
            .windows(marker.len())
            .enumerate()
            .filter(|(_, w)| *w == marker)
            .map(|(i, _)| i)
            .collect();
        if starts.is_empty() {
            return Ok(());
        }
        let Some(&start) = starts.get(step) else {
            return Err(self.invalid(&format!(
                "time step {step} asked of a file holding {} steps",
                starts.len()
            )));
        };
        let end_marker = b"END TIME STEP";
        let Some(end) = self.bytes[start..]
            .windows(end_marker.len())
            .position(|w| w == end_marker)
            .map(|p| start + p)
        else {
            self.at = start;
            return Err(self.invalid(&format!(
                "time step {step} has no END TIME STEP: the file is cut short"
            )));
        };
        self.at = start;
        self.end = end;
        self.line()?;
        Ok(())
    }
}

/// A number as Fortran and C write it, also with the exponent's `e`
/// dropped (`3.300003+000`).
fn parse_float(token: &str) -> Option<f64> {
    if let Ok(v) = token.parse::<f64>() {
        return Some(v);
    }
    if !token.is_ascii() || token.len() < 2 {
        return None;
    }
    let at = token[1..].rfind(['+', '-'])? + 1;
    if token[..at].contains(['e', 'E']) {
        return None;
    }
    format!("{}e{}", &token[..at], &token[at..]).parse().ok()
}
