//! Input files that would pull data from elsewhere or cost more than they hold (issue 25,
//! items 2 and 3), through the real `gsph` binary: HDF5 files with external storage,
//! virtual datasets, external links or a filter plugin are refused naming the dataset; a
//! file declaring more than it holds (an HDF5 dataset, a CSV or STL without line breaks, an
//! STL header) is refused in one line, in bounded memory and time.

mod io_common;

use io_common::*;

// ----- item 2: HDF5 files read only from themselves --------------------------------

#[test]
fn hdf5_data_from_outside_the_file_or_through_a_plugin_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), PARTICLES_1D).unwrap();
    // the control: the file as written reads
    std::fs::copy(snapshot_file(d, "good.h5"), d.join("p.h5")).unwrap();
    assert!(ok(d, &["check", "scene.toml"]).contains("particles 10"));

    // external storage: the values of `rho` in another file (a secret of the user's)
    let secret = d.join("secret.bin");
    let bytes: Vec<u8> = (0..10).flat_map(|_| 2700.0f64.to_le_bytes()).collect();
    std::fs::write(&secret, &bytes).unwrap();
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, _| {
        g.new_dataset::<f64>()
            .shape(10)
            .external(secret.to_str().unwrap(), 0, 80)
            .create(name)
            .unwrap();
    });
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: stored in an external file; gsph reads data stored in the file itself",
    );

    // a virtual dataset mapping another file's dataset
    let src = snapshot_file(d, "src.h5");
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, _| {
        g.new_dataset::<f64>()
            .shape(10)
            .virtual_map(src.to_str().unwrap(), "/step_000000/rho", 10, .., 10, ..)
            .create(name)
            .unwrap();
    });
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: a virtual dataset",
    );

    // a filter other than deflate and shuffle
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, rho| {
        g.new_dataset_builder()
            .with_data(rho)
            .chunk(10)
            .fletcher32()
            .create(name)
            .unwrap();
    });
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: filter fletcher32 (id 3); gsph reads data compressed with deflate (gzip) and shuffle only",
    );

    // a filter no library has: HDF5 would look for a plugin to decode it
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, _| optional_unknown_filter(g, name, 10));
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: filter (a plugin) (id 32100)",
    );

    // an external link in place of the snapshot's group
    let p = snapshot_file(d, "p.h5");
    {
        let _h5 = h5_lock();
        let f = hdf5::File::open_rw(&p).unwrap();
        f.unlink("step_000000").unwrap();
        f.link_external(src.to_str().unwrap(), "step_000000", "step_000000")
            .unwrap();
    }
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000: a link to another file",
    );

    // gsph plot particles reads the same way
    let run = d.join("run");
    std::fs::create_dir(&run).unwrap();
    std::fs::copy(d.join("p.h5"), run.join("snapshots.h5")).unwrap();
    refused(
        d,
        &["plot", "particles", "run", "--field", "rho"],
        "a link to another file",
    );
}

/// Dataset `name` of `n` f64 in `g`, chunked, with the optional filter 32100 (which no
/// library registers; HDF5 accepts an optional filter it cannot apply).
fn optional_unknown_filter(g: &hdf5::Group, name: &str, n: usize) {
    use hdf5_sys::{h5d, h5p, h5z};
    let dcpl = hdf5::plist::DatasetCreate::build()
        .chunk(n)
        .finish()
        .unwrap();
    let space = hdf5::Dataspace::try_new(n).unwrap();
    let dtype = hdf5::Datatype::from_type::<f64>().unwrap();
    let cname = std::ffi::CString::new(name).unwrap();
    // SAFETY: valid identifiers of live objects; the dataset id is closed at once
    unsafe {
        assert!(
            h5p::H5Pset_filter(
                dcpl.id(),
                32100,
                h5z::H5Z_FLAG_OPTIONAL,
                0,
                std::ptr::null()
            ) >= 0
        );
        let ds = h5d::H5Dcreate2(
            g.id(),
            cname.as_ptr(),
            dtype.id(),
            space.id(),
            h5p::H5P_DEFAULT,
            dcpl.id(),
            h5p::H5P_DEFAULT,
        );
        assert!(ds >= 0);
        h5d::H5Dclose(ds);
    }
}

// ----- item 3: bounded memory on any input -----------------------------------------

#[test]
fn hdf5_files_declaring_more_than_they_hold_are_refused_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), PARTICLES_1D).unwrap();
    let p = bomb(d, "p.h5", 1 << 33, false);
    assert!(std::fs::metadata(&p).unwrap().len() < 1 << 20);
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "/step_000000/id: 8589934592 particles, more than the scene's limit 1e8 (`max_particles` raises it)",
        10,
    );
    // under the particle limit, but not in the file
    bomb(d, "p.h5", 50_000_000, false);
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "/step_000000/id: declares 50000000 values (200000000 bytes), more than the file holds for it",
        10,
    );
    bomb(d, "p.h5", 50_000_000, true);
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "more than the file holds for it",
        10,
    );
    // gsph plot particles
    let run = d.join("run");
    std::fs::create_dir(&run).unwrap();
    std::fs::rename(bomb(d, "b.h5", 1 << 33, false), run.join("snapshots.h5")).unwrap();
    refused_cheaply(
        d,
        &["plot", "particles", "run", "--field", "rho"],
        // no scene, so no particle limit: the memory the reading would need
        "8589934592 particles need about",
        10,
    );
    // a restart (its checkpoint.h5 replaced)
    let scene = flyer(d);
    let mut args = run_args(scene.to_str().unwrap(), "ck");
    args.extend(["--stop-after-steps", "3"]);
    ok(d, &args);
    let c = bomb(d, "c.h5", 1 << 33, false);
    // of the checkpoint's run (a restart refuses another run's snapshots before it reads)
    let id = gsph::checkpoint::Checkpoint::read(&d.join("ck"))
        .unwrap()
        .run_id;
    {
        let _h5 = h5_lock();
        let f = hdf5::File::open_rw(&c).unwrap();
        f.delete_attr("run_id").unwrap();
        let v: hdf5::types::VarLenUnicode = id.parse().unwrap();
        f.new_attr::<hdf5::types::VarLenUnicode>()
            .create("run_id")
            .unwrap()
            .write_scalar(&v)
            .unwrap();
    }
    std::fs::rename(c, d.join("ck/checkpoint.h5")).unwrap();
    refused_cheaply(
        d,
        &["run", "--restart", "ck", "--quiet"],
        "8589934592 particles, more than the scene's limit 1e8 (`max_particles` raises it)",
        10,
    );
}

#[test]
fn a_huge_csv_without_line_breaks_is_refused_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut text = PARTICLES_1D.replace("p.h5", "big.csv");
    text.push_str("spacing = 1e-4\n");
    std::fs::write(d.join("scene.toml"), text).unwrap();
    // 12 GB, sparse: "x,m," then zeros, no line break
    let f = std::fs::File::create(d.join("big.csv")).unwrap();
    std::io::Write::write_all(&mut &f, b"x,m,").unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.csv: line 1: longer than 65536 bytes",
        10,
    );
}

#[test]
fn huge_stl_files_are_refused_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = "dim = 3\nscheme = \"pm\"\nt_end = 1e-7\n[[materials]]\nname = \"al\"\nrho0 = 2700.0\neos = { type = \"linear\", c0 = 5000.0 }\n[[bodies]]\nmaterial = \"al\"\nshape = { type = \"stl\", file = \"big.stl\" }\nspacing = 1e-4\n";
    std::fs::write(d.join("scene.toml"), scene).unwrap();
    // ASCII: a first line of 12 GB
    let f = std::fs::File::create(d.join("big.stl")).unwrap();
    std::io::Write::write_all(&mut &f, b"solid big ").unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.stl: line 1: longer than 65536 bytes",
        10,
    );
    // ASCII: a facet line of 12 GB
    let f = std::fs::File::create(d.join("big.stl")).unwrap();
    std::io::Write::write_all(&mut &f, b"solid big\nfacet normal 0 0 0").unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "facet 0: line 2: longer than 65536 bytes",
        10,
    );
    // binary: a header declaring 4e9 facets
    let mut head = vec![0u8; 84];
    head[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    std::fs::write(d.join("big.stl"), &head).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.stl: the header declares 4294967295 facets, more than the limit 1e8",
        10,
    );
    // binary, 12 GB of facets streamed: the first one is refused
    let f = std::fs::File::create(d.join("big.stl")).unwrap();
    head[80..84].copy_from_slice(&100_000_000u32.to_le_bytes());
    std::io::Write::write_all(&mut &f, &head).unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.stl: facet 0: zero area",
        10,
    );
}
