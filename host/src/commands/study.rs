//! `gsph study`: a scene for a grid of schemes and resolutions ([`crate::study`]).

use crate::scene::{self, scene_name};
use std::path::PathBuf;

/// Arguments of `gsph study`.
#[derive(clap::Args, Debug)]
pub struct StudyArgs {
    /// Scene file.
    pub scene: PathBuf,
    /// Schemes, comma-separated.
    #[arg(long, default_value = "av,pm,ts1,ts2,tkc")]
    pub schemes: String,
    /// Resolution scales, comma-separated.
    #[arg(long, default_value = "1,2,4")]
    pub resolutions: String,
    /// Summary key used as the error (default: l1_error, radius_error or energy_rel_error).
    #[arg(long)]
    pub metric: Option<String>,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: super::Overrides,
    /// Output directory (default `out/<scene name>_study`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long, allow_negative_numbers = true)]
    pub threads: Option<usize>,
}

/// Runs `gsph study`.
pub fn command(args: StudyArgs) -> Result<(), String> {
    let StudyArgs {
        scene: path,
        schemes,
        resolutions,
        metric,
        overrides,
        out,
        threads,
    } = args;
    let set = overrides.list();
    let sc = scene::load(&path, &set).map_err(|e| e.to_string())?;
    let name = scene_name(&sc, &path);
    let opts = crate::study::StudyOptions {
        schemes: crate::study::parse_schemes(&schemes)?,
        resolutions: super::parse_positive("--resolutions", &resolutions)?,
        overrides: set,
        metric,
        out: match out {
            Some(o) => o,
            None => crate::outdir::default_dir(&name, "_study")?,
        },
    };
    let pool = super::pool(threads)?;
    pool.install(|| crate::study::run_study(&path, &opts))?;
    out!(
        "{}",
        std::fs::read_to_string(opts.out.join("study.md")).unwrap_or_default()
    );
    out!("wrote {}", opts.out.display());
    Ok(())
}
