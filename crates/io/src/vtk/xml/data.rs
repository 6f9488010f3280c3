//! Decoding a `.vtu` DataArray: ASCII text, inline base64, appended raw or
//! base64 data; UInt32 or UInt64 headers; optional zlib blocks; either byte
//! order.
//!
//! Binary layouts (VTK XML format): uncompressed data is `[nbytes][data]`;
//! zlib data is `[nblocks][block size][last block size]`, then one
//! compressed size per block, then the compressed blocks; the last block
//! size is 0 when the last block is full. Header integers have the file's `header_type`.
//! In base64, VTK encodes the header and the data either as one stream or
//! as two separately padded ones; decoding group by group (four characters
//! at a time, padding allowed in any group) reads both.

use std::borrow::Cow;
use std::io::Read;
use tetray_mesh::cells::CellError;

use super::tree::{AppendedEncoding, Format, VtuDoc, XmlArray};
use crate::vtk::VtkError;
use crate::vtk::numeric::{Scalar, decode_f64, decode_i64, parse_f64, parse_i64, u64_of};

pub(crate) const ZLIB: &str = "vtkZLibDataCompressor";

/// Decodes the arrays of one document.
pub(crate) struct ArrayDecoder<'a, 'd> {
    pub file: &'a str,
    pub doc: &'d VtuDoc<'a>,
}

impl ArrayDecoder<'_, '_> {
    fn scalar(&self, a: &XmlArray, section: &str) -> Result<Scalar, VtkError> {
        Scalar::from_vtu_name(&a.type_name).ok_or_else(|| {
            VtkError::Cell(CellError::Unsupported {
                file: self.file.into(),
                section: section.into(),
                what: "DataArray type",
                value: a.type_name.clone(),
            })
        })
    }

    /// The array's values as f64 (exact for every type up to 2^53).
    pub fn floats(&self, a: &XmlArray, section: &str) -> Result<Vec<f64>, VtkError> {
        let ty = self.scalar(a, section)?;
        if a.format == Format::Ascii {
            return self.ascii(a, ty, section, parse_f64);
        }
        let bytes = self.payload(a, ty, section)?;
        Ok(decode_f64(ty, &bytes, self.doc.big_endian))
    }

    /// The array's values as integers; float arrays are refused.
    pub fn ints(&self, a: &XmlArray, section: &str) -> Result<Vec<i64>, VtkError> {
        let ty = self.scalar(a, section)?;
        if ty.is_float() {
            return Err(VtkError::Cell(CellError::Invalid {
                file: self.file.into(),
                section: section.into(),
                message: format!("must have an integer type, found {}", ty.vtu_name()),
            }));
        }
        if a.format == Format::Ascii {
            return self.ascii(a, ty, section, parse_i64);
        }
        let bytes = self.payload(a, ty, section)?;
        decode_i64(ty, &bytes, self.doc.big_endian).map_err(|i| {
            VtkError::Cell(CellError::Invalid {
                file: self.file.into(),
                section: section.into(),
                message: format!("value {i} does not fit in a signed 64-bit integer"),
            })
        })
    }

    fn ascii<T>(
        &self,
        a: &XmlArray,
        ty: Scalar,
        section: &str,
        parse: fn(Scalar, &str) -> Option<T>,
    ) -> Result<Vec<T>, VtkError> {
        let mut out = Vec::new();
        for (i, token) in a
            .text
            .split(u8::is_ascii_whitespace)
            .filter(|t| !t.is_empty())
            .enumerate()
        {
            let v = std::str::from_utf8(token).ok().and_then(|s| parse(ty, s));
            let Some(v) = v else {
                return Err(VtkError::Syntax {
                    file: self.file.into(),
                    line: a.line,
                    message: format!(
                        "{section}: value {i}: \"{}\" is not a {}",
                        String::from_utf8_lossy(token),
                        ty.vtu_name()
                    ),
                });
            };
            out.push(v);
        }
        Ok(out)
    }

    /// The decoded (and inflated) bytes of a binary or appended array, a
    /// whole number of elements of `ty`; raw appended data is borrowed, not
    /// copied.
    fn payload<'s>(
        &'s self,
        a: &'s XmlArray,
        ty: Scalar,
        section: &'s str,
    ) -> Result<Cow<'s, [u8]>, VtkError> {
        let mut source = self.source(a, section)?;
        let bytes = match self.doc.compressor.as_deref() {
            None => {
                let n = self.header_value(&mut source)?;
                source.take(n)?
            }
            Some(ZLIB) => Cow::Owned(self.inflate(&mut source)?),
            Some(other) => {
                return Err(VtkError::Cell(CellError::Unsupported {
                    file: self.file.into(),
                    section: section.into(),
                    what: "compressor",
                    value: other.into(),
                }));
            }
        };
        if bytes.len() % ty.size() != 0 {
            return Err(VtkError::Cell(CellError::Invalid {
                file: self.file.into(),
                section: section.into(),
                message: format!(
                    "{} bytes is not a whole number of {} values",
                    bytes.len(),
                    ty.vtu_name()
                ),
            }));
        }
        Ok(bytes)
    }

    fn source<'s>(&'s self, a: &'s XmlArray, section: &'s str) -> Result<Source<'s>, VtkError> {
        let context = Context {
            file: self.file,
            section,
        };
        let offset = match a.format {
            Format::Binary => return Ok(Source::base64(&a.text, context)),
            Format::Appended { offset } => offset,
            Format::Ascii => 0,
        };
        let Some(appended) = &self.doc.appended else {
            return Err(VtkError::Cell(CellError::Invalid {
                file: self.file.into(),
                section: section.into(),
                message: "an appended DataArray but the file has no <AppendedData>".into(),
            }));
        };
        if offset > appended.data.len() {
            return Err(VtkError::Truncated {
                file: self.file.into(),
                section: format!("{section}, appended data at offset {offset}"),
                expected: offset,
                found: appended.data.len(),
                unit: "bytes before the array",
            });
        }
        let data = &appended.data[offset..];
        Ok(match appended.encoding {
            AppendedEncoding::Raw => Source::Raw {
                data,
                pos: 0,
                context,
            },
            AppendedEncoding::Base64 => Source::base64(data, context),
        })
    }

    /// One header integer (UInt32 or UInt64, the file's byte order).
    fn header_value(&self, source: &mut Source<'_>) -> Result<usize, VtkError> {
        let size = if self.doc.header_u64 { 8 } else { 4 };
        let v = u64_of(&source.take(size)?, self.doc.big_endian);
        usize::try_from(v).map_err(|_| {
            source
                .context()
                .invalid(format!("header value {v} is too large"))
        })
    }

    fn inflate(&self, source: &mut Source<'_>) -> Result<Vec<u8>, VtkError> {
        let blocks = self.header_value(source)?;
        let block_size = self.header_value(source)?;
        let last_size = self.header_value(source)?;
        // Read one compressed size at a time: a corrupt block count then
        // fails on missing bytes instead of allocating.
        let mut compressed_sizes = Vec::new();
        for _ in 0..blocks {
            compressed_sizes.push(self.header_value(source)?);
        }
        let mut out = Vec::new();
        for (block, &csize) in compressed_sizes.iter().enumerate() {
            let expected = if block + 1 == blocks && last_size != 0 {
                last_size
            } else {
                block_size
            };
            let compressed = source.take(csize)?;
            let zlib_error = |message: String| VtkError::Zlib {
                file: self.file.into(),
                section: source.context().section.into(),
                block,
                blocks,
                message,
            };
            let before = out.len();
            let mut decoder = flate2::read::ZlibDecoder::new(&compressed[..]);
            (&mut decoder)
                .take((expected as u64).saturating_add(1))
                .read_to_end(&mut out)
                .map_err(|e| zlib_error(e.to_string()))?;
            let got = out.len() - before;
            if got != expected {
                return Err(zlib_error(format!(
                    "inflates to {got} bytes, the header says {expected}"
                )));
            }
        }
        Ok(out)
    }
}

#[derive(Debug, Clone, Copy)]
struct Context<'s> {
    file: &'s str,
    section: &'s str,
}

impl Context<'_> {
    fn invalid(&self, message: String) -> VtkError {
        VtkError::Cell(CellError::Invalid {
            file: self.file.into(),
            section: self.section.into(),
            message,
        })
    }

    fn truncated(&self, expected: usize, found: usize) -> VtkError {
        VtkError::Truncated {
            file: self.file.into(),
            section: self.section.into(),
            expected,
            found,
            unit: "bytes",
        }
    }
}

/// Bytes of one array, raw or base64-decoded on the fly.
enum Source<'s> {
    Raw {
        data: &'s [u8],
        pos: usize,
        context: Context<'s>,
    },
    Base64(Base64Stream<'s>),
}

impl<'s> Source<'s> {
    fn base64(text: &'s [u8], context: Context<'s>) -> Self {
        Source::Base64(Base64Stream {
            text,
            pos: 0,
            pending: Vec::new(),
            context,
        })
    }

    fn context(&self) -> Context<'s> {
        match self {
            Source::Raw { context, .. } => *context,
            Source::Base64(s) => s.context,
        }
    }

    /// The next `n` bytes (borrowed from raw data, decoded from base64).
    fn take(&mut self, n: usize) -> Result<Cow<'s, [u8]>, VtkError> {
        match self {
            Source::Raw { data, pos, context } => {
                let left = data.len() - *pos;
                if n > left {
                    return Err(context.truncated(n, left));
                }
                *pos += n;
                let data: &'s [u8] = data;
                Ok(Cow::Borrowed(&data[*pos - n..*pos]))
            }
            Source::Base64(stream) => stream.take(n).map(Cow::Owned),
        }
    }
}

struct Base64Stream<'s> {
    text: &'s [u8],
    pos: usize,
    /// Decoded bytes not yet taken (at most 2).
    pending: Vec<u8>,
    context: Context<'s>,
}

impl Base64Stream<'_> {
    fn take(&mut self, n: usize) -> Result<Vec<u8>, VtkError> {
        // Never trust `n` for the allocation: 4 characters give 3 bytes.
        let bound = (self.text.len() - self.pos) / 4 * 3 + 3 + self.pending.len();
        let mut out = Vec::with_capacity(n.min(bound));
        let from_pending = n.min(self.pending.len());
        out.extend(self.pending.drain(..from_pending));
        while out.len() < n {
            let Some((group, len)) = self.group()? else {
                return Err(self.context.truncated(n, out.len()));
            };
            let need = (n - out.len()).min(len);
            out.extend_from_slice(&group[..need]);
            self.pending.extend_from_slice(&group[need..len]);
        }
        Ok(out)
    }

    /// Decodes the next group of four characters (whitespace skipped): up
    /// to three bytes, fewer with padding or at an unpadded end.
    fn group(&mut self) -> Result<Option<([u8; 3], usize)>, VtkError> {
        let mut sextets = [0u8; 4];
        let mut count = 0;
        let mut padding = 0;
        while count < 4 {
            let Some(&c) = self.text.get(self.pos) else {
                break;
            };
            let at = self.pos;
            self.pos += 1;
            if c.is_ascii_whitespace() {
                continue;
            }
            let value = match c {
                b'A'..=b'Z' => c - b'A',
                b'a'..=b'z' => c - b'a' + 26,
                b'0'..=b'9' => c - b'0' + 52,
                b'+' => 62,
                b'/' => 63,
                b'=' if count >= 2 => {
                    padding += 1;
                    0
                }
                _ => return Err(self.bad(at, format!("unexpected character {:?}", c as char))),
            };
            if padding > 0 && c != b'=' {
                return Err(self.bad(at, "data after '=' padding inside a group".into()));
            }
            sextets[count] = value;
            count += 1;
        }
        let len = match (count, padding) {
            (0, _) => return Ok(None),
            (1, _) => return Err(self.bad(self.pos, "a lone character at the end".into())),
            (c, 0) => c - 1,
            (4, p) => 3 - p,
            _ => return Err(self.bad(self.pos, "misplaced padding".into())),
        };
        let [a, b, c, d] = sextets;
        let bytes = [(a << 2) | (b >> 4), (b << 4) | (c >> 2), (c << 6) | d];
        Ok(Some((bytes, len)))
    }

    fn bad(&self, position: usize, message: String) -> VtkError {
        VtkError::Base64 {
            file: self.context.file.into(),
            section: self.context.section.into(),
            position,
            message,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(text: &str, n: usize) -> Result<Vec<u8>, VtkError> {
        let context = Context {
            file: "t",
            section: "s",
        };
        Source::base64(text.as_bytes(), context)
            .take(n)
            .map(Cow::into_owned)
    }

    #[test]
    fn base64_groups_decode_joined_or_separately_padded() {
        assert_eq!(decode("aGVsbG8=", 5).ok(), Some(b"hello".to_vec()));
        // "he" and "llo" encoded separately: padding mid-stream.
        assert_eq!(decode("aGU=\n bGxv", 5).ok(), Some(b"hello".to_vec()));
        assert_eq!(decode("aGVsbG8", 5).ok(), Some(b"hello".to_vec()));
        assert!(matches!(
            decode("aGVs", 5),
            Err(VtkError::Truncated { found: 3, .. })
        ));
        assert!(matches!(
            decode("aG*s", 3),
            Err(VtkError::Base64 { position: 2, .. })
        ));
        assert!(matches!(decode("a=Vs", 3), Err(VtkError::Base64 { .. })));
        assert!(matches!(decode("aG=s", 3), Err(VtkError::Base64 { .. })));
    }
}
