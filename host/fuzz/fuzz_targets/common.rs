//! Helpers shared by the numeric fuzz targets.
#![allow(dead_code)]

/// `x` itself when it lies in `[lo, hi]`, otherwise a value of `[lo, hi]` taken from its
/// bits (uniform): every input maps into the range, and the fuzzer can still hit the
/// range's end points exactly.
pub fn fit(x: f64, lo: f64, hi: f64) -> f64 {
    if x >= lo && x <= hi {
        return x;
    }
    let u = (x.to_bits() >> 11) as f64 / (1u64 << 53) as f64;
    (lo + (hi - lo) * u).clamp(lo, hi)
}

/// Like [`fit`] but uniform in `log10` between `lo > 0` and `hi`.
pub fn fit_log(x: f64, lo: f64, hi: f64) -> f64 {
    if x >= lo && x <= hi {
        return x;
    }
    let u = (x.to_bits() >> 11) as f64 / (1u64 << 53) as f64;
    (lo * (hi / lo).powf(u)).clamp(lo, hi)
}

/// Asserts that every value is finite, naming the first that is not.
#[track_caller]
pub fn all_finite(what: &str, values: &[f64]) {
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        panic!("{what}: output {k} is {} in {values:?}", values[k]);
    }
}
