//! The rayon executor of the core's per-particle loops (in `gsph-steps`, which compiles
//! the step specialisations for it), the instruction-set level the steps run at
//! (`gsph --simd`, the environment variable `GSPH_SIMD`), and the bound on the worker
//! threads a caller may ask for (`gsph --threads`, the C ABI's `gsph_set_threads`).

use std::sync::Mutex;

pub use gsph_core::simd::{Simd, SimdLevel};
pub use gsph_steps::Rayon;

/// Whether this CPU has the instructions of `simd`'s loops.
pub fn available(simd: Simd) -> bool {
    match simd {
        Simd::Baseline => true,
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => std::arch::is_x86_feature_detected!("avx2"),
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => {
            std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx2")
        }
        #[cfg(not(target_arch = "x86_64"))]
        Simd::Avx2 | Simd::Avx512 => false,
    }
}

/// The highest level this CPU has.
pub fn highest() -> Simd {
    Simd::ALL
        .into_iter()
        .rev()
        .find(|&l| available(l))
        .unwrap_or(Simd::Baseline)
}

/// The level `auto` picks: the highest this CPU has, except that AVX-512 is run only when
/// asked for by name (`--simd avx512`): on the one AVX-512 machine measured (an Intel Xeon,
/// docs/performance.md "SIMD levels"; docs/notes/performance_history_28_continued.md) its
/// loops were no faster than the AVX2 ones and up to 8 % slower (bitwise the same results
/// either way).
pub fn detect() -> Simd {
    match highest() {
        Simd::Avx512 => Simd::Avx2,
        l => l,
    }
}

/// The level as the core takes it, if this CPU has it.
pub fn level(simd: Simd) -> Result<SimdLevel, String> {
    if !available(simd) {
        return Err(format!(
            "this CPU cannot run the level `{simd}` (it has up to `{}`)",
            highest()
        ));
    }
    // SAFETY: checked just above
    Ok(unsafe { SimdLevel::assume(simd) })
}

/// The environment variable that picks the instruction-set level of every simulation of
/// the process (`baseline`, `avx2`, `avx512` or `auto`; unset: `auto`, [`detect`]'s
/// choice). `gsph --simd` overrides it.
pub const SIMD_ENV: &str = "GSPH_SIMD";

static SIMD_CHOICE: Mutex<Option<Simd>> = Mutex::new(None);

/// The level `name` asks for (`auto`: [`detect`]'s choice), or why it cannot run here
/// (a one-line error without the key; the caller names it).
pub fn parse_simd(name: &str) -> Result<Simd, String> {
    let name = name.trim();
    if name == "auto" {
        return Ok(detect());
    }
    let Some(l) = Simd::from_name(name) else {
        return Err(format!(
            "unknown instruction-set level `{name}` ({})",
            level_names()
        ));
    };
    level(l).map(|_| l)
}

/// `one of auto, baseline, avx2, avx512`: what `--simd` and `GSPH_SIMD` take.
fn level_names() -> String {
    let names: Vec<&str> = Simd::ALL.iter().map(|l| l.name()).collect();
    format!("one of auto, {}", names.join(", "))
}

/// Sets the level of the simulations this process builds from now on (`gsph --simd`);
/// an error if the CPU lacks it.
pub fn set_simd(simd: Simd) -> Result<(), String> {
    level(simd)?;
    *SIMD_CHOICE.lock().unwrap_or_else(|e| e.into_inner()) = Some(simd);
    Ok(())
}

/// The level a new simulation runs at: the one [`set_simd`] chose, else [`SIMD_ENV`]'s,
/// else [`detect`]'s choice; an error naming `GSPH_SIMD` if that variable asks for an
/// unknown level or one this CPU lacks.
pub fn simd() -> Result<SimdLevel, String> {
    let chosen = *SIMD_CHOICE.lock().unwrap_or_else(|e| e.into_inner());
    let simd = match (chosen, std::env::var(SIMD_ENV)) {
        (Some(l), _) => l,
        (None, Ok(v)) => parse_simd(&v).map_err(|e| format!("{SIMD_ENV}={v}: {e}"))?,
        (None, Err(std::env::VarError::NotPresent)) => detect(),
        (None, Err(std::env::VarError::NotUnicode(_))) => {
            return Err(format!("{SIMD_ENV}: not valid UTF-8 ({})", level_names()))
        }
    };
    level(simd)
}

/// Most worker threads per core a caller may ask for.
pub const MAX_THREADS_PER_CORE: usize = 8;

/// `Ok` if `threads` worker threads are at most [`MAX_THREADS_PER_CORE`] per core of this
/// machine; else why not (`this machine has 2 cores; more than 8 threads per core (16)
/// only slows a run down`), for the caller to prefix with what it names (`--threads N`).
pub fn check_threads(threads: usize) -> Result<(), String> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if threads > MAX_THREADS_PER_CORE * cores {
        return Err(format!(
            "this machine has {cores} cores; more than {MAX_THREADS_PER_CORE} threads per core ({}) only slows a run down",
            MAX_THREADS_PER_CORE * cores
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `auto` is the CPU's best level except AVX-512, which runs only when named; a named
    /// level runs exactly where the CPU has it.
    #[test]
    fn auto_never_picks_avx512_and_named_levels_follow_the_cpu() {
        let auto = parse_simd("auto").unwrap();
        assert_ne!(auto, Simd::Avx512);
        assert!(available(auto));
        assert_eq!(auto == Simd::Avx2, available(Simd::Avx2));
        assert!(highest() >= auto);
        for l in Simd::ALL {
            assert_eq!(parse_simd(l.name()).is_ok(), available(l), "{l}");
        }
        let err = parse_simd("avx1024").unwrap_err();
        assert!(err.contains("one of auto, baseline, avx2, avx512"), "{err}");
    }
}
