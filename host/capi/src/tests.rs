//! The C boundary from Rust: every pointer check, the thread-local message, a scene error
//! through the ABI, and the header against the code.

use super::*;
use std::ffi::{CStr, CString};
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
