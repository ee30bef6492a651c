//! `gsph stability`: every hard case with every scheme ([`crate::stability`]).

use crate::stability::{run_suite, to_markdown, StabilityOptions, Verdict};
use std::path::PathBuf;

/// Arguments of `gsph stability`.
#[derive(clap::Args, Debug)]
pub struct StabilityArgs {
    /// Reduced sizes and shorter runs (a few minutes in all).
    #[arg(long)]
    pub quick: bool,
    /// Schemes, comma-separated.
    #[arg(long, default_value = "av,pm,ts1,ts2,tkc")]
    pub schemes: String,
    /// Output directory for stability.csv and stability.md.
    #[arg(long, default_value = "out/stability")]
    pub out: PathBuf,
    /// Directory of hard cases (every *.toml in it).
    #[arg(long, default_value = "cases/hard")]
    pub cases: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long, allow_negative_numbers = true)]
    pub threads: Option<usize>,
}

/// `gsph stability`: runs the suite, prints the table; an error (non-zero exit) if any run
/// fails.
pub fn command(args: StabilityArgs) -> Result<(), String> {
    let opts = StabilityOptions {
        cases: args.cases.clone(),
        schemes: crate::study::parse_schemes(&args.schemes)?,
        quick: args.quick,
        out: Some(args.out.clone()),
        verbose: true,
    };
    let pool = super::pool(args.threads)?;
    let rows = pool.install(|| run_suite(&opts))?;
    let md = to_markdown(&rows, opts.quick, pool.current_num_threads());
    out!("{md}");
    out!("wrote {}", args.out.display());
    let failed = rows.iter().filter(|r| r.verdict == Verdict::Fail).count();
    if failed > 0 {
        return Err(format!(
            "stability: {failed} of {} runs FAIL (see {})",
            rows.len(),
            args.out.join("stability.md").display()
        ));
    }
    Ok(())
}
