//! Bodies from files (issue 17): particles read from a CSV file or a `snapshots.h5`
//! (shape `particles`), and closed STL surfaces filled with a lattice (shape `stl`).
//!
//! File names are relative to the scene file's directory, as `include` of a material is
//! (`resolve_path`); the scene keeps the resolved path, so messages name the file as it
//! was opened. Every error is one line naming the key, the file and the row (CSV: line and
//! column; HDF5: step and particle id) or the facet (STL: its index from 0, in file order).
//!
//! # Particle files
//! A CSV file has one header line naming its columns (blank lines and lines starting with
//! `#` are skipped), then one particle a line, comma-separated. Columns ([`STATE_COLUMNS`]):
//! `x` and as many of `y`, `z` as the dimension needs (required); `vx`, `vy`, `vz` (missing
//! ones are 0); `m`; `rho`; `e`; the deviator `sxx, syy, szz, sxy, sxz, syz` (all six or
//! none); `eps_p`, `damage`, `temperature`. `material` selects rows
//! (the shape's `file_material`); [`ignored_columns`] (the id, the pressure and
//! smoothing length, which the run recomputes, and the derived stress columns of
//! `final.csv`) are skipped unread. Any other column is refused, so that a misspelt one
//! (`Vx`) cannot silently leave a field at its default. Columns beyond the scene's
//! dimension (`z` in 2D) must be 0. A `snapshots.h5` (recognised by its signature or an
//! `.h5`/`.hdf5` name) gives every column; its snapshot of `step` (default: the last) is
//! read and must be of the scene's dimension.
//!
//! What a particle gets: position from the file; velocity from the body's `velocity` if
//! given, else the file's; density, energy and deviator from the body's `initial` if
//! given, else the file's columns, else `rho0`, 0 and 0; mass from `m`, else
//! `rho spacing^dim` (then `spacing` is required); plastic strain, damage and temperature
//! from the file, else 0, 0 and the material's initial temperature. Each particle's
//! spacing (the overlap check, the monitors) is the body's `spacing` if given, else
//! `(m/rho)^(1/dim)`. The run recomputes the pressure, sound speeds and smoothing length
//! from this state, so a run started from another run's final state with the same
//! materials continues it exactly.
//!
//! # STL surfaces
//! Read with the `stl_io` crate, streamed (ASCII or binary; a binary file whose 80-byte
//! header starts with `solid`, as some exporters write, is recognised by its length; at
//! most `max_particles` facets, an ASCII line at most
//! [`MAX_LINE`](crate::output::safe::MAX_LINE) bytes). The surface must be closed: every edge (vertices identified by their exact coordinates) shared by
//! exactly two facets; coordinates finite; no facet of zero area (collinear vertices to
//! the file's single precision). The body is the `box` lattice over the surface's bounding
//! box (same sites, same particle volume) kept where the site is inside the surface.
//!
//! The facets must also be consistently oriented: the two facets on an edge run it in
//! opposite directions (the STL rule: corners counter-clockwise seen from outside, normals
//! outward; a flipped facet is refused naming it and its neighbour).
//!
//! The inside test casts one ray along +x per lattice column (y, z) and sums the facets it
//! crosses by their orientation: +1 through a facet facing -x (into a solid), -1 through one
//! facing +x. The sum before a site is the surface's winding number about it; the site is
//! inside where it is not 0. So several shells fill their union, overlapping ones included
//! (two outward solids sharing a region wind twice about it; a parity count would leave that
//! region empty), a cavity whose facets face into it (as exporters write a hollow) winds
//! back to 0 and stays empty, and a surface turned inside out as a whole still fills
//! (winding -1). Whether the ray crosses a facet is decided in the facet's
//! projection onto the y-z plane with exact orientation predicates (Shewchuk's, the
//! `robust` crate) and a symbolic perturbation of the ray, (y + ε, z + ε²), for the exact
//! ties (a ray through an edge or a vertex, as lattice rays through the diagonals of a
//! cube's faces are). The side of each edge is then decided exactly and the same way for
//! both facets sharing it, so the crossings are those of a ray in general position: the
//! winding number is right for every closed surface, however the ray meets edges and
//! vertices; only sites on the surface itself (to rounding) may fall either way. Binning
//! the facets by lattice column makes the rays cost about columns × facets per column
//! (a winding-number sum over all facets per site would cost sites × facets).

use crate::output::{read_frame, read_snapshot_times, ParticleTable};
use crate::scene::spec::{BodySpec, Scene, ShapeSpec};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

#[path = "import_csv.rs"]
mod csv_file;
use csv_file::{count_rows, parse_csv};

pub(super) use super::stl::{read_stl, Mesh};

/// `file` relative to `base` (the scene file's directory; the working directory when the
/// scene text does not come from a file), as a material's `include` is resolved.
pub(super) fn resolve_path(base: Option<&Path>, file: &str) -> PathBuf {
    match base {
        Some(dir) if Path::new(file).is_relative() => dir.join(file),
        _ => PathBuf::from(file),
    }
}

/// Rewrites the `file` of every `particles` and `stl` shape relative to `base`.
pub(in crate::scene) fn resolve_files(scene: &mut Scene, base: Option<&Path>) {
    for b in &mut scene.bodies {
        if let ShapeSpec::Particles { file, .. } | ShapeSpec::Stl { file, .. } = &mut b.shape {
            if !file.is_empty() {
                *file = resolve_path(base, file).to_string_lossy().into_owned();
            }
        }
    }
}

use super::initial::state_column;
pub use super::initial::STATE_COLUMNS;

/// Columns of a particle file that are skipped unread: every column of `final.csv` a
/// file cannot set: the id (particles get new ids in file order), the state columns of
/// the fields initial particles do not carry (the pressure and smoothing length, which
/// the run recomputes) and the derived columns. From the output table, so a column added
/// there is known here.
pub fn ignored_columns() -> Vec<&'static str> {
    use crate::output::{meta::DERIVED_COLUMNS, table::COLUMNS};
    COLUMNS
        .iter()
        .chain(&DERIVED_COLUMNS)
        .copied()
        .filter(|c| !STATE_COLUMNS.contains(c) && *c != "material")
        .collect()
}

/// Indices into [`STATE_COLUMNS`].
const X: usize = state_column("x");
const V: usize = state_column("vx");
const M: usize = state_column("m");
const RHO: usize = state_column("rho");
const E: usize = state_column("e");
const S: usize = state_column("sxx");
const EPS_P: usize = state_column("eps_p");
const DAMAGE: usize = state_column("damage");
const TEMPERATURE: usize = state_column("temperature");
const X0: usize = state_column("x0");

/// Where the rows of a particle file are, for messages.
#[derive(Debug, Clone)]
enum Rows {
    /// CSV: the line of each row (from 1).
    Lines(Vec<usize>),
    /// HDF5: the snapshot's step and each particle's id.
    Snapshot { step: u64, ids: Vec<u32> },
}

/// The particles of a file: the state columns it has, its `material` column, where each
/// row is.
#[derive(Debug, Clone)]
pub(super) struct FileParticles {
    /// The file, for messages.
    shown: String,
    cols: [Option<Vec<f64>>; STATE_COLUMNS.len()],
    material: Option<Vec<u32>>,
    rows: Rows,
}

impl FileParticles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        match &self.rows {
            Rows::Lines(l) => l.len(),
            Rows::Snapshot { ids, .. } => ids.len(),
        }
    }

    /// `line 7` or `step 40, particle id 17`.
    fn label(&self, i: usize) -> String {
        match &self.rows {
            Rows::Lines(l) => format!("line {}", l[i]),
            Rows::Snapshot { step, ids } => format!("step {step}, particle id {}", ids[i]),
        }
    }

    /// Value of column `c` (a [`STATE_COLUMNS`] index) of row `i`, if the file has it.
    fn get(&self, c: usize, i: usize) -> Option<f64> {
        self.cols[c].as_ref().map(|v| v[i])
    }

    /// Keeps the rows where `keep` holds.
    fn retain(&mut self, keep: &[bool]) {
        for v in self.cols.iter_mut().flatten() {
            keep_where(v, keep);
        }
        match &mut self.rows {
            Rows::Lines(l) => keep_where(l, keep),
            Rows::Snapshot { ids, .. } => keep_where(ids, keep),
        }
        if let Some(m) = &mut self.material {
            keep_where(m, keep);
        }
    }
}

/// Keeps the elements of `v` where `keep` holds.
fn keep_where<T>(v: &mut Vec<T>, keep: &[bool]) {
    let mut k = keep.iter();
    v.retain(|_| *k.next().expect("one flag per element"));
}

/// A particle file opened but not yet read: a CSV file with its number of rows (counted,
/// so that the memory check comes before the columns are read), or the snapshot read.
pub(super) enum ParticleSource {
    Csv { path: PathBuf, rows: usize },
    Snapshot(Box<FileParticles>),
}

impl ParticleSource {
    /// Number of rows (before `file_material` selects some).
    pub fn rows(&self) -> usize {
        match self {
            ParticleSource::Csv { rows, .. } => *rows,
            ParticleSource::Snapshot(f) => f.len(),
        }
    }
}

/// The signature that starts an HDF5 file.
const HDF5_SIGNATURE: &[u8; 8] = b"\x89HDF\r\n\x1a\n";

/// Whether a file is an HDF5 file: its signature, or an `.h5`/`.hdf5` name.
fn is_hdf5(path: &Path) -> bool {
    let mut head = [0u8; 8];
    let signed = std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok()
        && &head == HDF5_SIGNATURE;
    signed
        || path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("h5") || e.eq_ignore_ascii_case("hdf5"))
}

/// Opens the particle file of a `particles` shape (`key` is the shape's key, e.g.
/// `bodies[0].shape`): counts a CSV file's rows, or reads the snapshot of `step` of an
/// HDF5 file (which must be of dimension `dim`); either holds at most `limit` particles
/// (the scene's `max_particles`), checked before they are read.
pub(super) fn open_particles(
    key: &str,
    file: &str,
    step: Option<u64>,
    dim: usize,
    limit: usize,
) -> Result<ParticleSource, String> {
    let path = Path::new(file);
    if let Err(e) = crate::output::safe::check_file_name(file) {
        return Err(format!("{key}.file: {e}"));
    }
    let at = |msg: String| format!("{key}.file: {file}: {msg}");
    // not a directory, a device or a pipe that never ends
    crate::output::safe::regular_file(path).map_err(at)?;
    if is_hdf5(path) {
        return read_snapshot(key, file, step, dim, limit)
            .map(|f| ParticleSource::Snapshot(Box::new(f)));
    }
    if step.is_some() {
        return Err(format!(
            "{key}.step: selects a snapshot of an HDF5 file; {file} is read as CSV"
        ));
    }
    let rows = count_rows(path, limit).map_err(at)?;
    Ok(ParticleSource::Csv {
        path: path.to_path_buf(),
        rows,
    })
}

/// Reads an opened particle file, checks every value and selects the rows of
/// `file_material`.
pub(super) fn read_particles(
    key: &str,
    src: ParticleSource,
    dim: usize,
    file_material: Option<u32>,
) -> Result<FileParticles, String> {
    let mut f = match src {
        ParticleSource::Csv { path, rows } => {
            let shown = path.display().to_string();
            parse_csv(&path, &shown, dim, rows).map_err(|e| format!("{key}.file: {shown}: {e}"))?
        }
        ParticleSource::Snapshot(f) => *f,
    };
    check_values(&f, dim).map_err(|e| format!("{key}.file: {}: {e}", f.shown))?;
    select_material(&mut f, key, file_material)?;
    Ok(f)
}

/// `0, 10, 20, ..., 200 (21 snapshots)`, or all of them when few.
fn list_steps(times: &[(u64, f64)]) -> String {
    let s: Vec<String> = times.iter().map(|(s, _)| s.to_string()).collect();
    if s.len() <= 6 {
        s.join(", ")
    } else {
        format!(
            "{}, ..., {} ({} snapshots)",
            s[..3].join(", "),
            s[s.len() - 1],
            s.len()
        )
    }
}

/// Reads the snapshot of `step` (default: the last) of a `snapshots.h5`.
fn read_snapshot(
    key: &str,
    file: &str,
    step: Option<u64>,
    dim: usize,
    limit: usize,
) -> Result<FileParticles, String> {
    let at = |msg: String| format!("{key}.file: {file}: {msg}");
    let times = read_snapshot_times(file).map_err(|e| at(e.to_string()))?;
    let Some(&(last, _)) = times.last() else {
        return Err(at("no snapshot in the file".into()));
    };
    let step = match step {
        None => last,
        Some(s) if times.iter().any(|&(t, _)| t == s) => s,
        Some(s) => {
            return Err(format!(
                "{key}.step: {file} has no snapshot of step {s} (it has steps {})",
                list_steps(&times)
            ))
        }
    };
    let frame = read_frame(file, step, limit).map_err(|e| at(e.to_string()))?;
    if frame.dim != dim {
        return Err(at(format!(
            "the snapshot of step {step} is {}D, the scene is {dim}D",
            frame.dim
        )));
    }
    let t: &ParticleTable = &frame.table;
    if t.is_empty() {
        return Err(at(format!("the snapshot of step {step} has no particle")));
    }
    let names = crate::output::table::FLOAT_COLUMNS;
    let floats = t.float_columns();
    let mut cols: [Option<Vec<f64>>; STATE_COLUMNS.len()] = Default::default();
    for (c, name) in STATE_COLUMNS.iter().enumerate() {
        let k = names
            .iter()
            .position(|n| n == name)
            .expect("a table column");
        // a snapshot written before the reference position was reads it as NaN: absent
        if c >= X0 && floats[k].iter().any(|v| v.is_nan()) {
            continue;
        }
        cols[c] = Some(floats[k].clone());
    }
    Ok(FileParticles {
        shown: file.to_string(),
        cols,
        material: Some(t.material.clone()),
        rows: Rows::Snapshot {
            step,
            ids: t.id.clone(),
        },
    })
}

/// Checks every value: finite; 0 beyond the dimension; m, rho positive; eps_p,
/// temperature non-negative; damage in [0, 1].
fn check_values(f: &FileParticles, dim: usize) -> Result<(), String> {
    for (c, col) in f.cols.iter().enumerate() {
        let Some(col) = col else { continue };
        let name = STATE_COLUMNS[c];
        let beyond = (c < V && c - X >= dim)
            || ((V..V + 3).contains(&c) && c - V >= dim)
            || ((X0..X0 + 3).contains(&c) && c - X0 >= dim);
        for (i, &v) in col.iter().enumerate() {
            let bad = if !v.is_finite() {
                Some("not finite".to_string())
            } else if beyond && v != 0.0 {
                Some(format!(
                    "must be 0 in a {dim}D scene (the columns beyond its dimension are)"
                ))
            } else {
                match c {
                    M | RHO if v <= 0.0 => Some("must be positive".into()),
                    EPS_P | TEMPERATURE if v < 0.0 => Some("must be non-negative".into()),
                    DAMAGE if !(0.0..=1.0).contains(&v) => Some("must lie in [0, 1]".into()),
                    _ => None,
                }
            };
            if let Some(why) = bad {
                return Err(format!(
                    "{}, column `{name}`: {} {why}",
                    f.label(i),
                    crate::scene::checks::num(v)
                ));
            }
        }
    }
    Ok(())
}

/// Material indices in ascending order, `0, 1`.
fn list_materials(m: &[u32]) -> String {
    let mut v = m.to_vec();
    v.sort_unstable();
    v.dedup();
    let s: Vec<String> = v.iter().take(8).map(u32::to_string).collect();
    if v.len() > 8 {
        format!("{}, ... ({} in all)", s.join(", "), v.len())
    } else {
        s.join(", ")
    }
}

/// Keeps the rows of material `pick`; without `pick`, refuses a file of several materials.
fn select_material(f: &mut FileParticles, key: &str, pick: Option<u32>) -> Result<(), String> {
    let shown = f.shown.clone();
    match (pick, &f.material) {
        (None, None) => Ok(()),
        (Some(_), None) => Err(format!(
            "{key}.file_material: {shown} has no `material` column to select rows by"
        )),
        (None, Some(m)) => {
            let first = m[0];
            if m.iter().all(|&k| k == first) {
                Ok(())
            } else {
                Err(format!(
                    "{key}.file: {shown} holds particles of materials {} (column `material`); a body is of one material: choose its rows with `file_material`",
                    list_materials(m)
                ))
            }
        }
        (Some(k), Some(m)) => {
            let keep: Vec<bool> = m.iter().map(|&x| x == k).collect();
            if !keep.contains(&true) {
                return Err(format!(
                    "{key}.file_material: no row of {shown} is of material {k} (it has {})",
                    list_materials(m)
                ));
            }
            f.retain(&keep);
            Ok(())
        }
    }
}

/// One particle of a file body, as the body's keys and the file's columns give it.
pub(super) struct FileParticle {
    pub x: [f64; 3],
    /// The file's velocity (the caller applies the body's `velocity` instead, if given).
    pub v: [f64; 3],
    pub m: f64,
    pub rho: f64,
    pub e: f64,
    pub s: gsph_core::math::Sym3,
    pub spacing: f64,
    pub eps_p: f64,
    pub damage: f64,
    pub temperature: f64,
    /// The file's reference position (`x0`, `y0`, `z0`: a `final.csv` of an earlier run),
    /// if it has one.
    pub x0: Option<[f64; 3]>,
}

/// The particles of a file body of material `mat` (see the module docs for what comes
/// from where). `initial` is the body's `initial` state (rho, e, deviator), if it has one.
pub(super) fn file_body(
    f: &FileParticles,
    key: &str,
    body: &BodySpec,
    dim: usize,
    mat: &gsph_core::material::Material,
    mat_name: &str,
    initial: Option<(f64, f64, gsph_core::math::Sym3)>,
) -> Result<Vec<FileParticle>, String> {
    use gsph_core::math::Sym3;
    let spacing = body.spacing.is_finite().then_some(body.spacing);
    if f.cols[M].is_none() && spacing.is_none() {
        return Err(format!(
            "{key}.spacing: missing: {} has no `m` column, so each particle's mass is rho spacing^{dim} (give `spacing`)",
            f.shown
        ));
    }
    let mut out = Vec::with_capacity(f.len());
    for i in 0..f.len() {
        let col = |c: usize| f.get(c, i);
        let mut x = [0.0; 3];
        let mut v = [0.0; 3];
        for a in 0..3 {
            x[a] = col(X + a).unwrap_or(0.0);
            v[a] = col(V + a).unwrap_or(0.0);
        }
        let (rho, e, s) = match initial {
            Some(state) => state,
            None => {
                let s = match f.cols[S] {
                    Some(_) => {
                        let d = |k: usize| col(S + k).expect("all six columns");
                        Sym3::new(d(0), d(1), d(2), d(3), d(4), d(5))
                    }
                    None => Sym3::ZERO,
                };
                (col(RHO).unwrap_or(mat.rho0), col(E).unwrap_or(0.0), s)
            }
        };
        let m = match (col(M), spacing) {
            (Some(m), _) => m,
            (None, Some(dx)) => rho * dx.powi(dim as i32),
            (None, None) => unreachable!("checked above"),
        };
        let st = mat.eos(rho, e);
        if !(st.p.is_finite() && st.c2.is_finite()) {
            return Err(format!(
                "{key}.file: {}: {}: the EOS of material `{mat_name}` has no state at density {} kg/m³, energy {} J/kg",
                f.shown,
                f.label(i),
                crate::scene::checks::num(rho),
                crate::scene::checks::num(e)
            ));
        }
        out.push(FileParticle {
            x,
            v,
            m,
            rho,
            e,
            s,
            spacing: spacing.unwrap_or_else(|| (m / rho).powf(1.0 / dim as f64)),
            eps_p: col(EPS_P).unwrap_or(0.0),
            damage: col(DAMAGE).unwrap_or(0.0),
            temperature: col(TEMPERATURE).unwrap_or_else(|| mat.initial_temperature()),
            x0: f.cols[X0].as_ref().map(|_| {
                let mut x0 = [0.0; 3];
                for (a, x0a) in x0.iter_mut().enumerate() {
                    *x0a = col(X0 + a).unwrap_or(0.0);
                }
                x0
            }),
        });
    }
    Ok(out)
}

#[cfg(test)]
#[path = "import_tests.rs"]
pub(super) mod tests;
