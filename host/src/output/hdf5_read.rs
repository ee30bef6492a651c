//! Reading back `snapshots.h5` files written by [`SnapshotWriter`](super::hdf5::SnapshotWriter):
//! the list of snapshot times and one snapshot as a [`Frame`].

use std::path::Path;

use super::error::OutputError;
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
