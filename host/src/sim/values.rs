//! A per-particle field's values as plain numbers, and the range the particle table
//! ([`gsph_core::particle_fields!`], its `api(…, range)`) gives them: what the library
//! checks of a written value and a restart of every value it reads back.

use gsph_core::math::{Sym3, Vector};

/// The range of a field's values (the table's `any`, `positive`, `nonnegative`,
/// `fraction`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Range {
    /// Any finite value.
    Any,
    /// Finite and > 0.
    Positive,
    /// Finite and >= 0.
    Nonnegative,
    /// Finite and in [0, 1].
    Fraction,
}

/// The [`Range`] of a table row's range word.
macro_rules! range_of {
    (any) => {
        $crate::sim::values::Range::Any
    };
    (positive) => {
        $crate::sim::values::Range::Positive
    };
    (nonnegative) => {
        $crate::sim::values::Range::Nonnegative
    };
    (fraction) => {
        $crate::sim::values::Range::Fraction
    };
}
pub(crate) use range_of;

impl Range {
    /// Why `v` lies outside the range, or `None` when it lies inside.
    pub fn refuses(self, v: f64) -> Option<&'static str> {
        if !v.is_finite() {
            return Some("is not finite");
        }
        match self {
            Range::Any => None,
            Range::Positive => (v <= 0.0).then_some("must be positive"),
            Range::Nonnegative => (v < 0.0).then_some("must not be negative"),
            Range::Fraction => (!(0.0..=1.0).contains(&v)).then_some("must lie in [0, 1]"),
        }
    }
}

/// A field's element as plain values (its components: one, `D` or six).
pub trait Values {
    /// Writes the components into `out` (as many as the element has).
    fn get(&self, out: &mut [f64]);
    /// Sets the element from its components.
    fn set(&mut self, x: &[f64]);
    /// The number of components.
    fn components(&self) -> usize;
}

impl Values for f64 {
    fn get(&self, out: &mut [f64]) {
        out[0] = *self;
    }
    fn set(&mut self, x: &[f64]) {
        *self = x[0];
    }
    fn components(&self) -> usize {
        1
    }
}

impl Values for u16 {
    fn get(&self, out: &mut [f64]) {
        out[0] = f64::from(*self);
    }
    fn set(&mut self, _: &[f64]) {
        unreachable!("read-only")
    }
    fn components(&self) -> usize {
        1
    }
}

impl Values for Sym3 {
    fn get(&self, out: &mut [f64]) {
        out.copy_from_slice(&self.to_array());
    }
    fn set(&mut self, x: &[f64]) {
        *self = Sym3::from_array([x[0], x[1], x[2], x[3], x[4], x[5]]);
    }
    fn components(&self) -> usize {
        6
    }
}

impl<const D: usize> Values for Vector<D> {
    fn get(&self, out: &mut [f64]) {
        out.copy_from_slice(self.as_slice());
    }
    fn set(&mut self, x: &[f64]) {
        *self = Vector::<D>::from_column_slice(x);
    }
    fn components(&self) -> usize {
        D
    }
}

/// The first element of `v` with a component outside its range (`range(i)` of element
/// `i`): its index, the component's value and why.
pub fn first_outside<T: Values>(
    v: &[T],
    range: impl Fn(usize) -> Range,
) -> Option<(usize, f64, &'static str)> {
    let mut buf = [0.0; 6];
    v.iter().enumerate().find_map(|(i, x)| {
        let c = &mut buf[..x.components()];
        x.get(c);
        let r = range(i);
        c.iter().find_map(|&y| r.refuses(y).map(|why| (i, y, why)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_refuse_what_they_should() {
        assert_eq!(Range::Any.refuses(-1e300), None);
        assert_eq!(Range::Any.refuses(f64::NAN), Some("is not finite"));
        assert!(Range::Positive.refuses(0.0).is_some());
        assert_eq!(Range::Nonnegative.refuses(0.0), None);
        assert!(Range::Fraction.refuses(1.5).is_some());
        let v = [Vector::<2>::new(1.0, 2.0), Vector::<2>::new(3.0, f64::NAN)];
        let (i, y, why) = first_outside(&v, |_| Range::Any).unwrap();
        assert_eq!((i, why), (1, "is not finite"));
        assert!(y.is_nan());
        assert_eq!(first_outside(&[0.5, 1.0], |_| Range::Fraction), None);
        let by = |i| if i == 0 { Range::Any } else { Range::Positive };
        assert_eq!(first_outside(&[0.0, 1.0], by), None);
        assert_eq!(first_outside(&[1.0, 0.0], by).map(|b| b.0), Some(1));
    }
}
