//! Reading back `snapshots.h5` files written by [`SnapshotWriter`](super::hdf5::SnapshotWriter):
//! the list of snapshot times, one snapshot as a [`Frame`] and the run's attributes as a
//! [`RunInfo`]. Files of both layouts read: format version 1 (before `stress`, `von_mises` and the
//! run attributes), 2 and 3 (2 with `run_id`); the derived datasets are not read back (the [`Frame`] holds `p` and the
//! deviator they come from).
//!
//! Every file read is checked before any data is (issue 25): it is a regular file; no link in
//! it leads to another file (external links), no dataset read is stored outside it (external
//! storage, virtual datasets) or filtered by anything but deflate and shuffle (a filter
//! plugin would be loaded and run to decode it), and each dataset's declared size is bounded
//! before it is allocated: at most the scene's `max_particles` where a scene reads it,
//! the values a particle has, stored in the file (a contiguous dataset's bytes at most the
//! file's size; a chunked one's at most [`MAX_DEFLATE_RATIO`] times its stored chunks, deflate's
//! own bound), and the whole snapshot within the memory available. So a small file declaring
//! 2^33 particles is refused in one line instead of aborting the allocation.

use std::path::Path;

use super::error::OutputError;
use super::meta::RunInfo;
use super::table::{Frame, ParticleTable, BASE_COLUMNS, FLOAT_COLUMNS};
use super::xdmf::group_name;
use hdf5::filters::Filter;
use hdf5::LinkType;

/// The most a deflated chunk expands (deflate's limit is 1032:1, for a run of equal bytes).
pub const MAX_DEFLATE_RATIO: u64 = 1100;

fn bad(msg: String) -> OutputError {
    OutputError::Format(msg)
}

/// Opens an HDF5 file to read: a regular file (HDF5 would block on a FIFO); refuses links
/// to other files among its root's members. Returns the file and its length.
fn open(path: &Path) -> Result<(hdf5::File, u64), OutputError> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(bad("not a regular file".into()));
    }
    let len = meta.len();
    let file = hdf5::File::open(path)?;
    no_external_links(&file)?;
    Ok((file, len))
}

/// Refuses a member of `g` that is a link to another file (`g` is read as a whole).
fn no_external_links(g: &hdf5::Group) -> Result<(), OutputError> {
    let mut external = None;
    g.iter_visit_default(|name, info| {
        if info.link_type == LinkType::External && external.is_none() {
            external = Some(name.to_owned());
        }
        Ok(())
    })?;
    match external {
        Some(name) => Err(bad(format!(
            "{}/{}: a link to another file; gsph reads no data from outside the file it was given",
            g.name().trim_end_matches('/'),
            super::safe::excerpt(&name)
        ))),
        None => Ok(()),
    }
}

/// Opens dataset `name` of `g` to read `values` values of `size` bytes each (what the
/// caller allocates): refuses it, naming it, if it is stored outside the file, filtered by
/// anything but deflate and shuffle, holds a different number of values, or declares more
/// bytes than the file can hold (`file_len`).
fn dataset(
    g: &hdf5::Group,
    name: &str,
    values: u64,
    size: u64,
    file_len: u64,
) -> Result<hdf5::Dataset, OutputError> {
    let ds = g.dataset(name)?;
    let shown = format!("{}/{name}", g.name());
    let plist = ds.create_plist()?;
    let layout = plist.layout();
    if !matches!(
        layout,
        hdf5::dataset::Layout::Contiguous
            | hdf5::dataset::Layout::Chunked
            | hdf5::dataset::Layout::Compact
    ) {
        return Err(bad(format!(
            "{shown}: a virtual dataset (its values come from other datasets or files); gsph reads data stored in the file itself"
        )));
    }
    if !plist.external().is_empty() {
        return Err(bad(format!(
            "{shown}: stored in an external file; gsph reads data stored in the file itself"
        )));
    }
    let filters = plist.get_filters().map_err(|e| {
        bad(format!(
            "{shown}: its filters cannot be read ({e}); gsph reads deflate and shuffle"
        ))
    })?;
    if let Some(f) = filters
        .iter()
        .find(|f| !matches!(f, Filter::Deflate(_) | Filter::Shuffle))
    {
        return Err(bad(format!(
            "{shown}: filter {} (id {}); gsph reads data compressed with deflate (gzip) and shuffle only",
            filter_name(f),
            f.id()
        )));
    }
    let declared = ds.size() as u64;
    if declared != values {
        return Err(bad(format!(
            "{shown}: {declared} values, expected {values}"
        )));
    }
    let bytes = declared.saturating_mul(size.max(ds.dtype()?.size() as u64));
    let stored = ds.storage_size();
    let room = match layout {
        hdf5::dataset::Layout::Chunked
            if filters.iter().any(|f| matches!(f, Filter::Deflate(_))) =>
        {
            stored.saturating_mul(MAX_DEFLATE_RATIO)
        }
        hdf5::dataset::Layout::Chunked => stored,
        _ => file_len,
    };
    if bytes > room {
        return Err(bad(format!(
            "{shown}: declares {declared} values ({bytes} bytes), more than the file holds for it ({stored} bytes stored, the file {file_len} bytes)"
        )));
    }
    Ok(ds)
}

fn filter_name(f: &Filter) -> &'static str {
    match f {
        Filter::Fletcher32 => "fletcher32",
        Filter::SZip(..) => "szip",
        Filter::NBit => "nbit",
        Filter::ScaleOffset(_) => "scale-offset",
        _ => "(a plugin)",
    }
}

/// Reads `(step, time)` of every snapshot in a file written by
/// [`SnapshotWriter`](super::hdf5::SnapshotWriter), sorted by step.
pub fn read_snapshot_times(path: impl AsRef<Path>) -> Result<Vec<(u64, f64)>, OutputError> {
    let (file, _) = open(path.as_ref())?;
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
    // an attribute's values are stored in the file: no more than it has bytes
    if a.size() as u64 > loc.file()?.size() {
        return Err(bad(format!(
            "attribute `{name}`: {} values, more than the file has bytes",
            a.size()
        )));
    }
    let v: Vec<hdf5::types::VarLenUnicode> = a.read_raw()?;
    Ok(v.iter().map(|s| s.as_str().to_owned()).collect())
}

/// The run a snapshot file comes from (its root attributes), or `None` for a file written before
/// they were (format version 1, no `format_version` attribute).
pub fn read_run_info(path: impl AsRef<Path>) -> Result<Option<RunInfo>, OutputError> {
    let (file, _) = open(path.as_ref())?;
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
        run_id: if file.attr_names()?.iter().any(|a| a == "run_id") {
            str_attr(&file, "run_id")?
        } else {
            String::new()
        },
    }))
}

/// Reads dataset `name` of `g`, `width` values per particle of `n`, checked first
/// ([`dataset`]).
fn read_values<T: hdf5::H5Type>(
    g: &hdf5::Group,
    name: &str,
    n: usize,
    width: usize,
    file_len: u64,
) -> Result<Vec<T>, OutputError> {
    let size = std::mem::size_of::<T>() as u64;
    let ds = dataset(g, name, (n * width) as u64, size, file_len)?;
    Ok(ds.read_raw::<T>()?)
}

/// Bytes a snapshot of one particle takes in memory as read: the columns of a
/// [`ParticleTable`] and the position and velocity read before they are split.
const BYTES_PER_PARTICLE: u64 = (FLOAT_COLUMNS.len() as u64 + 6) * 8 + 8;

/// Reads the snapshot of `step` from a file written by
/// [`SnapshotWriter`](super::hdf5::SnapshotWriter), of at most `limit` particles (a
/// scene's `max_particles` where a scene reads it; `usize::MAX` leaves the bound to the
/// memory this machine has), checked before anything is allocated.
pub fn read_frame(path: impl AsRef<Path>, step: u64, limit: usize) -> Result<Frame, OutputError> {
    let path = path.as_ref();
    let (file, len) = open(path)?;
    let name = group_name(step);
    if !file.link_exists(&name) {
        return Err(OutputError::Format(format!(
            "{}: no snapshot for step {step}",
            path.display()
        )));
    }
    let g = file.group(&name)?;
    no_external_links(&g)?;
    let dim = file.attr("dim")?.read_scalar::<u32>()? as usize;
    let time = g.attr("time")?.read_scalar::<f64>()?;
    let step = g.attr("step")?.read_scalar::<u64>()?;
    // the particle count, from the shape of `id`, bounded before anything is allocated
    let n = g.dataset("id")?.size();
    if n > limit {
        return Err(bad(format!(
            "{}/id: {n} particles, more than the scene's limit {:.0e} (`max_particles` raises it)",
            g.name(),
            limit as f64
        )));
    }
    let need = n as u64 * BYTES_PER_PARTICLE;
    if let Some(avail) = crate::memory::available() {
        if need > avail {
            return Err(bad(format!(
                "{}: {n} particles need about {:.1} GiB of memory to read, more than the {:.1} GiB available",
                g.name(),
                need as f64 / (1u64 << 30) as f64,
                avail as f64 / (1u64 << 30) as f64
            )));
        }
    }
    let id = read_values::<u32>(&g, "id", n, 1, len)?;
    let position = read_values::<f64>(&g, "position", n, 3, len)?;
    let velocity = read_values::<f64>(&g, "velocity", n, 3, len)?;
    let mut table = ParticleTable {
        material: read_values::<u32>(&g, "material", n, 1, len)?,
        id,
        ..ParticleTable::default()
    };
    for (k, (col, &cname)) in table
        .float_columns_mut()
        .into_iter()
        .zip(FLOAT_COLUMNS)
        .enumerate()
    {
        // a column appended after the file was written reads as NaN
        if k + 2 >= BASE_COLUMNS && !g.link_exists(cname) {
            *col = vec![f64::NAN; n];
            continue;
        }
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
            _ => read_values::<f64>(&g, cname, n, 1, len)?,
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
