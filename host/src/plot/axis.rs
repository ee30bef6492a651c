//! Axis ranges, tick placement and tick labels.
//!
//! Plots are drawn on linear f64 coordinates; a logarithmic axis stores log10 of the data, so one
//! chart type serves every combination of linear and log axes. [`Axis`] is itself the plotters
//! coordinate: it hands plotters its own ticks and labels.

use std::ops::Range;

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};

/// Fraction of the data span added on each side of a linear axis.
const MARGIN: f64 = 0.04;

/// One axis: its range in plot coordinates (log10 of the value on a log axis) and its ticks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    /// Lower end (plot coordinates).
    pub lo: f64,
    /// Upper end (plot coordinates).
    pub hi: f64,
    /// Logarithmic axis.
    pub log: bool,
    /// Labelled ticks (plot coordinates).
    pub ticks: Vec<f64>,
    /// Unlabelled minor grid lines (plot coordinates).
    pub minor: Vec<f64>,
    /// Spacing of the labelled ticks (plot coordinates).
    step: f64,
}

impl Axis {
    /// An axis covering `values` (non-finite values, and non-positive ones on a log axis, are
    /// ignored) with a small margin, or whole decades on a log axis.
    pub fn from_values(values: impl IntoIterator<Item = f64>, log: bool) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for t in values.into_iter().filter_map(|v| to_plot(v, log)) {
            lo = lo.min(t);
            hi = hi.max(t);
        }
        if lo > hi {
            return Self::exact(0.0, 1.0, log);
        }
        if log {
            let (a, b) = (lo.floor(), hi.ceil());
            return Self::exact(a, if b > a { b } else { a + 1.0 }, true);
        }
        let (lo, hi) = widen(lo, hi);
        let pad = (hi - lo) * MARGIN;
        Self::exact(lo - pad, hi + pad, false)
    }

    /// An axis over exactly `lo..hi` (plot coordinates; widened if empty).
    pub fn exact(lo: f64, hi: f64, log: bool) -> Self {
        let (lo, hi) = widen(lo, hi);
        let mut axis = Self {
            lo,
            hi,
            log,
            ticks: Vec::new(),
            minor: Vec::new(),
            step: 1.0,
        };
        axis.place_ticks();
        axis
    }

    /// Moves the ends to `lo..hi` (plot coordinates) and places the ticks again.
    pub fn set_range(&mut self, lo: f64, hi: f64) {
        *self = Self::exact(lo, hi, self.log);
    }

    fn place_ticks(&mut self) {
        let span = self.hi - self.lo;
        if self.log {
            let stride = (span / 10.0).ceil().max(1.0);
            self.step = stride;
            self.ticks = multiples(self.lo, self.hi, stride);
            if span <= 8.0 {
                let decades = multiples(self.lo - 1.0, self.hi, 1.0);
                self.minor = decades
                    .iter()
                    .flat_map(|d| (2..10).map(move |m| d + f64::from(m).log10()))
                    .filter(|t| (self.lo..=self.hi).contains(t))
                    .collect();
            } else {
                self.minor = Vec::new();
            }
        } else {
            self.step = nice_step(span / 7.0);
            self.ticks = multiples(self.lo, self.hi, self.step);
            self.minor = multiples(self.lo, self.hi, self.step / 5.0);
        }
    }

    /// A data value in plot coordinates; `None` when it cannot be shown on this axis.
    pub fn map(&self, v: f64) -> Option<f64> {
        to_plot(v, self.log)
    }

    /// The label of the tick at plot coordinate `t`.
    pub fn label(&self, t: f64) -> String {
        if self.log {
            return format!("10{}", superscript(t.round() as i64));
        }
        let big = self.lo.abs().max(self.hi.abs());
        if !(1e-3..1e5).contains(&big) {
            let top = self.ticks.iter().fold(0f64, |m, t| m.max(t.abs()));
            let digits = (top.log10().floor() - self.step.log10().floor()).clamp(0.0, 4.0);
            sci_label(t, self.step, digits as usize)
        } else {
            let decimals = (-self.step.log10().floor()).clamp(0.0, 9.0) as usize;
            let t = if t.abs() < self.step * 1e-6 { 0.0 } else { t };
            format!("{t:.decimals$}")
        }
    }

    /// The labels of all ticks.
    pub fn labels(&self) -> Vec<String> {
        self.ticks.iter().map(|&t| self.label(t)).collect()
    }
}

impl Ranged for Axis {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let u = (v - self.lo) / (self.hi - self.lo);
        let len = f64::from(limit.1 - limit.0);
        limit.0 + (len * u.clamp(-10.0, 11.0)).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for Axis {
    fn format_ext(&self, value: &f64) -> String {
        self.label(*value)
    }
}

/// `v` in plot coordinates of a linear (`log` false) or log axis.
fn to_plot(v: f64, log: bool) -> Option<f64> {
    match (v.is_finite(), log) {
        (false, _) => None,
        (true, false) => Some(v),
        (true, true) => (v > 0.0).then(|| v.log10()),
    }
}

/// `lo..hi` widened around its centre when it is empty (or reversed).
fn widen(lo: f64, hi: f64) -> (f64, f64) {
    if hi > lo {
        return (lo, hi);
    }
    let c = 0.5 * (lo + hi);
    let d = if c == 0.0 { 1.0 } else { 0.1 * c.abs() };
    (c - d, c + d)
}

/// The 1, 2 or 5 times a power of ten nearest above `raw`.
fn nice_step(raw: f64) -> f64 {
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let m = if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    };
    m * mag
}

/// The multiples of `step` in `lo..=hi` (with a little tolerance at the ends).
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let eps = step * 1e-9;
    let first = ((lo - eps) / step).ceil() as i64;
    let last = ((hi + eps) / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// `t` as `m.me±x` with `decimals` mantissa decimals (0 for zero, within `step`).
fn sci_label(t: f64, step: f64, decimals: usize) -> String {
    if t.abs() < step * 1e-6 {
        return "0".to_string();
    }
    let mut e = t.abs().log10().floor() as i32;
    let mut m = t / 10f64.powi(e);
    if format!("{:.decimals$}", m.abs()).starts_with("10") {
        e += 1;
        m = t / 10f64.powi(e);
    }
    format!("{m:.decimals$}e{e}")
}

/// `n` in Unicode superscript digits.
fn superscript(n: i64) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s: String = n
        .unsigned_abs()
        .to_string()
        .bytes()
        .map(|b| DIGITS[usize::from(b - b'0')])
        .collect();
    if n < 0 {
        s.insert(0, '⁻');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_and_labels() {
        let a = Axis::from_values([0.0, 1.0, f64::NAN, 0.5], false);
        assert!(a.lo < 0.0 && a.hi > 1.0);
        assert_eq!(a.labels().first().map(String::as_str), Some("0.0"));
        let a = Axis::from_values([1e9, 3e9], false);
        assert!(a.labels().iter().any(|l| l == "2.0e9"), "{:?}", a.labels());
        let a = Axis::from_values([-2e-4, 2e-4], false);
        assert!(a.labels().iter().any(|l| l == "0"), "{:?}", a.labels());
        let a = Axis::from_values([5.0, 5.0], false);
        assert!(a.hi > a.lo);
    }

    #[test]
    fn log_ticks_are_decades() {
        let a = Axis::from_values([0.0, -1.0, 2e-3, 40.0, f64::INFINITY], true);
        assert_eq!((a.lo, a.hi), (-3.0, 2.0));
        assert_eq!(a.labels(), ["10⁻³", "10⁻²", "10⁻¹", "10⁰", "10¹", "10²"]);
        assert!(!a.minor.is_empty());
        assert_eq!(a.map(-1.0), None);
    }
}
