//! The hourglass stiffness of solids (effect `hourglass`, `options.hourglass = xi`): a
//! stored, non-dissipative restoring force against the zero-energy particle modes of
//! SPH elasticity, derived from an energy so that its work is exact (issue 46).
//!
//! **State.** Each particle carries an *hourglass displacement* `d_i` (the particle field
//! `hg`): how far it has moved away from the affine motion of its neighbours, integrated
//! in time and rotated with its spin,
//!
//! ```text
//! d_i' = W_i d_i + a_i,   a_i = sum_j w_ij (v_i - v_j) - L_i y_i,
//! w_ij = V_j omega_ij,    omega_ij = r_ij |W'(r_ij)| / D,    y_i = sum_j w_ij (x_i - x_j),
//! L_i  = sum_j V_j (v_j - v_i) ⊗ C_i grad_i W_ij,   C_i = (sum_j V_j (x_j - x_i) ⊗ grad_i W_ij)^-1,
//! ```
//!
//! with `W_i` the skew part of the corrected velocity gradient `L_i`. `a_i` vanishes for
//! every affine velocity field `v = G x + c` wherever `C_i` exists, free surfaces included
//! (`sum_j w_ij (v_i - v_j) = G y_i`), so a rigid rotation or a uniform strain stores
//! nothing, and the rotation keeps `d` objective. The weights sum to about one inside a
//! body (`sum_j V_j r |W'| = D`), so `d_i` is about the particle's offset from the
//! position its neighbours' affine motion predicts.
//!
//! **Energy and force.** The stored energy is `Phi = sum_i k_i |d_i|^2 / 2` with
//! `k_i = xi G_i V_i / h_i^2` (`G` the shear modulus; scaled by `1 - damage`). The
//! rotation does no work (`d . W d = 0`), so `dPhi/dt = sum_i q_i . a_i` with
//! `q_i = k_i d_i`, a linear form in the velocities: the force whose power is exactly
//! `-dPhi/dt` is, on particle `i`,
//!
//! ```text
//! f_i = sum_j [ omega_ij (V_i q_j - V_j q_i) - (V_i T_j + V_j T_i) grad_i W_ij ],   T_i = (q_i ⊗ y_i) C_i
//! ```
//!
//! (the first term from `sum_j w_ij (v_i - v_j)`, the second, a stress-like term, from
//! `L_i y_i`). Each pair's share is antisymmetric, so linear momentum is conserved to
//! round-off; the force is not central, and angular momentum is conserved as well as
//! the corrected gradient's stress forces conserve it. No peer code does it this way:
//! SPHinXsys's GNOG penalty integrates a per-particle *acceleration* whose work is no
//! energy's (its total energy grows 4-12 % on the breathing ring, issue 46), and
//! Ganzenmüller's stiffness (LAMMPS SMD) needs a total-Lagrangian reference. This is
//! Flanagan & Belytschko's hourglass stiffness (1981) in particle form: a rate-form
//! generalised displacement, co-rotated, with the force its energy's adjoint. Per
//! particle, not per pair, so it lives in the particle table (checkpoints, halos,
//! migrations and walls' images carry it as any field) and costs two pair passes.
//!
//! **Time integration.** [`update`] advances `d` from the start-of-step state (the same
//! velocities and positions the deviator is advanced from), then [`add_forces`] adds the
//! force of the new `d` to a sub-step's sums with the scheme's own power booking (the
//! pair-mean velocity, as the deviatoric forces): the scheme's energy equation books its
//! work into internal energy exactly, so total energy (kinetic + internal) stays what the
//! scheme makes it, and `Phi` ([`stored_energy`]) is the part of the internal energy the
//! stiffness holds; the monitor counts it with the strain energy.

use crate::effects::EffectSet;
use crate::exec::Executor;
use crate::math::{det, inverse, real, Matrix, Real, Vector};
use crate::schemes::av::records::AvRates;
use crate::schemes::common::outer;
use crate::schemes::pairs::for_each_pair;
use crate::schemes::workspace::StepParams;
use crate::state::{Aux, Hourglass, PairGeom, PairSums, System};

/// The stiffness `k = xi G V / h^2` of a particle (N/m per unit length in 2D), zero for a
/// material without shear modulus and scaled by `1 - damage`.
#[inline(always)]
pub fn stiffness(xi: Real, shear_modulus: Real, vol: Real, h: Real, damage: Real) -> Real {
    xi * shear_modulus * vol / (h * h) * (1.0 - damage)
}

/// The energy `k |d|^2 / 2` the stiffness stores in one particle, J (per unit length in 2D).
#[inline(always)]
pub fn stored_energy<const D: usize>(k: Real, d: &Vector<D>) -> Real {
    0.5 * k * d.norm_squared()
}

/// The exact rotation `(I - A/2)^-1 (I + A/2)` of the Cayley transform of `A = W dt`
/// (orthogonal for a skew `A`: `|R d| = |d|` to round-off), or the identity where it is
/// singular (never for a skew `A`).
#[inline(always)]
fn cayley<const D: usize>(a: &Matrix<D>) -> Matrix<D> {
    let half = a * 0.5;
    let id = Matrix::<D>::identity();
    match inverse(&(id - half)) {
        Some(inv) => inv * (id + half),
        None => id,
    }
}

/// Advances every particle's hourglass displacement over `params.dt` from the state at
/// the start of the step (`d <- R(W dt) d + a dt`, `R` the Cayley rotation) and writes
/// the records the force pass reads (`hg`): the step of the first-order integrators.
/// Reads of its neighbours x, v and the volumes in `aux`; a pair pass.
pub fn update<const D: usize, X: Executor>(
    sys: &mut System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    hg: &mut [Hourglass<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let dt = params.dt;
    let (x, v, h, mat, damage) = (&*sys.x, &*sys.v, &*sys.h, sys.mat, &*sys.damage);
    exec.run(
        (&mut *sys.hg, hg),
        |off, (disp, recs): (&mut [Vector<D>], &mut [Hourglass<D>])| {
            for (k, (d, rec)) in disp.iter_mut().zip(recs.iter_mut()).enumerate() {
                let i = off + k;
                let kin = kinematics(x, v, aux, geom, params, i);
                *d = cayley(&(kin.spin * dt)) * *d + kin.rate * dt;
                *rec = kin.record(d, (h, mat, damage), aux, params, i);
            }
        },
    );
}

/// The leap-frog's evaluation at the predicted end state: the rate `d' = W d + a` of
/// every particle's hourglass displacement into `rates` (`dhg`), and the records the
/// forces of that state read into `hg`. With `half = Some(dt/2)` (every evaluation but
/// the first) the displacement is first completed to the end of the step,
/// `d = d_half + d' dt/2` (`hg_half`, the first half of the step's kick), so that the
/// forces act with the final displacement as they act at the final positions (velocity
/// Verlet); with the predicted one instead the stiff hourglass modes gained energy
/// (the breathing ring's (KE + SE)/E0 reached 1.054, issue 46). A pair pass.
#[allow(clippy::too_many_arguments)] // the pass's inputs, its two outputs and the half step
pub fn rates<const D: usize, X: Executor>(
    sys: &mut System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    hg: &mut [Hourglass<D>],
    rates: &mut [AvRates<D>],
    params: &StepParams<'_, D>,
    half: Option<Real>,
    exec: &X,
) {
    let (x, v, h, mat, damage) = (&*sys.x, &*sys.v, &*sys.h, sys.mat, &*sys.damage);
    exec.run(
        (&mut *sys.hg, (rates, hg)),
        |off, (disp, (out, recs)): (&mut [Vector<D>], (&mut [AvRates<D>], &mut [Hourglass<D>]))| {
            for (k, (d, (r, rec))) in disp
                .iter_mut()
                .zip(out.iter_mut().zip(recs.iter_mut()))
                .enumerate()
            {
                let i = off + k;
                let kin = kinematics(x, v, aux, geom, params, i);
                r.dhg = kin.spin * *d + kin.rate;
                if let Some(hdt) = half {
                    *d = r.hg_half + r.dhg * hdt;
                }
                *rec = kin.record(d, (h, mat, damage), aux, params, i);
            }
        },
    );
}

/// What a particle's neighbourhood gives the stiffness: the correction `C_i`, the
/// corrected gradient `L_i` and its spin, the first moment `y_i` and the rate `a_i`.
struct Kinematics<const D: usize> {
    c: Matrix<D>,
    l: Matrix<D>,
    spin: Matrix<D>,
    y: Vector<D>,
    rate: Vector<D>,
}

/// The sums of particle `i` (module docs).
#[inline(always)]
fn kinematics<const D: usize>(
    x: &[Vector<D>],
    v: &[Vector<D>],
    aux: &[Aux],
    geom: &[PairGeom<D>],
    params: &StepParams<'_, D>,
    i: usize,
) -> Kinematics<D> {
    let d_inv = 1.0 / D as Real;
    let (xi_, vi) = (x[i], v[i]);
    let mut a_mat = Matrix::<D>::zeros();
    let mut l_raw = Matrix::<D>::zeros();
    let mut sv = Vector::<D>::zeros();
    let mut y = Vector::<D>::zeros();
    for_each_pair(params, geom, i, |pr, _| {
        let j = pr.j;
        let vol = aux[j].vol;
        let gw = pr.grad * vol;
        let xji = x[j] - xi_;
        let vji = v[j] - vi;
        a_mat += outer(&xji, &gw);
        l_raw += outer(&vji, &gw);
        // w_ij = V_j r |W'| / D (zero outside the support: dw = 0)
        let w = -vol * pr.r * pr.dw * d_inv;
        sv -= vji * w;
        y -= xji * w;
    });
    let c = match inverse(&a_mat) {
        Some(inv) if det(&a_mat) >= params.options.det_epsilon => inv,
        _ => Matrix::<D>::identity(),
    };
    let l = l_raw * c.transpose();
    Kinematics {
        c,
        l,
        spin: (l - l.transpose()) * 0.5,
        y,
        rate: sv - l * y,
    }
}

impl<const D: usize> Kinematics<D> {
    /// The record of particle `i` with displacement `d`.
    #[inline(always)]
    fn record(
        &self,
        d: &Vector<D>,
        (h, mat, damage): (&[Real], &[u16], &[Real]),
        aux: &[Aux],
        params: &StepParams<'_, D>,
        i: usize,
    ) -> Hourglass<D> {
        let m = &params.materials[mat[i] as usize];
        let dmg = if damage.is_empty() { 0.0 } else { damage[i] };
        let k = stiffness(
            params.options.hourglass,
            m.shear_modulus,
            aux[i].vol,
            h[i],
            dmg,
        );
        let q = *d * k;
        Hourglass {
            q,
            t: outer(&q, &self.y) * self.c,
            vol: aux[i].vol,
            c: self.c,
            l: self.l,
            ..Hourglass::default()
        }
    }
}

/// Adds the stiffness's force (module docs) to every particle's `acc` and its power at
/// the pair-mean velocity to `power` (per unit mass, as the deviatoric pass books its
/// forces), less `acc . v_i` where the scheme's `power` is an internal-energy rate at the
/// start-of-step velocity (`INTERNAL`: `pm`'s seed form). Reads the neighbours' records
/// `hg` ([`update`]); a pair pass.
pub fn add_forces<const D: usize, X: Executor, const INTERNAL: bool>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    hg: &[Hourglass<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            // the stress-like term -(V_i T_j + V_j T_i) grad_i W
            let (f, mut power) = pair_force(sys, geom, hg, params, i, |ri, rj, g| {
                -((rj.t * ri.vol + ri.t * rj.vol) * g)
            });
            if INTERNAL {
                power -= f.dot(&sys.v[i]);
            }
            let inv_m = 1.0 / sys.m[i];
            out.acc += f * inv_m;
            out.power += power * inv_m;
        }
    });
}

/// Advances the deviator of local particle `k` with the stiffness's corrected gradient
/// (`rec.l`), and with plasticity returns its hourglass displacement ([`yield_with`]):
/// the deviator update of every scheme that runs the stiffness.
#[inline(always)]
pub(crate) fn advance_deviator<const D: usize, E: crate::effects::Effects>(
    s: &mut System<'_, D>,
    k: usize,
    mat: &crate::material::Material,
    rec: &mut Hourglass<D>,
    xi: Real,
    dt: Real,
) {
    let s_old = s.s[k];
    crate::schemes::common::advance_deviator::<D, E>(s, k, mat, &rec.l, dt);
    if s.has_plasticity::<E>() {
        let (s_new, h) = (s.s[k], s.h[k]);
        yield_with(rec, &mut s.hg[k], &s_old, &s_new, mat, h, xi, dt);
    }
}

/// The stiffness yields with the material: where the plastic return brought the trial
/// deviator `s_old + S' dt` (from the corrected gradient `rec.l`) back to the yield
/// surface `s_new`, the hourglass displacement is limited to the one whose stiffness
/// stress `xi G |d|/h` equals the flow stress `sqrt(3/2) |s_new|`: `|d| <= sqrt(3/2) |s_new|
/// h / (xi G)`, and the record's force terms with it (a radial return of `d`). A particle's
/// rearrangement with its neighbours in plastic flow is then not held back as elastic:
/// without it the stiffness resisted the collapse of the beryllium ring (tkc's
/// inner-radius error −1.04 % became +2.73 %; scaling `d` by the deviator's own return
/// factor, +2.39 %). The energy the return releases stays in the internal energy, where
/// the force's work was booked: it becomes heat, as plastic work does.
#[inline(always)]
#[allow(clippy::too_many_arguments)] // the record, the state and the material's scale
fn yield_with<const D: usize>(
    rec: &mut Hourglass<D>,
    d: &mut Vector<D>,
    s_old: &crate::math::Sym3,
    s_new: &crate::math::Sym3,
    mat: &crate::material::Material,
    h: Real,
    xi: Real,
    dt: Real,
) {
    let trial = *s_old + crate::schemes::common::deviator_rate(s_old, mat, &rec.l) * dt;
    let (t2, n2) = (trial.ddot(&trial), s_new.ddot(s_new));
    let g = mat.shear_modulus;
    if n2 < t2 && g > 0.0 {
        let d_max = real::sqrt(1.5 * n2) * h / (xi * g);
        let len = d.norm();
        if len > d_max {
            let f = d_max / len;
            *d *= f;
            rec.q *= f;
            rec.t *= f;
        }
    }
}

/// The one tensor `P_i = S_i C_i - T_i/V_i` of [`stress_forces`] from the advanced
/// deviator `s` of particle `i`'s record.
#[inline(always)]
pub fn fuse_stress<const D: usize>(rec: &mut Hourglass<D>, s: &crate::math::Sym3) {
    let mut sc = Matrix::<D>::zeros();
    for a in 0..D {
        for b in 0..D {
            let mut v = 0.0;
            for k in 0..D {
                v += s.get(a, k) * rec.c[(k, b)];
            }
            sc[(a, b)] = v;
        }
    }
    rec.p = sc - rec.t / rec.vol;
}

/// `ts`'s deviatoric step with the stiffness, in one pass: the deviator's force as the
/// adjoint of the corrected gradient, `V_i V_j (S_i C_i + S_j C_j) grad_i W_ij`, and the
/// stiffness's force (module docs), whose stress-like part has the same form, so that
/// each pair needs one tensor per side, `P = S C - T/V` ([`fuse_stress`]):
/// `f_ij = omega_ij (V_i q_j - V_j q_i) + V_i V_j (P_i + P_j) grad_i W_ij`, with the
/// volumes the rate was summed with. Writes `acc` and the power at the pair-mean velocity
/// (per unit mass). The same sums as [`add_forces`] after the deviatoric pass's
/// corrected force, to round-off; 1.4 times the step's cost became 1.3 (issue 46).
pub fn stress_forces<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    hg: &[Hourglass<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let (f, power) = pair_force(sys, geom, hg, params, i, |ri, rj, g| {
                (ri.p + rj.p) * g * (ri.vol * rj.vol)
            });
            let inv_m = 1.0 / sys.m[i];
            out.acc = f * inv_m;
            out.power = power * inv_m;
        }
    });
}

/// The force on particle `i` and its power at the pair-mean velocities: per pair
/// `omega_ij (V_i q_j - V_j q_i)` plus the stress-like term `term(r_i, r_j, grad_i W_ij)`
/// of [`add_forces`] or [`stress_forces`].
#[inline(always)]
fn pair_force<const D: usize>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    hg: &[Hourglass<D>],
    params: &StepParams<'_, D>,
    i: usize,
    term: impl Fn(&Hourglass<D>, &Hourglass<D>, &Vector<D>) -> Vector<D>,
) -> (Vector<D>, Real) {
    let d_inv = 1.0 / D as Real;
    let vi = sys.v[i];
    let ri = &hg[i];
    let mut f = Vector::<D>::zeros();
    let mut power = 0.0;
    for_each_pair(params, geom, i, |pr, _| {
        let rj = &hg[pr.j];
        let omega = -pr.r * pr.dw * d_inv;
        let fij = (rj.q * ri.vol - ri.q * rj.vol) * omega + term(ri, rj, &pr.grad);
        f += fij;
        power += fij.dot(&((vi + sys.v[pr.j]) * 0.5));
    });
    (f, power)
}

/// True when the step of a run with `effects` runs the stiffness.
#[inline(always)]
pub(crate) fn on<const D: usize, E: crate::effects::Effects>(params: &StepParams<'_, D>) -> bool {
    params.has::<E>(EffectSet::HOURGLASS)
}

#[cfg(test)]
mod tests;
