//! Pieces shared by every scheme: the pair loop, the SPH gradient, the constitutive
//! update (Hooke + Jaumann + plastic return) and the equation-of-state refresh.

use super::pairs::for_each_pair;
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, GhostWorkspace, Halo};
use crate::material::{strength, Material, Strength};
use crate::math::{real, Matrix, Real, Sym3, Vector};
use crate::schemes::workspace::StepParams;
use crate::state::{smoothing_length, Aux, PairGeom, System};

/// Calls the caller's halo hook with `x` when the step of a run with `effects` makes it
/// (see [`crate::halo`]). Takes the four workspace arrays neighbours read, not the workspace,
/// so that a step can hold the pair geometry borrowed across the call.
#[inline(always)]
pub(crate) fn exchange<const D: usize>(
    effects: EffectSet,
    halo: &mut dyn Halo<D>,
    x: &Exchange,
    sys: &mut System<'_, D>,
    ws: GhostWorkspace<'_, D>,
) {
    if x.applies(effects) {
        halo.refresh(x, sys, ws);
    }
}

/// [`exchange`] with the step's effects and the four workspace arrays neighbours read:
/// `halo_exchange!(params, halo, x, sys, ws)`. A macro, not a method of the workspace,
/// so that the step can keep other workspace fields borrowed across the call.
macro_rules! halo_exchange {
    ($params:expr, $halo:expr, $x:expr, $sys:expr, $ws:expr) => {
        $crate::schemes::common::exchange(
            $params.effects,
            $halo,
            $x,
            $sys,
            $crate::halo::GhostWorkspace {
                grad: $ws.grad,
                grad_stress: $ws.grad_stress,
                corr: $ws.corr,
                hg: $ws.hg,
            },
        )
    };
}
pub(crate) use halo_exchange;

/// Fills the per-particle quantities the pair loops read ([`Aux`]) from the current
/// density: `1/rho`, `m/rho`, and with `CT` the transverse sound speed `sqrt(G/rho)`.
pub(crate) fn refresh_aux<const D: usize, const CT: bool, X: Executor>(
    sys: &System<'_, D>,
    aux: &mut [Aux],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(aux, |off, chunk: &mut [Aux]| {
        for (k, a) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let inv_rho = 1.0 / sys.rho[i];
            *a = Aux {
                inv_rho,
                vol: sys.m[i] * inv_rho,
                ct: if CT {
                    real::sqrt(params.materials[sys.mat[i] as usize].shear_modulus * inv_rho)
                } else {
                    0.0
                },
            };
        }
    });
}

/// The artificial stress tensor `R_i` of every particle from its current stress and
/// density (effect `artificial_stress`; see [`super::artificial_stress`]).
pub(crate) fn artificial_stress_tensors<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    art: &mut [Matrix<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let eps = params.options.artificial_stress;
    exec.run(art, |off, chunk: &mut [Matrix<D>]| {
        for (k, r) in chunk.iter_mut().enumerate() {
            let i = off + k;
            *r = super::artificial_stress::tensor::<D>(&cauchy::<D, E>(sys, i), sys.rho[i], eps);
        }
    });
}

/// `a ⊗ b` as a `D x D` matrix (`(a ⊗ b)_kl = a_k b_l`).
#[inline(always)]
pub(crate) fn outer<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> Matrix<D> {
    a * b.transpose()
}

/// Advances the deviator of local particle `k` over `dt` with the velocity gradient
/// `grad_v` (`dv_a/dx_b`): hypoelastic Hooke's law on the full 3x3 deviator plus the
/// Jaumann spin terms, then the material's return (see [`return_deviator`]).
#[inline(always)]
pub(crate) fn advance_deviator<const D: usize, E: Effects>(
    sys: &mut System<'_, D>,
    k: usize,
    mat: &Material,
    grad_v: &Matrix<D>,
    dt: Real,
) {
    let s = sys.s[k];
    let rate = deviator_rate(&s, mat, grad_v);
    let strain_rate = equivalent_strain_rate(grad_v);
    return_deviator::<D, E>(sys, k, mat, s + rate * dt, strain_rate, dt, true);
}

/// Equivalent (von Mises) strain rate `sqrt(2/3 e:e)` of the deviatoric strain rate.
#[inline(always)]
pub(crate) fn equivalent_strain_rate<const D: usize>(grad_v: &Matrix<D>) -> Real {
    let e = Sym3::sym_of(grad_v).deviator();
    real::sqrt(2.0 / 3.0 * e.ddot(&e))
}

/// Brings the trial deviator of local particle `k` back to the material's yield surface
/// and stores it: von Mises radial return, Johnson–Cook (with the temperature rise of the
/// plastic work, effect `heat`) or JH1 (with damage, effect `damage`). With `commit`, the
/// plastic strain, temperature and damage increments are accumulated; without (the
/// predictor stage of the leap-frog), only the deviator is updated.
#[inline(always)]
pub(crate) fn return_deviator<const D: usize, E: Effects>(
    sys: &mut System<'_, D>,
    k: usize,
    mat: &Material,
    trial: Sym3,
    strain_rate: Real,
    dt: Real,
    commit: bool,
) {
    if !sys.has_plasticity::<E>() {
        sys.s[k] = trial;
        return;
    }
    let g = mat.shear_modulus;
    let (s, d_eps) = match mat.strength {
        Strength::VonMises { yield_stress } => {
            let r = strength::radial_return(trial, yield_stress, g);
            (r.s, r.d_eps_p)
        }
        Strength::JohnsonCook(jc) => {
            let heat = sys.has_heat::<E>();
            let temp = if heat { sys.temp[k] } else { jc.t_room };
            let r = jc.return_map(trial, g, sys.rho[k], sys.eps_p[k], temp, dt);
            if heat && commit {
                sys.temp[k] += r.d_temperature;
            }
            (r.s, r.d_eps_p)
        }
        Strength::Jh1(jh) => {
            let damaged = sys.has_damage::<E>();
            let damage = if damaged { sys.damage[k] } else { 0.0 };
            let r = jh.update(trial, g, sys.p[k], damage, strain_rate);
            if damaged && commit {
                sys.damage[k] = r.damage;
            }
            (r.s, r.d_eps_p)
        }
        Strength::Fluid | Strength::Elastic => (trial, 0.0),
    };
    sys.s[k] = s;
    if commit {
        sys.eps_p[k] += d_eps;
    }
}

/// True if particle `i` has failed (damage 1; seed 000 Algorithm 1).
#[inline(always)]
pub(crate) fn failed<const D: usize, E: Effects>(sys: &System<'_, D>, i: usize) -> bool {
    // one bounds check serves as the flag: no damage stored, no failed particle
    E::RUNTIME.contains(EffectSet::DAMAGE) && matches!(sys.damage.get(i), Some(&d) if d >= 1.0)
}

/// Pressure of particle `i` as a pair sees it: a failed particle carries no tension.
#[inline(always)]
pub(crate) fn pair_pressure<const D: usize, E: Effects>(sys: &System<'_, D>, i: usize) -> Real {
    if failed::<D, E>(sys, i) {
        real::max(sys.p[i], 0.0)
    } else {
        sys.p[i]
    }
}

/// The deviator rate `2G dev(sym L) + W.S - S.W`.
#[inline(always)]
pub(crate) fn deviator_rate<const D: usize>(s: &Sym3, mat: &Material, grad_v: &Matrix<D>) -> Sym3 {
    Sym3::sym_of(grad_v).deviator() * (2.0 * mat.shear_modulus) + s.jaumann(grad_v)
}

/// Refreshes pressure, sound speeds and smoothing length of local particle `k` of a chunk
/// (the smoothing length stays as it is with [`crate::schemes::options::SchemeOptions::constant_h`]).
#[inline(always)]
pub(crate) fn refresh_eos<const D: usize>(
    sys: &mut System<'_, D>,
    k: usize,
    mat: &Material,
    params: &StepParams<'_, D>,
) {
    refresh_pressure(sys, k, mat);
    if !params.options.constant_h {
        sys.h[k] = smoothing_length::<D>(params.h_factor, sys.m[k], sys.rho[k]);
    }
}

/// Refreshes pressure and sound speeds of local particle `k` (smoothing length unchanged).
#[inline(always)]
pub(crate) fn refresh_pressure<const D: usize>(sys: &mut System<'_, D>, k: usize, mat: &Material) {
    let st = mat.eos(sys.rho[k], sys.e[k]);
    let c2 = real::max(st.c2, 0.0);
    sys.p[k] = st.p;
    sys.c[k] = real::sqrt(c2);
    sys.cl[k] = mat.c_long(sys.rho[k], c2);
}

/// The Cauchy stress `S - P I` of particle `i` (just `-P I` without strength).
#[inline(always)]
pub(crate) fn cauchy<const D: usize, E: Effects>(sys: &System<'_, D>, i: usize) -> Sym3 {
    let p = pair_pressure::<D, E>(sys, i);
    if E::STRENGTH {
        sys.s[i] - Sym3::isotropic(p)
    } else {
        Sym3::isotropic(-p)
    }
}

/// Relative margin of the umbrella scan ([`open_neighbourhood`]): a neighbour on the
/// region's boundary (a corner's edge neighbours lie at exactly 45 degrees from its
/// diagonal normal) is outside it whatever the round-off.
pub(crate) const SCAN_TOLERANCE: Real = 1e-9;

/// Whether particle `i`'s neighbourhood is open on one side (a free surface), by the
/// umbrella scan of Marrone et al. (2010, Comput. Methods Appl. Mech. Engrg. 199, 1526):
/// with the outward normal `n` of `-sum V_j grad_i W_ij`, the neighbourhood is closed if
/// some neighbour lies in the cone of half-angle 45 degrees about `n` (those nearer than
/// `sqrt 2 h`) or within `h` of `x_i + h n` (the others). Purely geometric: a neighbourhood
/// stretched or compressed (the Taylor rod's face, whose radial neighbours leave the
/// kernel while the axial ones crowd in) or closed by wall mirrors is not open, whatever
/// `L`'s eigenvalues say. A neighbourhood whose normal sum vanishes exactly is closed.
pub(crate) fn open_neighbourhood<const D: usize>(
    params: &StepParams<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    i: usize,
    h: Real,
) -> bool {
    let mut nu = Vector::<D>::zeros();
    for_each_pair(params, geom, i, |pr, _| {
        if pr.r > 0.0 {
            nu -= pr.grad * aux[pr.j].vol;
        }
    });
    let len = nu.norm();
    if len <= 0.0 || !len.is_finite() {
        return false;
    }
    let n = nu / len;
    let cone = core::f64::consts::FRAC_1_SQRT_2 as Real + SCAN_TOLERANCE;
    let far = core::f64::consts::SQRT_2 as Real * h;
    let disk = h * (1.0 - SCAN_TOLERANCE);
    let mut closed = false;
    for_each_pair(params, geom, i, |pr, _| {
        if pr.r > 0.0 && !closed {
            closed = if pr.r >= far {
                (pr.n * pr.r - n * h).norm() < disk
            } else {
                n.dot(&pr.n) > cone
            };
        }
    });
    !closed
}

/// Smallest eigenvalue of the symmetric part of a `D x D` matrix (closed forms).
pub(crate) fn min_sym_eigenvalue<const D: usize>(m: &Matrix<D>) -> Real {
    let a = |i: usize, j: usize| 0.5 * (m[(i, j)] + m[(j, i)]);
    match D {
        1 => a(0, 0),
        2 => {
            let (p, q, r) = (a(0, 0), a(1, 1), a(0, 1));
            let mean = 0.5 * (p + q);
            let rad = real::sqrt(0.25 * (p - q) * (p - q) + r * r);
            mean - rad
        }
        _ => {
            // Symmetric 3x3: trigonometric closed form (Smith 1961).
            let p1 = a(0, 1) * a(0, 1) + a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2);
            let tr = a(0, 0) + a(1, 1) + a(2, 2);
            let q = tr / 3.0;
            if p1 <= 0.0 {
                return real::min(a(0, 0), real::min(a(1, 1), a(2, 2)));
            }
            let p2 = (a(0, 0) - q) * (a(0, 0) - q)
                + (a(1, 1) - q) * (a(1, 1) - q)
                + (a(2, 2) - q) * (a(2, 2) - q)
                + 2.0 * p1;
            let p = real::sqrt(p2 / 6.0);
            let b = |i: usize, j: usize| (a(i, j) - if i == j { q } else { 0.0 }) / p;
            let det_b = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1))
                - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
                + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
            let r = real::max(-1.0, real::min(1.0, 0.5 * det_b));
            let phi = libm_acos(r) / 3.0;
            // eigenvalues: q + 2p cos(phi + 2 pi k/3); the smallest is k = 1
            q + 2.0 * p * real::cos(phi + 2.0 * crate::math::PI / 3.0)
        }
    }
}

#[inline]
fn libm_acos(x: Real) -> Real {
    real::atan2(real::sqrt(real::max(0.0, 1.0 - x * x)), x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smallest_eigenvalue_closed_forms() {
        let m2 = Matrix::<2>::new(2.0, 1.0, 1.0, 2.0);
        assert!((min_sym_eigenvalue(&m2) - 1.0).abs() < 1e-14);
        // diag(3, 1, 2) rotated by a permutation-like orthogonal matrix keeps eigenvalue 1
        let m3 = Matrix::<3>::new(2.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 5.0);
        assert!((min_sym_eigenvalue(&m3) - 1.0).abs() < 1e-12);
        let id = Matrix::<3>::identity();
        assert!((min_sym_eigenvalue(&id) - 1.0).abs() < 1e-14);
        let m1 = Matrix::<1>::new(0.4);
        assert_eq!(min_sym_eigenvalue(&m1), 0.4);
    }
}
