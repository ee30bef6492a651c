//! The files `gsph hugoniot` writes: hugoniot.csv, each point's averaged profiles (fig 9)
//! and the u_s(u_p) plot against the seed's fits (fig 8), and `gsph plot hugoniot`, which
//! overlays the points of several runs (for example several resolutions). The plots need
//! the cargo feature `plot`; without it only the CSV files are written.

#[cfg(feature = "plot")]
use super::hugoniot::seed_fit;
use super::hugoniot::{to_csv, HugoniotPoint};
#[cfg(feature = "plot")]
use crate::plot::xy::{Series, SeriesStyle, XyPlot};
use std::path::Path;

/// Every file `gsph hugoniot` writes into its folder for the points of `opts` (checked for
/// links before it starts): each point's profile and plots, the partial and final tables and
/// the plot.
pub fn files(opts: &super::hugoniot::HugoniotOptions) -> Vec<String> {
    let mut names: Vec<String> = [
        "hugoniot.partial.csv",
        "hugoniot.csv",
        "hugoniot.png",
        "hugoniot.svg",
    ]
    .map(String::from)
    .to_vec();
    for up in &opts.ups {
        let stem = format!("profile_up{up}");
        names.push(format!("{stem}.csv"));
        for plot in ["stress", "density"] {
            for ext in ["png", "svg"] {
                names.push(format!("{stem}_{plot}.{ext}"));
            }
        }
    }
    names
}

/// Writes the files of one point into `dir`: `profile_up<UP>.csv` with
/// `profile_up<UP>_stress.png` and `profile_up<UP>_density.png` (fig 9), PNG and SVG (the
/// plots only with the feature `plot`).
pub fn write_point(dir: &Path, p: &HugoniotPoint) -> Result<(), String> {
    use crate::output::write_atomic;
    let io = |e: std::io::Error| format!("{}: {e}", dir.display());
    std::fs::create_dir_all(dir).map_err(io)?;
    let stem = format!("profile_up{}", p.up);
    write_atomic(
        dir.join(format!("{stem}.csv")),
        p.profile.to_csv().as_bytes(),
    )
    .map_err(io)?;
    #[cfg(feature = "plot")]
    plot_point(dir, &stem, p)?;
    Ok(())
}

/// The plots of [`write_point`].
#[cfg(feature = "plot")]
fn plot_point(dir: &Path, stem: &str, p: &HugoniotPoint) -> Result<(), String> {
    let bins = p.profile.bins();
    let line = |name: &str, f: &dyn Fn(&super::profile::Bin) -> f64| Series {
        name: name.into(),
        points: bins.iter().map(|b| (b.x * 1e6, f(b))).collect(),
        style: SeriesStyle::Line,
    };
    let title = format!(
        "u_p = {} m/s, u_s = {:.1} m/s: averaged over {} profiles",
        p.up, p.us, p.profile.instants
    );
    let stress = XyPlot {
        title: title.clone(),
        x_label: "x in the window, um".into(),
        y_label: "-sigma_xx, GPa".into(),
        series: vec![
            line("bulk -sigma_xx (volume average, pores at zero)", &|b| {
                b.stress_bulk * 1e-9
            }),
            line("matrix -sigma_xx (mean over particles)", &|b| {
                b.stress * 1e-9
            }),
        ],
        ..Default::default()
    };
    let density = XyPlot {
        title,
        x_label: "x in the window, um".into(),
        y_label: "density, kg/m3".into(),
        series: vec![
            line("mean particle density", &|b| b.rho),
            line("bulk density (pores included)", &|b| b.rho_bulk),
        ],
        ..Default::default()
    };
    for ext in ["png", "svg"] {
        stress
            .save(&dir.join(format!("{stem}_stress.{ext}")))
            .map_err(|e| e.to_string())?;
        density
            .save(&dir.join(format!("{stem}_density.{ext}")))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The u_s(u_p) plot: each `(name, points)` as markers, and the seed's two fits dashed
/// over the range of the points (fig 8).
#[cfg(feature = "plot")]
pub fn hugoniot_plot(runs: &[(String, Vec<(f64, f64)>)]) -> XyPlot {
    let curve = |a: f64, b: f64| -> Vec<(f64, f64)> {
        (0..=40)
            .map(|k| a + (b - a) * k as f64 / 40.0)
            .map(|u| (u, seed_fit(u)))
            .collect()
    };
    let ups = || runs.iter().flat_map(|(_, pts)| pts.iter().map(|p| p.0));
    let top = ups().fold(200.0, f64::max);
    let bottom = ups().fold(40.0, f64::min).min(0.0);
    let mut series: Vec<Series> = runs
        .iter()
        .map(|(name, pts)| Series {
            name: name.clone(),
            points: pts.clone(),
            style: SeriesStyle::Markers,
        })
        .collect();
    series.push(Series {
        name: "Rublev & Murzov fit, 226.8 + 1.886 u_p".into(),
        points: curve(bottom, 130.0),
        style: SeriesStyle::Dashed,
    });
    series.push(Series {
        name: "Rublev & Murzov fit, 14.58 + 3.573 u_p - 0.0003967 u_p^2".into(),
        points: curve(130.0, top),
        style: SeriesStyle::Dashed,
    });
    XyPlot {
        title: "Shock Hugoniot of porous copper (m = 1.35)".into(),
        x_label: "u_p, m/s".into(),
        y_label: "u_s, m/s".into(),
        series,
        ..Default::default()
    }
}

/// Writes `hugoniot.csv` and `hugoniot.png`/`.svg` (u_s against u_p with the seed's fits;
/// only with the feature `plot`) into `dir`, after all points are done.
pub fn write_outputs(dir: &Path, points: &[HugoniotPoint]) -> Result<(), String> {
    use crate::output::write_atomic;
    let io = |e: std::io::Error| format!("{}: {e}", dir.display());
    std::fs::create_dir_all(dir).map_err(io)?;
    #[cfg(feature = "plot")]
    {
        let plot = hugoniot_plot(&[(
            "gsph moving window".to_string(),
            points.iter().map(|p| (p.up, p.us)).collect(),
        )]);
        for ext in ["png", "svg"] {
            plot.save(&dir.join(format!("hugoniot.{ext}")))
                .map_err(|e| e.to_string())?;
        }
    }
    write_atomic(dir.join("hugoniot.csv"), to_csv(points).as_bytes()).map_err(io)?;
    Ok(())
}

/// `gsph plot hugoniot DIR... --labels A,B,... --out FILE`: the u_s(u_p) points of the
/// `hugoniot.csv` in each directory (labelled by `labels`, default the directory names)
/// on one plot with the seed's fits. Returns the file written.
#[cfg(feature = "plot")]
pub fn plot_runs(dirs: &[std::path::PathBuf], labels: &[String], out: &Path) -> Result<(), String> {
    if !labels.is_empty() && labels.len() != dirs.len() {
        return Err(format!(
            "--labels: {} labels for {} directories",
            labels.len(),
            dirs.len()
        ));
    }
    let mut runs = Vec::new();
    for (k, dir) in dirs.iter().enumerate() {
        let path = dir.join("hugoniot.csv");
        let text = crate::output::safe::read_text(&path, crate::output::safe::MAX_TABLE)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
        let col = |name: &str| {
            header
                .iter()
                .position(|h| *h == name)
                .ok_or_else(|| format!("{}: no column `{name}`", path.display()))
        };
        let (iu, is) = (col("up")?, col("us")?);
        let mut pts = Vec::new();
        for (n, line) in lines.enumerate() {
            let f: Vec<&str> = line.split(',').collect();
            let num = |i: usize| {
                f.get(i).and_then(|v| v.parse::<f64>().ok()).ok_or_else(|| {
                    format!(
                        "{}: line {}: not a number in column {i}",
                        path.display(),
                        n + 2
                    )
                })
            };
            pts.push((num(iu)?, num(is)?));
        }
        let name = labels.get(k).cloned().unwrap_or_else(|| {
            dir.file_name().map_or_else(
                || dir.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            )
        });
        runs.push((name, pts));
    }
    hugoniot_plot(&runs).save(out).map_err(|e| e.to_string())
}
