//! Setting up `gsph run` with checkpoints: the scene with its source text, the policy from
//! the flags and the scene keys, and the restart of a checkpointed run.

use super::{Checkpoint, Policy, SceneSource};
use crate::driver::CheckpointOptions;
use crate::scene::{self, Scene};
use std::path::{Path, PathBuf};

/// Checks the checkpoint flags of `gsph run`.
pub fn check_flags(p: &Policy) -> Result<(), String> {
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
pub fn merge(flags: Policy, scene: &Scene) -> Policy {
    Policy {
        every_steps: flags.every_steps.or(scene.output.checkpoint_steps),
        every_seconds: flags.every_seconds.or(scene.output.checkpoint_seconds),
        stop_after_steps: flags.stop_after_steps,
    }
}

/// Loads a scene file with its overrides, keeping the text for checkpoints.
pub fn load(path: &Path, overrides: &[String]) -> Result<(Scene, SceneSource), String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read scene: {e}", path.display()))?;
    let origin = path.display().to_string();
    let sc = scene::parse(&text, &origin, overrides).map_err(|e| e.to_string())?;
    let name = crate::driver::scene_name(&sc, path);
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
pub fn restart(dir: &Path, flags: Policy) -> Result<(Scene, PathBuf, CheckpointOptions), String> {
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
