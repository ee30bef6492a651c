//! The C boundary from Rust: every pointer check, the thread-local message, a scene error
//! through the ABI, two threads on one handle, the thread cap, and the header against the
//! code.

use super::*;
use std::ffi::{c_char, CStr, CString};
use std::path::Path;

fn case(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../cases")
        .join(name)
}

fn last_error() -> String {
    unsafe { CStr::from_ptr(gsph_last_error()) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn c_abi_checks_every_pointer() {
    unsafe {
        let path = CString::new(case("flyer_plate.toml").to_str().unwrap()).unwrap();
        let mut sim: *mut GsphSim = std::ptr::null_mut();
        assert_eq!(
            gsph_create_from_file(path.as_ptr(), std::ptr::null(), 0, &mut sim),
            GSPH_OK
        );
        assert_eq!(last_error(), "");
        let mut n = 0usize;
        assert_eq!(gsph_count(sim, &mut n), GSPH_OK);
        assert_eq!(n, 100);
        // null handle, null output, null name
        assert_eq!(gsph_count(std::ptr::null_mut(), &mut n), GSPH_ERR_POINTER);
        assert_eq!(last_error(), "sim: null handle");
        assert_eq!(gsph_count(sim, std::ptr::null_mut()), GSPH_ERR_POINTER);
        assert_eq!(last_error(), "count: null pointer");
        let mut buf = vec![0.0f64; 101];
        assert_eq!(
            gsph_read_field(sim, std::ptr::null(), buf.as_mut_ptr(), 100),
            GSPH_ERR_POINTER
        );
        // misaligned buffer
        let name = CString::new("rho").unwrap();
        let bytes = buf.as_mut_ptr().cast::<u8>().add(1).cast::<f64>();
        assert_eq!(
            gsph_read_field(sim, name.as_ptr(), bytes, 100),
            GSPH_ERR_POINTER
        );
        assert!(last_error().contains("misaligned"));
        // wrong length, then the right one
        assert_eq!(
            gsph_read_field(sim, name.as_ptr(), buf.as_mut_ptr(), 101),
            GSPH_ERR_ARGUMENT
        );
        assert_eq!(
            gsph_read_field(sim, name.as_ptr(), buf.as_mut_ptr(), 100),
            GSPH_OK
        );
        assert_eq!(buf[0], 6100.0);
        // not UTF-8
        let bad = [0xffu8, 0];
        assert_eq!(
            gsph_read_field(sim, bad.as_ptr().cast(), buf.as_mut_ptr(), 100),
            GSPH_ERR_ARGUMENT
        );
        assert!(last_error().starts_with("name: not UTF-8"));
        // a scene error names the key; the out handle is null
        let set = CString::new("t_end=-1").unwrap();
        let sets = [set.as_ptr()];
        let mut other: *mut GsphSim = std::ptr::dangling_mut::<GsphSim>();
        assert_eq!(
            gsph_create_from_file(path.as_ptr(), sets.as_ptr(), 1, &mut other),
            GSPH_ERR_SCENE
        );
        assert!(other.is_null());
        assert!(last_error().contains("t_end"), "{}", last_error());
        // a foreign pointer is caught by the tag
        let mut junk = [0u64; 64];
        assert_eq!(
            gsph_count(junk.as_mut_ptr().cast(), &mut n),
            GSPH_ERR_POINTER
        );
        assert!(last_error().contains("not a live gsph handle"));
        // the error is per thread
        std::thread::spawn(|| assert_eq!(last_error(), ""))
            .join()
            .unwrap();
        let mut dt = 0.0;
        assert_eq!(gsph_step(sim, 0.0, &mut dt), GSPH_OK);
        assert!(dt > 0.0);
        let mut need = 0usize;
        assert_eq!(
            gsph_summary_json(sim, std::ptr::null_mut(), 0, &mut need),
            GSPH_ERR_ARGUMENT
        );
        let mut text = vec![0u8; need];
        assert_eq!(
            gsph_summary_json(sim, text.as_mut_ptr().cast(), need, &mut need),
            GSPH_OK
        );
        let json: serde_json::Value =
            serde_json::from_str(CStr::from_bytes_with_nul(&text).unwrap().to_str().unwrap())
                .unwrap();
        assert_eq!(json["steps"], 1);
        gsph_destroy(sim);
        gsph_destroy(std::ptr::null_mut());
    }
}

fn create(overrides: &[&str]) -> *mut GsphSim {
    let path = CString::new(case("flyer_plate.toml").to_str().unwrap()).unwrap();
    let sets: Vec<CString> = overrides
        .iter()
        .map(|s| CString::new(*s).unwrap())
        .collect();
    let ptrs: Vec<*const c_char> = sets.iter().map(|s| s.as_ptr()).collect();
    let mut sim: *mut GsphSim = std::ptr::null_mut();
    let rc = unsafe { gsph_create_from_file(path.as_ptr(), ptrs.as_ptr(), ptrs.len(), &mut sim) };
    assert_eq!(rc, GSPH_OK, "{}", last_error());
    sim
}

/// A handle as a number, to hand to another thread.
#[derive(Clone, Copy)]
struct Handle(usize);

impl Handle {
    fn of(sim: *mut GsphSim) -> Self {
        Handle(sim.addr())
    }
    fn sim(self) -> *mut GsphSim {
        std::ptr::without_provenance_mut(self.0)
    }
}

/// Destroying a handle while another thread steps it ends the stepping thread with a
/// refusal, never a crash or a call on freed memory (before the handle table: 4 crashes in
/// 8 tries); the handle stays refused after, and a second destroy is ignored.
#[test]
fn destroy_racing_a_stepping_thread_is_refused_not_a_crash() {
    for k in 0..8u64 {
        let h = Handle::of(create(&[]));
        let stepper = std::thread::spawn(move || {
            let mut steps = 0u64;
            loop {
                let rc = unsafe { gsph_step(h.sim(), 0.0, std::ptr::null_mut()) };
                if rc != GSPH_OK {
                    return (rc, last_error(), steps);
                }
                steps += 1;
            }
        });
        std::thread::sleep(std::time::Duration::from_millis(2 + 3 * k));
        unsafe { gsph_destroy(h.sim()) };
        let (rc, msg, steps) = stepper.join().unwrap();
        assert!(
            (rc == GSPH_ERR_POINTER && msg.contains("not a live gsph handle"))
                || (rc == GSPH_ERR_BUSY && msg.contains("in use")),
            "try {k}: {rc} {msg} after {steps} steps"
        );
        let mut n = 0usize;
        assert_eq!(unsafe { gsph_count(h.sim(), &mut n) }, GSPH_ERR_POINTER);
        unsafe { gsph_destroy(h.sim()) };
    }
}

/// A call while another thread is inside the handle fails with GSPH_ERR_BUSY; destroying
/// the handle stops a long gsph_run after its step (it returns GSPH_ERR_BUSY), and destroy
/// waits only for that step.
#[test]
fn a_busy_handle_refuses_and_destroy_stops_a_run() {
    // about 1.4e6 steps: a minute or more
    let h = Handle::of(create(&["t_end=1e-2", "output.snapshots=1"]));
    let t0 = std::time::Instant::now();
    let runner = std::thread::spawn(move || loop {
        let mut steps = 0u64;
        let rc = unsafe { gsph_run(h.sim(), &mut steps) };
        // the main thread's gsph_count may hold the handle as the run starts: try again
        if rc == GSPH_ERR_BUSY && last_error().contains("in use") {
            std::thread::sleep(std::time::Duration::from_millis(1));
            continue;
        }
        return (rc, last_error());
    });
    let mut n = 0usize;
    let busy = loop {
        let rc = unsafe { gsph_count(h.sim(), &mut n) };
        if rc != GSPH_OK || t0.elapsed().as_secs_f64() > 20.0 {
            break rc;
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
    };
    assert_eq!(busy, GSPH_ERR_BUSY, "{}", last_error());
    assert_eq!(
        last_error(),
        "sim: in use by a call on another thread (one call at a time per handle)"
    );
    std::thread::sleep(std::time::Duration::from_millis(50));
    let t1 = std::time::Instant::now();
    unsafe { gsph_destroy(h.sim()) };
    let waited = t1.elapsed().as_secs_f64();
    let (rc, msg) = runner.join().unwrap();
    assert_eq!(rc, GSPH_ERR_BUSY, "{msg}");
    assert!(
        msg.starts_with("gsph_run: the handle was destroyed by another thread"),
        "{msg}"
    );
    assert!(waited < 1.0, "destroy waited {waited} s");
    assert!(t0.elapsed().as_secs_f64() < 20.0);
}

/// `gsph_set_threads` has the cap of `gsph run --threads` (was: 100000 threads spawned).
#[test]
fn set_threads_is_capped_as_the_cli() {
    assert_eq!(gsph_set_threads(100_000), GSPH_ERR_ARGUMENT);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let per_core = gsph_rs::exec::MAX_THREADS_PER_CORE;
    assert_eq!(
        last_error(),
        format!(
            "threads 100000: this machine has {cores} cores; more than {per_core} threads per core ({}) only slows a run down",
            per_core * cores
        )
    );
}

/// host/include/gsph.h is what cbindgen generates from this crate now: fails when the
/// checked-in header is stale; `UPDATE_HEADER=1 cargo test -p gsph-capi` rewrites it.
#[test]
fn header_is_current() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config =
        cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(crate_dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen parses host/capi/src")
        .write(&mut generated);
    let header = crate_dir.join("../include/gsph.h");
    if std::env::var_os("UPDATE_HEADER").is_some() {
        std::fs::write(&header, &generated).unwrap();
        return;
    }
    let current = std::fs::read(&header).unwrap_or_default();
    assert!(
        current == generated,
        "host/include/gsph.h is stale: run `UPDATE_HEADER=1 cargo test -p gsph-capi` and commit it"
    );
}
