//! A scene's particles before the run ([`InitialParticles`]) and the state columns a
//! particle file may give ([`STATE_COLUMNS`]), both generated from the rows of the core's
//! particle table ([`gsph_core::particle_fields!`]) that carry `init(…)`: a field added
//! there with `init` is carried from the scene to the run and read from particle files
//! without an edit here.

use gsph_core::math::{Real, Sym3, Vector};

/// Initial particles are not yet of a dimension: their vectors have three components
/// (the unused ones 0). The table's `Vector<D>` is read with this `D`.
const D: usize = 3;

/// The element type a field of the particle table has in [`InitialParticles`].
pub trait InitialType {
    /// The element type (`[f64; 3]` for a vector).
    type T: Copy + std::fmt::Debug;
}

impl InitialType for Vector<D> {
    type T = [f64; 3];
}

impl InitialType for Real {
    type T = f64;
}

impl InitialType for Sym3 {
    type T = Sym3;
}

impl InitialType for u16 {
    type T = u16;
}

/// The rows of the particle table with `init(…)`, passed on to [`define_initial`].
macro_rules! initial_rows {
    (() $($rows:tt)*) => {
        initial_rows! { @acc [] $($rows)* }
    };
    (@acc [$($acc:tt)*]) => {
        define_initial! { $($acc)* }
    };
    (@acc [$($acc:tt)*] $name:ident: $ty:ty, $kind:ident, $when:ident, $access:ident, $unit:literal, $doc:literal, {
        api $api:tt
        out[$($col:ident $cdoc:literal),*]
        init($how:ident $($default:literal)?)
    }; $($rest:tt)*) => {
        initial_rows! { @acc [$($acc)* $name: $ty, $doc, $how [$($default)?] [$($col)*];] $($rest)* }
    };
    (@acc [$($acc:tt)*] $name:ident: $ty:ty, $kind:ident, $when:ident, $access:ident, $unit:literal, $doc:literal, {
        api $api:tt
        out $out:tt
    }; $($rest:tt)*) => {
        initial_rows! { @acc [$($acc)*] $($rest)* }
    };
}

/// The doc of an initial field: the table's, and what an empty array means.
macro_rules! initial_doc {
    ($doc:literal, required []) => {
        concat!($doc, ".")
    };
    ($doc:literal, optional [$default:literal]) => {
        concat!($doc, "; or empty: ", $default, " for every particle.")
    };
}

/// Appends particle `i`'s value of a field: always (`required`), or where `src` has the
/// field (`optional`: one per particle or none).
macro_rules! push_initial {
    (required, $to:expr, $from:expr, $i:expr) => {
        $to.push($from[$i])
    };
    (optional, $to:expr, $from:expr, $i:expr) => {
        if let Some(&v) = $from.get($i) {
            $to.push(v);
        }
    };
}

/// [`InitialParticles`] and [`STATE_COLUMNS`] from the rows [`initial_rows`] passes.
macro_rules! define_initial {
    ($($name:ident: $ty:ty, $doc:literal, $how:ident [$($default:literal)?] [$($col:ident)*];)*) => {
        /// Particles of a scene before the run (vectors padded to 3 components): a field
        /// per row of the particle table with `init(…)`, then where each particle comes
        /// from.
        #[derive(Debug, Clone, Default)]
        pub struct InitialParticles {
            /// Dimension.
            pub dim: usize,
            $(
                #[doc = initial_doc!($doc, $how [$($default)?])]
                pub $name: Vec<<$ty as InitialType>::T>,
            )*
            /// Body index.
            pub body: Vec<u16>,
            /// Lattice spacing of the particle's body, m.
            pub spacing: Vec<f64>,
            /// Porosity of each body as built, m = V_lattice / V_particles (1 without
            /// pores): the volume of the whole lattice over that of the particles kept
            /// outside the pores.
            pub porosity: Vec<f64>,
            /// What the relaxation of each `relaxed` body did, a line each (for the run
            /// log).
            pub layout: Vec<String>,
        }

        impl InitialParticles {
            /// Appends particle `i` of `src`.
            pub fn push_from(&mut self, src: &InitialParticles, i: usize) {
                $( push_initial!($how, self.$name, src.$name, i); )*
                self.body.push(src.body[i]);
                self.spacing.push(src.spacing[i]);
            }
        }

        /// The state columns a particle file may give (the `out` columns of the fields
        /// initial particles carry), in `final.csv` order.
        pub const STATE_COLUMNS: &[&str] = &[$($(stringify!($col),)*)*];
    };
}

gsph_core::particle_fields!(initial_rows {});

impl InitialParticles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.x.len()
    }
    /// True if empty.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// An empty set with the dimension and body porosities of `self`.
    pub fn empty_like(&self) -> Self {
        InitialParticles {
            dim: self.dim,
            porosity: self.porosity.clone(),
            ..Default::default()
        }
    }
}

/// The index of column `name` in [`STATE_COLUMNS`] (a build error if there is none).
pub const fn state_column(name: &str) -> usize {
    let mut c = 0;
    while c < STATE_COLUMNS.len() {
        let (a, b) = (STATE_COLUMNS[c].as_bytes(), name.as_bytes());
        if a.len() == b.len() {
            let mut k = 0;
            while k < a.len() && a[k] == b[k] {
                k += 1;
            }
            if k == a.len() {
                return c;
            }
        }
        c += 1;
    }
    panic!("not a state column")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_initial_fields_and_columns_are_the_tables() {
        let parts = InitialParticles::default();
        // every field a particle file sets, and only those
        assert_eq!(
            STATE_COLUMNS,
            [
                "x",
                "y",
                "z",
                "vx",
                "vy",
                "vz",
                "m",
                "rho",
                "e",
                "sxx",
                "syy",
                "szz",
                "sxy",
                "sxz",
                "syz",
                "eps_p",
                "damage",
                "temperature",
                "x0",
                "y0",
                "z0"
            ]
        );
        assert_eq!(state_column("x0"), 18);
        assert!(parts.temp.is_empty() && parts.mat.is_empty());
    }
}
