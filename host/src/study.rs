//! `gsph study`: what accuracy costs in time. Runs a scene for a grid of schemes and
//! resolutions and records, per run, the error against the scene's reference, wall time,
//! steps, particles and pair interactions; writes `study.csv`, `study.md` and log-log plots
//! of error against wall time (Pareto front marked) and against particle count.

use crate::driver::{run, RunOptions};
use crate::scene;
use gsph_core::schemes::Scheme;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One run of a study.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyRow {
    /// Scheme.
    pub scheme: String,
    /// Resolution scale.
    pub resolution: f64,
    /// Particles.
    pub particles: u64,
    /// The error measure (see [`StudyOptions::metric`]).
    pub error: f64,
    /// Wall time of the stepping loop, s.
    pub wall_s: f64,
    /// Steps.
    pub steps: u64,
    /// Pair interactions evaluated.
    pub pair_interactions: u64,
    /// Relative total-energy error.
    pub energy_rel_error: f64,
    /// On the Pareto front of (wall time, error).
    pub pareto: bool,
}

/// What to run.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    /// Schemes.
    pub schemes: Vec<Scheme>,
    /// Resolution scales.
    pub resolutions: Vec<f64>,
    /// Extra `--set` overrides applied to every run.
    pub overrides: Vec<String>,
    /// Summary key used as the error (absolute value). Default: `l1_error`, else
    /// `radius_error`, else `energy_rel_error`.
    pub metric: Option<String>,
    /// Output directory.
    pub out: PathBuf,
}

/// The default error key of a summary.
pub fn default_metric(summary: &crate::driver::Summary) -> &'static str {
    for k in ["l1_error", "radius_error"] {
        if summary.measure(k).is_some() {
            return k;
        }
    }
    "energy_rel_error"
}

/// Marks the rows not dominated in (wall time, error) by any other row.
pub fn mark_pareto(rows: &mut [StudyRow]) {
    let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r.wall_s, r.error)).collect();
    for (k, r) in rows.iter_mut().enumerate() {
        r.pareto = r.error.is_finite()
            && !pts.iter().enumerate().any(|(j, &(t, e))| {
                j != k && t <= pts[k].0 && e <= pts[k].1 && (t < pts[k].0 || e < pts[k].1)
            });
    }
}

/// Refuses a `--metric` that the summaries of this scene do not have, from a run of one
/// step (the first scheme at the first resolution).
fn check_metric(scene_path: &Path, opts: &StudyOptions, key: &str) -> Result<(), String> {
    let (Some(&res), Some(&scheme)) = (opts.resolutions.first(), opts.schemes.first()) else {
        return Ok(());
    };
    let mut set = opts.overrides.clone();
    set.push(format!("resolution_scale={res}"));
    set.push("max_steps=1".into());
    let (sc, _) =
        scene::load_for_scheme(scene_path, &set, scheme.name()).map_err(|e| e.to_string())?;
    let name = crate::scene::scene_name(&sc, scene_path);
    let r = run(
        &sc,
        &name,
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .map_err(|e| format!("{}: {e}", scheme.name()))?;
    let numbers = r.summary.number_keys();
    if numbers.iter().any(|k| k == key) {
        return Ok(());
    }
    Err(format!(
        "--metric: `{key}` is not in the summary of {} (numbers there: {})",
        scene_path.display(),
        numbers.join(", ")
    ))
}

/// The files a study writes into its folder (checked for links before it starts).
pub const STUDY_FILES: [&str; 6] = [
    "study.csv",
    "study.md",
    "error_vs_time.png",
    "error_vs_time.svg",
    "error_vs_particles.png",
    "error_vs_particles.svg",
];

/// Runs the study; returns the rows and the metric used.
pub fn study(scene_path: &Path, opts: &StudyOptions) -> Result<(Vec<StudyRow>, String), String> {
    // everything that can be refused is refused before the first run: every scene of the
    // grid, the output folder, the metric
    let _lock = crate::outdir::OutLock::acquire_for(&opts.out, &STUDY_FILES)?;
    for &res in &opts.resolutions {
        for &scheme in &opts.schemes {
            let mut set = opts.overrides.clone();
            set.push(format!("resolution_scale={res}"));
            scene::load_for_scheme(scene_path, &set, scheme.name()).map_err(|e| e.to_string())?;
        }
    }
    if let Some(key) = &opts.metric {
        check_metric(scene_path, opts, key)?;
    }
    let mut rows = Vec::new();
    let mut metric = opts.metric.clone();
    let total = opts.schemes.len() * opts.resolutions.len();
    for &res in &opts.resolutions {
        for &scheme in &opts.schemes {
            let mut set = opts.overrides.clone();
            set.push(format!("resolution_scale={res}"));
            let (sc, dropped) = scene::load_for_scheme(scene_path, &set, scheme.name())
                .map_err(|e| e.to_string())?;
            if res == opts.resolutions[0] {
                for key in dropped {
                    eprintln!(
                        "study: {key} left out of the {} runs (not read by {})",
                        scheme.name(),
                        scheme.name()
                    );
                }
            }
            let name = crate::scene::scene_name(&sc, scene_path);
            eprintln!(
                "study: run {}/{total}: {} at resolution {res}",
                rows.len() + 1,
                scheme.name()
            );
            let r = run(
                &sc,
                &name,
                &RunOptions {
                    out: None,
                    progress: false,
                },
            )
            .map_err(|e| format!("{} at resolution {res}: {e}", scheme.name()))?;
            let s = &r.summary;
            let key = metric
                .get_or_insert_with(|| default_metric(s).to_string())
                .clone();
            let error = s
                .number(&key)
                .ok_or_else(|| format!("summary has no number `{key}` (choose another --metric)"))?
                .abs();
            rows.push(StudyRow {
                scheme: scheme.name().to_string(),
                resolution: res,
                particles: s.particles as u64,
                error,
                wall_s: s.wall_s,
                steps: s.steps,
                pair_interactions: s.pair_interactions,
                energy_rel_error: s.energy_rel_error,
                pareto: false,
            });
        }
    }
    mark_pareto(&mut rows);
    let metric = metric.unwrap_or_else(|| "l1_error".into());
    write_outputs(scene_path, &rows, &metric, &opts.out)?;
    Ok((rows, metric))
}

/// The study table as CSV.
pub fn to_csv(rows: &[StudyRow]) -> String {
    let mut s = String::from("scheme,resolution,particles,error,wall_s,steps,pair_interactions,energy_rel_error,pareto\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{:e},{:e},{},{},{:e},{}",
            r.scheme,
            r.resolution,
            r.particles,
            r.error,
            r.wall_s,
            r.steps,
            r.pair_interactions,
            r.energy_rel_error,
            r.pareto
        );
    }
    s
}

/// The study table as Markdown.
pub fn to_markdown(scene: &str, metric: &str, rows: &[StudyRow]) -> String {
    let mut s = format!(
        "# Study of `{scene}`\n\nError measure: `{metric}`. Wall time is the stepping loop on {} threads. \
         `*` marks the Pareto front of (wall time, error): no other run is both faster and more accurate.\n\n\
         | scheme | resolution | particles | error | wall s | steps | pair interactions | energy error | |\n\
         | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n",
        rayon::current_num_threads()
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.4e} | {:.3} | {} | {} | {:.2e} | {} |",
            r.scheme,
            r.resolution,
            r.particles,
            r.error,
            r.wall_s,
            r.steps,
            r.pair_interactions,
            r.energy_rel_error,
            if r.pareto { "*" } else { "" }
        );
    }
    s
}

fn write_outputs(
    scene_path: &Path,
    rows: &[StudyRow],
    metric: &str,
    out: &Path,
) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let name = scene_path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    crate::output::write_atomic(out.join("study.csv"), to_csv(rows).as_bytes())
        .map_err(|e| e.to_string())?;
    crate::output::write_atomic(
        out.join("study.md"),
        to_markdown(&name, metric, rows).as_bytes(),
    )
    .map_err(|e| e.to_string())?;
    Ok(())
}

/// A study row as JSON (the Python package's `gsph.study` returns these).
pub fn row_json(r: &StudyRow) -> serde_json::Value {
    serde_json::json!({
        "scheme": r.scheme,
        "resolution": r.resolution,
        "particles": r.particles,
        "error": r.error,
        "wall_s": r.wall_s,
        "steps": r.steps,
        "pair_interactions": r.pair_interactions,
        "energy_rel_error": r.energy_rel_error,
        "pareto": r.pareto,
    })
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

/// Runs a study (which writes study.csv and study.md) and writes its plots: error against
/// wall time and against particles (only with the feature `plot`).
pub fn run_study(scene: &Path, opts: &StudyOptions) -> Result<Vec<StudyRow>, String> {
    let (rows, metric) = study(scene, opts)?;
    #[cfg(feature = "plot")]
    write_study_plots(scene, opts, &rows, &metric)?;
    #[cfg(not(feature = "plot"))]
    {
        let _ = metric;
        eprintln!("study: plots left out: {}", crate::NO_PLOT);
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
    use crate::plot::{Series, SeriesStyle, XyPlot};
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

#[cfg(test)]
mod tests {
    use super::*;

    fn row(t: f64, e: f64) -> StudyRow {
        StudyRow {
            scheme: "x".into(),
            resolution: 1.0,
            particles: 1,
            error: e,
            wall_s: t,
            steps: 1,
            pair_interactions: 1,
            energy_rel_error: 0.0,
            pareto: false,
        }
    }

    #[test]
    fn pareto_front_keeps_only_undominated_runs() {
        let mut rows = vec![
            row(1.0, 1.0),
            row(2.0, 0.5),
            row(3.0, 0.7),
            row(0.5, 2.0),
            row(2.0, 0.5),
        ];
        mark_pareto(&mut rows);
        let front: Vec<bool> = rows.iter().map(|r| r.pareto).collect();
        // (3, 0.7) is dominated by (2, 0.5); equal points do not dominate each other
        assert_eq!(front, vec![true, true, false, true, true]);
    }
}
