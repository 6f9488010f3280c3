//! Numeric element types shared by the legacy and XML formats, and their
//! decoding from bytes and from ASCII tokens.

/// A numeric element type of a VTK array.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Scalar {
    /// Bytes per element.
    pub(crate) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::I64 | Scalar::U64 | Scalar::F64 => 8,
        }
    }

    pub(crate) fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The `type` attribute of an XML DataArray.
    pub(crate) fn from_vtu_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "Int8" => Scalar::I8,
            "UInt8" => Scalar::U8,
            "Int16" => Scalar::I16,
            "UInt16" => Scalar::U16,
            "Int32" => Scalar::I32,
            "UInt32" => Scalar::U32,
            "Int64" => Scalar::I64,
            "UInt64" => Scalar::U64,
            "Float32" => Scalar::F32,
            "Float64" => Scalar::F64,
            _ => return None,
        })
    }

    pub(crate) fn vtu_name(self) -> &'static str {
        match self {
            Scalar::I8 => "Int8",
            Scalar::U8 => "UInt8",
            Scalar::I16 => "Int16",
            Scalar::U16 => "UInt16",
            Scalar::I32 => "Int32",
            Scalar::U32 => "UInt32",
            Scalar::I64 => "Int64",
            Scalar::U64 => "UInt64",
            Scalar::F32 => "Float32",
            Scalar::F64 => "Float64",
        }
    }

    /// A legacy-format data type name (case-insensitive). `long` is taken as
    /// 8 bytes (LP64, what VTK on Linux and macOS writes); `vtkIdType` as 4
    /// bytes, because VTK's legacy writer stores id arrays as `int`.
    pub(crate) fn from_legacy_name(name: &str) -> Option<Scalar> {
        Some(match name.to_ascii_lowercase().as_str() {
            "char" | "signed_char" | "vtktypeint8" => Scalar::I8,
            "unsigned_char" | "vtktypeuint8" => Scalar::U8,
            "short" | "vtktypeint16" => Scalar::I16,
            "unsigned_short" | "vtktypeuint16" => Scalar::U16,
            "int" | "vtkidtype" | "vtktypeint32" => Scalar::I32,
            "unsigned_int" | "vtktypeuint32" => Scalar::U32,
            "long" | "vtktypeint64" => Scalar::I64,
            "unsigned_long" | "vtktypeuint64" => Scalar::U64,
            "float" | "vtktypefloat32" => Scalar::F32,
            "double" | "vtktypefloat64" => Scalar::F64,
            _ => return None,
        })
    }
}

/// Elements per rayon task when a whole array is decoded.
const DECODE_CHUNK: usize = 1 << 16;

/// Decodes a whole array of `ty` elements to `T`, in parallel, with the
/// element width and byte order fixed outside the loop (`convert` takes
/// the element's bits widened to 64, then its sign extended for signed
/// types).
fn decode_all<T: Send, const N: usize>(
    bytes: &[u8],
    big_endian: bool,
    convert: impl Fn(u64) -> T + Sync,
) -> Vec<T> {
    use rayon::prelude::*;
    let read = |b: &[u8]| {
        let mut word = [0u8; 8];
        if big_endian {
            word[8 - N..].copy_from_slice(b);
            u64::from_be_bytes(word)
        } else {
            word[..N].copy_from_slice(b);
            u64::from_le_bytes(word)
        }
    };
    bytes
        .par_chunks_exact(N)
        .with_min_len(DECODE_CHUNK)
        .map(|b| convert(read(b)))
        .collect()
}

/// Sign-extends the low `bits` bits of `u`.
fn signed(u: u64, bits: u32) -> i64 {
    ((u << (64 - bits)) as i64) >> (64 - bits)
}

/// A whole array of `ty` elements (a whole number of them) as f64 (exact
/// for every float type and for integers up to 2^53).
pub(crate) fn decode_f64(ty: Scalar, bytes: &[u8], big_endian: bool) -> Vec<f64> {
    let b = big_endian;
    match ty {
        Scalar::F32 => decode_all::<_, 4>(bytes, b, |u| f32::from_bits(u as u32) as f64),
        Scalar::F64 => decode_all::<_, 8>(bytes, b, f64::from_bits),
        Scalar::U8 => decode_all::<_, 1>(bytes, b, |u| u as f64),
        Scalar::U16 => decode_all::<_, 2>(bytes, b, |u| u as f64),
        Scalar::U32 => decode_all::<_, 4>(bytes, b, |u| u as f64),
        Scalar::U64 => decode_all::<_, 8>(bytes, b, |u| u as f64),
        Scalar::I8 => decode_all::<_, 1>(bytes, b, |u| signed(u, 8) as f64),
        Scalar::I16 => decode_all::<_, 2>(bytes, b, |u| signed(u, 16) as f64),
        Scalar::I32 => decode_all::<_, 4>(bytes, b, |u| signed(u, 32) as f64),
        Scalar::I64 => decode_all::<_, 8>(bytes, b, |u| u as i64 as f64),
    }
}

/// A whole array of integer elements as i64; `Err(i)`: element `i` is a
/// float type's or an unsigned value beyond i64.
pub(crate) fn decode_i64(ty: Scalar, bytes: &[u8], big_endian: bool) -> Result<Vec<i64>, usize> {
    let b = big_endian;
    Ok(match ty {
        Scalar::F32 | Scalar::F64 => return if bytes.is_empty() { Ok(vec![]) } else { Err(0) },
        Scalar::U8 => decode_all::<_, 1>(bytes, b, |u| u as i64),
        Scalar::U16 => decode_all::<_, 2>(bytes, b, |u| u as i64),
        Scalar::U32 => decode_all::<_, 4>(bytes, b, |u| u as i64),
        Scalar::U64 => {
            let out = decode_all::<_, 8>(bytes, b, |u| u as i64);
            // Beyond i64 reads as negative.
            if let Some(i) = out.iter().position(|&v| v < 0) {
                return Err(i);
            }
            out
        }
        Scalar::I8 => decode_all::<_, 1>(bytes, b, |u| signed(u, 8)),
        Scalar::I16 => decode_all::<_, 2>(bytes, b, |u| signed(u, 16)),
        Scalar::I32 => decode_all::<_, 4>(bytes, b, |u| signed(u, 32)),
        Scalar::I64 => decode_all::<_, 8>(bytes, b, |u| u as i64),
    })
}

/// The bytes as an unsigned integer of their length (1 to 8).
pub(crate) fn u64_of(b: &[u8], big_endian: bool) -> u64 {
    let fold = |acc: u64, &x: &u8| (acc << 8) | x as u64;
    if big_endian {
        b.iter().fold(0, fold)
    } else {
        b.iter().rev().fold(0, fold)
    }
}

/// Parses one ASCII token as a value of `ty`, returned as f64. Float32
/// tokens are parsed as f32 so that the shortest decimal of an f32 gives
/// back the same bits (parsing as f64 then rounding could round twice).
pub(crate) fn parse_f64(ty: Scalar, token: &str) -> Option<f64> {
    match ty {
        Scalar::F32 => token.parse::<f32>().ok().map(f64::from),
        Scalar::F64 => token.parse::<f64>().ok(),
        _ => parse_i64(ty, token).map(|v| v as f64),
    }
}

/// Parses one ASCII token as an integer of `ty`, checking its range.
pub(crate) fn parse_i64(ty: Scalar, token: &str) -> Option<i64> {
    let v: i128 = token.parse().ok()?;
    let (lo, hi): (i128, i128) = match ty {
        Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
        Scalar::U8 => (0, u8::MAX.into()),
        Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
        Scalar::U16 => (0, u16::MAX.into()),
        Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
        Scalar::U32 => (0, u32::MAX.into()),
        // Unsigned 64-bit values beyond i64 cannot be point indices or
        // cell types; they are rejected as unparsable.
        Scalar::I64 | Scalar::U64 => (
            if ty == Scalar::U64 {
                0
            } else {
                i64::MIN.into()
            },
            i64::MAX.into(),
        ),
        Scalar::F32 | Scalar::F64 => return None,
    };
    (lo..=hi).contains(&v).then_some(v as i64)
}

#[cfg(test)]
mod tests {
    use super::*;

    // The per-element decoders the whole-array ones are checked against:
    // bytes folded one at a time, the type matched per element.

    /// One element of `ty` from exactly `ty.size()` bytes, as f64 (exact for
    /// every float type and for integers up to 2^53).
    fn element_f64(ty: Scalar, b: &[u8], big_endian: bool) -> f64 {
        match ty {
            Scalar::F32 => f32::from_bits(u64_of(b, big_endian) as u32) as f64,
            Scalar::F64 => f64::from_bits(u64_of(b, big_endian)),
            Scalar::U8 | Scalar::U16 | Scalar::U32 | Scalar::U64 => u64_of(b, big_endian) as f64,
            _ => i64_of(ty, b, big_endian) as f64,
        }
    }

    /// One integer element; `None` for float types and for unsigned values
    /// beyond i64.
    fn element_i64(ty: Scalar, b: &[u8], big_endian: bool) -> Option<i64> {
        match ty {
            Scalar::F32 | Scalar::F64 => None,
            Scalar::U64 => i64::try_from(u64_of(b, big_endian)).ok(),
            Scalar::U8 | Scalar::U16 | Scalar::U32 => Some(u64_of(b, big_endian) as i64),
            _ => Some(i64_of(ty, b, big_endian)),
        }
    }

    fn i64_of(ty: Scalar, b: &[u8], big_endian: bool) -> i64 {
        let u = u64_of(b, big_endian);
        // Sign-extend from the element's width.
        let shift = 64 - 8 * ty.size() as u32;
        ((u << shift) as i64) >> shift
    }

    #[test]
    fn decodes_both_byte_orders_and_signs() {
        assert_eq!(element_i64(Scalar::I16, &[0xff, 0xfe], true), Some(-2));
        assert_eq!(element_i64(Scalar::I16, &[0xfe, 0xff], false), Some(-2));
        assert_eq!(element_i64(Scalar::U16, &[0xff, 0xfe], true), Some(0xfffe));
        assert_eq!(element_i64(Scalar::U64, &[0xff; 8], true), None);
        let x = 1.5f32;
        assert_eq!(element_f64(Scalar::F32, &x.to_be_bytes(), true), 1.5);
        assert_eq!(
            element_f64(Scalar::F64, &(-2.25f64).to_le_bytes(), false),
            -2.25
        );
        assert_eq!(element_f64(Scalar::I8, &[0x80], false), -128.0);
        // The same values through the whole-array decoders the readers use.
        assert_eq!(decode_i64(Scalar::I16, &[0xff, 0xfe], true), Ok(vec![-2]));
        assert_eq!(decode_i64(Scalar::I16, &[0xfe, 0xff], false), Ok(vec![-2]));
        assert_eq!(
            decode_i64(Scalar::U16, &[0xff, 0xfe], true),
            Ok(vec![0xfffe])
        );
        assert_eq!(decode_i64(Scalar::U64, &[0xff; 8], true), Err(0));
        assert_eq!(decode_f64(Scalar::F32, &x.to_be_bytes(), true), vec![1.5]);
        assert_eq!(
            decode_f64(Scalar::F64, &(-2.25f64).to_le_bytes(), false),
            vec![-2.25]
        );
        assert_eq!(decode_f64(Scalar::I8, &[0x80], false), vec![-128.0]);
    }

    #[test]
    fn whole_arrays_decode_as_each_element_does() {
        // Pseudo-random bytes, long enough for several parallel tasks, in
        // every type and both byte orders, against the per-element decoders.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let bytes: Vec<u8> = (0..3 * DECODE_CHUNK * 8)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                state as u8
            })
            .collect();
        let types = [
            Scalar::I8,
            Scalar::U8,
            Scalar::I16,
            Scalar::U16,
            Scalar::I32,
            Scalar::U32,
            Scalar::I64,
            Scalar::U64,
            Scalar::F32,
            Scalar::F64,
        ];
        for ty in types {
            for big in [false, true] {
                let floats = decode_f64(ty, &bytes, big);
                let ints = decode_i64(ty, &bytes, big);
                let elements = bytes.chunks_exact(ty.size());
                assert_eq!(floats.len(), elements.len());
                for (i, b) in elements.clone().enumerate() {
                    let f = element_f64(ty, b, big);
                    assert!(
                        floats[i] == f || (f.is_nan() && floats[i].is_nan()),
                        "{ty:?} {i}"
                    );
                }
                for (i, b) in elements.enumerate() {
                    match element_i64(ty, b, big) {
                        Some(v) => assert_eq!(ints.as_ref().map(|a| a[i]), Ok(v), "{ty:?} {i}"),
                        // The first element that does not fit is the error.
                        None => {
                            assert_eq!(ints, Err(i), "{ty:?}");
                            break;
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn parses_tokens_with_range_checks() {
        assert_eq!(parse_i64(Scalar::U8, "255"), Some(255));
        assert_eq!(parse_i64(Scalar::U8, "256"), None);
        assert_eq!(parse_i64(Scalar::I32, "-5"), Some(-5));
        assert_eq!(parse_i64(Scalar::I32, "1.0"), None);
        assert_eq!(parse_f64(Scalar::F32, "0.1"), Some(0.1f32 as f64));
        assert!(parse_f64(Scalar::F64, "nan").is_some_and(f64::is_nan));
    }
}
