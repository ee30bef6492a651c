//! The particle table: the state of all particles at one time, stored as columns.
//!
//! The columns are the `out[…]` columns of the core's particle table
//! ([`gsph_core::particle_fields!`], then [`gsph_core::derived_fields!`]), in table order
//! ([`COLUMNS`]); they are the start of the header of `final.csv` (the stress columns
//! [`DERIVED_COLUMNS`](super::meta::DERIVED_COLUMNS) follow) and the set of datasets in each
//! snapshot group of `snapshots.h5`. Components that a dimension lacks are stored as 0. Units
//! and meanings: [`FLOAT_QUANTITIES`], [`quantities`](super::meta::quantities).

/// The output columns of the state fields (`out[…]` of the core's
/// [`gsph_core::particle_fields!`]), each with its field's unit; passes them on to
/// [`derived_columns`], which adds those of [`gsph_core::derived_fields!`].
macro_rules! state_columns {
    (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, {
        api($api:literal [$($alias:ident),*], $w:ident, $range:ident)
        out[$($col:ident $cdoc:literal),*]
        $(init $init:tt)?
    };)*) => {
        gsph_core::derived_fields!(derived_columns { $($( $col $unit $cdoc, )*)* });
    };
}

/// See [`state_columns`].
macro_rules! derived_columns {
    (($($col:ident $unit:literal $cdoc:literal,)*) $($name:ident: $dunit:literal, $doc:literal, {
        api($api:literal [$($alias:ident),*], $w:ident, $range:ident)
        out[$($dcol:ident $dcdoc:literal),*]
        $(init $init:tt)?
    };)*) => {
        particle_types! { $($col $unit $cdoc,)* $($($dcol $dunit $dcdoc,)*)* }

        /// The float columns computed from the state for output (the core's
        /// `derived_fields!`): not state, and NaN where undefined (`det_f` of a particle
        /// without neighbours).
        pub const DERIVED_FLOAT_COLUMNS: &[&str] = &[$($(stringify!($dcol)),*),*];
    };
}

/// Defines [`ParticleRow`], [`ParticleTable`], the column lists and their units and meanings
/// from the list of float columns, so they can never disagree.
macro_rules! particle_types {
    ($($f:ident $unit:literal $doc:literal,)+) => {
        /// One particle's state: one row of [`ParticleTable`] (and of `final.csv`).
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct ParticleRow {
            /// Particle id (stable over the run).
            pub id: u32,
            /// Material index (position in the scene's material list).
            pub material: u32,
            $(#[doc = concat!($doc, " (", $unit, ")")] pub $f: f64,)+
        }

        /// The state of all particles at one time, as columns (structure of arrays).
        ///
        /// All columns have the same length; use [`ParticleTable::push`] to keep them so.
        #[derive(Debug, Clone, PartialEq, Default)]
        pub struct ParticleTable {
            /// Particle ids.
            pub id: Vec<u32>,
            /// Material indices.
            pub material: Vec<u32>,
            $(#[doc = concat!($doc, " (", $unit, ")")] pub $f: Vec<f64>,)+
        }

        /// Names of the float columns, in [`COLUMNS`] order (everything after `id` and `material`).
        pub const FLOAT_COLUMNS: &[&str] = &[$(stringify!($f)),+];

        /// All column names in order; `final.csv`'s header is these, then the derived columns.
        pub const COLUMNS: &[&str] = &["id", "material", $(stringify!($f)),+];

        /// Unit and meaning of each float column, in [`FLOAT_COLUMNS`] order.
        pub const FLOAT_QUANTITIES: &[Quantity] = &[$(Quantity {
            name: stringify!($f),
            unit: $unit,
            description: $doc,
        }),+];

        impl ParticleRow {
            /// The float fields in [`FLOAT_COLUMNS`] order.
            pub fn floats(&self) -> [f64; NUM_FLOAT_COLUMNS] {
                [$(self.$f),+]
            }

            /// Builds a row from its id, material and float fields in [`FLOAT_COLUMNS`] order.
            pub fn from_parts(id: u32, material: u32, floats: [f64; NUM_FLOAT_COLUMNS]) -> Self {
                let [$($f),+] = floats;
                Self { id, material, $($f),+ }
            }
        }

        impl ParticleTable {
            /// The float columns in [`FLOAT_COLUMNS`] order.
            pub fn float_columns(&self) -> [&Vec<f64>; NUM_FLOAT_COLUMNS] {
                [$(&self.$f),+]
            }

            /// The float columns in [`FLOAT_COLUMNS`] order, mutably.
            pub fn float_columns_mut(&mut self) -> [&mut Vec<f64>; NUM_FLOAT_COLUMNS] {
                [$(&mut self.$f),+]
            }
        }
    };
}

use super::quantity::Quantity;

/// Columns every `final.csv` and snapshot has held (`id` .. `h`): later ones were appended,
/// and a file written before them reads them as NaN.
pub const BASE_COLUMNS: usize = 22;

/// Number of float columns (all columns but `id` and `material`).
pub const NUM_FLOAT_COLUMNS: usize = FLOAT_COLUMNS.len();

gsph_core::particle_fields!(state_columns {});

impl ParticleTable {
    /// An empty table with room for `n` particles in every column.
    pub fn with_capacity(n: usize) -> Self {
        let mut t = Self {
            id: Vec::with_capacity(n),
            material: Vec::with_capacity(n),
            ..Self::default()
        };
        for c in t.float_columns_mut() {
            c.reserve_exact(n);
        }
        t
    }

    /// Appends one particle.
    pub fn push(&mut self, row: &ParticleRow) {
        self.id.push(row.id);
        self.material.push(row.material);
        for (c, v) in self.float_columns_mut().into_iter().zip(row.floats()) {
            c.push(v);
        }
    }

    /// Number of particles.
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// True when the table holds no particle.
    pub fn is_empty(&self) -> bool {
        self.id.is_empty()
    }

    /// Particle `i` as a row, or `None` past the end.
    pub fn row(&self, i: usize) -> Option<ParticleRow> {
        let id = *self.id.get(i)?;
        let material = self.material[i];
        let floats = self.float_columns().map(|c| c[i]);
        Some(ParticleRow::from_parts(id, material, floats))
    }

    /// Iterates over the rows.
    pub fn rows(&self) -> impl Iterator<Item = ParticleRow> + '_ {
        (0..self.len()).filter_map(|i| self.row(i))
    }

    /// A float column borrowed by name (`x` .. `h`); `None` for `id`, `material` or an unknown
    /// name.
    pub fn float_column(&self, name: &str) -> Option<&[f64]> {
        let k = FLOAT_COLUMNS.iter().position(|c| *c == name)?;
        Some(self.float_columns()[k].as_slice())
    }

    /// Any column by name as f64 (ids and materials converted); `None` for an unknown name.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        match name {
            "id" => Some(self.id.iter().map(|&v| f64::from(v)).collect()),
            "material" => Some(self.material.iter().map(|&v| f64::from(v)).collect()),
            _ => self.float_column(name).map(<[f64]>::to_vec),
        }
    }
}

/// The state of all particles at one output time.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    /// Simulation time (s).
    pub time: f64,
    /// Step number.
    pub step: u64,
    /// Spatial dimension of the run (1, 2 or 3).
    pub dim: usize,
    /// The particles.
    pub table: ParticleTable,
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A table of `n` particles whose every value depends on the particle and column.
    pub(crate) fn sample_table(n: usize, seed: f64) -> ParticleTable {
        let mut t = ParticleTable::with_capacity(n);
        for i in 0..n {
            let mut floats = [0.0; NUM_FLOAT_COLUMNS];
            for (k, v) in floats.iter_mut().enumerate() {
                *v = (seed + i as f64 * 0.1 + k as f64) / 3.0 * 10f64.powi(k as i32 - 10);
            }
            floats[1] = -floats[1];
            t.push(&ParticleRow::from_parts(
                i as u32 * 7,
                (i % 3) as u32,
                floats,
            ));
        }
        t
    }

    #[test]
    fn column_order_matches_header() {
        assert_eq!(COLUMNS[0], "id");
        assert_eq!(COLUMNS[1], "material");
        assert_eq!(&COLUMNS[2..], FLOAT_COLUMNS);
        // the snapshots store the first six as the datasets `position` and `velocity`
        assert_eq!(&FLOAT_COLUMNS[..6], ["x", "y", "z", "vx", "vy", "vz"]);
        // new columns are only ever appended (readers of older files rely on it)
        assert!(COLUMNS.join(",").starts_with(
            "id,material,x,y,z,vx,vy,vz,m,rho,p,e,sxx,syy,szz,sxy,sxz,syz,eps_p,damage,temperature,h"
        ));
    }

    #[test]
    fn push_row_and_columns() {
        let t = sample_table(4, 1.0);
        assert_eq!(t.len(), 4);
        assert!(!t.is_empty());
        let r = t.row(2).unwrap();
        assert_eq!(r.id, 14);
        assert_eq!(r.x, t.x[2]);
        assert_eq!(r.h, t.h[2]);
        assert_eq!(t.column("material").unwrap(), vec![0.0, 1.0, 2.0, 0.0]);
        assert_eq!(t.column("rho").unwrap(), t.rho);
        assert_eq!(t.float_column("damage").unwrap(), &t.damage[..]);
        assert!(t.column("nope").is_none());
        assert!(t.float_column("id").is_none());
        assert!(t.row(4).is_none());
        assert_eq!(t.rows().count(), 4);
    }
}
