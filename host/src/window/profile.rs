//! 1D profiles along the flow axis of a window, averaged over the cross-section and over
//! any number of instants (seed 004 fig 9: density and −σ_xx averaged over 75 profiles).
//!
//! Two averages of the stress: the **bulk** (macroscopic) stress
//! `sum_i sigma_i V_i / V_bin`, `V_i = m_i/rho_i`, with the pores counting as zero stress,
//! which is what the Rankine–Hugoniot jump conditions and the seed's `sigma_HEL` and
//! `Δsigma = rho0 u_s u_p` refer to (the traction across a section averaged over a period);
//! and the **matrix** stress, the plain mean over the particles, which is the stress in the
//! solid and exceeds the bulk one by `V_bin / sum V_i` (about `m = 1.35` ahead of a
//! compaction front).

use crate::scene::WindowGeometry;
use crate::sim::Sim;

/// Sums per bin along x over the particles of one or more instants.
#[derive(Debug, Clone)]
pub struct Profile {
    /// Left end of bin 0, m.
    pub lo: f64,
    /// Bin width, m.
    pub bin: f64,
    count: Vec<f64>,
    mass: Vec<f64>,
    vx: Vec<f64>,
    rho: Vec<f64>,
    sxx: Vec<f64>,
    vol: Vec<f64>,
    sxx_vol: Vec<f64>,
    /// Cross-section of the window (length in 2D, area in 3D; 1 in 1D).
    section: f64,
    /// Instants added.
    pub instants: usize,
}

/// One averaged bin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bin {
    /// Bin centre, m.
    pub x: f64,
    /// Mean particle density, kg/m³.
    pub rho: f64,
    /// Bulk density: mass in the bin over its volume (pores included), kg/m³.
    pub rho_bulk: f64,
    /// Matrix stress: mean −σ_xx = p − s_xx over the particles, Pa.
    pub stress: f64,
    /// Bulk stress: `sum (p − s_xx) V_i` over the bin's volume (pores count as zero), Pa.
    pub stress_bulk: f64,
    /// Mean velocity along x, m/s.
    pub vx: f64,
    /// Fraction of the bin's volume that the particles fill, `sum V_i / V_bin` (1: no
    /// pores left).
    pub solid_fraction: f64,
}

impl Profile {
    /// Empty profile over the window, bins `bin` wide.
    pub fn new(geo: &WindowGeometry, bin: f64) -> Self {
        let n = ((geo.x_r - geo.x_l) / bin).ceil() as usize;
        Profile {
            lo: geo.x_l,
            bin,
            count: vec![0.0; n],
            mass: vec![0.0; n],
            vx: vec![0.0; n],
            rho: vec![0.0; n],
            sxx: vec![0.0; n],
            vol: vec![0.0; n],
            sxx_vol: vec![0.0; n],
            section: 0.0,
            instants: 0,
        }
    }

    /// Adds the particles of `sim` (those inside the window).
    pub fn add<const D: usize>(&mut self, sim: &Sim<D>) {
        let n = self.count.len();
        for i in 0..sim.len() {
            let k = (sim.x[i][0] - self.lo) / self.bin;
            if !(k >= 0.0 && (k as usize) < n) {
                continue;
            }
            let k = k as usize;
            let sxx = sim.s.get(i).map_or(0.0, |s| s.xx);
            self.count[k] += 1.0;
            self.mass[k] += sim.m[i];
            self.vx[k] += sim.v[i][0];
            self.rho[k] += sim.rho[i];
            self.sxx[k] += sim.p[i] - sxx;
            let v = sim.m[i] / sim.rho[i];
            self.vol[k] += v;
            self.sxx_vol[k] += (sim.p[i] - sxx) * v;
        }
        self.section = (1..D).map(|a| sim.periodic.len[a]).product();
        self.instants += 1;
    }

    /// The averaged bins (those that held a particle).
    pub fn bins(&self) -> Vec<Bin> {
        let vol = self.bin * self.section * self.instants.max(1) as f64;
        (0..self.count.len())
            .filter(|&k| self.count[k] > 0.0)
            .map(|k| {
                let c = self.count[k];
                Bin {
                    x: self.lo + (k as f64 + 0.5) * self.bin,
                    rho: self.rho[k] / c,
                    rho_bulk: self.mass[k] / vol,
                    stress: self.sxx[k] / c,
                    stress_bulk: self.sxx_vol[k] / vol,
                    solid_fraction: self.vol[k] / vol,
                    vx: self.vx[k] / c,
                }
            })
            .collect()
    }

    /// The front: the right end of the first run of bins, from the exit end, whose mean
    /// velocity reaches `threshold` (material behind the front moves at u_out, ahead of it
    /// at u_in < u_out). NaN if no bin does.
    pub fn front(&self, threshold: f64) -> f64 {
        let bins = self.bins();
        let first = bins.iter().position(|b| b.vx >= threshold);
        match first {
            None => f64::NAN,
            Some(f) => {
                let end = bins[f..]
                    .iter()
                    .position(|b| b.vx < threshold)
                    .map_or(bins.len() - 1, |e| f + e - 1);
                bins[end].x + 0.5 * self.bin
            }
        }
    }

    /// Mean of `field` over the bins with centres in [a, b] (NaN if none).
    pub fn mean(&self, a: f64, b: f64, field: impl Fn(&Bin) -> f64) -> f64 {
        let v: Vec<f64> = self
            .bins()
            .iter()
            .filter(|bin| bin.x >= a && bin.x <= b)
            .map(field)
            .collect();
        v.iter().sum::<f64>() / v.len() as f64
    }

    /// CSV: `x,rho,rho_bulk,minus_sigma_xx_bulk,minus_sigma_xx_matrix,vx,solid_fraction`
    /// (bulk: volume average over the bin with pores at zero; matrix: mean over the
    /// particles).
    pub fn to_csv(&self) -> String {
        let mut s = String::from(
            "x,rho,rho_bulk,minus_sigma_xx_bulk,minus_sigma_xx_matrix,vx,solid_fraction\n",
        );
        for b in self.bins() {
            s.push_str(&format!(
                "{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
                b.x, b.rho, b.rho_bulk, b.stress_bulk, b.stress, b.vx, b.solid_fraction
            ));
        }
        s
    }
}
