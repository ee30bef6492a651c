//! The particle table: the state of all particles at one time, stored as columns.
//!
//! The column order is fixed ([`COLUMNS`]); it is the start of the header of `final.csv` (the
//! derived columns [`DERIVED_COLUMNS`](super::meta::DERIVED_COLUMNS) follow) and the set of
//! datasets in each snapshot group of `snapshots.h5`. Components that a dimension lacks are stored
//! as 0. Units and meanings: [`QUANTITIES`](super::meta::QUANTITIES).

/// Defines [`ParticleRow`], [`ParticleTable`] and the float-column list from one list of fields, so
/// the three can never disagree.
macro_rules! particle_types {
    ($($(#[doc = $doc:literal])+ $f:ident),+ $(,)?) => {
        /// One particle's state: one row of [`ParticleTable`] (and of `final.csv`).
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct ParticleRow {
            /// Particle id (stable over the run).
            pub id: u32,
            /// Material index (position in the scene's material list).
            pub material: u32,
            $($(#[doc = $doc])+ pub $f: f64,)+
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
            $($(#[doc = $doc])+ pub $f: Vec<f64>,)+
        }

        /// Names of the float columns, in [`COLUMNS`] order (everything after `id` and `material`).
        pub const FLOAT_COLUMNS: [&str; NUM_FLOAT_COLUMNS] = [$(stringify!($f)),+];

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

/// Number of float columns (all columns but `id` and `material`).
pub const NUM_FLOAT_COLUMNS: usize = 20;

/// All column names in order; `final.csv`'s header is these, then the derived columns.
pub const COLUMNS: [&str; 22] = [
    "id",
    "material",
    "x",
    "y",
    "z",
    "vx",
    "vy",
    "vz",
    "m",
    "rho",
    "p",
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
    "h",
];

particle_types! {
    /// Position x (m).
    x,
    /// Position y (m); 0 in 1D.
    y,
    /// Position z (m); 0 in 1D and 2D.
    z,
    /// Velocity x (m/s).
    vx,
    /// Velocity y (m/s); 0 in 1D.
    vy,
    /// Velocity z (m/s); 0 in 1D and 2D.
    vz,
    /// Mass (kg; per unit area in 1D, per unit length in 2D).
    m,
    /// Density (kg/m3).
    rho,
    /// Pressure (Pa), positive in compression.
    p,
    /// Specific internal energy (J/kg).
    e,
    /// Deviatoric stress S_xx (Pa).
    sxx,
    /// Deviatoric stress S_yy (Pa).
    syy,
    /// Deviatoric stress S_zz (Pa).
    szz,
    /// Deviatoric stress S_xy (Pa).
    sxy,
    /// Deviatoric stress S_xz (Pa).
    sxz,
    /// Deviatoric stress S_yz (Pa).
    syz,
    /// Equivalent plastic strain.
    eps_p,
    /// Damage in [0, 1].
    damage,
    /// Temperature (K).
    temperature,
    /// Smoothing length (m).
    h,
}

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
        assert_eq!(&COLUMNS[2..], &FLOAT_COLUMNS[..]);
        assert_eq!(
            COLUMNS.join(","),
            "id,material,x,y,z,vx,vy,vz,m,rho,p,e,sxx,syy,szz,sxy,sxz,syz,eps_p,damage,temperature,h"
        );
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
