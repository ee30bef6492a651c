//! Reading back `snapshots.h5` files written by [`SnapshotWriter`](super::hdf5::SnapshotWriter):
//! the list of snapshot times, one snapshot as a [`Frame`] and the run's attributes as a
//! [`RunInfo`]. Files of both layouts read: format version 1 (before `stress`, `von_mises` and the
//! run attributes) and 2; the derived datasets are not read back (the [`Frame`] holds `p` and the
//! deviator they come from).

use std::path::Path;

use super::error::OutputError;
use super::meta::RunInfo;
use super::table::{Frame, ParticleTable, FLOAT_COLUMNS};
use super::xdmf::group_name;

/// Reads `(step, time)` of every snapshot in a file written by
/// [`SnapshotWriter`](super::hdf5::SnapshotWriter), sorted by step.
pub fn read_snapshot_times(path: impl AsRef<Path>) -> Result<Vec<(u64, f64)>, OutputError> {
    let file = hdf5::File::open(path)?;
    let mut out = Vec::new();
    for name in file.member_names()? {
        if name.starts_with("step_") {
            let g = file.group(&name)?;
            out.push((
                g.attr("step")?.read_scalar()?,
                g.attr("time")?.read_scalar()?,
            ));
        }
    }
    out.sort_by_key(|&(s, _)| s);
    Ok(out)
}

fn str_attr(loc: &hdf5::Location, name: &str) -> Result<String, OutputError> {
    let v: hdf5::types::VarLenUnicode = loc.attr(name)?.read_scalar()?;
    Ok(v.as_str().to_owned())
}

fn str_list_attr(loc: &hdf5::Location, name: &str) -> Result<Vec<String>, OutputError> {
    let a = loc.attr(name)?;
    if a.size() == 0 {
        return Ok(Vec::new());
    }
    let v: Vec<hdf5::types::VarLenUnicode> = a.read_raw()?;
    Ok(v.iter().map(|s| s.as_str().to_owned()).collect())
}

/// The run a snapshot file comes from (its root attributes), or `None` for a file written before
/// they were (format version 1, no `format_version` attribute).
pub fn read_run_info(path: impl AsRef<Path>) -> Result<Option<RunInfo>, OutputError> {
    let file = hdf5::File::open(path)?;
    if !file.attr_names()?.iter().any(|a| a == "format_version") {
        return Ok(None);
    }
    Ok(Some(RunInfo {
        name: str_attr(&file, "scene_name")?,
        scene: str_attr(&file, "scene")?,
        overrides: str_list_attr(&file, "scene_overrides")?,
        scheme: str_attr(&file, "scheme")?,
        effects: str_list_attr(&file, "effects")?,
        materials: str_list_attr(&file, "material_names")?,
    }))
}

fn read_1d<T: hdf5::H5Type>(g: &hdf5::Group, name: &str, n: usize) -> Result<Vec<T>, OutputError> {
    let v = g.dataset(name)?.read_raw::<T>()?;
    if v.len() != n {
        return Err(OutputError::Format(format!(
            "{}/{name}: {} values, expected {n}",
            g.name(),
            v.len()
        )));
    }
    Ok(v)
}

/// Reads the snapshot of `step` from a file written by
/// [`SnapshotWriter`](super::hdf5::SnapshotWriter).
pub fn read_frame(path: impl AsRef<Path>, step: u64) -> Result<Frame, OutputError> {
    let path = path.as_ref();
    let file = hdf5::File::open(path)?;
    let name = group_name(step);
    if !file.link_exists(&name) {
        return Err(OutputError::Format(format!(
            "{}: no snapshot for step {step}",
            path.display()
        )));
    }
    let g = file.group(&name)?;
    let dim = file.attr("dim")?.read_scalar::<u32>()? as usize;
    let time = g.attr("time")?.read_scalar::<f64>()?;
    let step = g.attr("step")?.read_scalar::<u64>()?;
    let id = g.dataset("id")?.read_raw::<u32>()?;
    let n = id.len();
    let position = read_1d::<f64>(&g, "position", 3 * n)?;
    let velocity = read_1d::<f64>(&g, "velocity", 3 * n)?;
    let mut table = ParticleTable {
        material: read_1d::<u32>(&g, "material", n)?,
        id,
        ..ParticleTable::default()
    };
    for (col, cname) in table.float_columns_mut().into_iter().zip(FLOAT_COLUMNS) {
        *col = match cname {
            "x" | "y" | "z" => position
                .iter()
                .skip(axis(cname))
                .step_by(3)
                .copied()
                .collect(),
            "vx" | "vy" | "vz" => velocity
                .iter()
                .skip(axis(cname))
                .step_by(3)
                .copied()
                .collect(),
            _ => read_1d::<f64>(&g, cname, n)?,
        };
    }
    Ok(Frame {
        time,
        step,
        dim,
        table,
    })
}

/// Component index (0, 1, 2) of a position or velocity column name.
fn axis(name: &str) -> usize {
    match name.chars().last() {
        Some('y') => 1,
        Some('z') => 2,
        _ => 0,
    }
}
