//! The `gsph plot`, `gsph study` and `gsph hugoniot` commands (argument handling around
//! `crate::plot`, [`crate::study`] and [`crate::window::hugoniot`]).
//!
//! The plots need the cargo feature `plot` (on by default). Without it the `plot_*`
//! functions are absent and [`run_study`] and [`run_hugoniot`] write their tables but no
//! plots ([`NO_PLOT`] on stderr).

#[cfg(feature = "plot")]
use crate::output::{read_frame, read_snapshot_times};
#[cfg(feature = "plot")]
use crate::plot::{ParticlePlot, Series, SeriesStyle, XyPlot};
use crate::study::{study, StudyOptions, StudyRow};
use gsph_core::schemes::Scheme;
use std::path::Path;
#[cfg(feature = "plot")]
use std::path::PathBuf;

/// Why a plot was refused or left out by a build without the cargo feature `plot`.
pub const NO_PLOT: &str = "this gsph was built without plotting (cargo feature `plot`)";

/// Renders one snapshot of a run directory as a picture coloured by `field`.
/// `step`/`time` pick the snapshot (exact step, or the one nearest in time; default last).
/// Needs the feature `hdf5` too (else an error naming it).
#[cfg(feature = "plot")]
#[allow(clippy::too_many_arguments)]
pub fn plot_particles(
    dir: &Path,
    field: &str,
    step: Option<u64>,
    time: Option<f64>,
    range: Option<(f64, f64)>,
    highlight_material: Option<u32>,
    out: Option<PathBuf>,
) -> Result<PathBuf, String> {
    let h5 = dir.join("snapshots.h5");
    let times = read_snapshot_times(&h5).map_err(|e| format!("{}: {e}", h5.display()))?;
    let (s, t) = match (step, time) {
        (Some(s), _) => *times.iter().find(|(k, _)| *k == s).ok_or_else(|| {
            format!(
                "{}: no snapshot at step {s} (steps: {})",
                h5.display(),
                list(&times)
            )
        })?,
        (None, Some(t)) => *times
            .iter()
            .min_by(|a, b| (a.1 - t).abs().total_cmp(&(b.1 - t).abs()))
            .ok_or_else(|| format!("{}: no snapshots", h5.display()))?,
        (None, None) => *times
            .last()
            .ok_or_else(|| format!("{}: no snapshots", h5.display()))?,
    };
    let frame = read_frame(&h5, s).map_err(|e| format!("{}: {e}", h5.display()))?;
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let out = out.unwrap_or_else(|| dir.join(format!("{field}_{s:06}.png")));
    ParticlePlot {
        table: &frame.table,
        field,
        title: format!("{name}: {field} at t = {:.4} us", t * 1e6),
        axes: (0, 1),
        range,
        highlight_material,
    }
    .save(&out)
    .map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(out)
}

#[cfg(feature = "plot")]
fn list(times: &[(u64, f64)]) -> String {
    let v: Vec<String> = times.iter().map(|(s, _)| s.to_string()).collect();
    v.join(", ")
}

/// The rows of a series table after its header: every row as many numbers as the header
/// has names (a short or truncated row, or a value that is not a number, is refused
/// naming the line).
pub fn series_rows<'a>(
    path: &Path,
    header: &[&str],
    lines: impl Iterator<Item = &'a str>,
) -> Result<Vec<Vec<f64>>, String> {
    lines
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(k, l)| {
            let line = k + 2;
            let fields: Vec<&str> = l.split(',').collect();
            if fields.len() != header.len() {
                return Err(format!(
                    "{} line {line}: {} values, the header names {} (a truncated file?)",
                    path.display(),
                    fields.len(),
                    header.len()
                ));
            }
            fields
                .iter()
                .zip(header)
                .map(|(v, name)| {
                    v.trim().parse::<f64>().map_err(|_| {
                        format!(
                            "{} line {line}, column {name}: `{v}` is not a number",
                            path.display()
                        )
                    })
                })
                .collect()
        })
        .collect()
}

/// Plots columns of a run's `series.csv` against time (in microseconds). Columns whose
/// name ends in `_exact` are drawn dashed, as analytic references.
#[cfg(feature = "plot")]
pub fn plot_series(
    dir: &Path,
    columns: &[String],
    y_label: Option<String>,
    out: Option<PathBuf>,
) -> Result<PathBuf, String> {
    let path = dir.join("series.csv");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let idx = |c: &str| {
        header.iter().position(|h| *h == c).ok_or_else(|| {
            format!(
                "{}: no column `{c}` (columns: {})",
                path.display(),
                header.join(", ")
            )
        })
    };
    let it = idx("t")?;
    let cols: Vec<usize> = columns.iter().map(|c| idx(c)).collect::<Result<_, _>>()?;
    let rows = series_rows(&path, &header, lines)?;
    let series = columns
        .iter()
        .zip(&cols)
        .map(|(name, &c)| Series {
            name: name.clone(),
            points: rows.iter().map(|r| (r[it] * 1e6, r[c])).collect(),
            style: if name.ends_with("_exact") {
                SeriesStyle::Dashed
            } else {
                SeriesStyle::Line
            },
        })
        .collect();
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let out = out.unwrap_or_else(|| dir.join(format!("series_{}.png", columns.join("_"))));
    XyPlot {
        title: format!("{name}: {}", columns.join(", ")),
        x_label: "t (us)".into(),
        y_label: y_label.unwrap_or_else(|| columns.first().cloned().unwrap_or_default()),
        log_x: false,
        log_y: false,
        series,
        highlight: Vec::new(),
        highlight_label: None,
    }
    .save(&out)
    .map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(out)
}

/// Parses a comma-separated list of schemes.
pub fn parse_schemes(s: &str) -> Result<Vec<Scheme>, String> {
    s.split(',')
        .map(|n| {
            Scheme::from_name(n.trim()).ok_or_else(|| {
                format!("--schemes: unknown scheme `{n}` (known: av, pm, ts1, ts2, tkc)")
            })
        })
        .collect()
}

/// Parses a comma-separated list of positive resolution scales.
pub fn parse_resolutions(s: &str) -> Result<Vec<f64>, String> {
    parse_positive("--resolutions", s)
}

/// Parses the comma-separated list of positive numbers given to `flag`.
pub fn parse_positive(flag: &str, s: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|n| match n.trim().parse::<f64>() {
            Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
            _ => Err(format!("{flag}: `{n}` is not a positive number")),
        })
        .collect()
}

/// `gsph hugoniot`: the Hugoniot points of a window scene, written into `out` (the tables;
/// the plots only with the feature `plot`).
pub fn run_hugoniot(
    scene: &crate::scene::Scene,
    opts: &crate::window::hugoniot::HugoniotOptions,
    out: &Path,
) -> Result<Vec<crate::window::hugoniot::HugoniotPoint>, String> {
    use crate::window::hugoniot::{hugoniot, seed_fit, to_csv};
    use crate::window::plot::{write_outputs, write_point};
    // each point's profiles are written as it finishes, and the rows finished so far go
    // into hugoniot.partial.csv (a run of hours that is stopped keeps its points under a
    // name that does not pass for the whole table); hugoniot.csv and the plot when all
    // points are done, and the partial table is then removed
    // refused before any computation: an --out that is a file, or a folder another
    // process writes
    let _lock = crate::outdir::OutLock::acquire(out)?;
    let partial = out.join("hugoniot.partial.csv");
    let mut rows = String::new();
    #[cfg(not(feature = "plot"))]
    eprintln!("hugoniot: plots left out: {NO_PLOT}");
    let points = hugoniot(scene, opts, |p| {
        write_point(out, p)?;
        let one = to_csv(std::slice::from_ref(p));
        match (rows.is_empty(), one.split_once('\n')) {
            (false, Some((_, row))) => rows.push_str(row),
            _ => rows.push_str(&one),
        }
        crate::output::write_atomic(&partial, rows.as_bytes())
            .map_err(|e| format!("{}: {e}", partial.display()))
    })?;
    write_outputs(out, &points)?;
    match std::fs::remove_file(&partial) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            return Err(format!("{}: {e}", partial.display()));
        }
        _ => {}
    }
    println!(
        "   u_p     u_s    fit    diff  bulk -sxx behind  precursor  u_prec  mass/RH  mom/RH  pores behind   wall"
    );
    for p in &points {
        let fit = seed_fit(p.up);
        println!(
            "{:6.1} {:7.1} {:6.1} {:+6.1}%  {:12.3} GPa  {:5.3} GPa {:5.1}   {:6.3}   {:6.3}  {:12.4} {:5.0} s",
            p.up,
            p.us,
            fit,
            100.0 * (p.us - fit) / fit,
            p.stress_behind * 1e-9,
            p.stress_precursor * 1e-9,
            p.precursor_velocity,
            p.mass_jump_ratio(),
            p.momentum_jump_ratio(),
            p.pores_behind,
            p.wall_s
        );
    }
    Ok(points)
}

/// Runs a study (which writes study.csv and study.md) and writes its plots: error against
/// wall time and against particles (only with the feature `plot`).
pub fn run_study(scene: &Path, opts: &StudyOptions) -> Result<Vec<StudyRow>, String> {
    let (rows, metric) = study(scene, opts)?;
    #[cfg(feature = "plot")]
    write_study_plots(scene, opts, &rows, &metric)?;
    #[cfg(not(feature = "plot"))]
    {
        let _ = metric;
        eprintln!("study: plots left out: {NO_PLOT}");
    }
    Ok(rows)
}

/// The plots of [`run_study`].
#[cfg(feature = "plot")]
fn write_study_plots(
    scene: &Path,
    opts: &StudyOptions,
    rows: &[StudyRow],
    metric: &str,
) -> Result<(), String> {
    let name = scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut schemes: Vec<&str> = Vec::new();
    for r in rows {
        if !schemes.contains(&r.scheme.as_str()) {
            schemes.push(&r.scheme);
        }
    }
    let lines = |x: &dyn Fn(&StudyRow) -> f64| -> Vec<Series> {
        schemes
            .iter()
            .map(|s| {
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.scheme == *s)
                    .map(|r| (x(r), r.error))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                Series {
                    name: s.to_string(),
                    points: pts,
                    style: SeriesStyle::LineMarkers,
                }
            })
            .collect()
    };
    for ext in ["png", "svg"] {
        XyPlot {
            title: format!("{name}: {metric} against wall time"),
            x_label: "wall time (s)".into(),
            y_label: metric.to_string(),
            log_x: true,
            log_y: true,
            series: lines(&|r| r.wall_s),
            highlight: rows
                .iter()
                .filter(|r| r.pareto)
                .map(|r| (r.wall_s, r.error))
                .collect(),
            highlight_label: Some("Pareto front".into()),
        }
        .save(&opts.out.join(format!("error_vs_time.{ext}")))
        .map_err(|e| e.to_string())?;
        XyPlot {
            title: format!("{name}: {metric} against particles"),
            x_label: "particles".into(),
            y_label: metric.to_string(),
            log_x: true,
            log_y: true,
            series: lines(&|r| r.particles as f64),
            highlight: Vec::new(),
            highlight_label: None,
        }
        .save(&opts.out.join(format!("error_vs_particles.{ext}")))
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Plots a run's `profile.csv`: sigma_xx of the particles (markers) against the exact
/// profile (dashed), like seed 000 fig 1 and seed 004 fig 2a.
#[cfg(feature = "plot")]
pub fn plot_profile(dir: &Path, out: Option<PathBuf>) -> Result<PathBuf, String> {
    let path = dir.join("profile.csv");
    let text = std::fs::read_to_string(&path).map_err(|e| {
        format!(
            "{}: {e} (only runs with an exact stress profile write it)",
            path.display()
        )
    })?;
    let mut sph = Vec::new();
    let mut exact = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let x: f64 = f.first().and_then(|v| v.parse().ok()).unwrap_or(f64::NAN);
        if let Some(v) = f.get(1).and_then(|v| v.parse::<f64>().ok()) {
            sph.push((x, v));
        }
        exact.push((
            x,
            f.get(2)
                .and_then(|v| v.parse::<f64>().ok())
                .unwrap_or(f64::NAN),
        ));
    }
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let out = out.unwrap_or_else(|| dir.join("profile.png"));
    XyPlot {
        title: format!("{name}: sigma_xx against the exact solution"),
        x_label: "x (m)".into(),
        y_label: "sigma_xx (Pa)".into(),
        log_x: false,
        log_y: false,
        series: vec![
            Series {
                name: "exact".into(),
                points: exact,
                style: SeriesStyle::Dashed,
            },
            Series {
                name: "SPH".into(),
                points: sph,
                style: SeriesStyle::Markers,
            },
        ],
        highlight: Vec::new(),
        highlight_label: None,
    }
    .save(&out)
    .map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(out)
}
