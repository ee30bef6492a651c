//! The shock Hugoniot of a porous sample from a moving window (seed 004 §3.1 steps 1–6,
//! §4): for each particle velocity u_p, the shock speed u_s at which the front stands
//! still in the window, found by bisection on the mean slope of
//! ω = (N − N0)/(ν N0).
//!
//! 1. Stage 1: the window starts in the frame where the exit regions are at rest
//!    (u_out = 0, u_in = −u_p: a piston seen from the piston), so the compaction front runs
//!    into the window; it stops when ω = 1, with ν chosen so that this happens when the
//!    front has crossed `target` of the window (ν = target (ρ1/ρ0 − 1), ρ1/ρ0 = u_s/(u_s − u_p)
//!    from mass balance at the middle of the bracket). The state is saved.
//! 2. Bisection 1: each trial restarts from the saved state in the frame of the trial u_s
//!    (a Galilean shift of every velocity) and runs until `samples` feed lengths have
//!    entered; the least-squares slope of ω(t) decides the side (positive: the front moves
//!    towards the entry, u_s too small). The bracket's ends must give opposite signs.
//! 3. Settling: from the saved state at the found u_s until half the window length has
//!    entered; the state is saved again.
//! 4. Bisection 2 around the found value (±max(8 tol, 2 %), widened if needed).
//! 5. Production: at the final u_s for `average` feed lengths, averaging `profiles`
//!    instantaneous 1D profiles (fig 9).

use super::{Profile, Window};
use crate::monitor::slope;
use crate::scene::{build_particles, InitialParticles, Scene, WindowGeometry};
use crate::sim::Sim;
use std::time::Instant;

/// Controls of a Hugoniot computation.
#[derive(Debug, Clone)]
pub struct HugoniotOptions {
    /// Particle velocities, m/s.
    pub ups: Vec<f64>,
    /// Initial bracket of u_s, m/s (default 0.85 times the full-compaction bound
    /// B = m u_p/(m − 1), and max(2 B, B + 300 m/s)); an end that gives the wrong sign moves
    /// outwards.
    pub bracket: Option<(f64, f64)>,
    /// Bisection stops when the bracket is narrower than this, m/s.
    pub tolerance: f64,
    /// Feed lengths entering during one trial (seed: n = 3).
    pub samples: f64,
    /// Fraction of the window the front has crossed when stage 1 ends.
    pub target: f64,
    /// Feed lengths over which the production profiles are averaged.
    pub average: f64,
    /// Instantaneous profiles averaged.
    pub profiles: usize,
    /// Most bisections (the first from stage 1, each later one after settling); they
    /// stop when u_s changes by less than max(2 tolerance, 0.5 %).
    pub max_rounds: usize,
    /// Print one line per stage and trial on stderr.
    pub verbose: bool,
}

impl Default for HugoniotOptions {
    fn default() -> Self {
        HugoniotOptions {
            ups: vec![100.0],
            bracket: None,
            tolerance: 1.0,
            samples: 3.0,
            target: 0.5,
            average: 4.5,
            profiles: 75,
            max_rounds: 4,
            verbose: true,
        }
    }
}

/// One point of the Hugoniot.
#[derive(Debug, Clone)]
pub struct HugoniotPoint {
    /// Particle velocity jump, m/s.
    pub up: f64,
    /// Shock speed found, m/s.
    pub us: f64,
    /// Final bracket width, m/s.
    pub bracket: f64,
    /// u_s after each bisection round, m/s.
    pub rounds: Vec<f64>,
    /// Bulk (volume-averaged, pores at zero) −σ_xx behind the compaction front, Pa.
    pub stress_behind: f64,
    /// Bulk −σ_xx between the front and the entry (the elastic precursor), Pa.
    pub stress_precursor: f64,
    /// Matrix −σ_xx (mean over the particles) behind the front, Pa.
    pub stress_behind_matrix: f64,
    /// Matrix −σ_xx in the precursor, Pa.
    pub stress_precursor_matrix: f64,
    /// Pore volume fraction left behind the front, `1 − sum V_i / V` (the sample starts
    /// at `1 − 1/m`, 0.26 for m = 1.35; 0 when the pores have closed).
    pub pores_behind: f64,
    /// Bulk density (pores included) behind the front and ahead of it, kg/m³.
    pub rho_behind: f64,
    /// Bulk density ahead of the front (in the precursor), kg/m³.
    pub rho_ahead: f64,
    /// Velocity of the material ahead of the front relative to the entry velocity, m/s
    /// (what the elastic precursor adds; the entry region holds u_in).
    pub precursor_velocity: f64,
    /// Front position at the end of the production run (window frame), m.
    pub front: f64,
    /// Slope of ω during the production run, 1/s.
    pub omega_slope: f64,
    /// Trials run (both bisections).
    pub trials: usize,
    /// Steps in all stages.
    pub steps: u64,
    /// Wall time for the point, s.
    pub wall_s: f64,
    /// The averaged profiles of the production run.
    pub profile: Profile,
}

impl HugoniotPoint {
    /// Measured compression over the one the mass jump condition requires of a steady
    /// wave, ρ_b/ρ_a against (u_s − δ)/(u_s − u_p), with δ the precursor velocity (1 for a
    /// steady wave).
    pub fn mass_jump_ratio(&self) -> f64 {
        let d = self.precursor_velocity;
        (self.rho_behind / self.rho_ahead) / ((self.us - d) / (self.us - self.up))
    }

    /// Measured bulk stress jump over the momentum jump condition ρ_a (u_s − δ)(u_p − δ)
    /// (1 for a steady wave; bulk stress and bulk density, as the jump conditions need).
    pub fn momentum_jump_ratio(&self) -> f64 {
        let d = self.precursor_velocity;
        (self.stress_behind - self.stress_precursor)
            / (self.rho_ahead * (self.us - d) * (self.up - d))
    }
}

/// The seed's fit of the porous-copper Hugoniot (seed 004 §4): linear up to 130 m/s,
/// quadratic above.
pub fn seed_fit(up: f64) -> f64 {
    if up <= 130.0 {
        226.8 + 1.886 * up
    } else {
        14.58 + 3.573 * up - 0.0003967 * up * up
    }
}

/// Computes the points for `opts.ups` (a window scene, validated), handing each to
/// `done` as it finishes.
pub fn hugoniot(
    scene: &Scene,
    opts: &HugoniotOptions,
    mut done: impl FnMut(&HugoniotPoint) -> Result<(), String>,
) -> Result<Vec<HugoniotPoint>, String> {
    let w = scene
        .window
        .as_ref()
        .ok_or("the scene has no [window] section")?;
    let geo = w.geometry(scene).map_err(|e| e.0)?;
    let parts = build_particles(scene).map_err(|e| e.0)?;
    let mut out = Vec::new();
    for &up in &opts.ups {
        let p = match scene.dim {
            1 => point::<1>(scene, geo, &parts, up, opts),
            2 => point::<2>(scene, geo, &parts, up, opts),
            _ => point::<3>(scene, geo, &parts, up, opts),
        }?;
        done(&p)?;
        out.push(p);
    }
    Ok(out)
}

struct Run<'a, const D: usize> {
    scene: &'a Scene,
    up: f64,
    nu: f64,
    opts: &'a HugoniotOptions,
    trials: usize,
    steps: u64,
}

type State<const D: usize> = (Sim<D>, Window<D>);

impl<const D: usize> Run<'_, D> {
    fn say(&self, msg: String) {
        if self.opts.verbose {
            eprintln!("[u_p {:.1} m/s] {msg}", self.up);
        }
    }

    fn omega(&self, s: &State<D>) -> f64 {
        s.1.excess(&s.0) / self.nu
    }

    /// Advances `s` by `duration` at its current frame; `each` sees the state after every
    /// step.
    fn advance(
        &mut self,
        s: &mut State<D>,
        duration: f64,
        mut each: impl FnMut(&State<D>) -> bool,
    ) -> Result<(), String> {
        let t_end = s.0.t + duration;
        while s.0.t < t_end {
            let dt =
                s.0.next_dt(self.scene.cfl(), self.scene.dt)
                    .map_err(|e| e.to_string())?;
            s.1.step(&mut s.0, dt).map_err(|e| e.to_string())?;
            self.steps += 1;
            if !each(s) {
                break;
            }
        }
        Ok(())
    }

    /// The mean slope of ω over one trial at `us`, from `saved`.
    fn trial(&mut self, saved: &State<D>, us: f64) -> Result<f64, String> {
        let mut s = saved.clone();
        s.1.set_entry_velocity(&mut s.0, -us);
        let duration = self.opts.samples * s.1.geo.feed / us;
        let mut pts = Vec::new();
        let nu = self.nu;
        self.advance(&mut s, duration, |s| {
            pts.push((s.0.t, s.1.excess(&s.0) / nu));
            true
        })?;
        self.trials += 1;
        Ok(slope(&pts))
    }

    /// Bisection on the sign of the ω slope over [lo, hi]. With `widen`, an end that gives
    /// the wrong sign moves outwards (by the bracket width, doubling, at most 4 times).
    fn bisect(
        &mut self,
        saved: &State<D>,
        stage: &str,
        (mut lo, mut hi): (f64, f64),
        widen: bool,
    ) -> Result<(f64, f64), String> {
        let mut s_lo = self.trial(saved, lo)?;
        let mut s_hi = self.trial(saved, hi)?;
        let mut step = hi - lo;
        for _ in 0..if widen { 4 } else { 0 } {
            if s_lo > 0.0 && s_hi < 0.0 {
                break;
            }
            if s_lo <= 0.0 {
                (hi, s_hi) = (lo, s_lo);
                lo = (lo - step).max(self.up + 1.0);
                s_lo = self.trial(saved, lo)?;
            } else {
                (lo, s_lo) = (hi, s_hi);
                hi += step;
                s_hi = self.trial(saved, hi)?;
            }
            step *= 2.0;
        }
        self.say(format!(
            "{stage}: bracket ends u_s {lo:.1} -> dω/dt {s_lo:+.3e} 1/s, {hi:.1} -> {s_hi:+.3e} 1/s"
        ));
        if !(s_lo > 0.0 && s_hi < 0.0) {
            return Err(format!(
                "u_p {} m/s, {stage}: the bracket u_s in [{lo:.1}, {hi:.1}] m/s does not hold the root (dω/dt {s_lo:+.3e} and {s_hi:+.3e} 1/s; the low end must give a positive slope, the high end a negative one): widen it with --bracket",
                self.up
            ));
        }
        while hi - lo > self.opts.tolerance {
            let mid = 0.5 * (lo + hi);
            let sl = self.trial(saved, mid)?;
            if sl > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            self.say(format!(
                "{stage} trial {}: u_s {mid:.2} -> dω/dt {sl:+.3e} 1/s; bracket [{lo:.2}, {hi:.2}]",
                self.trials
            ));
        }
        Ok((lo, hi))
    }
}

fn point<const D: usize>(
    scene: &Scene,
    geo: WindowGeometry,
    parts: &InitialParticles,
    up: f64,
    opts: &HugoniotOptions,
) -> Result<HugoniotPoint, String> {
    let t0 = Instant::now();
    let m = parts.porosity.first().copied().unwrap_or(1.0);
    let (lo, hi) = match opts.bracket {
        Some(b) => b,
        None if m > 1.0 => {
            let bound = m * up / (m - 1.0);
            (0.85 * bound, (2.0 * bound).max(bound + 300.0))
        }
        None => return Err("a sample without pores needs --bracket".into()),
    };
    let us_est = 0.5 * (lo + hi);
    let mut sc = scene.clone();
    if let Some(w) = sc.window.as_mut() {
        w.up = up;
        w.us = up.max(1e-9);
    }
    let mut sim = Sim::<D>::new(&sc, parts).map_err(|e| e.to_string())?;
    let win = Window::new(&sc, geo, parts, &mut sim);
    let mut run = Run {
        scene,
        up,
        nu: opts.target * (us_est / (us_est - up) - 1.0),
        opts,
        trials: 0,
        steps: 0,
    };
    // stage 1: the front runs into the window until ω = 1
    let len = geo.x_r - geo.x_l;
    let cap = 4.0 * opts.target * len / (0.5 * lo).max(1e-9);
    let mut s: State<D> = (sim, win);
    let nu = run.nu;
    run.advance(&mut s, cap, |s| s.1.excess(&s.0) / nu < 1.0)?;
    if run.omega(&s) < 1.0 {
        return Err(format!(
            "u_p {up} m/s, stage 1: ω reached only {:.3} in {cap:.3e} s (the front did not enter the window)",
            run.omega(&s)
        ));
    }
    run.say(format!(
        "stage 1: ω = 1 at t = {:.3e} s, front at {:.1} um",
        s.0.t,
        s.1.front(&s.0) * 1e6
    ));
    let (mut a, mut b) = run.bisect(&s, "bisection 1", (lo, hi), true)?;
    let mut us = 0.5 * (a + b);
    let mut rounds = vec![us];
    // steps 5-6, repeated until the speed settles: run at the found speed while half the
    // window length enters (the relaxation zone keeps densifying after stage 1, which
    // biases the first bisection), then bisect again around it
    for round in 2..=opts.max_rounds {
        s.1.set_entry_velocity(&mut s.0, -us);
        run.advance(&mut s, 0.5 * len / us, |_| true)?;
        run.say(format!(
            "settled at u_s {us:.2}: t = {:.3e} s, ω = {:.3}, front at {:.1} um",
            s.0.t,
            run.omega(&s),
            s.1.front(&s.0) * 1e6
        ));
        let w = (4.0 * opts.tolerance).max(0.03 * us);
        (a, b) = run.bisect(&s, &format!("bisection {round}"), (us - w, us + w), true)?;
        let new = 0.5 * (a + b);
        let change = new - us;
        us = new;
        rounds.push(us);
        if change.abs() <= (2.0 * opts.tolerance).max(0.005 * us) {
            break;
        }
    }
    // production: averaged profiles at the final speed
    s.1.set_entry_velocity(&mut s.0, -us);
    let duration = opts.average * geo.feed / us;
    let every = (duration / opts.profiles.max(1) as f64).max(0.0);
    let mut profile = Profile::new(&geo, geo.dx);
    let mut pts = Vec::new();
    let mut next = s.0.t + every;
    run.advance(&mut s, duration, |s| {
        pts.push((s.0.t, s.1.excess(&s.0) / nu));
        if s.0.t >= next {
            profile.add(&s.0);
            next += every;
        }
        true
    })?;
    let u_in = -us;
    let front = profile.front(u_in + 0.5 * up);
    let margin = 2.0 * geo.feed;
    let behind_lo = geo.x_l + geo.d_out1 + geo.feed;
    let ahead_hi = geo.x_r - geo.d_in - geo.dx;
    let stress_behind = profile.mean(behind_lo, front - margin, |b| b.stress_bulk);
    let stress_precursor = profile.mean(front + margin, ahead_hi, |b| b.stress_bulk);
    let stress_behind_matrix = profile.mean(behind_lo, front - margin, |b| b.stress);
    let stress_precursor_matrix = profile.mean(front + margin, ahead_hi, |b| b.stress);
    let pores_behind = 1.0 - profile.mean(behind_lo, front - margin, |b| b.solid_fraction);
    let rho_behind = profile.mean(behind_lo, front - margin, |b| b.rho_bulk);
    let rho_ahead = profile.mean(front + margin, ahead_hi, |b| b.rho_bulk);
    let precursor_velocity = profile.mean(front + margin, ahead_hi, |b| b.vx) - u_in;
    let point = HugoniotPoint {
        up,
        us,
        bracket: b - a,
        rounds,
        stress_behind,
        stress_precursor,
        stress_behind_matrix,
        stress_precursor_matrix,
        pores_behind,
        rho_behind,
        rho_ahead,
        precursor_velocity,
        front,
        omega_slope: slope(&pts),
        trials: run.trials,
        steps: run.steps,
        wall_s: t0.elapsed().as_secs_f64(),
        profile,
    };
    run.say(format!(
        "u_s = {us:.2} m/s (fit {:.1}), −σ_xx behind {:.3} GPa, precursor {:.3} GPa, {} trials, {:.0} s",
        seed_fit(up),
        stress_behind * 1e-9,
        stress_precursor * 1e-9,
        point.trials,
        point.wall_s
    ));
    Ok(point)
}

/// `hugoniot.csv`: one row per point (DESIGN §6 contract: `up, us, sigma_behind,
/// sigma_precursor, …`; velocities m/s, stresses −σ_xx in Pa, densities kg/m³).
/// `sigma_behind`, `sigma_precursor` are bulk stresses (volume averages with the pores at
/// zero: what the jump conditions and the seed's σ_HEL refer to); `sigma_*_matrix` are the
/// means over the particles (the stress in the solid); `rho_*` are bulk densities.
pub fn to_csv(points: &[HugoniotPoint]) -> String {
    let mut s = String::from(
        "up,us,sigma_behind,sigma_precursor,us_fit,us_rel_diff,bracket,us_rounds,precursor_velocity,rho_ahead,rho_behind,mass_jump_ratio,momentum_jump_ratio,front_m,omega_slope,trials,steps,wall_s,sigma_behind_matrix,sigma_precursor_matrix,pores_behind\n",
    );
    for p in points {
        let fit = seed_fit(p.up);
        let rounds: Vec<String> = p.rounds.iter().map(|u| format!("{u:.2}")).collect();
        s.push_str(&format!(
            "{},{:.3},{:.6e},{:.6e},{:.3},{:.5},{:.3},{},{:.3},{:.2},{:.2},{:.5},{:.5},{:.6e},{:.4e},{},{},{:.1},{:.6e},{:.6e},{:.5}\n",
            p.up,
            p.us,
            p.stress_behind,
            p.stress_precursor,
            fit,
            (p.us - fit) / fit,
            p.bracket,
            rounds.join(";"),
            p.precursor_velocity,
            p.rho_ahead,
            p.rho_behind,
            p.mass_jump_ratio(),
            p.momentum_jump_ratio(),
            p.front,
            p.omega_slope,
            p.trials,
            p.steps,
            p.wall_s,
            p.stress_behind_matrix,
            p.stress_precursor_matrix,
            p.pores_behind
        ));
    }
    s
}

/// The points as JSON, the columns of [`to_csv`] (the Python package's `gsph.hugoniot`).
pub fn to_json(points: &[HugoniotPoint]) -> serde_json::Value {
    let rows = points.iter().map(|p| {
        let fit = seed_fit(p.up);
        serde_json::json!({
            "up": p.up,
            "us": p.us,
            "sigma_behind": p.stress_behind,
            "sigma_precursor": p.stress_precursor,
            "us_fit": fit,
            "us_rel_diff": (p.us - fit) / fit,
            "bracket": p.bracket,
            "us_rounds": p.rounds,
            "precursor_velocity": p.precursor_velocity,
            "rho_ahead": p.rho_ahead,
            "rho_behind": p.rho_behind,
            "mass_jump_ratio": p.mass_jump_ratio(),
            "momentum_jump_ratio": p.momentum_jump_ratio(),
            "front_m": p.front,
            "omega_slope": p.omega_slope,
            "trials": p.trials,
            "steps": p.steps,
            "wall_s": p.wall_s,
            "sigma_behind_matrix": p.stress_behind_matrix,
            "sigma_precursor_matrix": p.stress_precursor_matrix,
            "pores_behind": p.pores_behind,
        })
    });
    serde_json::Value::Array(rows.collect())
}
