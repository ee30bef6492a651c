//! What 512-bit registers buy on this CPU, and what they cost the code around them: the
//! evidence behind `gsph run --simd auto` not picking `avx512` (docs/performance.md "SIMD
//! levels"; docs/notes/performance_history_28_continued.md).
//!
//!     cargo run --release -p gsph --example avx512_clock
//!
//! Prints, for five interleaved rounds:
//! - the throughput of `f64` multiplications and of divisions in `zmm` registers over that
//!   in `ymm` registers, per element (2 = twice as many elements per second);
//! - the time of a fixed scalar integer loop run right after a burst of `ymm` or `zmm`
//!   multiplications, over its time with no burst before it (> 1: the scalar code ran
//!   slower, as it does when the core lowers its clock for 512-bit instructions).

#[cfg(target_arch = "x86_64")]
mod x86 {
    use core::arch::x86_64::*;
    use std::hint::black_box;
    use std::time::Instant;

    /// Eight independent chains of `op` in `zmm` registers, `n` rounds.
    #[target_feature(enable = "avx512f")]
    unsafe fn zmm(n: usize, div: bool) -> f64 {
        let (mut a, m) = ([_mm512_set1_pd(1.0); 8], _mm512_set1_pd(1.000_000_1));
        for _ in 0..n {
            for x in a.iter_mut() {
                *x = if div {
                    _mm512_div_pd(*x, m)
                } else {
                    _mm512_mul_pd(*x, m)
                };
            }
        }
        a.iter().map(|&x| _mm512_reduce_add_pd(x)).sum()
    }

    /// The same in `ymm` registers.
    #[target_feature(enable = "avx2")]
    unsafe fn ymm(n: usize, div: bool) -> f64 {
        let (mut a, m) = ([_mm256_set1_pd(1.0); 8], _mm256_set1_pd(1.000_000_1));
        for _ in 0..n {
            for x in a.iter_mut() {
                *x = if div {
                    _mm256_div_pd(*x, m)
                } else {
                    _mm256_mul_pd(*x, m)
                };
            }
        }
        let mut out = [0.0; 4];
        a.iter()
            .map(|&x| {
                _mm256_storeu_pd(out.as_mut_ptr(), x);
                out.iter().sum::<f64>()
            })
            .sum()
    }

    /// A dependent scalar chain of `n` steps.
    fn scalar(n: u64) -> u64 {
        let mut x = black_box(1u64);
        for i in 0..black_box(n) {
            x = (x ^ (x >> 7))
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(i);
        }
        x
    }

    /// Seconds of `f`.
    fn time(f: impl FnOnce() -> f64) -> (f64, f64) {
        let t = Instant::now();
        let v = f();
        (t.elapsed().as_secs_f64(), v)
    }

    /// Seconds of the scalar loop right after each of 500 bursts (`burst`: 0 none, 1 ymm,
    /// 2 zmm, the same number of elements multiplied).
    fn after_bursts(burst: u8) -> (f64, f64) {
        let (mut total, mut sink) = (0.0, 0.0);
        for _ in 0..500 {
            // SAFETY: `run` checked the CPU's features
            sink += unsafe {
                match burst {
                    1 => ymm(black_box(2000), false),
                    2 => zmm(black_box(1000), false),
                    _ => 0.0,
                }
            };
            let t = Instant::now();
            sink += scalar(100_000) as f64;
            total += t.elapsed().as_secs_f64();
        }
        (total, sink)
    }

    pub fn run() {
        if !(is_x86_feature_detected!("avx512f") && is_x86_feature_detected!("avx2")) {
            println!("this CPU has no AVX-512F: nothing to compare");
            return;
        }
        let mut sink = 0.0;
        println!("round  mul zmm/ymm  div zmm/ymm  scalar after ymm  scalar after zmm");
        for round in 1..=5 {
            let n = 20_000_000;
            // SAFETY: the features are checked above
            let (tz, a) = time(|| unsafe { zmm(black_box(n / 2), false) });
            let (ty, b) = time(|| unsafe { ymm(black_box(n), false) });
            let (tzd, c) = time(|| unsafe { zmm(black_box(n / 16), true) });
            let (tyd, d) = time(|| unsafe { ymm(black_box(n / 8), true) });
            let (none, e) = after_bursts(0);
            let (after_y, f) = after_bursts(1);
            let (after_z, g) = after_bursts(2);
            sink += a + b + c + d + e + f + g;
            println!(
                "{round:>5}  {:>11.2}  {:>11.2}  {:>16.3}  {:>16.3}",
                ty / tz,
                tyd / tzd,
                after_y / none,
                after_z / none
            );
        }
        black_box(sink);
    }
}

fn main() {
    #[cfg(target_arch = "x86_64")]
    x86::run();
    #[cfg(not(target_arch = "x86_64"))]
    println!("x86-64 only");
}
