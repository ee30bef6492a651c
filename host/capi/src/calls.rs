//! The calls on a simulation: sizes and time, stepping, fields, external accelerations,
//! budgets. Each runs on the handle's simulation under its lock ([`crate::handles`]).

use crate::guard::{cstr, guard, out, put, slice, slice_mut, Failure};
use crate::{handles, GsphSim};
use gsph_rs::api::ApiError;
use std::ffi::{c_char, c_int};

/// Stops a long call after its step once the handle is destroyed.
fn stop_if_destroyed(entry: &handles::Entry, call: &str) -> Result<(), ApiError> {
    match entry.destroyed() {
        true => Err(ApiError::Stopped(format!(
            "{call}: the handle was destroyed by another thread during the call; stopped after the step in progress"
        ))),
        false => Ok(()),
    }
}

/// Dimension of the simulation (1, 2, 3).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_dim(sim: *mut GsphSim, dim: *mut usize) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            *unsafe { out(dim, "dim")? } = s.dim();
            Ok(())
        })
    })
}

/// Number of particles.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_count(sim: *mut GsphSim, count: *mut usize) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            *unsafe { out(count, "count")? } = s.len();
            Ok(())
        })
    })
}

/// Simulated time, s, and steps taken (either output may be null).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_time(sim: *mut GsphSim, t: *mut f64, steps: *mut u64) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            unsafe { put(t, "t", s.time())? };
            unsafe { put(steps, "steps", s.steps())? };
            Ok(())
        })
    })
}

/// The time step the scene's rule gives now (its fixed `dt`, or the CFL step), s.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_stable_dt(sim: *mut GsphSim, dt: *mut f64) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let slot = unsafe { out(dt, "dt")? };
            *slot = s.stable_dt()?;
            Ok(())
        })
    })
}

/// The scene's end time `t_end`, s, and its snapshot count (the times `t_end k /
/// snapshots` that [`gsph_run`] lands on); either output may be null.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_schedule(
    sim: *mut GsphSim,
    t_end: *mut f64,
    snapshots: *mut usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            unsafe { put(t_end, "t_end", s.scene().t_end)? };
            unsafe { put(snapshots, "snapshots", s.scene().output.snapshots)? };
            Ok(())
        })
    })
}

/// Takes one step: `dt` > 0 is the step (refused above the CFL-1 limit), `dt` = 0 takes
/// the scene's rule. `dt_taken` (may be null) receives the step taken.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_step(sim: *mut GsphSim, dt: f64, dt_taken: *mut f64) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let taken = s.step((dt != 0.0).then_some(dt))?;
            unsafe { put(dt_taken, "dt_taken", taken)? };
            Ok(())
        })
    })
}

/// Steps until time `t`, the last step shortened to land on it. `steps` (may be null)
/// receives the number of steps taken.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_advance(sim: *mut GsphSim, t: f64, steps: *mut u64) -> c_int {
    guard(|| {
        handles::with(sim, |s, entry| {
            let n = s.advance_to_with(t, || stop_if_destroyed(entry, "gsph_advance"))?;
            unsafe { put(steps, "steps", n)? };
            Ok(())
        })
    })
}

/// Runs to the scene's `t_end` through its snapshot times: the steps of `gsph run`.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_run(sim: *mut GsphSim, steps: *mut u64) -> c_int {
    guard(|| {
        handles::with(sim, |s, entry| {
            let n = s.run_with(|| stop_if_destroyed(entry, "gsph_run"))?;
            unsafe { put(steps, "steps", n)? };
            Ok(())
        })
    })
}

/// Values per particle of the field `name`: an `api` name of the core's particle table
/// (position, velocity, mass, material, density, pressure, energy, sound_speed,
/// longitudinal_sound_speed, deviator, plastic_strain, damage, temperature, h,
/// reference_position, det_f) or the table's own (x, v, m, mat, rho, p, e, c, cl, s,
/// eps_p, temp, x0); docs/embedding.md.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_field_components(
    sim: *mut GsphSim,
    name: *const c_char,
    components: *mut usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let c = s.components(unsafe { cstr(name, "name")? })?;
            *unsafe { out(components, "components")? } = c;
            Ok(())
        })
    })
}

/// Copies the field `name` into `buf` (`len` = count x components doubles, id order).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_read_field(
    sim: *mut GsphSim,
    name: *const c_char,
    buf: *mut f64,
    len: usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let name = unsafe { cstr(name, "name")? };
            let buf = unsafe { slice_mut(buf, len, "buf")? };
            Ok(s.read(name, buf)?)
        })
    })
}

/// Sets the field `name` from `data` (`len` = count x components doubles, id order);
/// every value is checked before any is written. Pressure, sound speed and material are
/// read-only; writing density or energy updates pressure through the EOS.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_write_field(
    sim: *mut GsphSim,
    name: *const c_char,
    data: *const f64,
    len: usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let name = unsafe { cstr(name, "name")? };
            let data = unsafe { slice(data, len, "data")? };
            Ok(s.write(name, data)?)
        })
    })
}

/// Copies the particle ids into `ids` (`len` = count), in the order of every field.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_read_ids(sim: *mut GsphSim, ids: *mut u32, len: usize) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let buf = unsafe { slice_mut(ids, len, "ids")? };
            if len != s.len() {
                return Err(Failure::argument(format!(
                    "ids: buffer of {len} values, {} needed",
                    s.len()
                )));
            }
            buf.copy_from_slice(&s.ids());
            Ok(())
        })
    })
}

/// Sets the external acceleration, m/s² (`len` = count x dim, id order), applied in every
/// following step (half before, half after it) until set again; `len` 0 removes it.
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_set_acceleration(
    sim: *mut GsphSim,
    acceleration: *const f64,
    len: usize,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let a = unsafe { slice(acceleration, len, "acceleration")? };
            Ok(s.set_external_acceleration(a)?)
        })
    })
}

/// Kinetic and internal energy, J (either may be null).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_energy(
    sim: *mut GsphSim,
    kinetic: *mut f64,
    internal: *mut f64,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            let (k, i) = s.energy();
            unsafe { put(kinetic, "kinetic", k)? };
            unsafe { put(internal, "internal", i)? };
            Ok(())
        })
    })
}

/// Total momentum (3 doubles, unused components 0) and the momentum the external
/// accelerations added so far (3 doubles; may be null).
///
/// Thread safety: one call at a time per handle (GSPH_ERR_BUSY otherwise); distinct handles
/// in parallel.
#[no_mangle]
pub unsafe extern "C" fn gsph_momentum(
    sim: *mut GsphSim,
    momentum: *mut f64,
    external: *mut f64,
) -> c_int {
    guard(|| {
        handles::with(sim, |s, _| {
            unsafe { slice_mut(momentum, 3, "momentum")? }.copy_from_slice(&s.momentum());
            if !external.is_null() {
                unsafe { slice_mut(external, 3, "external")? }
                    .copy_from_slice(&s.external_impulse());
            }
            Ok(())
        })
    })
}
