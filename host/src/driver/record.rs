//! What a run records while it steps: the series (`series.csv`: energies, momentum, the
//! reference's and the monitor's quantities, the moving window's), the largest kinetic
//! energy, and the stress profile against the exact one at the end (`profile.csv`). The
//! library ([`crate::api::Simulation`]) records with the same [`Recorder`].

use super::*;

/// The series so far and the quantities sampled with it.
#[derive(Clone)]
pub struct Recorder {
    /// `series.csv` so far: the header, then one line per [`Recorder::push`].
    pub series: String,
    /// The largest kinetic energy sampled, J.
    pub kinetic_max: f64,
    /// The scene's monitor (its columns in the series, its measures in the summary).
    pub monitor: Monitor,
    /// The scene's exact reference, if it has one.
    pub reference: Option<Reference>,
    /// The reference's series columns (empty without a reference).
    extra: &'static [&'static str],
}

impl Recorder {
    /// A recorder with the series header: the fixed columns, then the reference's, the
    /// monitor's and (with a moving window) the window's.
    pub fn new(reference: Option<Reference>, monitor: Monitor, window: &[&str]) -> Self {
        let mut series =
            String::from("t,step,dt,kinetic,internal,total,momentum_x,momentum_y,momentum_z");
        let extra = reference.as_ref().map_or(&[][..], |r| r.series_names());
        let monitor_names = monitor.series_names();
        for name in extra
            .iter()
            .copied()
            .chain(monitor_names.iter().map(String::as_str))
            .chain(window.iter().copied())
        {
            series.push(',');
            series.push_str(name);
        }
        series.push('\n');
        Recorder {
            series,
            kinetic_max: 0.0,
            monitor,
            reference,
            extra,
        }
    }

    /// Appends one row of the series at the state of `sim` after a step of `dt`.
    pub fn push<const D: usize>(&mut self, sim: &Sim<D>, window: &Option<Window<D>>, dt: f64) {
        let series = &mut self.series;
        let (k, i) = sim.energy();
        self.kinetic_max = self.kinetic_max.max(k);
        let p = sim.momentum();
        series.push_str(&format!(
            "{:e},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            sim.t,
            sim.step,
            dt,
            k,
            i,
            k + i,
            p[0],
            p[1],
            p[2]
        ));
        if !self.extra.is_empty() || self.monitor.samples() {
            let table = sim.table();
            let mut values = self
                .reference
                .as_ref()
                .map_or_else(Vec::new, |r| r.series_values(&table, sim.t));
            values.extend(self.monitor.sample(&table, sim.t));
            for v in values {
                series.push_str(&format!(",{v:e}"));
            }
        }
        if let Some(w) = window {
            for v in w.series_values(sim) {
                series.push_str(&format!(",{v:e}"));
            }
        }
        series.push('\n');
    }

    /// sigma_xx of every particle against the exact profile at time t, sorted by x
    /// (`x,sigma_xx,sigma_xx_exact`; the exact value is empty where it does not hold), or
    /// `None` without a reference that is a stress profile.
    pub fn profile_csv(&self, table: &crate::output::ParticleTable, t: f64) -> Option<String> {
        let rows = self.reference.as_ref()?.profile(table, t)?;
        let mut s = String::from("x,sigma_xx,sigma_xx_exact\n");
        for (x, sxx, ex) in rows {
            s.push_str(&format!(
                "{x:e},{sxx:e},{}\n",
                ex.map(|v| format!("{v:e}")).unwrap_or_default()
            ));
        }
        Some(s)
    }
}
