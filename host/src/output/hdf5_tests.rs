//! Tests of the snapshot writer (`hdf5.rs`) and its reader (`hdf5_read.rs`).

use super::super::hdf5_read::{read_frame, read_run_info, read_snapshot_times};
use super::super::meta::{cauchy_stress, von_mises};
use super::super::table::tests::sample_table;
use super::super::table::BASE_COLUMNS;
use super::super::xdmf::check_balanced_tags;
use super::*;

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn frame(step: u64, time: f64, n: usize) -> Frame {
    Frame {
        time,
        step,
        dim: 2,
        table: sample_table(n, step as f64),
    }
}

fn info() -> RunInfo {
    RunInfo {
        name: "impact".into(),
        scene: "dim = 2\nscheme = \"ts2\"  # ü <&>\n".into(),
        overrides: vec!["t_end=1e-7".into(), "bodies.0.spacing=5e-4".into()],
        scheme: "ts2".into(),
        effects: vec!["strength".into(), "damage".into()],
        materials: vec!["steel".into(), "sic".into(), "al".into()],
        run_id: "0123456789abcdef".into(),
    }
}

fn writer(dir: &Path) -> SnapshotWriter {
    SnapshotWriter::create(dir, 2, &info()).unwrap()
}

fn read_str(a: hdf5::Attribute) -> String {
    a.read_scalar::<hdf5::types::VarLenUnicode>()
        .unwrap()
        .as_str()
        .to_owned()
}

fn partial_xdmf(dir: &Path) -> String {
    std::fs::read_to_string(dir.join(SNAPSHOTS_PARTIAL_XDMF)).unwrap()
}

#[test]
fn round_trip_two_frames_of_different_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let frames = [frame(0, 0.0, 17), frame(123, 1.25e-6, 9)];
    let mut w = writer(dir.path());
    for f in &frames {
        w.append(f).unwrap();
    }
    assert_eq!(w.len(), 2);
    assert!(w.tmp_path().ends_with(SNAPSHOTS_PARTIAL_H5) && w.tmp_path().exists());
    assert_eq!(
        names(dir.path()),
        vec![SNAPSHOTS_PARTIAL_H5, SNAPSHOTS_PARTIAL_XDMF],
        "not complete before finish"
    );
    w.finish().unwrap();
    assert_eq!(names(dir.path()), vec![SNAPSHOTS_H5, SNAPSHOTS_XDMF]);

    let h5 = dir.path().join(SNAPSHOTS_H5);
    assert_eq!(
        read_snapshot_times(&h5).unwrap(),
        vec![(0, 0.0), (123, 1.25e-6)]
    );
    for f in &frames {
        assert_eq!(&read_frame(&h5, f.step, usize::MAX).unwrap(), f);
    }
    let e = read_frame(&h5, 7, usize::MAX).unwrap_err();
    assert!(matches!(e, OutputError::Format(_)) && e.to_string().contains("step 7"));

    let x = std::fs::read_to_string(dir.path().join(SNAPSHOTS_XDMF)).unwrap();
    check_balanced_tags(&x).unwrap();
    assert!(x.contains("<Information Name=\"status\" Value=\"complete\"/>"));
    assert!(x.contains("Name=\"material_names\" Value=\"0: steel, 1: sic, 2: al\""));
    assert!(!x.contains("partial"));
    assert!(x.contains("NumberOfElements=\"17\"") && x.contains("NumberOfElements=\"9\""));
    assert!(x.contains("Dimensions=\"17 3\"") && x.contains("Dimensions=\"9 3 3\""));
    assert!(x.contains(">snapshots.h5:/step_000000/position<"));
    assert!(x.contains(">snapshots.h5:/step_000123/velocity<"));
    assert!(x.contains("<Time Value=\"0e0\"/>") && x.contains("<Time Value=\"1.25e-6\"/>"));
    // Every dataset the XDMF references exists in its group, with the declared shape.
    let file = hdf5::File::open(&h5).unwrap();
    for f in &frames {
        let g = file.group(&group_name(f.step)).unwrap();
        let n = f.table.len();
        for ds in scalar_datasets().chain(["position", "velocity", "stress"]) {
            assert!(g.link_exists(ds), "{ds}");
            assert!(x.contains(&format!("/{}/{ds}<", group_name(f.step))));
        }
        assert_eq!(g.dataset("position").unwrap().shape(), vec![n, 3]);
        assert_eq!(g.dataset("stress").unwrap().shape(), vec![n, 3, 3]);
        assert_eq!(g.dataset("von_mises").unwrap().shape(), vec![n]);
    }
}

#[test]
fn stress_von_mises_units_and_compression() {
    let dir = tempfile::tempdir().unwrap();
    let f = frame(4, 1e-7, 40_000);
    let mut w = writer(dir.path());
    w.append(&f).unwrap();
    w.finish().unwrap();
    let file = hdf5::File::open(dir.path().join(SNAPSHOTS_H5)).unwrap();
    let g = file.group("step_000004").unwrap();
    let t = &f.table;
    let stress = g.dataset("stress").unwrap().read_raw::<f64>().unwrap();
    let vm = g.dataset("von_mises").unwrap().read_raw::<f64>().unwrap();
    for i in [0, 1, 12_345, 39_999] {
        let s = &stress[9 * i..9 * i + 9];
        assert_eq!(s, cauchy_stress(t, i));
        assert_eq!(s[0], t.sxx[i] - t.p[i]);
        assert_eq!(s[4], t.syy[i] - t.p[i]);
        assert_eq!(s[8], t.szz[i] - t.p[i]);
        assert_eq!(
            (s[1], s[3], s[2], s[5]),
            (t.sxy[i], t.sxy[i], t.sxz[i], t.syz[i])
        );
        assert_eq!(vm[i], von_mises(t, i));
    }
    let expect = [
        ("position", "m"),
        ("velocity", "m/s"),
        ("stress", "Pa"),
        ("von_mises", "Pa"),
        ("p", "Pa"),
        ("m", "kg/m"),
        ("rho", "kg/m^3"),
        ("eps_p", "1"),
        ("temperature", "K"),
        ("id", ""),
    ];
    for (name, u) in expect {
        let ds = g.dataset(name).unwrap();
        assert_eq!(read_str(ds.attr("units").unwrap()), u, "{name}");
        assert!(!read_str(ds.attr("description").unwrap()).is_empty());
    }
    let d = read_str(g.dataset("p").unwrap().attr("description").unwrap());
    assert!(d.contains("compression"), "{d}");
    for name in scalar_datasets().chain(["position", "velocity", "stress"]) {
        let ds = g.dataset(name).unwrap();
        let filters = ds.filters();
        assert_eq!(filters.len(), 2, "{name}: {filters:?}");
        assert!(
            matches!(filters[0], hdf5::filters::Filter::Shuffle),
            "{name}"
        );
        assert!(
            matches!(filters[1], hdf5::filters::Filter::Deflate(DEFLATE_LEVEL)),
            "{name}"
        );
        let chunk = ds.chunk().unwrap();
        let row: usize = chunk[1..].iter().product();
        assert!(
            chunk[0] * row * ds.dtype().unwrap().size() <= CHUNK_BYTES,
            "{name}"
        );
        assert_eq!(chunk[1..], ds.shape()[1..], "{name}: whole rows");
    }
    // 40,000 smooth values compress: the file is well under the raw size
    let raw = 40_000 * (20 + 9 + 1) * 8;
    let size = std::fs::metadata(dir.path().join(SNAPSHOTS_H5))
        .unwrap()
        .len();
    assert!(size < raw as u64 / 2, "{size} bytes for {raw} raw");
}

#[test]
fn run_attributes_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = writer(dir.path());
    w.append(&frame(1, 0.5, 3)).unwrap();
    w.finish().unwrap();
    let h5 = dir.path().join(SNAPSHOTS_H5);
    assert_eq!(read_run_info(&h5).unwrap(), Some(info()));
    let file = hdf5::File::open(&h5).unwrap();
    assert_eq!(read_str(file.attr("gsph_version").unwrap()), GSPH_VERSION);
    assert!(read_str(file.attr("conventions").unwrap()).contains("-p I + S"));
    let v = |name: &str| file.attr(name).unwrap().read_scalar::<u32>().unwrap();
    assert_eq!((v("dim"), v("format_version")), (2, FORMAT_VERSION));
    // empty lists and texts
    let dir = tempfile::tempdir().unwrap();
    let w = SnapshotWriter::create(dir.path(), 1, &RunInfo::default()).unwrap();
    w.finish().unwrap();
    let got = read_run_info(dir.path().join(SNAPSHOTS_H5)).unwrap();
    assert_eq!(got, Some(RunInfo::default()));
}

#[test]
fn partial_pair_follows_the_run_and_finish_replaces_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = writer(dir.path());
    let x = partial_xdmf(dir.path());
    check_balanced_tags(&x).unwrap();
    assert!(
        x.contains("Value=\"partial: run in progress; no snapshot\""),
        "{x}"
    );
    w.append(&frame(0, 0.0, 5)).unwrap();
    w.append(&frame(10, 2e-6, 5)).unwrap();
    let x = partial_xdmf(dir.path());
    check_balanced_tags(&x).unwrap();
    assert!(x.starts_with("<?xml") && x.contains("<!-- PARTIAL OUTPUT"));
    assert!(x.contains(
        "Value=\"partial: run in progress; 2 snapshot(s), the last at step 10, t = 2e-6 s\""
    ));
    assert!(x.contains(">snapshots.partial.h5:/step_000010/stress<"));
    // the partial file is whole between snapshots: another reader sees both
    let partial = dir.path().join(SNAPSHOTS_PARTIAL_H5);
    assert_eq!(read_snapshot_times(&partial).unwrap().len(), 2);
    assert_eq!(
        read_frame(&partial, 10, usize::MAX).unwrap(),
        frame(10, 2e-6, 5)
    );
    w.finish().unwrap();
    assert_eq!(names(dir.path()), vec![SNAPSHOTS_H5, SNAPSHOTS_XDMF]);
}

#[test]
fn interrupt_marks_the_partial_pair() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = writer(dir.path());
    w.append(&frame(0, 0.0, 4)).unwrap();
    w.interrupt(37, 3.5e-6).unwrap();
    let x = partial_xdmf(dir.path());
    check_balanced_tags(&x).unwrap();
    let status = "partial: run interrupted at step 37, t = 3.5e-6 s; 1 snapshot(s), the last \
                  at step 0, t = 0e0 s";
    assert!(x.contains(&format!("Value=\"{status}\"")), "{x}");
    assert!(x.contains(">snapshots.partial.h5:/step_000000/stress<"));
    assert_eq!(
        names(dir.path()),
        vec![SNAPSHOTS_PARTIAL_H5, SNAPSHOTS_PARTIAL_XDMF]
    );
    let partial = dir.path().join(SNAPSHOTS_PARTIAL_H5);
    assert_eq!(
        read_frame(&partial, 0, usize::MAX).unwrap(),
        frame(0, 0.0, 4)
    );
}

#[test]
fn drop_without_finish_leaves_a_marked_partial_pair_only() {
    let dir = tempfile::tempdir().unwrap();
    for stale in [SNAPSHOTS_H5, SNAPSHOTS_XDMF, "snapshots.h5.tmp"] {
        std::fs::write(dir.path().join(stale), b"stale").unwrap();
    }
    let mut w = writer(dir.path());
    w.append(&frame(1, 0.5, 4)).unwrap();
    drop(w);
    assert_eq!(
        names(dir.path()),
        vec![SNAPSHOTS_PARTIAL_H5, SNAPSHOTS_PARTIAL_XDMF]
    );
    let x = partial_xdmf(dir.path());
    check_balanced_tags(&x).unwrap();
    assert!(x.contains(
        "Value=\"partial: run ended without finishing (error or stop); 1 snapshot(s), the \
         last at step 1, t = 5e-1 s\""
    ));
    // the next run into the folder starts clean
    let w = writer(dir.path());
    assert!(!partial_xdmf(dir.path()).contains("step_000001"));
    assert!(read_snapshot_times(w.tmp_path()).unwrap().is_empty());
    w.finish().unwrap();
    assert_eq!(names(dir.path()), vec![SNAPSHOTS_H5, SNAPSHOTS_XDMF]);
}

#[test]
fn same_frames_give_the_same_bytes() {
    // restarts rebuild snapshots.h5 by the same writes and promise the same bytes
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    for dir in [a.path(), b.path()] {
        let mut w = writer(dir);
        for (k, n) in [(0, 30), (5, 31), (9, 0)] {
            w.append(&frame(k, k as f64 * 1e-7, n)).unwrap();
        }
        w.finish().unwrap();
    }
    for f in [SNAPSHOTS_H5, SNAPSHOTS_XDMF] {
        let read = |d: &Path| std::fs::read(d.join(f)).unwrap();
        assert!(read(a.path()) == read(b.path()), "{f} differs");
    }
}

/// What the writer of format version 1 wrote (no run attributes, no stress, no filters).
fn write_version_1(path: &Path, f: &Frame) {
    let file = hdf5::File::create(path).unwrap();
    file.new_attr::<u32>()
        .create("dim")
        .unwrap()
        .write_scalar(&2u32)
        .unwrap();
    let g = file.create_group(&group_name(f.step)).unwrap();
    g.new_attr::<f64>()
        .create("time")
        .unwrap()
        .write_scalar(&f.time)
        .unwrap();
    g.new_attr::<u64>()
        .create("step")
        .unwrap()
        .write_scalar(&f.step)
        .unwrap();
    let t = &f.table;
    let n = t.len();
    for (name, c) in [
        ("position", [&t.x, &t.y, &t.z]),
        ("velocity", [&t.vx, &t.vy, &t.vz]),
    ] {
        let flat: Vec<f64> = (0..n).flat_map(|i| c.map(|c| c[i])).collect();
        let ds = g.new_dataset::<f64>().shape((n, 3)).create(name).unwrap();
        ds.write_raw(&flat).unwrap();
    }
    let ds = g.new_dataset::<u32>().shape(n).create("id").unwrap();
    ds.write_raw(&t.id).unwrap();
    let ds = g.new_dataset::<u32>().shape(n).create("material").unwrap();
    ds.write_raw(&t.material).unwrap();
    // the columns files have always held (`m` .. `h`)
    for name in scalar_datasets().skip(2).take(14) {
        let ds = g.new_dataset::<f64>().shape(n).create(name).unwrap();
        ds.write_raw(t.float_column(name).unwrap()).unwrap();
    }
}

#[test]
fn files_of_format_version_1_still_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(SNAPSHOTS_H5);
    let f = frame(3, 1.5, 6);
    write_version_1(&path, &f);
    assert_eq!(read_snapshot_times(&path).unwrap(), vec![(3, 1.5)]);
    // the columns appended since read as NaN
    let mut want = f.clone();
    for c in want
        .table
        .float_columns_mut()
        .into_iter()
        .skip(BASE_COLUMNS - 2)
    {
        c.fill(f64::NAN);
    }
    let got = read_frame(&path, 3, usize::MAX).unwrap();
    assert_eq!(format!("{got:?}"), format!("{want:?}"));
    assert_eq!(read_run_info(&path).unwrap(), None);
}

#[test]
fn empty_frame_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = writer(dir.path());
    w.append(&frame(5, 1.0, 0)).unwrap();
    w.finish().unwrap();
    let f = read_frame(dir.path().join(SNAPSHOTS_H5), 5, usize::MAX).unwrap();
    assert_eq!(f, frame(5, 1.0, 0));
}

#[test]
fn bad_frames_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    assert!(SnapshotWriter::create(dir.path(), 4, &info()).is_err());
    assert!(names(dir.path()).is_empty());
    let mut w = writer(dir.path());
    w.append(&frame(1, 0.5, 4)).unwrap();
    let e = w.append(&frame(1, 0.6, 4)).unwrap_err();
    assert!(e.to_string().contains("twice"), "{e}");
    let mut f3 = frame(2, 0.7, 4);
    f3.dim = 3;
    assert!(w.append(&f3).is_err());
    let mut ragged = frame(3, 0.8, 4);
    ragged.table.rho.pop();
    assert!(w.append(&ragged).is_err());
    w.finish().unwrap();
    let times = read_snapshot_times(dir.path().join(SNAPSHOTS_H5)).unwrap();
    assert_eq!(times, vec![(1, 0.5)]);
}

#[test]
fn a_missing_directory_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let e = SnapshotWriter::create(&dir.path().join("nope"), 2, &info()).unwrap_err();
    assert!(!e.to_string().contains('\n'), "{e}");
    assert!(names(dir.path()).is_empty());
}

#[test]
fn errors_display_on_one_line() {
    let e = read_frame("/nonexistent/snapshots.h5", 0, usize::MAX).unwrap_err();
    let s = e.to_string();
    assert!(s.starts_with("I/O error") && !s.contains('\n'), "{s}");
    let dir = tempfile::tempdir().unwrap();
    let e = read_frame(dir.path(), 0, usize::MAX)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "bad output data: not a regular file");
    let io = OutputError::from(io::Error::other("a\nb"));
    assert_eq!(io.to_string(), "I/O error: a b");
}
