//! The host's side of the core's particle table ([`gsph_core::particle_fields!`]): the
//! macros that expand one loop over every per-particle field, the [`Sim`](super::Sim)
//! struct's state arrays, and [`Particle`], one particle's whole state.
//!
//! Declared before the other modules of `sim`, so its macros are in scope in them.

use gsph_core::math::{Real, Sym3, Vector};

/// `$f(&mut $sim.FIELD, $arg);` for each per-particle state field of the core's table
/// ([`gsph_core::particle_fields!`]), in table order: use as
/// `gsph_core::particle_fields!(each_state_field { self, f, arg })` (in the modules of
/// `sim`). The other arms pass the field differently (see each).
macro_rules! each_state_field {
    (($s:expr, $f:expr, $arg:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $( $f(&mut $s.$name, $arg); )*
    };
    // read only: `$f(&$sim.FIELD, $arg)`
    ((ref $s:expr, $f:expr, $arg:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $( $f(&$s.$name, $arg); )*
    };
    // with the field's name and `?`: `$f(stringify!(FIELD), &mut $sim.FIELD, $arg)?`
    ((named $s:expr, $f:expr, $arg:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $( $f(stringify!($name), &mut $s.$name, $arg)?; )*
    };
    // the first value outside the range the table gives the field (its `api` range,
    // where the particle's material calls for the field's effect: [`Sim::outside`]),
    // with the field's name: `$f(stringify!(FIELD), $sim.outside(&$sim.FIELD, range, effect))?`
    ((ranged $s:expr, $f:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, {
        api($api:literal [$($alias:ident),*], $w:ident, $range:ident)
        out[$($col:ident $cdoc:literal),*]
        $(init $init:tt)?
    };)*) => {
        $( $f(
            stringify!($name),
            $s.outside(
                &$s.$name,
                $crate::sim::values::range_of!($range),
                gsph_core::effects::EffectSet::$when,
            ),
        )?; )*
    };
    // with whether the run stores the field: `$f(&$sim.FIELD, stored, $arg)`
    ((stored $s:expr, $f:expr, $arg:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $( $f(&$s.$name, $s.effects.contains(gsph_core::effects::EffectSet::$when), $arg); )*
    };
    // the same, mutable: `$f(&mut $sim.FIELD, stored, $arg)`
    ((stored_mut $s:expr, $f:expr, $arg:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $( $f(&mut $s.$name, $s.effects.contains(gsph_core::effects::EffectSet::$when), $arg); )*
    };
    // by the field's kind: `$module::KIND(&mut $sim.FIELD, $arg)` (`point`, `vector` …)
    ((kind $s:expr, $module:ident, $arg:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $( $module::$kind(&mut $s.$name, $arg); )*
    };
    // the core's `System` over the arrays (use with `particle_fields!(step …)`): an
    // expression, so the borrows stay per field
    ((system $s:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        gsph_core::state::System { $( $name: borrow_field!($acc, $s.$name), )* }
    };
    // a `Sim` literal with every state array empty and the other fields as given
    ((literal $S:ident { $($init:tt)* }) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $S { $( $name: Vec::new(), )* $($init)* }
    };
}

/// `&mut v` for a field a step writes, `&v` for one it reads.
macro_rules! borrow_field {
    (mut, $v:expr) => {
        &mut $v
    };
    (ref, $v:expr) => {
        &$v
    };
}

/// The `Sim` struct: one `Vec` per field of the core's table, then the fields given.
macro_rules! define_sim {
    (($(#[$m:meta])* pub struct $S:ident { $($extra:tt)* }) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        $(#[$m])*
        pub struct $S<const D: usize> {
            $(
                #[doc = $doc]
                pub $name: Vec<$ty>,
            )*
            $($extra)*
        }
    };
}

/// [`Particle`] and the loops that read, write and append one.
macro_rules! define_particle {
    (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        /// One particle's whole state, a value per field of the core's table
        /// ([`gsph_core::particle_fields!`]; a field the run does not store holds zero).
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct Particle<const D: usize> {
            $(
                #[doc = $doc]
                pub $name: $ty,
            )*
        }

        impl<const D: usize> super::Sim<D> {
            /// The state of particle `i` (zero where the run does not store a field).
            pub fn particle(&self, i: usize) -> Particle<D> {
                Particle { $( $name: self.$name.get(i).copied().unwrap_or_else(Blank::blank), )* }
            }

            /// Overwrites the stored fields of particle `i` with `p`.
            pub fn set_particle(&mut self, i: usize, p: &Particle<D>) {
                $( if let Some(slot) = self.$name.get_mut(i) { *slot = p.$name; } )*
            }

            /// Appends `p`'s stored fields (the fields the run stores).
            pub(super) fn push_particle(&mut self, p: &Particle<D>) {
                $(
                    if self.effects.contains(gsph_core::effects::EffectSet::$when) {
                        self.$name.push(p.$name);
                    }
                )*
            }
        }
    };
}

gsph_core::particle_fields!(define_particle {});

/// The zero of a field's element type (what [`Particle`] holds for a field not stored).
pub trait Blank {
    /// Zero.
    fn blank() -> Self;
}

impl Blank for Real {
    fn blank() -> Self {
        0.0
    }
}

impl Blank for u16 {
    fn blank() -> Self {
        0
    }
}

impl Blank for Sym3 {
    fn blank() -> Self {
        Sym3::ZERO
    }
}

impl<const D: usize> Blank for Vector<D> {
    fn blank() -> Self {
        Vector::<D>::zeros()
    }
}

/// A field's value as output columns: a point or vector three (0 past the dimension), a
/// tensor six (`xx yy zz xy xz yz`), a scalar one.
pub trait Columns {
    /// Writes the columns to `out[*k..]` and advances `k` past them.
    fn put_columns(&self, out: &mut [f64], k: &mut usize);
}

impl Columns for Real {
    fn put_columns(&self, out: &mut [f64], k: &mut usize) {
        out[*k] = *self;
        *k += 1;
    }
}

impl Columns for u16 {
    fn put_columns(&self, out: &mut [f64], k: &mut usize) {
        out[*k] = f64::from(*self);
        *k += 1;
    }
}

impl Columns for Sym3 {
    fn put_columns(&self, out: &mut [f64], k: &mut usize) {
        out[*k..*k + 6].copy_from_slice(&self.to_array());
        *k += 6;
    }
}

impl<const D: usize> Columns for Vector<D> {
    fn put_columns(&self, out: &mut [f64], k: &mut usize) {
        for a in 0..3 {
            out[*k + a] = if a < D { self[a] } else { 0.0 };
        }
        *k += 3;
    }
}

/// The particle-table row of a particle: the `out[…]` columns of the core's table, state
/// fields then derived quantities ([`super::derived`]).
macro_rules! define_row {
    (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, {
        api($api:literal [$($alias:ident),*], $w:ident, $range:ident)
        out[$($col:ident $cdoc:literal),*]
        $(init $init:tt)?
    };)*) => {
        impl<const D: usize> super::Sim<D> {
            /// Writes the output columns of the state of particle `i` to `out[*k..]` (zero
            /// where the run does not store a field).
            pub(super) fn state_columns(&self, i: usize, out: &mut [f64], k: &mut usize) {
                $(
                    if !<[&str]>::is_empty(&[$(stringify!($col)),*]) {
                        let v: $ty = self.$name.get(i).copied().unwrap_or_else(Blank::blank);
                        v.put_columns(out, k);
                    }
                )*
            }
        }
    };
}

gsph_core::particle_fields!(define_row {});

/// The derived quantities' columns, each over all particles (memory order), in the order of
/// the core's [`gsph_core::derived_fields!`].
macro_rules! define_derived {
    (() $($name:ident: $unit:literal, $doc:literal, $io:tt;)*) => {
        impl<const D: usize> super::Sim<D> {
            /// Each derived quantity over the particles (memory order), in table order.
            pub(super) fn derived_columns(&self) -> Vec<Vec<f64>> {
                vec![$(super::derived::$name(self)),*]
            }

            /// The derived quantity `name` over the particles (memory order), or `None`
            /// for a name the table lacks.
            pub fn derived(&self, name: &str) -> Option<Vec<f64>> {
                match name {
                    $(stringify!($name) => Some(super::derived::$name(self)),)*
                    _ => None,
                }
            }
        }
    };
}

gsph_core::derived_fields!(define_derived {});
