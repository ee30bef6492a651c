//! Rendering tests: every plot kind to PNG and SVG, checked for a plausible file.
//!
//! Set `GSPH_PLOT_DIR` to keep the pictures in that directory instead of a temporary one.

use std::path::{Path, PathBuf};

use super::*;
use crate::output::table::{ParticleRow, ParticleTable};

/// The output directory (kept when `GSPH_PLOT_DIR` is set) and the guard of a temporary one.
fn out_dir() -> (PathBuf, Option<tempfile::TempDir>) {
    if let Some(d) = std::env::var_os("GSPH_PLOT_DIR") {
        let d = PathBuf::from(d);
        std::fs::create_dir_all(&d).unwrap();
        return (d, None);
    }
    let t = tempfile::tempdir().unwrap();
    (t.path().to_path_buf(), Some(t))
}

fn check_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
        "{}",
        path.display()
    );
    assert!(
        bytes.len() > 10_000,
        "{}: {} bytes",
        path.display(),
        bytes.len()
    );
}

fn check_svg(path: &Path, needle: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("<svg"), "{}", path.display());
    assert!(text.contains(needle), "{} lacks {needle}", path.display());
}

fn linear_plot() -> XyPlot {
    let xs: Vec<f64> = (0..=200).map(|i| f64::from(i) * 0.05).collect();
    let curve = |f: &dyn Fn(f64) -> f64| xs.iter().map(|&x| (x, f(x))).collect::<Vec<_>>();
    XyPlot {
        title: "Free-surface velocity".into(),
        x_label: "time (µs)".into(),
        y_label: "velocity (m/s)".into(),
        series: vec![
            Series {
                name: "GSPH".into(),
                points: curve(&|x| 300.0 * (1.0 - (-x).exp()) + 20.0 * (3.0 * x).sin()),
                style: SeriesStyle::Line,
            },
            Series {
                name: "experiment".into(),
                points: curve(&|x| 300.0 * (1.0 - (-x).exp()))
                    .into_iter()
                    .step_by(10)
                    .collect(),
                style: SeriesStyle::Markers,
            },
            Series {
                name: "analytic".into(),
                points: curve(&|x| 300.0 * (1.0 - (-x).exp())),
                style: SeriesStyle::Dashed,
            },
            Series {
                name: "SPH (with a gap)".into(),
                points: curve(&|x| {
                    if (4.0..5.0).contains(&x) {
                        f64::NAN
                    } else {
                        250.0 - 10.0 * x
                    }
                })
                .into_iter()
                .step_by(8)
                .collect(),
                style: SeriesStyle::LineMarkers,
            },
        ],
        ..XyPlot::default()
    }
}

fn loglog_plot() -> XyPlot {
    let points = |c: f64, k: f64| -> Vec<(f64, f64)> {
        (0..40)
            .map(|i| 1e-3 * 1.3f64.powi(i))
            .map(|h| (h, c * h.powf(k)))
            .collect()
    };
    let mut noisy = points(2e-2, 1.0);
    noisy.extend([(0.0, 1.0), (-1.0, 1.0), (1e-2, f64::NAN), (1e-2, -3.0)]);
    XyPlot {
        title: "Convergence".into(),
        x_label: "h (m)".into(),
        y_label: "L1 error".into(),
        log_x: true,
        log_y: true,
        series: vec![
            Series {
                name: "density".into(),
                points: noisy,
                style: SeriesStyle::LineMarkers,
            },
            Series {
                name: "second order".into(),
                points: points(1.0, 2.0),
                style: SeriesStyle::Dashed,
            },
        ],
        highlight: points(2e-2, 1.0).into_iter().step_by(9).collect(),
        highlight_label: Some("Pareto front".into()),
    }
}

/// A ring (inner radius 0.5 m, outer 1 m, spacing 0.025 m: about 3800 particles) of material
/// 0 whose plastic strain varies with angle, and a small disk of material 1 above it.
fn annulus() -> ParticleTable {
    let dx = 0.025;
    let mut t = ParticleTable::default();
    let n = (1.3 / dx) as i32;
    for i in -n..=n {
        for j in -n..=n {
            let (x, y) = (f64::from(i) * dx, f64::from(j) * dx);
            let r = x.hypot(y);
            let disk = x.hypot(y - 1.2) < 0.1;
            if !(0.5..1.0).contains(&r) && !disk {
                continue;
            }
            let th = y.atan2(x);
            let s = 1e8 * (2.0 * th).cos();
            t.push(&ParticleRow {
                id: t.len() as u32,
                material: u32::from(disk),
                x,
                y,
                vx: -50.0 * x,
                vy: -50.0 * y,
                m: 7850.0 * dx * dx,
                rho: 7850.0 * (1.0 + 0.01 * r),
                p: 1e9 * (1.0 - r),
                sxx: s,
                syy: -s,
                sxy: 0.5 * s,
                eps_p: 0.2 * (1.0 + th.cos()) * (r - 0.5),
                h: 1.2 * dx,
                ..ParticleRow::default()
            });
        }
    }
    t
}

/// A 1D table: a flyer (material 1) on a target, with a pressure pulse.
fn line_table() -> ParticleTable {
    let mut t = ParticleTable::default();
    for i in 0..400 {
        let x = -0.002 + f64::from(i) * 2.5e-5;
        t.push(&ParticleRow {
            id: i,
            material: u32::from(x < 0.0),
            x,
            vx: if x < 0.0 { 500.0 } else { 0.0 },
            rho: 2700.0,
            p: 5e9 * (-((x - 0.004) / 5e-4).powi(2)).exp(),
            ..ParticleRow::default()
        });
    }
    t
}

#[test]
fn xy_linear_and_loglog() {
    let (dir, _guard) = out_dir();
    for (name, plot) in [("xy_linear", linear_plot()), ("xy_loglog", loglog_plot())] {
        let png = dir.join(format!("{name}.png"));
        plot.save(&png).unwrap();
        check_png(&png);
        let svg = dir.join(format!("{name}.svg"));
        plot.save(&svg).unwrap();
        check_svg(&svg, &plot.series[0].name);
    }
    // No data at all still gives a (blank) plot.
    let empty = dir.join("xy_empty.png");
    XyPlot::default().save(&empty).unwrap();
    assert!(empty.exists());
}

#[test]
fn particle_plots_2d() {
    let (dir, _guard) = out_dir();
    let table = annulus();
    assert!((3000..6000).contains(&table.len()), "{}", table.len());
    for (field, hl) in [
        ("eps_p", None),
        ("von_mises", Some(1)),
        ("sigma_xx", None),
        ("vr", None),
    ] {
        let plot = ParticlePlot {
            table: &table,
            field,
            title: format!("Ring, {field}"),
            axes: (0, 1),
            range: None,
            highlight_material: hl,
        };
        let png = dir.join(format!("ring_{field}.png"));
        plot.save(&png).unwrap();
        check_png(&png);
        let svg = dir.join(format!("ring_{field}.svg"));
        plot.save(&svg).unwrap();
        check_svg(&svg, field);
    }
    // Swapped axes and a fixed range.
    let plot = ParticlePlot {
        table: &table,
        field: "rho",
        title: String::new(),
        axes: (1, 0),
        range: Some((7850.0, 7950.0)),
        highlight_material: None,
    };
    let png = dir.join("ring_rho_yx.png");
    plot.save(&png).unwrap();
    check_png(&png);
}

#[test]
fn particle_plot_1d_profile() {
    let (dir, _guard) = out_dir();
    let table = line_table();
    for (field, hl) in [("p", Some(1)), ("vx", None)] {
        let plot = ParticlePlot {
            table: &table,
            field,
            title: format!("Flyer plate, {field}"),
            axes: (0, 1),
            range: None,
            highlight_material: hl,
        };
        let png = dir.join(format!("flyer_{field}.png"));
        plot.save(&png).unwrap();
        check_png(&png);
        let svg = dir.join(format!("flyer_{field}.svg"));
        plot.save(&svg).unwrap();
        check_svg(&svg, field);
    }
}

#[test]
fn errors_are_clean() {
    let (dir, _guard) = out_dir();
    let table = annulus();
    let mut plot = ParticlePlot {
        table: &table,
        field: "stress",
        title: String::new(),
        axes: (0, 1),
        range: None,
        highlight_material: None,
    };
    let err = plot.save(&dir.join("bad.png")).unwrap_err();
    assert!(matches!(err, PlotError::UnknownField { .. }));
    let msg = err.to_string();
    assert!(msg.contains("`stress`") && msg.contains("von_mises") && msg.contains("rho"));
    assert!(!msg.contains('\n'));
    assert!(!dir.join("bad.png").exists());

    plot.field = "rho";
    plot.axes = (1, 1);
    assert_eq!(
        plot.save(&dir.join("bad.png")),
        Err(PlotError::InvalidAxes(1, 1))
    );
    plot.axes = (0, 1);
    let err = plot.save(&dir.join("bad.pdf")).unwrap_err();
    assert!(matches!(err, PlotError::UnsupportedFormat(_)), "{err}");
    let empty = ParticleTable::default();
    plot.table = &empty;
    assert!(matches!(
        plot.save(&dir.join("bad.png")),
        Err(PlotError::NoData(_))
    ));
    init_fonts();
    init_fonts();
}
