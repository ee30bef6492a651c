//! The `gsph` command line (DESIGN §6). `main` only calls [`main_with_args`].

/// `println!` that ignores a closed stdout (`gsph check scene | head -1` must not panic).
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        // under MPI only rank 0 reports
        if crate::dist_rank() == 0 {
            let _ = writeln!(std::io::stdout(), $($arg)*);
        }
    }};
}

pub use crate::driver::scene_name;

use crate::driver::{run_checkpointed, CheckpointOptions, Outcome, RunError, RunOptions};
use crate::reference::Reference;
use crate::scene::{self, build_particles};
use crate::sim::{Sim, SimError};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Godunov SPH for solids under shock and impact.
#[derive(Parser, Debug)]
#[command(name = "gsph", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run a scene for a grid of schemes and resolutions: error against the reference,
    /// wall time, steps, particles, pair interactions (study.csv, study.md, plots).
    Study {
        /// Scene file.
        scene: PathBuf,
        /// Schemes, comma-separated.
        #[arg(long, default_value = "av,pm,ts1,ts2,tkc")]
        schemes: String,
        /// Resolution scales, comma-separated.
        #[arg(long, default_value = "1,2,4")]
        resolutions: String,
        /// Summary key used as the error (default: l1_error, radius_error or energy_rel_error).
        #[arg(long)]
        metric: Option<String>,
        /// Override a scene key in every run.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Remove a scene key in every run (dotted path), e.g. --unset options.riemann.
        #[arg(long = "unset", value_name = "KEY")]
        unset: Vec<String>,
        /// Output directory (default `out/<scene name>_study`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Shock Hugoniot of a moving-window scene (seed 004 §3.1): u_s for each u_p by
    /// bisection, stress behind the wave and in the precursor, averaged profiles
    /// (hugoniot.csv, hugoniot.png, profile_up*.csv/png).
    Hugoniot {
        /// Scene file with a `[window]` section.
        scene: PathBuf,
        /// Particle velocities u_p, m/s, comma-separated.
        #[arg(long, default_value = "50,75,100,125,150,200")]
        up: String,
        /// Initial bracket of u_s, m/s, `LO,HI` (default from the full-compaction bound B = m u_p/(m-1): 0.85 B and max(2 B, B + 300)); widened if it misses the root.
        #[arg(long)]
        bracket: Option<String>,
        /// Bisection stops below this bracket width, m/s.
        #[arg(long, default_value_t = 1.0)]
        tolerance: f64,
        /// Feed lengths entering during each trial (seed: 3).
        #[arg(long, default_value_t = 3.0)]
        samples: f64,
        /// Feed lengths over which the production profiles are averaged.
        #[arg(long, default_value_t = 4.5)]
        average: f64,
        /// Override a scene key (dotted path).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Remove a scene key (dotted path).
        #[arg(long = "unset", value_name = "KEY")]
        unset: Vec<String>,
        /// Output directory (default `out/<scene name>_hugoniot`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// No per-trial progress lines.
        #[arg(long)]
        quiet: bool,
    },
    /// Every hard case (cases/hard/) with every scheme: reached t_end, NaN, density,
    /// energy and momentum errors, PASS/FAIL (stability.csv, stability.md); exits non-zero
    /// if any run fails.
    Stability(crate::stability::StabilityArgs),
    /// Pictures of a run's output directory.
    #[command(subcommand)]
    Plot(PlotCommand),
    /// The material library (cases/materials/, compiled in): one line per material; with
    /// NAME, its TOML (source and units in comments); with --scene, the scene's materials
    /// as a run resolves them and where each came from.
    Materials {
        /// A library material to print.
        #[arg(conflicts_with = "scene")]
        name: Option<String>,
        /// Print the resolved materials of this scene instead.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Override a scene key (dotted path; with --scene).
        #[arg(long = "set", value_name = "KEY=VALUE", requires = "scene")]
        set: Vec<String>,
        /// Remove a scene key (dotted path; with --scene).
        #[arg(long = "unset", value_name = "KEY", requires = "scene")]
        unset: Vec<String>,
    },
    /// Validate a scene, print particle counts and the resolved effects.
    Check {
        /// Scene file.
        scene: PathBuf,
        /// Override a scene key (dotted path), e.g. --set scheme=ts2.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Remove a scene key (dotted path), e.g. --unset options.riemann to run a scene
        /// that asks for the two-shock solver with scheme av.
        #[arg(long = "unset", value_name = "KEY")]
        unset: Vec<String>,
    },
    /// Run a scene.
    Run {
        /// Scene file (not with --restart).
        #[arg(required_unless_present = "restart")]
        scene: Option<PathBuf>,
        /// Output directory (default `out/<scene name>`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Override a scene key (dotted path), e.g. --set bodies.0.spacing=5e-4.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Remove a scene key (dotted path), e.g. --unset options.riemann.
        #[arg(long = "unset", value_name = "KEY")]
        unset: Vec<String>,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Write OUT/checkpoint.bin every K steps (docs/checkpoint.md).
        #[arg(long, value_name = "K")]
        checkpoint_every_steps: Option<u64>,
        /// Write OUT/checkpoint.bin every S seconds of wall time.
        #[arg(long, value_name = "S")]
        checkpoint_every_seconds: Option<f64>,
        /// Continue the run checkpointed in DIR to t_end; its outputs go to DIR.
        #[arg(long, value_name = "DIR", conflicts_with_all = ["scene", "out", "set", "unset"])]
        restart: Option<PathBuf>,
        /// Write a checkpoint after step N and stop, as if interrupted (tests).
        #[arg(long, value_name = "N", hide = true)]
        stop_after_steps: Option<u64>,
    },
}

/// What to plot.
#[derive(Subcommand, Debug)]
pub enum PlotCommand {
    /// A snapshot, particles coloured by a field (PNG or SVG by the extension of --out).
    Particles {
        /// Run output directory (holds snapshots.h5).
        dir: PathBuf,
        /// Field: a final.csv column or sigma_xx, sigma_yy, tau_xy, von_mises, speed, vr, r.
        #[arg(long, default_value = "eps_p")]
        field: String,
        /// Snapshot step (default: the last).
        #[arg(long)]
        step: Option<u64>,
        /// Snapshot nearest this time, s.
        #[arg(long)]
        time: Option<f64>,
        /// Colour range `MIN,MAX`.
        #[arg(long)]
        range: Option<String>,
        /// Draw this material index in black (e.g. a projectile).
        #[arg(long)]
        highlight_material: Option<u32>,
        /// Output file (default `DIR/<field>_<step>.png`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// sigma_xx of the final state against the exact profile (profile.csv).
    Profile {
        /// Run output directory (holds profile.csv).
        dir: PathBuf,
        /// Output file (default `DIR/profile.png`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Columns of series.csv against time (`*_exact` columns dashed).
    Series {
        /// Run output directory (holds series.csv).
        dir: PathBuf,
        /// Columns, comma-separated.
        #[arg(long)]
        columns: String,
        /// Label of the y axis (default: the first column's name).
        #[arg(long)]
        y_label: Option<String>,
        /// Output file (default `DIR/series_<columns>.png`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// u_s against u_p from the hugoniot.csv of one or more `gsph hugoniot` outputs, with
    /// the seed's fits (PNG or SVG by the extension of --out).
    Hugoniot {
        /// Output directories of `gsph hugoniot` (each holds hugoniot.csv).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Legend entries, comma-separated, one per directory (default: the names).
        #[arg(long)]
        labels: Option<String>,
        /// Output file.
        #[arg(long)]
        out: PathBuf,
    },
}

/// The exit code of a failed command when not 1: 128 + the signal's number after
/// SIGINT/SIGTERM stopped a run.
static EXIT_CODE: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(0);

/// Most worker threads per core `--threads` may ask for.
pub const MAX_THREADS_PER_CORE: usize = 8;

fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool, String> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        if t == 0 {
            return Err("--threads must be at least 1".into());
        }
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        if t > MAX_THREADS_PER_CORE * cores {
            return Err(format!(
                "--threads {t}: this machine has {cores} cores; more than {MAX_THREADS_PER_CORE} threads per core ({}) only slows a run down",
                MAX_THREADS_PER_CORE * cores
            ));
        }
        b = b.num_threads(t);
    }
    b.build().map_err(|e| format!("cannot start threads: {e}"))
}

/// Sets the scene up as a run would (neighbour lists, overlap check, specialisation), so
/// `gsph check` fails where `gsph run` would fail before its first step.
fn probe(sc: &scene::Scene, parts: &scene::InitialParticles) -> Result<(), SimError> {
    match sc.dim {
        1 => Sim::<1>::new(sc, parts).map(drop),
        2 => Sim::<2>::new(sc, parts).map(drop),
        _ => Sim::<3>::new(sc, parts).map(drop),
    }
}

/// Runs the CLI on `args`; returns the process exit code. Errors are printed as one line.
pub fn main_with_args(args: impl IntoIterator<Item = std::ffi::OsString>) -> i32 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) if e.use_stderr() => {
            // clap's message is a paragraph, then usage: keep the paragraph, on one line
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            eprintln!("{}", first.join(" "));
            return 2;
        }
        Err(e) => {
            let _ = e.print();
            return 0;
        }
    };
    let ranks = crate::dist_size();
    if ranks > 1 && !matches!(cli.command, Command::Run { .. }) {
        if crate::dist_rank() == 0 {
            eprintln!(
                "error: only `gsph run` runs on several MPI ranks (this is rank 0 of {ranks}); run the others in one process"
            );
        }
        return 2;
    }
    match execute(cli.command) {
        Ok(()) => 0,
        Err(msg) => {
            let code = match EXIT_CODE.load(std::sync::atomic::Ordering::Relaxed) {
                0 => 1,
                c => c,
            };
            let who = match crate::dist_rank() {
                0 => String::new(),
                r => format!("rank {r}: "),
            };
            eprintln!("{who}error: {}", msg.replace('\n', " "));
            code
        }
    }
}

/// `gsph plot ...`.
#[cfg(feature = "plot")]
fn plot(cmd: PlotCommand) -> Result<(), String> {
    match cmd {
        PlotCommand::Particles {
            dir,
            field,
            step,
            time,
            range,
            highlight_material,
            out,
        } => {
            let range = match range {
                None => None,
                Some(r) => {
                    let v: Vec<f64> = r
                        .split(',')
                        .map(|x| x.trim().parse().unwrap_or(f64::NAN))
                        .collect();
                    if v.len() != 2 || v.iter().any(|x| !x.is_finite()) || v[0] >= v[1] {
                        return Err(format!(
                            "--range: expected MIN,MAX (finite numbers, MIN < MAX), got `{r}`"
                        ));
                    }
                    Some((v[0], v[1]))
                }
            };
            if let Some(t) = time.filter(|t| !t.is_finite()) {
                return Err(format!(
                    "--time: must be a finite number of seconds (got {t})"
                ));
            }
            let path = crate::commands::plot_particles(
                &dir,
                &field,
                step,
                time,
                range,
                highlight_material,
                out,
            )?;
            out!("wrote {}", path.display());
            Ok(())
        }
        PlotCommand::Profile { dir, out } => {
            let path = crate::commands::plot_profile(&dir, out)?;
            out!("wrote {}", path.display());
            Ok(())
        }
        PlotCommand::Hugoniot { dirs, labels, out } => {
            let labels: Vec<String> = labels
                .map(|l| l.split(',').map(|x| x.trim().to_string()).collect())
                .unwrap_or_default();
            crate::window::plot::plot_runs(&dirs, &labels, &out)?;
            out!("wrote {}", out.display());
            Ok(())
        }
        PlotCommand::Series {
            dir,
            columns,
            y_label,
            out,
        } => {
            let cols: Vec<String> = columns.split(',').map(|c| c.trim().to_string()).collect();
            let path = crate::commands::plot_series(&dir, &cols, y_label, out)?;
            out!("wrote {}", path.display());
            Ok(())
        }
    }
}

/// `gsph plot ...` in a build without plotting: refused.
#[cfg(not(feature = "plot"))]
fn plot(_cmd: PlotCommand) -> Result<(), String> {
    Err(format!("gsph plot: {}", crate::commands::NO_PLOT))
}

fn execute(cmd: Command) -> Result<(), String> {
    match cmd {
        Command::Study {
            scene: path,
            schemes,
            resolutions,
            metric,
            set,
            unset,
            out,
            threads,
        } => {
            let set = scene::with_unsets(set, &unset);
            let sc = scene::load(&path, &set).map_err(|e| e.to_string())?;
            let name = scene_name(&sc, &path);
            let opts = crate::study::StudyOptions {
                schemes: crate::commands::parse_schemes(&schemes)?,
                resolutions: crate::commands::parse_resolutions(&resolutions)?,
                overrides: set,
                metric,
                out: match out {
                    Some(o) => o,
                    None => crate::outdir::default_dir(&name, "_study")?,
                },
            };
            let pool = pool(threads)?;
            pool.install(|| crate::commands::run_study(&path, &opts))?;
            out!(
                "{}",
                std::fs::read_to_string(opts.out.join("study.md")).unwrap_or_default()
            );
            out!("wrote {}", opts.out.display());
            Ok(())
        }
        Command::Stability(args) => crate::stability::command(&args),
        Command::Materials {
            name,
            scene: path,
            set,
            unset,
        } => {
            use crate::scene::library;
            let text = match (name, path) {
                (Some(name), _) => library::show(&name)?,
                (None, Some(path)) => {
                    library::scene_report(&path, &scene::with_unsets(set, &unset))?
                }
                (None, None) => library::list()?,
            };
            out!("{}", text.trim_end());
            Ok(())
        }
        Command::Plot(cmd) => plot(cmd),
        Command::Check {
            scene: path,
            set,
            unset,
        } => {
            let set = scene::with_unsets(set, &unset);
            let sc = scene::load(&path, &set).map_err(|e| e.to_string())?;
            let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
            let parts = build_particles(&sc).map_err(|e| at(&e))?;
            Reference::from_scene(&sc, &parts.x, &parts.spacing).map_err(|e| at(&e))?;
            probe(&sc, &parts).map_err(|e| at(&e))?;
            let materials: Vec<_> = sc
                .materials
                .iter()
                .map(crate::materials::material_of)
                .collect();
            let effects = crate::sim::resolve_effects(&sc, &materials);
            out!("scene     {}", scene_name(&sc, &path));
            out!("dim       {}", sc.dim);
            out!("scheme    {}", sc.scheme);
            // where each material came from: the scene, the library or an included file
            for (k, m) in sc.materials.iter().enumerate() {
                let source = sc.material_sources.get(k).map_or("scene", String::as_str);
                out!("material  {}: {source}", m.name);
            }
            out!("particles {}", parts.len());
            for (b, body) in sc.bodies.iter().enumerate() {
                let n = parts.body.iter().filter(|&&k| k as usize == b).count();
                match &body.pores {
                    Some(pores) => out!(
                        "  body {b} ({}): {n}, porosity m = {:.4} as built ({:.4} from the pore geometry)",
                        body.material,
                        parts.porosity[b],
                        crate::scene::pores::geometric_porosity(pores)
                    ),
                    None => out!("  body {b} ({}): {n}", body.material),
                }
            }
            out!("effects   {effects}");
            if sc.options.riemann.as_deref() == Some("two_shock") {
                // the two-shock solver's Us = c + s up slope of each material
                let slopes: Vec<String> = sc
                    .materials
                    .iter()
                    .zip(&materials)
                    .map(|(spec, m)| {
                        let how = match m.eos {
                            gsph_core::material::Eos::MieGruneisen(_)
                            | gsph_core::material::Eos::Hugoniot(_)
                            | gsph_core::material::Eos::TwoCurve(_) => "the EOS's",
                            _ => "weak-shock (1 + K')/4",
                        };
                        format!("{} {:.4} ({how})", spec.name, m.eos.hugoniot_slope())
                    })
                    .collect();
                out!(
                    "riemann   two_shock, Hugoniot slope s: {}",
                    slopes.join(", ")
                );
            }
            let dim = sc.dim;
            let scheme = gsph_core::schemes::Scheme::from_name(&sc.scheme).expect("validated");
            let (n, all) = crate::specs::compiled();
            match crate::specs::find(dim, scheme.family(), effects) {
                Some(s) if s.compiled => {
                    out!(
                        "kernel    {} (compiled; this build contains {n} of {all} specialisations)",
                        s.name
                    );
                    // what crosses rank boundaries under MPI (docs/mpi.md)
                    let halo: Vec<String> = gsph_core::halo::exchanges_of(scheme.family())
                        .iter()
                        .filter(|x| x.applies(effects))
                        .map(|x| {
                            let f: Vec<&str> = x.fields.names().collect();
                            format!("{} ({})", x.before, f.join(" "))
                        })
                        .collect();
                    out!(
                        "halo      under MPI, ghosts refreshed before: {}",
                        halo.join(", ")
                    );
                }
                Some(_) => {
                    return Err(at(&SimError::NotCompiled {
                        dim,
                        scheme,
                        effects,
                    }))
                }
                None => {
                    return Err(format!(
                        "no specialisation exists for {dim}D {} with effects {effects}",
                        sc.scheme
                    ))
                }
            }
            Ok(())
        }
        Command::Hugoniot {
            scene: path,
            up,
            bracket,
            tolerance,
            samples,
            average,
            set,
            unset,
            out,
            threads,
            quiet,
        } => {
            let set = scene::with_unsets(set, &unset);
            let sc = scene::load(&path, &set).map_err(|e| e.to_string())?;
            if sc.window.is_none() {
                return Err(format!(
                    "{}: no [window] section: `gsph hugoniot` needs a moving-window scene",
                    path.display()
                ));
            }
            let name = scene_name(&sc, &path);
            let bracket = match bracket {
                None => None,
                Some(b) => match crate::commands::parse_positive("--bracket", &b)?[..] {
                    [lo, hi] if lo < hi => Some((lo, hi)),
                    _ => return Err(format!("--bracket: `{b}` must be LO,HI with LO < HI")),
                },
            };
            for (flag, v) in [
                ("--tolerance", tolerance),
                ("--samples", samples),
                ("--average", average),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(format!("{flag}: must be positive (got {v})"));
                }
            }
            let opts = crate::window::hugoniot::HugoniotOptions {
                ups: crate::commands::parse_positive("--up", &up)?,
                bracket,
                tolerance,
                samples,
                average,
                verbose: !quiet,
                ..Default::default()
            };
            let out = match out {
                Some(o) => o,
                None => crate::outdir::default_dir(&name, "_hugoniot")?,
            };
            let pool = pool(threads)?;
            pool.install(|| crate::commands::run_hugoniot(&sc, &opts, &out))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            out!("wrote {}", out.display());
            Ok(())
        }
        Command::Run {
            scene,
            out,
            set,
            unset,
            threads,
            quiet,
            checkpoint_every_steps,
            checkpoint_every_seconds,
            restart,
            stop_after_steps,
        } => {
            let set = scene::with_unsets(set, &unset);
            use crate::checkpoint::{setup, Policy};
            let flags = Policy {
                every_steps: checkpoint_every_steps,
                every_seconds: checkpoint_every_seconds,
                stop_after_steps,
            };
            setup::check_flags(&flags)?;
            let (sc, out, ckpt) = match (restart, scene) {
                (Some(dir), _) => setup::restart(&dir, flags)?,
                (None, Some(path)) => {
                    // nothing touches the output folder until the run is validated and
                    // holds its lock (the driver; under MPI rank 0 alone)
                    let (sc, source) = setup::load(&path, &set)?;
                    let ranks = crate::dist_size();
                    if ranks > 1 && sc.window.is_some() {
                        return Err(format!(
                            "{}: the moving window (`window`) runs on one rank; this run has {ranks} MPI ranks",
                            path.display()
                        ));
                    }
                    let out = match out {
                        Some(o) => o,
                        None => crate::outdir::default_dir(&source.name, "")?,
                    };
                    let policy = setup::merge(flags, &sc);
                    (
                        sc,
                        out,
                        CheckpointOptions {
                            policy,
                            source,
                            resume: None,
                        },
                    )
                }
                (None, None) => return Err("a scene file or --restart DIR is needed".into()),
            };
            let name = ckpt.source.name.clone();
            let origin = ckpt.source.origin.clone();
            let pool = pool(threads)?;
            crate::interrupt::install()?;
            let opts = RunOptions {
                out: Some(out.clone()),
                progress: !quiet,
            };
            let outcome = pool
                .install(|| run_checkpointed(&sc, &name, &opts, &ckpt))
                .map_err(|e| match e {
                    RunError::Output(e) => format!("{}: cannot write output: {e}", out.display()),
                    e @ RunError::Interrupted { signal, .. } => {
                        EXIT_CODE.store(128 + signal, std::sync::atomic::Ordering::Relaxed);
                        format!("{origin}: {e}")
                    }
                    e @ RunError::Checkpoint(_) => e.to_string(),
                    e => format!("{origin}: {e}"),
                })?;
            let res = match outcome {
                Outcome::Finished(res) => res,
                Outcome::Stopped { step } => {
                    out!(
                        "{name}: stopped after step {step}; checkpoint in {}",
                        out.display()
                    );
                    return Ok(());
                }
            };
            let s = &res.summary;
            let g = |k: &str| s.get(k).cloned().unwrap_or_default();
            out!(
                "{name}: {} {}D, {} particles, {} steps, wall {:.3} s, energy error {:.3e}{}",
                g("scheme").as_str().unwrap_or(""),
                g("dim"),
                g("particles"),
                g("steps"),
                g("wall_s").as_f64().unwrap_or(0.0),
                g("energy_rel_error").as_f64().unwrap_or(0.0),
                s.get("l1_error")
                    .and_then(|v| v.as_f64())
                    .map(|v| format!(", L1 error {v:.4e}"))
                    .unwrap_or_default()
            );
            out!("wrote {}", out.display());
            Ok(())
        }
    }
}
