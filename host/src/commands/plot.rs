//! `gsph plot`: pictures of a run's output directory ([`crate::plot::runs`]) and of
//! Hugoniot runs ([`crate::window::plot`]).

use std::path::PathBuf;

/// What to plot.
#[derive(clap::Subcommand, Debug)]
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
        /// Colour range `MIN,MAX` (MIN may be negative: `--range -2e8,2e8`).
        #[arg(long, allow_hyphen_values = true)]
        range: Option<String>,
        /// Draw this material index in black (e.g. a projectile).
        #[arg(long)]
        highlight_material: Option<u32>,
        /// The coordinates along the width and height, e.g. `x,z` for a side view in 3D.
        #[arg(long, default_value = "x,y")]
        axes: String,
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
    /// The final outline of a rod after a Taylor impact (from final.csv) for one or more
    /// runs, with a measured outline (a CSV `r_mm,z_mm`) dashed.
    Rod {
        /// Run output directories (each holds final.csv).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Legend entries, comma-separated, one per directory (default: the names).
        #[arg(long)]
        labels: Option<String>,
        /// The measured outline, e.g. cases/data/taylor_wilkins_guinan_1973.csv.
        #[arg(long)]
        outline: Option<PathBuf>,
        /// The rod's axis: 0, 1 or 2.
        #[arg(long, default_value_t = 2, allow_negative_numbers = true)]
        axis: usize,
        /// A point of the impact face on the axis, `X,Y,Z` (m).
        #[arg(long, default_value = "0,0,0")]
        base: String,
        /// Output file (PNG or SVG by the extension).
        #[arg(long)]
        out: PathBuf,
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

/// Runs `gsph plot ...`.
#[cfg(feature = "plot")]
pub fn command(cmd: PlotCommand) -> Result<(), String> {
    match cmd {
        PlotCommand::Particles {
            dir,
            field,
            step,
            time,
            range,
            highlight_material,
            axes,
            out,
        } => {
            let bad = || format!("--axes: expected two of x, y, z such as `x,z` (got `{axes}`)");
            let pick: Vec<Option<usize>> = axes
                .split(',')
                .map(|n| ["x", "y", "z"].iter().position(|a| *a == n.trim()))
                .collect();
            let (a, b) = match pick[..] {
                [Some(a), Some(b)] if a != b => (a, b),
                _ => return Err(bad()),
            };
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
            let path = crate::plot::runs::particles(
                &dir,
                &field,
                step,
                time,
                range,
                highlight_material,
                (a, b),
                out,
            )?;
            out!("wrote {}", path.display());
            Ok(())
        }
        PlotCommand::Profile { dir, out } => {
            let path = crate::plot::runs::profile(&dir, out)?;
            out!("wrote {}", path.display());
            Ok(())
        }
        PlotCommand::Rod {
            dirs,
            labels,
            outline,
            axis,
            base,
            out,
        } => {
            let labels = super::labels(labels);
            let b = super::parse_finite("--base", &base)?;
            if b.len() != 3 {
                return Err(format!("--base: expected X,Y,Z (got `{base}`)"));
            }
            let base = [b[0], b[1], b[2]];
            crate::plot::runs::rod(&dirs, &labels, base, axis, outline.as_deref(), &out)?;
            out!("wrote {}", out.display());
            Ok(())
        }
        PlotCommand::Hugoniot { dirs, labels, out } => {
            let labels = super::labels(labels);
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
            let path = crate::plot::runs::series(&dir, &cols, y_label, out)?;
            out!("wrote {}", path.display());
            Ok(())
        }
    }
}

/// `gsph plot ...` in a build without plotting: refused.
#[cfg(not(feature = "plot"))]
pub fn command(_cmd: PlotCommand) -> Result<(), String> {
    Err(format!("gsph plot: {}", crate::NO_PLOT))
}
