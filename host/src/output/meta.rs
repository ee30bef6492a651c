//! What the output files say about themselves: the run they come from ([`RunInfo`]), the unit
//! and meaning of every column and dataset ([`quantities`], [`unit()`]), and the quantities
//! derived from the particle table (the Cauchy stress, the von Mises stress).
//!
//! Sign convention (the code's): the pressure `p` is positive in compression and `sxx` .. `syz`
//! are the components of the stress deviator S, so the Cauchy stress is
//! `sigma = -p I + S` (tension positive) and `sigma_xx = sxx - p`; the von Mises stress is
//! `sqrt(3/2 S:S)`. All units are SI; docs/output.md has the same table for readers.

pub use super::quantity::Quantity;
use super::table::{ParticleTable, FLOAT_QUANTITIES};

/// The gsph version written into every snapshot file (`gsph_version`).
pub const GSPH_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The run a snapshot file comes from, written as root attributes of `snapshots.h5`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RunInfo {
    /// Scene name (`name` key or file stem).
    pub name: String,
    /// The scene text as given (the TOML file), before the overrides.
    pub scene: String,
    /// The `--set KEY=VALUE` / `--unset KEY` overrides applied to it, in order.
    pub overrides: Vec<String>,
    /// Scheme (`av`, `pm`, `ts1`, `ts2`, `tkc`).
    pub scheme: String,
    /// The resolved effects (`strength`, `damage`, ...).
    pub effects: Vec<String>,
    /// Material names; the `material` column is an index into this list.
    pub materials: Vec<String>,
    /// The run's id, as in its `summary.json`, `run.log` and `checkpoint.bin`: a restart
    /// continues only the files of its own run (empty in files of layout 2 and earlier).
    pub run_id: String,
}

const fn q(name: &'static str, unit: &'static str, description: &'static str) -> Quantity {
    Quantity {
        name,
        unit,
        description,
    }
}

/// Unit and meaning of the columns and datasets that are not particle-table float columns
/// ([`FLOAT_QUANTITIES`]): `id`, `material`, the stress columns ([`DERIVED_COLUMNS`]) and the
/// snapshot-only datasets `position`, `velocity`, `stress`.
pub const OTHER_QUANTITIES: [Quantity; 12] = [
    q("id", "", "particle id, stable over the run"),
    q(
        "material",
        "",
        "material index into material_names (the scene's [[materials]] order)",
    ),
    q(
        "sigma_xx",
        "Pa",
        "Cauchy stress sigma_xx = sxx - p (tension positive)",
    ),
    q(
        "sigma_yy",
        "Pa",
        "Cauchy stress sigma_yy = syy - p (tension positive)",
    ),
    q(
        "sigma_zz",
        "Pa",
        "Cauchy stress sigma_zz = szz - p (tension positive)",
    ),
    q("sigma_xy", "Pa", "Cauchy stress sigma_xy = sxy"),
    q("sigma_xz", "Pa", "Cauchy stress sigma_xz = sxz"),
    q("sigma_yz", "Pa", "Cauchy stress sigma_yz = syz"),
    q("von_mises", "Pa", "von Mises stress sqrt(3/2 S:S)"),
    q("position", "m", "positions (x, y, z), N x 3"),
    q("velocity", "m/s", "velocities (vx, vy, vz), N x 3"),
    q(
        "stress",
        "Pa",
        "Cauchy stress tensor sigma = -p I + S (tension positive), N x 3 x 3, row-major: \
         [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]",
    ),
];

/// Every column of `final.csv` and every dataset of a snapshot group, with unit and meaning:
/// the particle-table columns ([`FLOAT_QUANTITIES`], from the core's particle table) and
/// [`OTHER_QUANTITIES`].
pub fn quantities() -> impl Iterator<Item = &'static Quantity> {
    FLOAT_QUANTITIES.iter().chain(&OTHER_QUANTITIES)
}

/// The columns `final.csv` has after [`super::COLUMNS`]: the Cauchy stress and the von Mises
/// stress, computed from `p` and the deviator.
pub const DERIVED_COLUMNS: [&str; 7] = [
    "sigma_xx",
    "sigma_yy",
    "sigma_zz",
    "sigma_xy",
    "sigma_xz",
    "sigma_yz",
    "von_mises",
];

/// The [`Quantity`] named `name`, if any.
pub fn quantity(name: &str) -> Option<&'static Quantity> {
    quantities().find(|q| q.name == name)
}

/// SI unit of `name` in a run of dimension `dim` (the mass is per unit area in 1D and per
/// unit length in 2D); empty for labels and unknown names.
pub fn unit(name: &str, dim: usize) -> &'static str {
    match (name, dim) {
        ("m", 1) => "kg/m^2",
        ("m", 2) => "kg/m",
        _ => quantity(name).map_or("", |q| q.unit),
    }
}

/// The Cauchy stress of particle `i`, row-major 3 x 3: `-p I + S`.
pub fn cauchy_stress(t: &ParticleTable, i: usize) -> [f64; 9] {
    let p = t.p[i];
    let (xy, xz, yz) = (t.sxy[i], t.sxz[i], t.syz[i]);
    [
        t.sxx[i] - p,
        xy,
        xz,
        xy,
        t.syy[i] - p,
        yz,
        xz,
        yz,
        t.szz[i] - p,
    ]
}

/// The von Mises stress of particle `i`: `sqrt(3/2 S:S)` (the same as `gsph plot`'s).
pub fn von_mises(t: &ParticleTable, i: usize) -> f64 {
    let diag = t.sxx[i].powi(2) + t.syy[i].powi(2) + t.szz[i].powi(2);
    let off = t.sxy[i].powi(2) + t.sxz[i].powi(2) + t.syz[i].powi(2);
    (1.5 * (diag + 2.0 * off)).sqrt()
}

/// The [`DERIVED_COLUMNS`] of particle `i`.
pub fn derived_row(t: &ParticleTable, i: usize) -> [f64; 7] {
    let s = cauchy_stress(t, i);
    [s[0], s[4], s[8], s[1], s[2], s[5], von_mises(t, i)]
}

#[cfg(test)]
mod tests {
    use super::super::table::tests::sample_table;
    use super::super::table::COLUMNS;
    use super::*;

    #[test]
    fn every_column_and_dataset_has_a_unit_and_meaning() {
        for name in COLUMNS.iter().chain(&DERIVED_COLUMNS) {
            let q = quantity(name).unwrap_or_else(|| panic!("{name}"));
            assert!(!q.description.is_empty());
        }
        let mut names: Vec<_> = quantities().map(|q| q.name).collect();
        let all = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all, "a name twice");
        assert_eq!(unit("m", 1), "kg/m^2");
        assert_eq!(unit("m", 2), "kg/m");
        assert_eq!(unit("m", 3), "kg");
        assert_eq!(unit("stress", 2), "Pa");
        assert_eq!(unit("eps_p", 3), "1");
        assert_eq!(unit("id", 3), "");
        assert_eq!(unit("nope", 3), "");
    }

    #[test]
    fn docs_list_every_column_with_its_unit() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/output.md");
        let doc = std::fs::read_to_string(path).unwrap();
        for name in COLUMNS.iter().chain(&DERIVED_COLUMNS) {
            let start = format!("| `{name}` |");
            let row = doc
                .lines()
                .find(|l| l.starts_with(&start))
                .unwrap_or_else(|| panic!("docs/output.md has no row for `{name}`"));
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            assert_eq!(cells[2], unit(name, 3), "docs/output.md: unit of `{name}`");
        }
    }

    #[test]
    fn stress_is_minus_p_plus_deviator_and_von_mises_matches() {
        let mut t = sample_table(3, 0.5);
        let i = 1;
        (t.p[i], t.sxx[i], t.syy[i], t.szz[i]) = (2.0, 3.0, -1.0, -2.0);
        (t.sxy[i], t.sxz[i], t.syz[i]) = (0.5, -0.25, 0.125);
        let s = cauchy_stress(&t, i);
        assert_eq!(s, [1.0, 0.5, -0.25, 0.5, -3.0, 0.125, -0.25, 0.125, -4.0]);
        // S:S = 9 + 1 + 4 + 2 (0.25 + 0.0625 + 0.015625)
        let vm = (1.5f64 * (14.0 + 2.0 * 0.328125)).sqrt();
        assert_eq!(von_mises(&t, i), vm);
        assert_eq!(derived_row(&t, i), [1.0, -3.0, -4.0, 0.5, -0.25, 0.125, vm]);
    }
}
