//! Progress of a run: a bar on a terminal (cargo feature `cli`), and plain lines on stderr
//! at a fixed wall-clock interval when stderr is not a terminal (a batch job's log):
//!
//! ```text
//! gsph: flyer_plate: step 1200, t = 3.200e-7 s of 5.000e-7 s (64.0 %), dt = 2.10e-10 s, elapsed 1m02s, ETA 35s
//! ```
//!
//! The interval is 10 s, or `GSPH_PROGRESS_SECONDS` (seconds, > 0) from the environment.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Default interval between progress lines in a batch log.
pub const DEFAULT_INTERVAL: Duration = Duration::from_secs(10);

/// The interval between progress lines: `GSPH_PROGRESS_SECONDS` or [`DEFAULT_INTERVAL`].
pub fn interval() -> Duration {
    std::env::var("GSPH_PROGRESS_SECONDS")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
        .map_or(DEFAULT_INTERVAL, Duration::from_secs_f64)
}

/// `1h02m03s`, `2m05s`, `7s`.
pub fn hms(secs: f64) -> String {
    if !secs.is_finite() || secs < 0.0 {
        return "?".into();
    }
    let s = secs.round() as u64;
    match (s / 3600, s / 60 % 60, s % 60) {
        (0, 0, s) => format!("{s}s"),
        (0, m, s) => format!("{m}m{s:02}s"),
        (h, m, s) => format!("{h}h{m:02}m{s:02}s"),
    }
}

/// Plain progress lines at a fixed interval.
struct Lines {
    name: String,
    every: Duration,
    start: Instant,
    last: Instant,
    t0: f64,
}

/// The progress display of a run.
pub struct Progress {
    #[cfg(feature = "cli")]
    bar: Option<indicatif::ProgressBar>,
    lines: Option<Lines>,
}

impl Progress {
    /// A bar if `show` and stderr is a terminal; progress lines if `show` and it is not.
    /// `t0` is the time the run starts from (a restart's checkpoint time).
    pub fn new(show: bool, name: &str, t0: f64) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let lines = (show && !terminal).then(|| Lines {
            name: name.to_owned(),
            every: interval(),
            start: Instant::now(),
            last: Instant::now(),
            t0,
        });
        #[cfg(feature = "cli")]
        {
            let bar = (show && terminal).then(|| {
                let b = indicatif::ProgressBar::new(1000);
                b.set_style(
                    indicatif::ProgressStyle::with_template(
                        "{spinner} [{elapsed_precise}] {bar:40} {percent:>3}% t={msg} eta {eta}",
                    )
                    .expect("valid template"),
                );
                b
            });
            Progress { bar, lines }
        }
        #[cfg(not(feature = "cli"))]
        Progress { lines }
    }

    /// After step `step` of size `dt`: time `t` of `t_end`.
    pub fn set(&mut self, t: f64, t_end: f64, step: u64, dt: f64) {
        #[cfg(feature = "cli")]
        if let Some(b) = &self.bar {
            b.set_position((1000.0 * t / t_end) as u64);
            b.set_message(format!("{t:.3e}"));
        }
        if let Some(l) = self.lines.as_mut() {
            if l.last.elapsed() >= l.every {
                l.last = Instant::now();
                let elapsed = l.start.elapsed().as_secs_f64();
                let done = (t - l.t0) / (t_end - l.t0);
                let eta = if done > 0.0 {
                    hms(elapsed * (1.0 - done) / done)
                } else {
                    "?".into()
                };
                eprintln!(
                    "gsph: {}: step {step}, t = {t:.3e} s of {t_end:.3e} s ({:.1} %), dt = {dt:.2e} s, elapsed {}, ETA {eta}",
                    l.name,
                    100.0 * t / t_end,
                    hms(elapsed)
                );
            }
        }
    }

    /// Removes the bar.
    pub fn finish(self) {
        #[cfg(feature = "cli")]
        if let Some(b) = self.bar {
            b.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::hms;

    #[test]
    fn durations_read_as_hours_minutes_seconds() {
        assert_eq!(hms(7.2), "7s");
        assert_eq!(hms(125.0), "2m05s");
        assert_eq!(hms(3723.0), "1h02m03s");
        assert_eq!(hms(f64::NAN), "?");
    }
}
