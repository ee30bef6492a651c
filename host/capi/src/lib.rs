//! The C ABI of gsph: `host/include/gsph.h` (generated from this crate by cbindgen and
//! checked in; the test `header_is_current` fails when it is stale). Built into
//! `libgsph.so` and `libgsph.a` (`cargo build --release -p gsph-capi`); see
//! docs/embedding.md.
//!
//! Conventions:
//! - Every function but [`gsph_version`], [`gsph_last_error`] and [`gsph_destroy`]
//!   returns a status: [`GSPH_OK`] (0) or an error code, with a one-line message for
//!   [`gsph_last_error`] on the calling thread.
//! - No panic crosses the boundary: one is caught and reported as [`GSPH_ERR_INTERNAL`].
//! - Pointers are checked for null and alignment, lengths against the particle count; a
//!   handle carries a tag that catches most stale or foreign pointers (not all: a
//!   destroyed handle must not be used).
//! - Fields are read and written in particle-id order, `components` values per particle
//!   (`gsph_field_components`), as `double`.
//! - Thread safety: a handle may move between threads but must not be used by two
//!   threads at once; distinct handles may be stepped concurrently (they share one
//!   thread pool). [`gsph_last_error`] is per thread.
#![allow(clippy::missing_safety_doc)]

mod guard;

use gsph_rs::api::{Particles, Simulation};
use guard::{cstr, guard, out, put, slice, slice_mut, strings, Failure};
use std::ffi::{c_char, c_int};
use std::path::Path;

pub use guard::gsph_last_error;

/// Success.
pub const GSPH_OK: c_int = 0;
/// A null, misaligned or foreign pointer, or a length that does not fit.
pub const GSPH_ERR_POINTER: c_int = 1;
/// A bad argument: unknown field, wrong buffer length, non-finite value, bad dt.
pub const GSPH_ERR_ARGUMENT: c_int = 2;
/// The scene (text, file or overrides) is invalid; the message names the key.
pub const GSPH_ERR_SCENE: c_int = 3;
/// The simulation failed (a step, a neighbour overflow); the message names step and particle.
pub const GSPH_ERR_SIMULATION: c_int = 4;
/// A snapshot or checkpoint could not be written, or a checkpoint read (a scene file
/// that cannot be read is a GSPH_ERR_SCENE).
pub const GSPH_ERR_IO: c_int = 5;
/// A bug in gsph (a caught panic); the message says where.
pub const GSPH_ERR_INTERNAL: c_int = 6;

const TAG: u64 = 0x6773_7068_2d73_696d; // "gsph-sim"

/// An opaque simulation handle: a tag at offset 0, read before the handle is trusted.
/// C sees only `typedef struct gsph_sim gsph_sim;` (cbindgen.toml `after_includes`).
///
/// cbindgen:ignore
#[repr(C)]
pub struct GsphSim {
    tag: u64,
    sim: Box<Simulation>,
}

/// Particles given by the caller to [`gsph_create_from_particles`]. Vectors hold `dim`
/// values per particle; optional arrays may be null.
#[repr(C)]
pub struct GsphParticles {
    /// Number of particles.
    pub count: usize,
    /// Positions, m (`count * dim`).
    pub position: *const f64,
    /// Velocities, m/s (`count * dim`; null: at rest).
    pub velocity: *const f64,
    /// Densities, kg/m³ (`count`; null: the material's `rho0`).
    pub density: *const f64,
    /// Specific internal energies, J/kg (`count`; null: 0).
    pub energy: *const f64,
    /// Masses, kg (`count`; null: `density * spacing^dim`).
    pub mass: *const f64,
    /// Material index of each particle into the settings' `[[materials]]` (`count`).
    pub material: *const u32,
    /// Lattice spacing, m: `spacing_count` values, `count` or 1.
    pub spacing: *const f64,
    /// Values in `spacing`.
    pub spacing_count: usize,
}

unsafe fn handle<'a>(p: *mut GsphSim) -> Result<&'a mut Simulation, Failure> {
    if p.is_null() {
        return Err(Failure::pointer("sim: null handle"));
    }
    if !p.is_aligned() {
        return Err(Failure::pointer("sim: misaligned handle"));
    }
    // SAFETY: non-null and aligned; the caller promises at least a readable u64 there (a
    // live handle from gsph_create_* is a GsphSim, tag first). The tag is read alone,
    // before any reference to a GsphSim is formed, and catches most foreign or destroyed
    // pointers.
    let tag = unsafe { std::ptr::read_volatile(p.cast::<u64>()) };
    if tag != TAG {
        return Err(Failure::pointer(
            "sim: not a live gsph handle (destroyed, or not from gsph_create_*)",
        ));
    }
    // SAFETY: the tag says this is a live GsphSim from Box::into_raw.
    Ok(unsafe { &mut *(*p).sim })
}

unsafe fn create(
    out_sim: *mut *mut GsphSim,
    f: impl FnOnce() -> Result<Simulation, Failure>,
) -> c_int {
    guard(|| {
        let slot = unsafe { out(out_sim, "out")? };
        *slot = std::ptr::null_mut();
        let sim = f()?;
        *slot = Box::into_raw(Box::new(GsphSim {
            tag: TAG,
            sim: Box::new(sim),
        }));
        Ok(())
    })
}

/// The gsph version, a static string. Any thread.
///
/// Thread safety: any thread, any time.
#[no_mangle]
pub extern "C" fn gsph_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// Sets the number of worker threads of the process-wide pool (0: one per core). Only
/// before the first simulation is created; later calls fail. Any thread.
///
/// Thread safety: any thread; once, before the first simulation is created.
#[no_mangle]
pub extern "C" fn gsph_set_threads(threads: usize) -> c_int {
    guard(|| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .map_err(|e| {
                Failure::argument(format!(
                    "threads: {e} (call gsph_set_threads before creating a simulation)"
                ))
            })
    })
}

/// Creates a simulation from a scene file, with `n_overrides` overrides `KEY=VALUE` (as
/// `gsph run --set`; may be null when 0). `*out` is the new handle, or null on error.
///
/// Thread safety: any thread, concurrently with other calls; the new handle belongs to the caller.
#[no_mangle]
pub unsafe extern "C" fn gsph_create_from_file(
    path: *const c_char,
    overrides: *const *const c_char,
    n_overrides: usize,
    out: *mut *mut GsphSim,
) -> c_int {
    unsafe {
        create(out, || {
            let path = cstr(path, "path")?;
            let set = strings(overrides, n_overrides, "overrides")?;
            Ok(Simulation::from_file(Path::new(path), &set)?)
        })
    }
}

/// Creates a simulation from scene text (TOML, as a scene file), with overrides.
///
/// Thread safety: any thread, concurrently with other calls; the new handle belongs to the caller.
#[no_mangle]
pub unsafe extern "C" fn gsph_create_from_text(
    text: *const c_char,
    overrides: *const *const c_char,
    n_overrides: usize,
    out: *mut *mut GsphSim,
) -> c_int {
    unsafe {
        create(out, || {
            let text = cstr(text, "text")?;
            let set = strings(overrides, n_overrides, "overrides")?;
            Ok(Simulation::from_text(text, "scene text", &set)?)
        })
    }
}

/// Creates a simulation of the caller's particles: `settings` is scene text without
/// `bodies` (dim, scheme, t_end, materials, options).
///
/// Thread safety: any thread, concurrently with other calls; the new handle belongs to the caller.
#[no_mangle]
pub unsafe extern "C" fn gsph_create_from_particles(
    settings: *const c_char,
    overrides: *const *const c_char,
    n_overrides: usize,
    particles: *const GsphParticles,
    out: *mut *mut GsphSim,
) -> c_int {
    unsafe {
        create(out, || {
            let text = cstr(settings, "settings")?;
            let set = strings(overrides, n_overrides, "overrides")?;
            let scene = gsph_rs::scene::parse_settings(text, "settings", &set)
                .map_err(|e| Failure::scene(e.to_string()))?;
            let p = guard::get(particles, "particles")?;
            let (n, d) = (p.count, scene.dim);
            let opt = |ptr: *const f64, len: usize, name: &str| -> Result<&[f64], Failure> {
                if ptr.is_null() {
                    Ok(&[])
                } else {
                    slice(ptr, len, name)
                }
            };
            let parts = Particles {
                position: slice(p.position, n * d, "particles.position")?,
                velocity: opt(p.velocity, n * d, "particles.velocity")?,
                density: opt(p.density, n, "particles.density")?,
                energy: opt(p.energy, n, "particles.energy")?,
                mass: opt(p.mass, n, "particles.mass")?,
                material: slice(p.material, n, "particles.material")?,
                spacing: slice(p.spacing, p.spacing_count, "particles.spacing")?,
            };
            Ok(Simulation::from_particles(text, "settings", &set, &parts)?)
        })
    }
}

/// Continues a simulation from a checkpoint written by [`gsph_write_checkpoint`].
///
/// Thread safety: any thread, concurrently with other calls; the new handle belongs to the caller.
#[no_mangle]
pub unsafe extern "C" fn gsph_create_from_checkpoint(
    dir: *const c_char,
    out: *mut *mut GsphSim,
) -> c_int {
    unsafe {
        create(out, || {
            Ok(Simulation::from_checkpoint(Path::new(cstr(dir, "dir")?))?)
        })
    }
}

/// Destroys a simulation (null is ignored). The handle must not be used afterwards.
///
/// Thread safety: not concurrently with any other call on the same handle.
#[no_mangle]
pub unsafe extern "C" fn gsph_destroy(sim: *mut GsphSim) {
    if sim.is_null() {
        return;
    }
    // not through `guard`: destroying leaves the thread's last message as it was
    let _ = std::panic::catch_unwind(|| {
        if unsafe { handle(sim) }.is_err() {
            return;
        }
        // SAFETY: a live handle from Box::into_raw (checked above). The tag is cleared
        // (a volatile write the optimiser keeps) so that a second destroy of the pointer
        // is caught while the freed memory still holds it.
        unsafe { std::ptr::write_volatile(sim.cast::<u64>(), 0) };
        drop(unsafe { Box::from_raw(sim) });
    });
}

/// Dimension of the simulation (1, 2, 3).
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_dim(sim: *mut GsphSim, dim: *mut usize) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        *unsafe { out(dim, "dim")? } = s.dim();
        Ok(())
    })
}

/// Number of particles.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_count(sim: *mut GsphSim, count: *mut usize) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        *unsafe { out(count, "count")? } = s.len();
        Ok(())
    })
}

/// Simulated time, s, and steps taken (either output may be null).
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_time(sim: *mut GsphSim, t: *mut f64, steps: *mut u64) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        unsafe { put(t, "t", s.time())? };
        unsafe { put(steps, "steps", s.steps())? };
        Ok(())
    })
}

/// The time step the scene's rule gives now (its fixed `dt`, or the CFL step), s.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_stable_dt(sim: *mut GsphSim, dt: *mut f64) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let slot = unsafe { out(dt, "dt")? };
        *slot = s.stable_dt()?;
        Ok(())
    })
}

/// The scene's end time `t_end`, s, and its snapshot count (the times `t_end k /
/// snapshots` that [`gsph_run`] lands on); either output may be null.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_schedule(
    sim: *mut GsphSim,
    t_end: *mut f64,
    snapshots: *mut usize,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        unsafe { put(t_end, "t_end", s.scene().t_end)? };
        unsafe { put(snapshots, "snapshots", s.scene().output.snapshots)? };
        Ok(())
    })
}

/// Takes one step: `dt` > 0 is the step (refused above the CFL-1 limit), `dt` = 0 takes
/// the scene's rule. `dt_taken` (may be null) receives the step taken.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_step(sim: *mut GsphSim, dt: f64, dt_taken: *mut f64) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let taken = s.step((dt != 0.0).then_some(dt))?;
        unsafe { put(dt_taken, "dt_taken", taken)? };
        Ok(())
    })
}

/// Steps until time `t`, the last step shortened to land on it. `steps` (may be null)
/// receives the number of steps taken.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_advance(sim: *mut GsphSim, t: f64, steps: *mut u64) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let n = s.advance_to(t)?;
        unsafe { put(steps, "steps", n)? };
        Ok(())
    })
}

/// Runs to the scene's `t_end` through its snapshot times: the steps of `gsph run`.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_run(sim: *mut GsphSim, steps: *mut u64) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let n = s.run()?;
        unsafe { put(steps, "steps", n)? };
        Ok(())
    })
}

/// Values per particle of the field `name` (position, velocity, mass, density, pressure,
/// energy, sound_speed, deviator, plastic_strain, damage, temperature, h, material; or
/// the short names of final.csv: x, v, m, rho, p, e, c, s, eps_p, temp).
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_field_components(
    sim: *mut GsphSim,
    name: *const c_char,
    components: *mut usize,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let c = s.components(unsafe { cstr(name, "name")? })?;
        *unsafe { out(components, "components")? } = c;
        Ok(())
    })
}

/// Copies the field `name` into `buf` (`len` = count x components doubles, id order).
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_read_field(
    sim: *mut GsphSim,
    name: *const c_char,
    buf: *mut f64,
    len: usize,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let name = unsafe { cstr(name, "name")? };
        let buf = unsafe { slice_mut(buf, len, "buf")? };
        Ok(s.read(name, buf)?)
    })
}

/// Sets the field `name` from `data` (`len` = count x components doubles, id order);
/// every value is checked before any is written. Pressure, sound speed and material are
/// read-only; writing density or energy updates pressure through the EOS.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_write_field(
    sim: *mut GsphSim,
    name: *const c_char,
    data: *const f64,
    len: usize,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let name = unsafe { cstr(name, "name")? };
        let data = unsafe { slice(data, len, "data")? };
        Ok(s.write(name, data)?)
    })
}

/// Copies the particle ids into `ids` (`len` = count), in the order of every field.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_read_ids(sim: *mut GsphSim, ids: *mut u32, len: usize) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
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
}

/// Sets the external acceleration, m/s² (`len` = count x dim, id order), applied in every
/// following step (half before, half after it) until set again; `len` 0 removes it.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_set_acceleration(
    sim: *mut GsphSim,
    acceleration: *const f64,
    len: usize,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let a = unsafe { slice(acceleration, len, "acceleration")? };
        Ok(s.set_external_acceleration(a)?)
    })
}

/// Kinetic and internal energy, J (either may be null).
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_energy(
    sim: *mut GsphSim,
    kinetic: *mut f64,
    internal: *mut f64,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let (k, i) = s.energy();
        unsafe { put(kinetic, "kinetic", k)? };
        unsafe { put(internal, "internal", i)? };
        Ok(())
    })
}

/// Total momentum (3 doubles, unused components 0) and the momentum the external
/// accelerations added so far (3 doubles; may be null).
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_momentum(
    sim: *mut GsphSim,
    momentum: *mut f64,
    external: *mut f64,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        unsafe { slice_mut(momentum, 3, "momentum")? }.copy_from_slice(&s.momentum());
        if !external.is_null() {
            unsafe { slice_mut(external, 3, "external")? }.copy_from_slice(&s.external_impulse());
        }
        Ok(())
    })
}

/// The summary as JSON (NUL-terminated) into `buf` of `len` bytes; `needed` (may be null)
/// receives the length including the NUL. A `buf` too small (or null with `len` 0) gets
/// nothing and the call fails with GSPH_ERR_ARGUMENT, `needed` set: call again.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_summary_json(
    sim: *mut GsphSim,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        let text = serde_json::Value::Object(s.summary()).to_string();
        let need = text.len() + 1;
        unsafe { put(needed, "needed", need)? };
        if len < need {
            return Err(Failure::argument(format!(
                "buf: {len} bytes, the summary needs {need}"
            )));
        }
        let b = unsafe { slice_mut(buf.cast::<u8>(), len, "buf")? };
        b[..text.len()].copy_from_slice(text.as_bytes());
        b[text.len()] = 0;
        Ok(())
    })
}

/// Writes the state as a CSV file with the columns of `gsph run`'s final.csv.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_write_snapshot(sim: *mut GsphSim, path: *const c_char) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        Ok(s.write_snapshot(Path::new(unsafe { cstr(path, "path")? }))?)
    })
}

/// Writes a checkpoint into the directory `dir` (created if missing), from which
/// [`gsph_create_from_checkpoint`] continues bitwise identically.
///
/// Thread safety: one thread at a time per handle (distinct handles in parallel are fine).
#[no_mangle]
pub unsafe extern "C" fn gsph_write_checkpoint(sim: *mut GsphSim, dir: *const c_char) -> c_int {
    guard(|| {
        let s = unsafe { handle(sim)? };
        Ok(s.write_checkpoint(Path::new(unsafe { cstr(dir, "dir")? }))?)
    })
}

#[cfg(test)]
mod tests;
