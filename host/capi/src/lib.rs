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
//! - Pointers are checked for null and alignment, lengths against the particle count. A
//!   handle is a key into gsph's table of simulations, never dereferenced: a destroyed or
//!   foreign handle is refused (`handles.rs`).
//! - Fields are read and written in particle-id order, `components` values per particle
//!   (`gsph_field_components`), as `double`.
//! - Thread safety: a handle may move between threads; one call at a time per handle (a
//!   call while another is inside fails with [`GSPH_ERR_BUSY`]; [`gsph_destroy`] waits
//!   for the call inside, stopping a run after its step). Distinct handles may be stepped
//!   concurrently (they share one thread pool). [`gsph_last_error`] is per thread.
#![allow(clippy::missing_safety_doc)]

mod calls;
mod guard;
mod handles;
mod results;

use gsph_rs::api::{Particles, Simulation};
use guard::{cstr, guard, out, slice, strings, Failure};
use std::ffi::{c_char, c_int};
use std::path::Path;

pub use calls::*;
pub use guard::gsph_last_error;
pub use results::*;

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
/// The handle is in use by a call on another thread (one call at a time per handle), or
/// was destroyed by another thread during this call (a run or advance then stops after
/// its step).
pub const GSPH_ERR_BUSY: c_int = 7;

/// An opaque simulation handle: a key into gsph's table of simulations (`handles.rs`),
/// never dereferenced. C sees only `typedef struct gsph_sim gsph_sim;` (cbindgen.toml
/// `after_includes`).
///
/// cbindgen:ignore
#[repr(C)]
pub struct GsphSim {
    _opaque: [u8; 0],
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

unsafe fn create(
    out_sim: *mut *mut GsphSim,
    f: impl FnOnce() -> Result<Simulation, Failure>,
) -> c_int {
    guard(|| {
        let slot = unsafe { out(out_sim, "out")? };
        *slot = std::ptr::null_mut();
        *slot = handles::register(f()?)?;
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

/// Sets the number of worker threads of the process-wide pool (0: one per core; at most
/// 8 per core, as `gsph run --threads`). Only before the first simulation is created;
/// later calls fail.
///
/// Thread safety: any thread; once, before the first simulation is created.
#[no_mangle]
pub extern "C" fn gsph_set_threads(threads: usize) -> c_int {
    guard(|| {
        if threads > 0 {
            gsph_rs::exec::check_threads(threads)
                .map_err(|e| Failure::argument(format!("threads {threads}: {e}")))?;
        }
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

/// Creates a simulation from a scene file, with `n_overrides` overrides applied in order
/// (`overrides` may be null when 0): `KEY=VALUE` sets a key (as `gsph run --set`),
/// `unset:KEY` removes one (as `gsph run --unset KEY`). `*out` is the new handle, or null
/// on error.
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

/// Creates a simulation from scene text (TOML, as a scene file), with overrides
/// (`KEY=VALUE`, `unset:KEY`).
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
/// `bodies` (dim, scheme, t_end, materials, options), with overrides (`KEY=VALUE`,
/// `unset:KEY`).
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

/// Destroys a simulation. Null, and a handle destroyed before, are ignored. A call inside
/// the simulation on another thread is waited for (a `gsph_run` or `gsph_advance` stops
/// after its step and returns GSPH_ERR_BUSY); then the memory is freed. Later calls with
/// the handle fail with GSPH_ERR_POINTER.
///
/// Thread safety: any thread, also while another thread is inside a call on the handle.
#[no_mangle]
pub unsafe extern "C" fn gsph_destroy(sim: *mut GsphSim) {
    if sim.is_null() {
        return;
    }
    // not through `guard`: destroying leaves the thread's last message as it was
    let _ = std::panic::catch_unwind(|| handles::destroy(sim));
}

#[cfg(test)]
mod tests;
