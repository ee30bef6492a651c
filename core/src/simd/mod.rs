//! Explicitly vectorised loops, several pairs per instruction, chosen at run time.
//!
//! A step runs a loop's vectorised version when [`StepParams::simd`](crate::schemes::workspace::StepParams)
//! says the CPU has the instructions. The core cannot ask the CPU (`no_std`): the host
//! detects the level and vouches for it through the `unsafe` [`SimdLevel::assume`]; an
//! embedded caller that never does runs the portable loops, which are the reference the
//! vectorised ones are tested against.
//!
//! **Results are bitwise identical at every level.** Each lane performs exactly the scalar
//! code's IEEE operations in the scalar code's order (no fused multiply-add: Rust never
//! contracts on its own, and the kernels call no FMA instruction), branches become blends
//! of both sides, and nothing is summed across lanes.
//!
//! This module holds only what no scheme owns: the levels ([`Simd`], [`SimdLevel`]), the
//! lane types (`lanes::Lanes`: `__m256d`, four lanes, for AVX2; `__m512d`, eight, for
//! AVX-512F), the lane operations, kernel shapes, limiters and vector algebra (`ops.rs`)
//! and each Riemann solver once (`riemann.rs`). A scheme's loops in lanes live in the
//! scheme's folder beside their portable twins, each entered through one function per level
//! compiled for its instructions (`…_avx2`, `…_avx512`; the AVX-512 entries run a row's
//! full groups of eight in `zmm` registers and the rest in `ymm` ones):
//!
//! | portable twin | lane twin | test that holds them bitwise equal |
//! | --- | --- | --- |
//! | `schemes/pairs/mod.rs` `geometry_pass` (the `pm` and `ts` families' pair geometry; the cubic spline and Wendland C2 kernels, periodic axes by the minimum image) | `schemes/pairs/lanes.rs` | `schemes/pairs/lanes_tests.rs` |
//! | `schemes/av/pairs.rs` `rates` (av's one pair loop, with the geometry in it) | `schemes/av/lanes.rs` | `schemes/av/lanes_tests.rs` |
//! | `schemes/ts/pairs.rs` `star` (ts1, ts2: MUSCL, acoustic or two-shock) | `schemes/ts/lanes.rs` | `schemes/star_tests.rs` (ts) |
//! | `schemes/pm/pairs.rs` `pair_star` (tkc, and pm with MUSCL or the two-shock solver: objective rotation, corrected traction axis, MUSCL in the pair frame) | `schemes/pm/lanes.rs`, `schemes/pm/lanes_frame.rs` | `schemes/star_tests.rs` (pm) |
//! | `crate::riemann` (acoustic, two-shock, vector elastic) | `simd/riemann.rs` | through the star tests |
//!
//! The star rows read their neighbours' fields from one compact record per particle
//! (`Workspace::rec`, written once before the rows), a register's records loaded four
//! reals at a time and transposed into lanes (a first version of av's loop that filled the
//! lanes from the per-particle arrays, about twenty scalar loads per neighbour, was 27 %
//! slower than the portable loop: the loops are bound by those loads, not by arithmetic).
//! A lane the vectorised path does not cover (a failed particle, an impedance that is not
//! positive and finite, a two-shock answer that is not finite) is solved again by the
//! portable code; options a row does not implement are declined by its `covers`, which
//! matches every option exhaustively. `tests/tests/determinism.rs` compares whole runs.

pub(crate) mod arith;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod lanes;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod ops;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod riemann;

/// The levels the core's unit tests compare with the portable loops: each vectorised
/// level this CPU has, and always the two emulated ones ([`Simd::Emu4`], [`Simd::Emu8`]:
/// the same generic rows on plain arrays, entered as AVX2's and AVX-512's are), so that a
/// CPU without AVX-512 still runs the eight-lane code. Says once, on the test binary's
/// standard error (uncaptured), which levels ran natively.
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
pub(crate) fn tested_levels() -> std::vec::Vec<SimdLevel> {
    extern crate std;
    use std::io::Write;
    static SAID: std::sync::Once = std::sync::Once::new();
    let mut out = std::vec::Vec::new();
    let mut said = std::vec::Vec::new();
    for (level, has) in [
        (Simd::Avx2, std::is_x86_feature_detected!("avx2")),
        (
            Simd::Avx512,
            std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx2"),
        ),
    ] {
        if has {
            // SAFETY: detected just above
            out.push(unsafe { SimdLevel::assume(level) });
            said.push(std::format!("{level} native"));
        } else {
            said.push(std::format!("{level} NOT native (this CPU lacks it)"));
        }
    }
    // SAFETY: the emulated levels need no instructions
    out.extend([Simd::Emu4, Simd::Emu8].map(|l| unsafe { SimdLevel::assume(l) }));
    said.push("emu4, emu8 emulated".into());
    SAID.call_once(|| {
        // written past the test harness's capture, so that a passing run says it too
        let _ = std::writeln!(std::io::stderr(), "simd levels tested: {}", said.join(", "));
    });
    out
}

/// An instruction-set level of the vectorised loops.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Simd {
    /// The portable loops (x86-64: SSE2, one pair at a time).
    #[default]
    Baseline,
    /// AVX2 (x86-64-v3: Intel since Haswell, AMD since Zen): four `f64` pairs per
    /// instruction.
    Avx2,
    /// AVX-512F (Intel Xeon since Skylake-SP, AMD since Zen 4): eight `f64` pairs per
    /// instruction.
    Avx512,
    /// Four emulated lanes (the core's unit tests only; `lanes::Emu`): AVX2's rows on plain
    /// arrays.
    #[cfg(test)]
    Emu4,
    /// Eight emulated lanes (the core's unit tests only): AVX-512's rows, full groups of
    /// eight and the rest in four, on plain arrays.
    #[cfg(test)]
    Emu8,
}

impl Simd {
    /// Every level, lowest first.
    pub const ALL: [Simd; 3] = [Simd::Baseline, Simd::Avx2, Simd::Avx512];

    /// The level's name (`baseline`, `avx2`, `avx512`), as `gsph --simd` and `GSPH_SIMD` take it.
    pub const fn name(self) -> &'static str {
        match self {
            Simd::Baseline => "baseline",
            Simd::Avx2 => "avx2",
            Simd::Avx512 => "avx512",
            #[cfg(test)]
            Simd::Emu4 => "emu4",
            #[cfg(test)]
            Simd::Emu8 => "emu8",
        }
    }

    /// The level of a name ([`Simd::name`]).
    pub fn from_name(s: &str) -> Option<Simd> {
        Simd::ALL.into_iter().find(|l| l.name() == s)
    }
}

impl core::fmt::Display for Simd {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// A level the CPU is known to have: the only way to reach a vectorised loop.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SimdLevel(Simd);

impl SimdLevel {
    /// The portable loops (always safe).
    pub const BASELINE: SimdLevel = SimdLevel(Simd::Baseline);

    /// Vouches that the CPU running the steps has `level`'s instructions.
    ///
    /// # Safety
    /// The CPU must have them (x86-64 AVX2 for [`Simd::Avx2`], AVX-512F (which implies
    /// AVX2) for [`Simd::Avx512`]; the host checks with
    /// `is_x86_feature_detected!`). A level the target architecture has no loops for runs
    /// the portable ones.
    pub const unsafe fn assume(level: Simd) -> SimdLevel {
        SimdLevel(level)
    }

    /// The level.
    pub const fn get(self) -> Simd {
        self.0
    }

    /// True when the vectorised loops may run (AVX2 or AVX-512).
    #[inline(always)]
    #[cfg_attr(
        not(all(target_arch = "x86_64", not(feature = "f32"))),
        allow(dead_code)
    )]
    pub(crate) fn vectorised(self) -> bool {
        cfg!(target_arch = "x86_64") && !cfg!(feature = "f32") && self.0 != Simd::Baseline
    }
}
