//! Pictures of a run's output directory (`gsph plot particles|series|profile|rod`): a
//! snapshot's particles, columns of series.csv, the stress profile against the exact one,
//! and a rod's final outline against a measured one.

use super::{ParticlePlot, Series, SeriesStyle, XyPlot};
use crate::output::safe::{excerpt, read_text, shorten_list, MAX_TABLE};
use crate::output::{read_frame, read_snapshot_times};
use std::path::{Path, PathBuf};

/// Renders one snapshot of a run directory as a picture coloured by `field`.
/// `step`/`time` pick the snapshot (exact step, or the one nearest in time; default last);
/// `axes` the coordinates along the picture's width and height (0 = x, 1 = y, 2 = z).
/// Needs the feature `hdf5` too (else an error naming it).
#[allow(clippy::too_many_arguments)]
pub fn particles(
    dir: &Path,
    field: &str,
    step: Option<u64>,
    time: Option<f64>,
    range: Option<(f64, f64)>,
    highlight_material: Option<u32>,
    axes: (usize, usize),
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
    // no scene here: the memory available bounds what is read
    let frame = read_frame(&h5, s, usize::MAX).map_err(|e| format!("{}: {e}", h5.display()))?;
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let out = out.unwrap_or_else(|| dir.join(format!("{field}_{s:06}.png")));
    ParticlePlot {
        table: &frame.table,
        field,
        title: format!("{name}: {field} at t = {:.4} us", t * 1e6),
        axes,
        range,
        highlight_material,
    }
    .save(&out)
    .map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(out)
}

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
    table_rows(path, header, lines, &[])
}

/// [`series_rows`] where the columns named in `blank` may be empty (read as NaN: where
/// profile.csv's exact solution has no value).
fn table_rows<'a>(
    path: &Path,
    header: &[&str],
    lines: impl Iterator<Item = &'a str>,
    blank: &[&str],
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
                    if v.trim().is_empty() && blank.contains(name) {
                        return Ok(f64::NAN);
                    }
                    v.trim().parse::<f64>().map_err(|_| {
                        format!(
                            "{} line {line}, column {}: `{}` is not a number",
                            path.display(),
                            excerpt(name),
                            excerpt(v)
                        )
                    })
                })
                .collect()
        })
        .collect()
}

/// Plots columns of a run's `series.csv` against time (in microseconds). Columns whose
/// name ends in `_exact` are drawn dashed, as analytic references.
pub fn series(
    dir: &Path,
    columns: &[String],
    y_label: Option<String>,
    out: Option<PathBuf>,
) -> Result<PathBuf, String> {
    let path = dir.join("series.csv");
    let text = read_text(&path, MAX_TABLE).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let idx = |c: &str| {
        header.iter().position(|h| *h == c).ok_or_else(|| {
            format!(
                "{}: no column `{}` (columns: {})",
                path.display(),
                excerpt(c),
                shorten_list(&header)
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

/// `gsph plot rod`: the final outline of each run's rod (from its `final.csv`; r from the
/// axis `axis` through `base` against the height above the base plane, in millimetres,
/// slabs one particle spacing thick, see [`crate::monitor::rod::Rod::profile`]), with a
/// measured outline (`outline`, see [`crate::monitor::rod::read_outline`]) drawn dashed.
pub fn rod(
    dirs: &[PathBuf],
    labels: &[String],
    base: [f64; 3],
    axis: usize,
    outline: Option<&Path>,
    out: &Path,
) -> Result<(), String> {
    if axis > 2 {
        return Err(format!("--axis: must be 0, 1 or 2 (got {axis})"));
    }
    if !labels.is_empty() && labels.len() != dirs.len() {
        return Err(format!(
            "--labels: {} labels for {} directories",
            labels.len(),
            dirs.len()
        ));
    }
    let measured = outline.map(crate::monitor::rod::read_outline).transpose()?;
    let rod = crate::monitor::rod::Rod::at(base, axis);
    let mut series = Vec::new();
    for (k, dir) in dirs.iter().enumerate() {
        let table = crate::output::read_csv(dir.join("final.csv"))?;
        let spacing = crate::plot::particle_spacing(&table);
        let points = rod
            .profile(&table, spacing)
            .into_iter()
            .map(|(z, r)| (r * 1e3, z * 1e3))
            .collect();
        let name = labels.get(k).cloned().unwrap_or_else(|| {
            dir.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        });
        series.push(Series {
            name,
            points,
            style: SeriesStyle::LineMarkers,
        });
    }
    if let (Some(points), Some(path)) = (measured, outline) {
        series.push(Series {
            name: format!(
                "measured ({})",
                path.file_stem().unwrap_or_default().to_string_lossy()
            ),
            points,
            style: SeriesStyle::Dashed,
        });
    }
    XyPlot {
        title: "final rod outline".into(),
        x_label: "distance from the axis (mm)".into(),
        y_label: "height above the wall (mm)".into(),
        series,
        ..XyPlot::default()
    }
    .save(out)
    .map_err(|e| format!("{}: {e}", out.display()))
}

/// Plots a run's `profile.csv`: sigma_xx of the particles (markers) against the exact
/// profile (dashed), like seed 000 fig 1 and seed 004 fig 2a.
pub fn profile(dir: &Path, out: Option<PathBuf>) -> Result<PathBuf, String> {
    let path = dir.join("profile.csv");
    let text = read_text(&path, MAX_TABLE).map_err(|e| {
        format!(
            "{}: {e} (only runs with an exact stress profile write it)",
            path.display()
        )
    })?;
    // checked as series.csv is: the header gsph writes, every row whole and a number
    // in each field (the exact value may be empty where the reference has none)
    const HEADER: &str = "x,sigma_xx,sigma_xx_exact";
    let mut lines = text.lines();
    let header = lines.next().unwrap_or("");
    if header.trim_end() != HEADER {
        return Err(format!(
            "{}: the header is `{}`, not gsph's `{HEADER}`",
            path.display(),
            excerpt(header)
        ));
    }
    let header: Vec<&str> = HEADER.split(',').collect();
    let rows = table_rows(&path, &header, lines, &["sigma_xx_exact"])?;
    let sph: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[1])).collect();
    let exact: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[2])).collect();
    if sph.is_empty() {
        return Err(format!("{}: no rows after the header", path.display()));
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
