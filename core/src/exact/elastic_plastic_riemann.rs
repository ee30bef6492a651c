//! The elastic–plastic Riemann problem of seed 004 §2.1.1 (eqs 24–37), derived with the
//! rarefactions as centred fans.
//!
//! Material: log EOS `P = B ln(V0/V)` (eq 24), constant shear modulus `G`, von Mises yield
//! `Y`; uniaxial strain, so along a particle path `dS_xx = (4G/3) dV/V` (eq 26) and
//! `|S_xx| <= 2Y/3`. Initial state (eq 25): `x < 0`: `sigma_xx = sigma1 < 0` at the
//! compressive yield limit (`S_xx = -2Y/3`, `P1 = -sigma1 - 2Y/3`, `rho1 = rho0 exp(P1/B)`),
//! `u = 0`; `x >= 0`: unstressed, `rho0`, `u = 0`.
//!
//! With `K = B + 4G/3` the stress on each branch is, as a function of `V = 1/rho`:
//! * left elastic (release from yield): `sigma = sigma1 + K ln(V/V1)`, up to
//!   `V_er = V1 exp(Y/G)` where `S` has gone from `-2Y/3` to `+2Y/3` (eq 33);
//! * left plastic (tensile yield): `sigma = 2Y/3 - B ln(V0/V)`;
//! * right elastic (from rest): `sigma = K ln(V/V0)`, down to `V_ec = V0 exp(-Y/(2G))`,
//!   `sigma_ec = -2Y/3 - B Y/(2G)` (eqs 30–31);
//! * right plastic (compressive yield): `sigma = -2Y/3 - B ln(V0/V)`.
//!
//! Every branch has `d²sigma/dV² = -(B or K)/V² < 0`, i.e. the compressive stress `-sigma`
//! is convex in `V`, so compressions are shocks and expansions are centred fans (a
//! rarefaction shock would violate the entropy condition; DESIGN §8).
//!
//! *Shocks* (right-going, Lagrangian mass flux `W > 0`): `sigma_b - sigma_a = W²(V_b - V_a)`
//! (Rayleigh line, eq 29) and `u_b - u_a = W (V_a - V_b)`, so
//! `u_b = u_a + sqrt((sigma_b - sigma_a)(V_b - V_a))`; Eulerian speed `D = u_a + W V_a`.
//!
//! *Fans* (left-going): the Lagrangian sound speed per unit reference volume is
//! `a = sqrt(dsigma/dV)` and the Eulerian one `c = V a` (`c² = V² dsigma/dV`). Across a
//! left-going simple wave the right-going Riemann invariant is constant: `du = a dV`, which
//! integrates on a branch with `dsigma/dV = M/V` (`M = K` or `B`) to
//! `u = u_head + 2 sqrt(M) (sqrt(V) - sqrt(V_head))`. The characteristic `x/t = u - c`
//! increases with `V`, so each fan is inverted in closed form:
//! `sqrt(V) = (x/t - u_head)/sqrt(M) + 2 sqrt(V_head)`.
//!
//! The contact state `(u_c, sigma_c)` is the root of `u_L(sigma) = u_R(sigma)` on
//! `[sigma1, 0]`, both curves explicit and monotone (Brent's method, [`super::root`]).
//!
//! Seed errata confirmed here (DESIGN §8): the line before eq 37 swaps `Δσ_pc` and `Δσ_pr`
//! (it must read `sigma_ec + Δσ_pc = sigma_c = sigma_er + Δσ_pr`, as eq 37 then does); eq 36
//! drops the factor `B`; the closed form for `D_ec` lacks `rho0`: dimensionally
//! `D_ec² = (2/3 + B/(2G)) Y / (rho0 (1 - exp(-Y/(2G))))`; fig 2 says copper but the data
//! are aluminium. The paper's discontinuous (rarefaction-shock) treatment gives a contact
//! stress within about 1e-6 relative of the fan solution (see the tests).

use super::error::{positive, ExactError};
use super::root::brent;
use crate::math::real::{exp, ln, sqrt};
use crate::math::Real;

/// Parameters of the elastic–plastic Riemann problem (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EpRiemannParams {
    /// Reference (unstressed) density `rho0`, kg/m³.
    pub rho0: Real,
    /// Bulk modulus `B` of the log EOS `P = B ln(V0/V)`, Pa.
    pub bulk_modulus: Real,
    /// Shear modulus `G` (constant), Pa.
    pub shear_modulus: Real,
    /// Von Mises yield stress `Y`, Pa.
    pub yield_stress: Real,
    /// Initial stress `sigma_xx` of the left state, Pa (negative: compressed).
    pub sigma1: Real,
}

impl EpRiemannParams {
    /// Seed 004's aluminium: `rho0 = 2688.9 kg/m³`, `B = 73 GPa`, `G = 23 GPa`,
    /// `Y = 0.3 GPa`, `sigma1 = -4 GPa`.
    pub fn seed004_aluminium() -> Self {
        Self {
            rho0: 2688.9,
            bulk_modulus: 73e9,
            shear_modulus: 23e9,
            yield_stress: 0.3e9,
            sigma1: -4e9,
        }
    }
}

/// A sampled 1D state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EpState {
    /// Axial Cauchy stress `sigma_xx`, Pa (tension positive).
    pub sigma_xx: Real,
    /// Velocity `u_x`, m/s.
    pub u: Real,
    /// Density, kg/m³.
    pub rho: Real,
}

/// The seven wave features from left to right: speeds in m/s (or positions in m, see
/// [`ElasticPlasticRiemann::wave_positions`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EpWaves {
    /// Head of the left-going elastic fan, `-c_l(rho1)`.
    pub elastic_fan_head: Real,
    /// Tail of the elastic fan, `u_er - sqrt(K V_er)`.
    pub elastic_fan_tail: Real,
    /// Head of the plastic fan, `u_er - sqrt(B V_er)`.
    pub plastic_fan_head: Real,
    /// Tail of the plastic fan, `u_c - sqrt(B V_pr)`.
    pub plastic_fan_tail: Real,
    /// Contact discontinuity, `u_c`.
    pub contact: Real,
    /// Right-going plastic shock `D_pc`.
    pub plastic_shock: Real,
    /// Right-going elastic precursor shock `D_ec`.
    pub precursor: Real,
}

impl EpWaves {
    /// The features as an array, left to right.
    pub fn as_array(&self) -> [Real; 7] {
        [
            self.elastic_fan_head,
            self.elastic_fan_tail,
            self.plastic_fan_head,
            self.plastic_fan_tail,
            self.contact,
            self.plastic_shock,
            self.precursor,
        ]
    }
}

/// The stress–volume branches and wave curves of the problem (module docs).
#[derive(Clone, Copy, Debug)]
struct Branches {
    b: Real,
    g: Real,
    y: Real,
    k: Real,
    sigma1: Real,
    v0: Real,
    v1: Real,
}

impl Branches {
    fn new(p: &EpRiemannParams) -> Self {
        let v0 = 1.0 / p.rho0;
        let (b, y) = (p.bulk_modulus, p.yield_stress);
        let p1 = -p.sigma1 - 2.0 * y / 3.0;
        Self {
            b,
            g: p.shear_modulus,
            y,
            k: b + 4.0 * p.shear_modulus / 3.0,
            sigma1: p.sigma1,
            v0,
            v1: v0 * exp(-p1 / b),
        }
    }
    /// End of the elastic release: `V_er = V1 exp(Y/G)` (eq 33).
    fn v_er(&self) -> Real {
        self.v1 * exp(self.y / self.g)
    }
    /// `sigma_er = sigma1 + 4Y/3 + B Y/G = sigma1 + K Y/G`.
    fn sigma_er(&self) -> Real {
        self.sigma1 + self.k * self.y / self.g
    }
    /// Velocity at the elastic fan tail, `2 sqrt(K) (sqrt(V_er) - sqrt(V1))`.
    fn u_er(&self) -> Real {
        2.0 * sqrt(self.k) * (sqrt(self.v_er()) - sqrt(self.v1))
    }
    /// HEL volume `V_ec = V0 exp(-Y/(2G))` (eq 31).
    fn v_ec(&self) -> Real {
        self.v0 * exp(-self.y / (2.0 * self.g))
    }
    /// HEL stress `sigma_ec = K ln(V_ec/V0) = -2Y/3 - B Y/(2G)`.
    fn sigma_ec(&self) -> Real {
        -self.k * self.y / (2.0 * self.g)
    }
    /// Velocity behind the precursor, `sqrt(sigma_ec (V_ec - V0))`.
    fn u_ec(&self) -> Real {
        sqrt(self.sigma_ec() * (self.v_ec() - self.v0))
    }
    /// Volume on the left release path at stress `sigma >= sigma1`.
    fn left_volume(&self, sigma: Real) -> Real {
        if sigma <= self.sigma_er() {
            self.v1 * exp((sigma - self.sigma1) / self.k)
        } else {
            self.v0 * exp((sigma - 2.0 * self.y / 3.0) / self.b)
        }
    }
    /// Velocity reached through the left fans at stress `sigma` (`du = sqrt(dsigma/dV) dV`).
    fn left_velocity(&self, sigma: Real) -> Real {
        let v = self.left_volume(sigma);
        if sigma <= self.sigma_er() {
            2.0 * sqrt(self.k) * (sqrt(v) - sqrt(self.v1))
        } else {
            self.u_er() + 2.0 * sqrt(self.b) * (sqrt(v) - sqrt(self.v_er()))
        }
    }
    /// Volume on the right shock path at stress `sigma <= 0`.
    fn right_volume(&self, sigma: Real) -> Real {
        if sigma >= self.sigma_ec() {
            self.v0 * exp(sigma / self.k)
        } else {
            self.v0 * exp((sigma + 2.0 * self.y / 3.0) / self.b)
        }
    }
    /// Velocity behind the right shocks at stress `sigma` (Rayleigh line + Hugoniot).
    fn right_velocity(&self, sigma: Real) -> Real {
        let v = self.right_volume(sigma);
        if sigma >= self.sigma_ec() {
            sqrt(sigma * (v - self.v0))
        } else {
            self.u_ec() + sqrt((sigma - self.sigma_ec()) * (v - self.v_ec()))
        }
    }
}

/// The exact four-wave solution of the elastic–plastic Riemann problem (module docs).
#[derive(Clone, Copy, Debug)]
pub struct ElasticPlasticRiemann {
    params: EpRiemannParams,
    br: Branches,
    sigma_c: Real,
    u_c: Real,
    v_pr: Real,
    v_pc: Real,
    waves: EpWaves,
}

impl ElasticPlasticRiemann {
    /// Builds the solution: validates the parameters, solves `u_L(sigma_c) = u_R(sigma_c)`
    /// for the contact, and checks that the four-wave configuration holds
    /// (`sigma_er < sigma_c < sigma_ec` and `D_pc < D_ec`); otherwise a
    /// [`ExactError::BadParameter`] naming `sigma1` (or the offending modulus) is returned.
    pub fn new(params: EpRiemannParams) -> Result<Self, ExactError> {
        positive("rho0", params.rho0)?;
        positive("bulk_modulus", params.bulk_modulus)?;
        positive("shear_modulus", params.shear_modulus)?;
        positive("yield_stress", params.yield_stress)?;
        positive("sigma1", -params.sigma1).map_err(|_| ExactError::BadParameter {
            name: "sigma1",
            reason: "must be finite and < 0 (compressed left state)",
        })?;
        let br = Branches::new(&params);
        let f = |s: Real| br.left_velocity(s) - br.right_velocity(s);
        let sigma_c = brent(f, params.sigma1, 0.0, 0.0, "contact stress")?;
        let config = |reason| ExactError::BadParameter {
            name: "sigma1",
            reason,
        };
        if sigma_c <= br.sigma_er() {
            return Err(config("release does not reach tensile yield"));
        }
        if sigma_c >= br.sigma_ec() {
            return Err(config("contact stress above the HEL: no plastic shock"));
        }
        let u_c = br.right_velocity(sigma_c);
        let (v_pr, v_pc) = (br.left_volume(sigma_c), br.right_volume(sigma_c));
        let (v_ec, v_er, u_er) = (br.v_ec(), br.v_er(), br.u_er());
        let w_ec = sqrt(br.sigma_ec() / (v_ec - br.v0));
        let w_pc = sqrt((sigma_c - br.sigma_ec()) / (v_pc - v_ec));
        let waves = EpWaves {
            elastic_fan_head: -sqrt(br.k * br.v1),
            elastic_fan_tail: u_er - sqrt(br.k * v_er),
            plastic_fan_head: u_er - sqrt(br.b * v_er),
            plastic_fan_tail: br.left_velocity(sigma_c) - sqrt(br.b * v_pr),
            contact: u_c,
            plastic_shock: br.u_ec() + w_pc * v_ec,
            precursor: w_ec * br.v0,
        };
        if waves.plastic_shock >= waves.precursor {
            return Err(config("plastic shock overdrives the elastic precursor"));
        }
        Ok(Self {
            params,
            br,
            sigma_c,
            u_c,
            v_pr,
            v_pc,
            waves,
        })
    }

    /// The parameters the solution was built from.
    pub fn params(&self) -> &EpRiemannParams {
        &self.params
    }

    /// Contact stress `sigma_c`, Pa.
    pub fn contact_stress(&self) -> Real {
        self.sigma_c
    }

    /// Contact velocity `u_c`, m/s.
    pub fn contact_velocity(&self) -> Real {
        self.u_c
    }

    /// Wave speeds, m/s (all waves are centred at `x = 0`, `t = 0`).
    pub fn wave_speeds(&self) -> EpWaves {
        self.waves
    }

    /// Wave positions at time `t`, m (`speed * t`).
    pub fn wave_positions(&self, t: Real) -> EpWaves {
        let w = self.waves;
        EpWaves {
            elastic_fan_head: w.elastic_fan_head * t,
            elastic_fan_tail: w.elastic_fan_tail * t,
            plastic_fan_head: w.plastic_fan_head * t,
            plastic_fan_tail: w.plastic_fan_tail * t,
            contact: w.contact * t,
            plastic_shock: w.plastic_shock * t,
            precursor: w.precursor * t,
        }
    }

    /// Longitudinal sound speed of the compressed left state, `c_l(rho1) = sqrt(K/rho1)`
    /// with `K = B + 4G/3`, m/s.
    pub fn c_long_left(&self) -> Real {
        sqrt(self.br.k * self.br.v1)
    }

    /// Left end of validity with a free left boundary initially at `x_left < 0`: the
    /// release from that end travels at `c_l(rho1)`, so the solution holds only for
    /// `x >= x_left + c_l(rho1) t` (m).
    pub fn valid_from(&self, x_left: Real, t: Real) -> Real {
        x_left + self.c_long_left() * t
    }

    /// Initial left state `(sigma1, 0, rho1)`.
    pub fn left_state(&self) -> EpState {
        state(self.br.sigma1, 0.0, self.br.v1)
    }

    /// Initial right state `(0, 0, rho0)`.
    pub fn right_state(&self) -> EpState {
        state(0.0, 0.0, self.br.v0)
    }

    /// State between the elastic and the plastic fan (end of elastic release, eq 33).
    pub fn elastic_release_state(&self) -> EpState {
        state(self.br.sigma_er(), self.br.u_er(), self.br.v_er())
    }

    /// State behind the elastic precursor (the HEL, eqs 30–31).
    pub fn precursor_state(&self) -> EpState {
        state(self.br.sigma_ec(), self.br.u_ec(), self.br.v_ec())
    }

    /// States left and right of the contact: `(sigma_c, u_c, 1/V_pr)`, `(sigma_c, u_c, 1/V_pc)`.
    pub fn contact_states(&self) -> (EpState, EpState) {
        (
            state(self.sigma_c, self.u_c, self.v_pr),
            state(self.sigma_c, self.u_c, self.v_pc),
        )
    }

    /// The exact state at `(x, t)` (m, s). For `t <= 0` the initial data (eq 25).
    pub fn sample(&self, x: Real, t: Real) -> EpState {
        if t <= 0.0 {
            return if x < 0.0 {
                self.left_state()
            } else {
                self.right_state()
            };
        }
        let xi = x / t;
        let (w, br) = (&self.waves, &self.br);
        if xi < w.elastic_fan_head {
            self.left_state()
        } else if xi < w.elastic_fan_tail {
            let sv = xi / sqrt(br.k) + 2.0 * sqrt(br.v1);
            let v = sv * sv;
            state(br.sigma1 + br.k * ln(v / br.v1), xi + sqrt(br.k) * sv, v)
        } else if xi < w.plastic_fan_head {
            self.elastic_release_state()
        } else if xi < w.plastic_fan_tail {
            let sv = (xi - br.u_er()) / sqrt(br.b) + 2.0 * sqrt(br.v_er());
            let v = sv * sv;
            let sigma = 2.0 * br.y / 3.0 - br.b * ln(br.v0 / v);
            state(sigma, xi + sqrt(br.b) * sv, v)
        } else if xi < w.contact {
            self.contact_states().0
        } else if xi < w.plastic_shock {
            self.contact_states().1
        } else if xi < w.precursor {
            self.precursor_state()
        } else {
            self.right_state()
        }
    }
}

fn state(sigma_xx: Real, u: Real, v: Real) -> EpState {
    EpState {
        sigma_xx,
        u,
        rho: 1.0 / v,
    }
}

#[cfg(test)]
mod tests;
