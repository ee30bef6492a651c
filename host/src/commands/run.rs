//! `gsph run`: a scene run to t_end, with checkpoints and restarts (docs/checkpoint.md):
//! the scene with its source text, the policy from the flags and the scene keys, and the
//! restart of a checkpointed run bound to the run that wrote it.

use crate::checkpoint::{Checkpoint, Policy, SceneSource};
use crate::driver::{run_checkpointed, CheckpointOptions, Outcome, RunError, RunOptions};
use crate::scene::{self, Scene};
use std::path::{Path, PathBuf};

/// Arguments of `gsph run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Scene file (not with --restart).
    #[arg(required_unless_present = "restart")]
    pub scene: Option<PathBuf>,
    /// Output directory (default `out/<scene name>`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: super::Overrides,
    /// Worker threads (default: all cores).
    #[arg(long, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Instruction-set level of the vectorised loops: auto (AVX2 where this CPU has it),
    /// baseline, avx2 or avx512; results are bitwise the same (default: GSPH_SIMD, else
    /// auto).
    #[arg(long, value_name = "LEVEL")]
    pub simd: Option<String>,
    /// Write OUT/checkpoint.bin every K steps (docs/checkpoint.md).
    #[arg(long, value_name = "K", allow_negative_numbers = true)]
    pub checkpoint_every_steps: Option<u64>,
    /// Write OUT/checkpoint.bin every S seconds of wall time.
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub checkpoint_every_seconds: Option<f64>,
    /// Continue the run checkpointed in DIR to t_end; its outputs go to DIR.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["scene", "out", "set", "unset"])]
    pub restart: Option<PathBuf>,
    /// Write a checkpoint after step N and stop, as if interrupted (tests).
    #[arg(long, value_name = "N", hide = true, allow_negative_numbers = true)]
    pub stop_after_steps: Option<u64>,
}

/// Runs `gsph run`.
pub fn command(args: RunArgs) -> Result<(), super::Failure> {
    let RunArgs {
        scene,
        out,
        overrides,
        threads,
        quiet,
        simd,
        checkpoint_every_steps,
        checkpoint_every_seconds,
        restart: restart_dir,
        stop_after_steps,
    } = args;
    let set = overrides.list();
    let flags = Policy {
        every_steps: checkpoint_every_steps,
        every_seconds: checkpoint_every_seconds,
        stop_after_steps,
    };
    check_flags(&flags)?;
    if let Some(name) = &simd {
        let level = crate::exec::parse_simd(name).map_err(|e| format!("--simd {name}: {e}"))?;
        crate::exec::set_simd(level).map_err(|e| format!("--simd {name}: {e}"))?;
    }
    let (sc, out, ckpt) = match (restart_dir, scene) {
        (Some(dir), _) => restart(&dir, flags)?,
        (None, Some(path)) => {
            // nothing touches the output folder until the run is validated and
            // holds its lock (the driver; under MPI rank 0 alone)
            // (a scene the ranks cannot run, such as a moving window, is refused by the
            // driver's set-up, before the folder is touched)
            let (sc, source) = load(&path, &set)?;
            let out = match out {
                Some(o) => o,
                None => crate::outdir::default_dir(&source.name, "")?,
            };
            let policy = merge(flags, &sc);
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
    let pool = super::pool(threads)?;
    crate::interrupt::install()?;
    let opts = RunOptions {
        out: Some(out.clone()),
        progress: !quiet,
    };
    let outcome = pool
        .install(|| run_checkpointed(&sc, &name, &opts, &ckpt))
        .map_err(|e| match e {
            RunError::Output(e) => format!("{}: cannot write output: {e}", out.display()).into(),
            e @ RunError::Interrupted { signal, .. } => super::Failure {
                message: format!("{origin}: {e}"),
                code: 128 + signal,
            },
            e @ RunError::Checkpoint(_) => e.to_string().into(),
            e => format!("{origin}: {e}").into(),
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
    out!(
        "{name}: {} {}D, {} particles, {} steps, wall {:.3} s, energy error {:.3e}{}",
        s.scheme,
        s.dim,
        s.particles,
        s.steps,
        s.wall_s,
        s.energy_rel_error,
        s.measure("l1_error")
            .map(|v| format!(", L1 error {v:.4e}"))
            .unwrap_or_default()
    );
    if s.ended == "max_steps" {
        out!(
            "{name}: stopped by max_steps = {} at t = {:e} s, before t_end",
            s.steps,
            s.t_end
        );
    }
    out!("wrote {}", out.display());
    Ok(())
}

/// Checks the checkpoint flags of `gsph run`.
fn check_flags(p: &Policy) -> Result<(), String> {
    if p.every_steps == Some(0) {
        return Err("--checkpoint-every-steps must be at least 1".into());
    }
    if let Some(s) = p.every_seconds {
        if !(s.is_finite() && s > 0.0) {
            return Err(format!(
                "--checkpoint-every-seconds must be positive (got {s})"
            ));
        }
    }
    if p.stop_after_steps == Some(0) {
        return Err("--stop-after-steps must be at least 1".into());
    }
    Ok(())
}

/// The policy of a run: the flags where given, else the scene's `[output]` keys.
fn merge(flags: Policy, scene: &Scene) -> Policy {
    Policy {
        every_steps: flags.every_steps.or(scene.output.checkpoint_steps),
        every_seconds: flags.every_seconds.or(scene.output.checkpoint_seconds),
        stop_after_steps: flags.stop_after_steps,
    }
}

/// Loads a scene file with its overrides, keeping the text for checkpoints.
fn load(path: &Path, overrides: &[String]) -> Result<(Scene, SceneSource), String> {
    let text = scene::read_scene(path).map_err(|e| e.to_string())?;
    let origin = path.display().to_string();
    let sc = scene::parse(&text, &origin, overrides).map_err(|e| e.to_string())?;
    let name = scene::scene_name(&sc, path);
    let source = SceneSource {
        origin,
        text,
        overrides: overrides.to_vec(),
        name,
    };
    Ok((sc, source))
}

/// A restart of the run checkpointed in `dir`: its scene, its output directory (`dir`) and
/// the checkpoint options (the flags where given, else the policy stored in the checkpoint).
fn restart(dir: &Path, flags: Policy) -> Result<(Scene, PathBuf, CheckpointOptions), String> {
    let ck = Checkpoint::read(dir).map_err(|e| e.to_string())?;
    let sc = scene::parse(&ck.source.text, &ck.source.origin, &ck.source.overrides)
        .map_err(|e| format!("{}: the checkpoint's scene: {e}", dir.display()))?;
    ck.check_state(&sc).map_err(|e| e.to_string())?;
    // bound to its run: never resumed over the results of another run, nor of its own
    // finished run
    match crate::outdir::summary_run_id(dir) {
        Some(id) if id == ck.run_id => {
            return Err(format!(
                "{}: the run of this checkpoint (run {id}) has finished (summary.json); nothing to resume",
                dir.display()
            ))
        }
        Some(id) => {
            return Err(format!(
                "{}: checkpoint.bin belongs to run {} but summary.json to run {id}, a later run; refusing to resume over its results",
                dir.display(),
                ck.run_id
            ))
        }
        None => {}
    }
    ck.check_same_run().map_err(|e| e.to_string())?;
    let policy = Policy {
        every_steps: flags.every_steps.or(ck.policy.every_steps),
        every_seconds: flags.every_seconds.or(ck.policy.every_seconds),
        stop_after_steps: flags.stop_after_steps,
    };
    let opts = CheckpointOptions {
        policy,
        source: ck.source.clone(),
        resume: Some(ck),
    };
    Ok((sc, dir.to_path_buf(), opts))
}
