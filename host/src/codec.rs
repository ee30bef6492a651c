//! The little-endian encoding of checkpoints: fixed-width integers and floats (floats as
//! their IEEE bit patterns, so every value, NaN payloads included, round-trips exactly),
//! length-prefixed strings and arrays, and the FNV-1a checksum of the payload.

use gsph_core::math::{Matrix, Real, Sym3, Vector};
use gsph_core::schemes::AvRates;
use gsph_core::state::{Correction, Gradients, Hourglass, PairSums};
use nalgebra::SMatrix;

/// 64-bit FNV-1a of `bytes`. Any change of a single byte changes the hash (each step of
/// the hash is a bijection of the state for a fixed input byte).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// An encoder appending to a byte buffer.
#[derive(Debug, Default)]
pub struct Enc {
    /// The bytes so far.
    pub buf: Vec<u8>,
}

impl Enc {
    /// Appends `v`.
    pub fn put<T: Codec>(&mut self, v: &T) {
        v.put(self);
    }
    fn raw(&mut self, b: &[u8]) {
        self.buf.extend_from_slice(b);
    }
}

/// A decoder reading from a byte slice; every read checks the bytes left.
#[derive(Debug)]
pub struct Dec<'a> {
    bytes: &'a [u8],
    pos: usize,
}

/// Why decoding failed: the payload ended early or held an impossible value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DecodeError(pub String);

impl<'a> Dec<'a> {
    /// A decoder over `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Dec { bytes, pos: 0 }
    }
    /// Bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }
    /// Reads a `T`.
    pub fn get<T: Codec>(&mut self) -> Result<T, DecodeError> {
        T::get(self)
    }
    fn take<const N: usize>(&mut self) -> Result<[u8; N], DecodeError> {
        let end = self.pos.checked_add(N).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| DecodeError("payload ends early".into()))?;
        let mut out = [0u8; N];
        out.copy_from_slice(&self.bytes[self.pos..end]);
        self.pos = end;
        Ok(out)
    }
    fn len_prefix(&mut self, min_size: usize) -> Result<usize, DecodeError> {
        let n = u64::get(self)?;
        // a length that cannot fit in what is left is refused before anything is allocated
        match usize::try_from(n) {
            Ok(n) if n.saturating_mul(min_size.max(1)) <= self.remaining() => Ok(n),
            _ => Err(DecodeError(format!(
                "length {n} exceeds the {} bytes left",
                self.remaining()
            ))),
        }
    }
}

/// A value with a fixed little-endian encoding.
pub trait Codec: Sized {
    /// Smallest encoded size, bytes (bounds array lengths read from a file).
    const MIN_SIZE: usize;
    /// Appends the encoding of `self`.
    fn put(&self, e: &mut Enc);
    /// Reads a value.
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError>;
}

macro_rules! int_codec {
    ($($t:ty),*) => {$(
        impl Codec for $t {
            const MIN_SIZE: usize = std::mem::size_of::<$t>();
            fn put(&self, e: &mut Enc) {
                e.raw(&self.to_le_bytes());
            }
            fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
                Ok(<$t>::from_le_bytes(d.take()?))
            }
        }
    )*};
}
int_codec!(u8, u16, u32, u64);

impl Codec for f64 {
    const MIN_SIZE: usize = 8;
    fn put(&self, e: &mut Enc) {
        self.to_bits().put(e);
    }
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
        Ok(f64::from_bits(u64::get(d)?))
    }
}

impl Codec for bool {
    const MIN_SIZE: usize = 1;
    fn put(&self, e: &mut Enc) {
        u8::from(*self).put(e);
    }
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
        match u8::get(d)? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(DecodeError(format!("boolean byte {b}"))),
        }
    }
}

impl Codec for String {
    const MIN_SIZE: usize = 8;
    fn put(&self, e: &mut Enc) {
        (self.len() as u64).put(e);
        e.raw(self.as_bytes());
    }
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
        let n = d.len_prefix(1)?;
        let bytes = d.bytes[d.pos..d.pos + n].to_vec();
        d.pos += n;
        String::from_utf8(bytes).map_err(|_| DecodeError("text is not UTF-8".into()))
    }
}

impl<T: Codec> Codec for Vec<T> {
    const MIN_SIZE: usize = 8;
    fn put(&self, e: &mut Enc) {
        (self.len() as u64).put(e);
        for v in self {
            v.put(e);
        }
    }
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
        let n = d.len_prefix(T::MIN_SIZE)?;
        let mut v = Vec::with_capacity(n);
        for _ in 0..n {
            v.push(T::get(d)?);
        }
        Ok(v)
    }
}

impl<T: Codec, const N: usize> Codec for [T; N] {
    const MIN_SIZE: usize = N * T::MIN_SIZE;
    fn put(&self, e: &mut Enc) {
        for v in self {
            v.put(e);
        }
    }
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
        let v: Vec<T> = (0..N).map(|_| T::get(d)).collect::<Result<_, _>>()?;
        v.try_into().map_err(|_| DecodeError("array length".into()))
    }
}

/// Vectors and matrices: their entries in column-major order.
impl<const R: usize, const C: usize> Codec for SMatrix<f64, R, C> {
    const MIN_SIZE: usize = 8 * R * C;
    fn put(&self, e: &mut Enc) {
        for v in self.as_slice() {
            v.put(e);
        }
    }
    fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
        let mut m = SMatrix::<f64, R, C>::zeros();
        for v in m.as_mut_slice() {
            *v = f64::get(d)?;
        }
        Ok(m)
    }
}

/// Structs of codec fields, encoded field by field in the order listed.
macro_rules! struct_codec {
    ($t:ident $(<$d:ident>)?, $($f:ident: $ft:ty),* $(,)?) => {
        impl$(<const $d: usize>)? Codec for $t$(<$d>)? {
            const MIN_SIZE: usize = 0 $(+ <$ft as Codec>::MIN_SIZE)*;
            fn put(&self, e: &mut Enc) {
                $(Codec::put(&self.$f, e);)*
            }
            fn get(d: &mut Dec<'_>) -> Result<Self, DecodeError> {
                Ok($t { $($f: <$ft as Codec>::get(d)?,)* })
            }
        }
    };
}

struct_codec!(Sym3, xx: f64, yy: f64, zz: f64, xy: f64, xz: f64, yz: f64);
/// The codec of each scratch record, field by field in the core's table
/// ([`gsph_core::scratch_records!`]).
macro_rules! scratch_codec {
    (() $($rec:ident $rdoc:literal { $($f:ident: $ty:ty = $default:expr, $kind:ident, $doc:literal;)* })*) => {
        $( struct_codec!($rec<D>, $($f: $ty),*); )*
    };
}
gsph_core::scratch_records!(scratch_codec {});
struct_codec!(AvRates<D>,
    acc: SMatrix<f64, D, 1>, de: f64, drho: f64, ds: Sym3, rate: f64,
    v_half: SMatrix<f64, D, 1>, e_half: f64, rho_half: f64, s_half: Sym3,
    dhg: SMatrix<f64, D, 1>, hg_half: SMatrix<f64, D, 1>);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_round_trip_bitwise() {
        let mut e = Enc::default();
        let nan = f64::from_bits(0x7ff8_0000_dead_beef);
        let v: Vec<f64> = vec![1.5, -0.0, nan, f64::INFINITY];
        e.put(&v);
        e.put(&"tkc ü".to_string());
        e.put(&true);
        let s = Sym3 {
            xx: 1.0,
            yy: 2.0,
            zz: 3.0,
            xy: 4.0,
            xz: 5.0,
            yz: 6.0,
        };
        let av = AvRates::<2> {
            ds: s,
            rate: 7.0,
            ..Default::default()
        };
        e.put(&vec![av]);
        let mut d = Dec::new(&e.buf);
        let back: Vec<f64> = d.get().unwrap();
        assert_eq!(
            back.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        assert_eq!(d.get::<String>().unwrap(), "tkc ü");
        assert!(d.get::<bool>().unwrap());
        assert_eq!(d.get::<Vec<AvRates<2>>>().unwrap(), vec![av]);
        assert_eq!(d.remaining(), 0);
        assert!(d.get::<u8>().is_err());
    }

    #[test]
    fn impossible_lengths_are_refused_without_allocating() {
        let mut e = Enc::default();
        e.put(&u64::MAX);
        assert!(Dec::new(&e.buf).get::<Vec<f64>>().is_err());
        let mut e = Enc::default();
        e.put(&3u64);
        e.put(&1.0f64);
        let err = Dec::new(&e.buf).get::<Vec<f64>>().unwrap_err();
        assert!(err.0.contains("exceeds"), "{err:?}");
    }

    #[test]
    fn fnv_detects_any_single_byte_change() {
        let data: Vec<u8> = (0..200u32).map(|i| (i * 7 % 251) as u8).collect();
        let h = fnv1a64(&data);
        for i in 0..data.len() {
            for flip in [1u8, 0x80, 0xff] {
                let mut d = data.clone();
                d[i] ^= flip;
                assert_ne!(fnv1a64(&d), h, "byte {i}");
            }
        }
    }
}
