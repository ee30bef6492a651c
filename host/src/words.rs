//! Per-particle values as `f64` words for MPI messages (bit-exact: every value is stored
//! as an `f64` and read back unchanged; small integers are exact in an `f64`).

use gsph_core::math::{Matrix, Real, Sym3, Vector};
use gsph_core::schemes::AvRates;
use gsph_core::state::{Correction, Gradients, Hourglass, PairSums};
use nalgebra::SMatrix;

/// A value that travels as a fixed number of `f64` words.
pub trait Words: Sized {
    /// Number of words.
    fn words() -> usize;
    /// Appends the words.
    fn put_words(&self, out: &mut Vec<f64>);
    /// Reads the value from the first [`Words::words`] words of `src`.
    fn from_words(src: &[f64]) -> Self;
}

impl Words for f64 {
    fn words() -> usize {
        1
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        out.push(*self);
    }
    fn from_words(src: &[f64]) -> Self {
        src[0]
    }
}

impl Words for u16 {
    fn words() -> usize {
        1
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        out.push(f64::from(*self));
    }
    fn from_words(src: &[f64]) -> Self {
        src[0] as u16
    }
}

impl<const R: usize, const C: usize> Words for SMatrix<f64, R, C> {
    fn words() -> usize {
        R * C
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self.as_slice());
    }
    fn from_words(src: &[f64]) -> Self {
        SMatrix::<f64, R, C>::from_column_slice(&src[..R * C])
    }
}

impl Words for Sym3 {
    fn words() -> usize {
        6
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(&[self.xx, self.yy, self.zz, self.xy, self.xz, self.yz]);
    }
    fn from_words(s: &[f64]) -> Self {
        Sym3 {
            xx: s[0],
            yy: s[1],
            zz: s[2],
            xy: s[3],
            xz: s[4],
            yz: s[5],
        }
    }
}

impl<const D: usize> Words for [Vector<D>; 6] {
    fn words() -> usize {
        6 * D
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        for v in self {
            v.put_words(out);
        }
    }
    fn from_words(s: &[f64]) -> Self {
        core::array::from_fn(|k| Vector::<D>::from_words(&s[k * D..]))
    }
}

impl Words for u8 {
    fn words() -> usize {
        1
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        out.push(*self as f64);
    }
    fn from_words(s: &[f64]) -> Self {
        s[0] as u8
    }
}

/// The words of each scratch record the halo carries, field by field in the core's
/// table ([`gsph_core::scratch_records!`]).
macro_rules! scratch_words {
    (() $($rec:ident $rdoc:literal { $($f:ident: $ty:ty = $default:expr, $kind:ident, $doc:literal;)* })*) => {
        $(
            impl<const D: usize> Words for $rec<D> {
                fn words() -> usize {
                    0 $(+ <$ty as Words>::words())*
                }
                fn put_words(&self, out: &mut Vec<f64>) {
                    $( self.$f.put_words(out); )*
                }
                fn from_words(s: &[f64]) -> Self {
                    let mut at = 0;
                    $(
                        let $f = <$ty as Words>::from_words(&s[at..]);
                        at += <$ty as Words>::words();
                    )*
                    let _ = at;
                    $rec { $($f,)* }
                }
            }
        )*
    };
}
gsph_core::scratch_records!(scratch_words {});

impl<const D: usize> Words for AvRates<D> {
    fn words() -> usize {
        4 * D + 17
    }
    fn put_words(&self, out: &mut Vec<f64>) {
        self.acc.put_words(out);
        out.extend_from_slice(&[self.de, self.drho]);
        self.ds.put_words(out);
        out.push(self.rate);
        self.v_half.put_words(out);
        out.extend_from_slice(&[self.e_half, self.rho_half]);
        self.s_half.put_words(out);
        self.dhg.put_words(out);
        self.hg_half.put_words(out);
    }
    fn from_words(s: &[f64]) -> Self {
        let mut at = 0;
        let mut next = |w: usize| {
            let r = &s[at..at + w];
            at += w;
            r
        };
        let acc = Vector::<D>::from_words(next(D));
        let de = next(1)[0];
        let drho = next(1)[0];
        let ds = Sym3::from_words(next(6));
        let rate = next(1)[0];
        let v_half = Vector::<D>::from_words(next(D));
        let e_half = next(1)[0];
        let rho_half = next(1)[0];
        let s_half = Sym3::from_words(next(6));
        let dhg = Vector::<D>::from_words(next(D));
        let hg_half = Vector::<D>::from_words(next(D));
        AvRates {
            acc,
            de,
            drho,
            ds,
            rate,
            v_half,
            e_half,
            rho_half,
            s_half,
            dhg,
            hg_half,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip<T: Words + PartialEq + core::fmt::Debug>(v: T) {
        let mut out = Vec::new();
        v.put_words(&mut out);
        assert_eq!(out.len(), T::words());
        assert_eq!(T::from_words(&out), v);
    }

    #[test]
    fn every_record_round_trips_bit_exactly() {
        round_trip(std::f64::consts::PI);
        round_trip(Vector::<3>::new(1.0, -2.5, 1e-300));
        round_trip(SMatrix::<f64, 2, 2>::new(1.0, 2.0, 3.0, 4.0));
        round_trip(Sym3 {
            xx: 1.0,
            yy: 2.0,
            zz: 3.0,
            xy: 4.0,
            xz: 5.0,
            yz: 6.0,
        });
        let mut g = Gradients::<2>::default();
        g.v[(0, 1)] = 7.0;
        g.ct[1] = -1.0;
        g.w[(1, 0)] = -0.5;
        g.sv[0] = 3.5;
        round_trip(g);
        round_trip(Correction::<3> {
            boundary: 2,
            lambda_min: 0.25,
            ..Default::default()
        });
        round_trip([Vector::<2>::new(1.0, 2.0); 6]);
        let mut a = AvRates::<2> {
            acc: Vector::<2>::new(1.0, 2.0),
            de: 3.0,
            drho: 4.0,
            ds: Sym3::ZERO,
            rate: 5.0,
            v_half: Vector::<2>::new(6.0, 7.0),
            e_half: 8.0,
            rho_half: 9.0,
            s_half: Sym3::ZERO,
            dhg: Vector::<2>::new(11.0, 12.0),
            hg_half: Vector::<2>::new(13.0, 14.0),
        };
        a.s_half.xy = 10.0;
        round_trip(a);
    }
}
