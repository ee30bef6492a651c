//! What a simulation gives back: its summary, series, snapshots (CSV, HDF5/XDMF) and
//! checkpoints.

use crate::guard::{cstr, guard, put, slice_mut, text_out, Failure};
use crate::{handles, GsphSim};
use std::ffi::{c_char, c_int};
use std::path::Path;

/// The summary as JSON (NUL-terminated) into `buf` of `len` bytes: energies, momenta, the
/// largest kinetic energy, the reference's and the `[monitor]`'s measures (the keys of
/// `gsph run`'s summary.json but timings). `needed` (may be null) receives the length
/// including the NUL. A `buf` too small (or null with `len` 0) gets
/// nothing and the call fails with GSPH_ERR_ARGUMENT, `needed` set: call again.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_summary_json(
    sim: *mut GsphSim,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let text = serde_json::Value::Object(s.summary()).to_string();
            unsafe { text_out(&text, buf, len, needed, "summary") }
        })
    })
}

/// Writes the state as a CSV file with the columns of `gsph run`'s final.csv (a path
/// ending in `.h5` or `.xdmf` is refused: see [`gsph_write_snapshots`]).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_write_snapshot(sim: *mut GsphSim, path: *const c_char) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            Ok(s.write_snapshot(Path::new(unsafe { cstr(path, "path")? }))?)
        })
    })
}

/// Writes a checkpoint into the directory `dir` (created if missing), from which
/// [`gsph_create_from_checkpoint`] continues bitwise identically (the series and monitor
/// included).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_write_checkpoint(sim: *mut GsphSim, dir: *const c_char) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            Ok(s.write_checkpoint(Path::new(unsafe { cstr(dir, "dir")? }))?)
        })
    })
}

/// The series recorded so far (`series.csv` of `gsph run`: one row per sample, `output.series`
/// samples per run, 200 by default, plus the initial state): its `rows` and `columns`
/// (either may be null).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_series_shape(
    sim: *mut GsphSim,
    rows: *mut usize,
    columns: *mut usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let series = s.series();
            unsafe { put(rows, "rows", series.rows.len())? };
            unsafe { put(columns, "columns", series.names.len())? };
            Ok(())
        })
    })
}

/// The series' column names, comma-separated as in the header of series.csv (t, step, dt,
/// kinetic, internal, total, momentum_x..z, then the reference's and the monitor's), into
/// `buf` as [`gsph_summary_json`] does.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_series_names(
    sim: *mut GsphSim,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let names = s.series().names.join(",");
            unsafe { text_out(&names, buf, len, needed, "series names") }
        })
    })
}

/// Copies the series into `buf` (`len` = rows x columns doubles, row after row).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_read_series(sim: *mut GsphSim, buf: *mut f64, len: usize) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let series = s.series();
            let want = series.rows.len() * series.names.len();
            if len != want {
                return Err(Failure::argument(format!(
                    "buf: {len} values, the series has {want} ({} rows x {} columns)",
                    series.rows.len(),
                    series.names.len()
                )));
            }
            let b = unsafe { slice_mut(buf, len, "buf")? };
            for (dst, v) in b.iter_mut().zip(series.rows.iter().flatten()) {
                *dst = *v;
            }
            Ok(())
        })
    })
}

/// Writes the series so far to the file `path` as series.csv (byte for byte what `gsph run`
/// writes for the same steps).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_write_series(sim: *mut GsphSim, path: *const c_char) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            Ok(s.write_series(Path::new(unsafe { cstr(path, "path")? }))?)
        })
    })
}

/// Writes `dir/snapshots.h5` + `dir/snapshots.xdmf` (the HDF5/XDMF pair of `gsph run`, read by
/// ParaView and `gsph plot particles`) holding the state now; `dir` is created if missing.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_write_snapshots(sim: *mut GsphSim, dir: *const c_char) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            Ok(s.write_snapshots(Path::new(unsafe { cstr(dir, "dir")? }))?)
        })
    })
}

/// Starts the snapshot pair in `dir` with the state now as its first snapshot; then
/// [`gsph_run`] adds one at each of the scene's snapshot times (as `gsph run`),
/// [`gsph_append_snapshot`] one at any time, and [`gsph_close_snapshots`] finishes the pair
/// (until then it is snapshots.partial.h5/.xdmf, marked partial; also if the simulation is
/// destroyed first). One file open per simulation; the folder is locked meanwhile.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_open_snapshots(sim: *mut GsphSim, dir: *const c_char) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            Ok(s.open_snapshots(Path::new(unsafe { cstr(dir, "dir")? }))?)
        })
    })
}

/// Adds the state now to the open snapshot file (refused without one, or when it holds
/// this step already).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_append_snapshot(sim: *mut GsphSim) -> c_int {
    guard(|| handles::with(sim, |s, _| Ok(s.append_snapshot()?)))
}

/// Finishes the open snapshot file: snapshots.h5 + snapshots.xdmf (status complete).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_close_snapshots(sim: *mut GsphSim) -> c_int {
    guard(|| handles::with(sim, |s, _| Ok(s.close_snapshots()?)))
}
