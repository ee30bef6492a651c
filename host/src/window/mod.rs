//! The moving observation window of seed 004 §3 (fig 6), in the frame of a stationary
//! front. Material flows along −x: it enters at `u_in = −us` through the right end
//! `x_r`, fed from a cycled copy of the last period of the initial sample, and leaves at
//! `u_out = u_in + up` through the left end `x_l`.
//!
//! Regions, by position at the start of each step (widths from [`WindowGeometry`]):
//! - entry region, `x > x_r − d_in`: velocity held at (u_in, 0, 0), state evolves;
//! - exit region 1, `x − x_l < d_out1`: velocity held at (u_out, 0, 0), state evolves: these
//!   particles act as the piston that drives the wave;
//! - exit region 2, `x − x_l < d_out2`: velocity held and the material state frozen at the
//!   value it had on entering (no free surface past `x_l` reaches inside);
//! - past `x_l`: removed at the next exchange.
//!
//! Held particles move exactly with their held velocity (their positions are reset after
//! the step to `x0 + v dt`), so the feed, which moves at u_in, joins the entry region
//! without gaps or overlaps. Every `every` steps particles past `x_l` are removed and the
//! feed particles that have crossed `x_r` are inserted (a neighbour-list rebuild follows).

mod profile;

pub use profile::Profile;

use crate::scene::{InitialParticles, Scene, WindowGeometry};
use crate::sim::{HeldState, Sim, SimError};
use gsph_core::math::Vector;
use std::collections::BTreeMap;

/// Which boundary region a particle is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Region {
    Free,
    Entry,
    Exit1,
    Exit2,
}

/// A moving window attached to a simulation.
#[derive(Clone)]
pub struct Window<const D: usize> {
    /// Geometry.
    pub geo: WindowGeometry,
    /// Particle-velocity jump u_out − u_in, m/s.
    pub up: f64,
    /// Entry velocity (−us), m/s.
    pub u_in: f64,
    every: u64,
    /// The feed sample (one period, as built), sorted by `xi`.
    feed: InitialParticles,
    /// Position of each feed particle relative to the left end of its feed copy.
    xi: Vec<f64>,
    /// Left end of feed copy 0 (it moves at u_in).
    feed_x: f64,
    /// Next feed particle to insert (copy `next / n_feed`, particle `next % n_feed`).
    next: u64,
    held: BTreeMap<u32, HeldState<D>>,
    /// Particles at the start.
    pub n0: usize,
    /// Particles inserted and removed so far.
    pub inserted: u64,
    /// Particles removed so far.
    pub removed: u64,
    /// Mass inserted so far, kg (per unit length in 2D, per unit area in 1D).
    pub mass_in: f64,
    /// Mass removed so far.
    pub mass_out: f64,
    steps: u64,
}

fn along_x<const D: usize>(u: f64) -> Vector<D> {
    Vector::<D>::from_fn(|k, _| if k == 0 { u } else { 0.0 })
}

impl<const D: usize> Window<D> {
    /// Attaches a window to `sim` (built from `parts` of `scene`) and sets the initial
    /// velocities: u_out in the exit regions, u_in elsewhere.
    pub fn new(
        scene: &Scene,
        geo: WindowGeometry,
        parts: &InitialParticles,
        sim: &mut Sim<D>,
    ) -> Self {
        let w = scene.window.as_ref().expect("a window scene");
        let start = geo.x_r - geo.feed;
        let mut idx: Vec<usize> = (0..parts.len())
            .filter(|&i| parts.x[i][0] >= start - 1e-9 * geo.dx)
            .collect();
        idx.sort_by(|&a, &b| parts.x[a][0].total_cmp(&parts.x[b][0]).then(a.cmp(&b)));
        let mut feed = parts.empty_like();
        for &i in &idx {
            feed.push_from(parts, i);
            let last = feed.len() - 1;
            feed.v[last] = [0.0; 3];
        }
        let xi = feed.x.iter().map(|x| x[0] - start).collect();
        let win = Window {
            geo,
            up: w.up,
            u_in: -w.us,
            every: w.every,
            feed,
            xi,
            feed_x: geo.x_r,
            next: 0,
            held: BTreeMap::new(),
            n0: sim.len(),
            inserted: 0,
            removed: 0,
            mass_in: 0.0,
            mass_out: 0.0,
            steps: 0,
        };
        for i in 0..sim.len() {
            sim.v[i] = along_x(win.u_in);
        }
        win.hold_velocities(sim);
        win
    }

    /// Exit velocity u_in + up.
    pub fn u_out(&self) -> f64 {
        self.u_in + self.up
    }

    /// Moves the window to the frame in which material enters at `u_in`: every particle
    /// velocity shifts by the same amount (a Galilean change of frame; the state is
    /// untouched).
    pub fn set_entry_velocity(&mut self, sim: &mut Sim<D>, u_in: f64) {
        let d = u_in - self.u_in;
        for v in sim.v.iter_mut() {
            v[0] += d;
        }
        self.u_in = u_in;
    }

    fn region(&self, x: f64) -> Region {
        let g = &self.geo;
        if x - g.x_l < g.d_out2 {
            Region::Exit2
        } else if x - g.x_l < g.d_out1 {
            Region::Exit1
        } else if x > g.x_r - g.d_in {
            Region::Entry
        } else {
            Region::Free
        }
    }

    fn held_velocity(&self, r: Region) -> Option<f64> {
        match r {
            Region::Free => None,
            Region::Entry => Some(self.u_in),
            Region::Exit1 | Region::Exit2 => Some(self.u_out()),
        }
    }

    fn hold_velocities(&self, sim: &mut Sim<D>) {
        for i in 0..sim.len() {
            if let Some(u) = self.held_velocity(self.region(sim.x[i][0])) {
                sim.v[i] = along_x(u);
            }
        }
    }

    /// One step of `sim` with the window's boundary conditions; every `every` steps,
    /// the exchange of particles through the ends.
    pub fn step(&mut self, sim: &mut Sim<D>, dt: f64) -> Result<(), SimError> {
        // a rebuild renumbers the particles: do it before taking their indices
        sim.maintain()?;
        let regions: Vec<Region> = sim.x.iter().map(|x| self.region(x[0])).collect();
        for (i, r) in regions.iter().enumerate() {
            if *r == Region::Exit2 && !self.held.contains_key(&sim.ids[i]) {
                self.held.insert(sim.ids[i], sim.held_state(i));
            }
        }
        // start positions of the held particles only (a few layers at each end)
        let held: Vec<(usize, Region, Vector<D>)> = regions
            .iter()
            .enumerate()
            .filter(|(_, r)| **r != Region::Free)
            .map(|(i, &r)| (i, r, sim.x[i]))
            .collect();
        sim.step(dt)?;
        for &(i, r, x0) in &held {
            if let Some(u) = self.held_velocity(r) {
                let v = along_x::<D>(u);
                sim.v[i] = v;
                sim.x[i] = sim.periodic.wrap(x0 + v * dt);
            }
            if r == Region::Exit2 {
                let st = self.held[&sim.ids[i]];
                sim.restore_state(i, &st);
            }
        }
        self.feed_x += self.u_in * dt;
        self.steps += 1;
        if self.steps.is_multiple_of(self.every) {
            self.exchange(sim);
        }
        Ok(())
    }

    /// Removes the particles past `x_l` and inserts the feed particles that have crossed
    /// `x_r`.
    pub fn exchange(&mut self, sim: &mut Sim<D>) {
        let keep: Vec<bool> = sim.x.iter().map(|x| x[0] >= self.geo.x_l).collect();
        if keep.iter().any(|k| !k) {
            for (i, k) in keep.iter().enumerate() {
                if !k {
                    self.mass_out += sim.m[i];
                    self.removed += 1;
                    self.held.remove(&sim.ids[i]);
                }
            }
            sim.retain(&keep);
        }
        let nf = self.feed.len() as u64;
        let mut add = self.feed.empty_like();
        loop {
            let (copy, k) = (self.next / nf, (self.next % nf) as usize);
            let x = self.feed_x + copy as f64 * self.geo.feed + self.xi[k];
            if x >= self.geo.x_r {
                break;
            }
            add.push_from(&self.feed, k);
            let last = add.len() - 1;
            add.x[last][0] = x;
            // a fed particle is created where it enters
            if let Some(x0) = add.x0.get_mut(last) {
                *x0 = add.x[last];
            }
            add.v[last] = [self.u_in, 0.0, 0.0];
            self.mass_in += self.feed.m[k];
            self.next += 1;
        }
        if !add.is_empty() {
            self.inserted += add.len() as u64;
            sim.append(&add);
        }
    }

    /// (N − N0)/N0: the particle excess in the window (ω of seed 004 eq. in §3.1 is this
    /// divided by ν).
    pub fn excess(&self, sim: &Sim<D>) -> f64 {
        (sim.len() as f64 - self.n0 as f64) / self.n0 as f64
    }

    /// Series column names of a window run.
    pub fn series_names() -> [&'static str; 5] {
        [
            "window_particles",
            "window_mass_in",
            "window_mass_out",
            "window_excess",
            "window_front",
        ]
    }

    /// Series values (same order as [`Window::series_names`]).
    pub fn series_values(&self, sim: &Sim<D>) -> [f64; 5] {
        [
            sim.len() as f64,
            self.mass_in,
            self.mass_out,
            self.excess(sim),
            self.front(sim),
        ]
    }

    /// The front position: see [`Profile::front`] (bins two spacings wide).
    pub fn front(&self, sim: &Sim<D>) -> f64 {
        let mut p = Profile::new(&self.geo, 2.0 * self.geo.dx);
        p.add(sim);
        p.front(self.u_in + 0.5 * self.up)
    }
}
pub mod hugoniot;
pub mod plot;
mod run;
pub use run::run_hugoniot;
