//! The passes of a `tl` step (module docs of [`super`]). What each keeps where:
//!
//! - the `Hourglass` record of particle i (`Workspace::hg`): `c` the correction `C_i`,
//!   `t` the displacement gradient `H_i = F_i - I`, `l` the rate `dF_i/dt`, `vol` the
//!   reference volume `V0_i`, `k` the stiffness factor `kappa_i`, `zp` the
//!   longitudinal impedance; `p` holds the stiffness's `A_i` after [`deformation`] and the force
//!   pass's stress `P_i + A_i/V0_i` after [`constitutive`];
//! - `PairSums` of particle i after [`forces`]: `acc` the acceleration, `power` the heat
//!   rate of its Riemann dissipation per unit mass (W/kg), `div` the energy `Phi_i` its
//!   pairs store in the stiffness at the new positions (J).

use crate::effects::Effects;
use crate::exec::Executor;
use crate::limiter::bounded_extrapolation;
use crate::material::Strength;
use crate::math::{det, inverse, real, Matrix, Real, Sym3, Vector};
use crate::schemes::av::records::AvRates;
use crate::schemes::common::{advance_deviator, cauchy, outer, refresh_pressure};
use crate::schemes::pairs::for_each_pair;
use crate::schemes::workspace::StepParams;
use crate::state::{Hourglass, PairGeom, PairSums, System};

/// `x += v dt` for every particle (the drift).
pub(crate) fn drift<const D: usize, X: Executor>(sys: &mut System<'_, D>, dt: Real, exec: &X) {
    exec.run(
        (&mut *sys.x, &*sys.v),
        |_, (x, v): (&mut [Vector<D>], &[Vector<D>])| {
            for (xk, vk) in x.iter_mut().zip(v) {
                *xk += vk * dt;
            }
        },
    );
}

/// The deformation pass: every particle's correction, `H = F - I` at the drifted
/// positions, `dF/dt` of the half-step velocities, the stiffness factor, the
/// longitudinal impedance and the stiffness's stress-like `A_i = kappa_i (H_i M_i - N_i)` (into
/// `rec.p`). Reads x, v, xr, vr of its neighbours; a pair pass.
pub(crate) fn deformation<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    hg: &mut [Hourglass<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let d_inv = 1.0 / D as Real;
    let xi = params.options.hourglass;
    exec.run(hg, |off, recs: &mut [Hourglass<D>]| {
        for (k, rec) in recs.iter_mut().enumerate() {
            let i = off + k;
            let (xri, ui, vi) = (sys.xr[i], sys.x[i] - sys.xr[i], sys.v[i]);
            let mut b = Matrix::<D>::zeros();
            let mut h_raw = Matrix::<D>::zeros();
            let mut fd_raw = Matrix::<D>::zeros();
            let mut m = Matrix::<D>::zeros();
            let mut n = Matrix::<D>::zeros();
            for_each_pair(params, geom, i, |pr, _| {
                let j = pr.j;
                let vol = sys.vr[j];
                let gw = pr.grad * vol;
                let dxr = sys.xr[j] - xri;
                let du = (sys.x[j] - sys.xr[j]) - ui;
                b += outer(&dxr, &gw);
                h_raw += outer(&du, &gw);
                fd_raw += outer(&(sys.v[j] - vi), &gw);
                // V0_j omega_ij (zero outside the support: dw = 0)
                let w = -vol * pr.r * pr.dw * d_inv;
                m += outer(&dxr, &dxr) * w;
                n += outer(&du, &dxr) * w;
            });
            let c = match inverse(&b) {
                Some(inv) if det(&b) >= params.options.det_epsilon => inv,
                _ => Matrix::<D>::identity(),
            };
            // sum du ⊗ (C grad W) = (sum du ⊗ grad W) C^T
            let h = h_raw * c.transpose();
            let mat = &params.materials[sys.mat[i] as usize];
            let intact = 1.0 - sys.damage.get(i).copied().unwrap_or(0.0);
            let g = mat.shear_modulus * intact;
            let rho0 = sys.m[i] / sys.vr[i];
            let kappa = xi * g * sys.vr[i] / (sys.h[i] * sys.h[i]);
            *rec = Hourglass {
                q: Vector::<D>::zeros(),
                t: h,
                vol: sys.vr[i],
                c,
                l: fd_raw * c.transpose(),
                p: (h * m - n) * kappa,
                k: kappa,
                zp: rho0 * sys.cl[i],
            };
        }
    });
}

/// The local update after [`deformation`]: density `rho0/det F`, the deviator from
/// `L = dF/dt F_mid^-1` (with the plastic return), the internal energy from the stress
/// power, the pressure; then the force pass's stress `P + A/V0` into `rec.p`.
pub(crate) fn constitutive<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    hg: &mut [Hourglass<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let dt = params.dt;
    exec.run(
        (sys.reborrow(), hg),
        |_, (mut s, recs): (System<'_, D>, &mut [Hourglass<D>])| {
            for (k, rec) in recs.iter_mut().enumerate() {
                let mat = &params.materials[s.mat[k] as usize];
                let id = Matrix::<D>::identity();
                let f = id + rec.t;
                let f_mid = f - rec.l * (0.5 * dt);
                let l = rec.l * inverse(&f_mid).unwrap_or(id);
                let j = det(&f);
                let (rho_old, e_old, p_old) = (s.rho[k], s.e[k], s.p[k]);
                let rho_new = s.m[k] / (s.vr[k] * j);
                s.rho[k] = rho_new;
                let mut dev_work = 0.0;
                if E::STRENGTH {
                    let s_old = s.s[k];
                    if matches!(mat.strength, Strength::Elastic) {
                        // hyperelastic: the deviator is a function of F
                        s.s[k] = neo_hookean_deviator(&f, mat.shear_modulus);
                    } else {
                        advance_deviator::<D, E>(&mut s, k, mat, &l, dt);
                    }
                    let s_mid = (s_old + s.s[k]) * 0.5;
                    dev_work = s_mid.ddot(&Sym3::sym_of(&l)) * dt / (0.5 * (rho_old + rho_new));
                }
                // the exact volume change, trapezoidal in p (a predictor for the end)
                let dvol = 1.0 / rho_new - 1.0 / rho_old;
                let p_pred = mat.eos(rho_new, e_old + dev_work - p_old * dvol).p;
                s.e[k] = e_old + dev_work - 0.5 * (p_old + p_pred) * dvol;
                refresh_pressure(&mut s, k, mat);
                piola::<D, E>(&s, k, rec);
            }
        },
    );
}

/// The deviatoric Cauchy stress of a compressible neo-Hookean solid, `G J^(-5/3) dev(F
/// F^T)` (the isochoric part of `W = G/2 (tr(J^(-2/3) F F^T) - 3)`), with `F` embedded in
/// 3D as the identity out of the run's plane or line (plane strain, uniaxial strain). At
/// small strain it is Hooke's `2 G dev(eps)`; it is objective and stores its work exactly
/// in the continuum, where the rate form's Jaumann integration of large rotations and
/// shears does not.
#[inline(always)]
pub(crate) fn neo_hookean_deviator<const D: usize>(f: &Matrix<D>, g: Real) -> Sym3 {
    let j = det(f);
    let mut b = Sym3::sym_of(&(f * f.transpose()));
    if D < 3 {
        b.zz = 1.0;
    }
    if D < 2 {
        b.yy = 1.0;
    }
    b.deviator() * (g * real::powf(j, -5.0 / 3.0))
}

/// The force pass's stress of particle `k` from its state as it is (the first step of a
/// run, which has no rates yet): `P + A/V0` into `rec.p`, as [`constitutive`] leaves it.
pub(crate) fn stress_records<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    hg: &mut [Hourglass<D>],
    exec: &X,
) {
    exec.run(
        (sys.reborrow(), hg),
        |_, (s, recs): (System<'_, D>, &mut [Hourglass<D>])| {
            for (k, rec) in recs.iter_mut().enumerate() {
                piola::<D, E>(&s, k, rec);
            }
        },
    );
}

/// `rec.p <- J sigma F^-T + A/V0` of particle `k` (`rec.p` holds `A` from [`deformation`]).
#[inline(always)]
fn piola<const D: usize, E: Effects>(s: &System<'_, D>, k: usize, rec: &mut Hourglass<D>) {
    let id = Matrix::<D>::identity();
    let f = id + rec.t;
    let sigma = cauchy::<D, E>(s, k).block::<D>();
    let p1 = sigma * inverse(&f).unwrap_or(id).transpose() * det(&f);
    rec.p = p1 + rec.p * (1.0 / rec.vol);
}

/// The force pass: every particle's acceleration, the heat rate of its Riemann
/// dissipation and the energy its pairs store in the stiffness (see the module docs for
/// where). Reads the neighbours' records, x, v, xr; a pair pass.
pub(crate) fn forces<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    hg: &[Hourglass<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let d_inv = 1.0 / D as Real;
    let dissipation = params.options.dissipation;
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let ri = &hg[i];
            let (xi_, xri, vi) = (sys.x[i], sys.xr[i], sys.v[i]);
            let ui = xi_ - xri;
            let mut f = Vector::<D>::zeros();
            let mut heat = 0.0;
            let mut phi = 0.0;
            for_each_pair(params, geom, i, |pr, _| {
                if pr.r <= 0.0 {
                    return;
                }
                let j = pr.j;
                let rj = &hg[j];
                let gw = pr.grad;
                let vv = ri.vol * rj.vol;
                let cgi = ri.c * gw;
                let cgj = rj.c * gw;
                // the stress and the stiffness's stress
                f += (ri.p * cgi + rj.p * cgj) * vv;
                // the stiffness's pair term
                let dxr = sys.xr[j] - xri;
                let du = (sys.x[j] - sys.xr[j]) - ui;
                let e_ij = ri.t * dxr - du;
                let e_ji = du - rj.t * dxr;
                let omega = -pr.r * pr.dw * d_inv;
                let (k_ij, k_ji) = (ri.k * rj.vol * omega, rj.k * ri.vol * omega);
                f += e_ji * k_ji - e_ij * k_ij;
                phi += 0.5 * k_ij * e_ij.norm_squared();
                // the Riemann dissipation on the reconstructed jump
                let dv = sys.v[j] - vi;
                let dx = sys.x[j] - xi_;
                let dist = dx.norm();
                if dist > 0.0 {
                    let nrm = dx * (1.0 / dist);
                    let half = dxr * 0.5;
                    let (si, sj) = (ri.l * half, rj.l * half);
                    let jn = dv.dot(&nrm);
                    let jn_star = jn
                        - bounded_extrapolation(si.dot(&nrm), 0.5 * jn)
                        - bounded_extrapolation(sj.dot(&nrm), 0.5 * jn);
                    let zp = pair_impedance(ri.zp, rj.zp);
                    let c_l = 0.5 * (ri.zp * ri.vol / sys.m[i] + rj.zp * rj.vol / sys.m[j]);
                    let w = dissipation.weight(vi.dot(&nrm), sys.v[j].dot(&nrm), c_l);
                    let area = ((cgi + cgj) * vv).norm();
                    let fd = nrm * (zp * jn_star * area * w);
                    f += fd;
                    heat += 0.5 * fd.dot(&dv);
                }
            });
            let inv_m = 1.0 / sys.m[i];
            out.acc = f * inv_m;
            out.power = heat * inv_m;
            out.div = phi;
        }
    });
}

/// The impedance `Z_i Z_j/(Z_i + Z_j)` of a pair's acoustic Riemann problem (zero where
/// either side has none).
#[inline(always)]
fn pair_impedance(zi: Real, zj: Real) -> Real {
    let sum = zi + zj;
    if sum > 0.0 {
        zi * zj / sum
    } else {
        0.0
    }
}

/// The first half kick of the step (velocity Verlet): `v += a dt/2` with the
/// acceleration of the step's start (`rates`).
pub(crate) fn half_kick<const D: usize, X: Executor>(
    sys: &mut System<'_, D>,
    rates: &[AvRates<D>],
    dt: Real,
    exec: &X,
) {
    exec.run(
        (&mut *sys.v, rates),
        |_, (v, rates): (&mut [Vector<D>], &[AvRates<D>])| {
            for (vk, r) in v.iter_mut().zip(rates) {
                *vk += r.acc * (0.5 * dt);
            }
        },
    );
}

/// The second half kick and the energy booking: `v += a dt/2` with the new
/// acceleration, which `rates` keeps for the next step's first half kick; the internal
/// energy gains the heat of the Riemann dissipation over the step and the change of the
/// energy the stiffness stores (`phi` keeps it); then the pressure is refreshed.
pub(crate) fn kick<const D: usize, X: Executor>(
    sys: &mut System<'_, D>,
    sums: &[PairSums<D>],
    rates: &mut [AvRates<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let dt = params.dt;
    exec.run(
        (sys.reborrow(), (sums, rates)),
        |_, (mut s, (sums, rates)): (System<'_, D>, (&[PairSums<D>], &mut [AvRates<D>]))| {
            for (k, (sm, r)) in sums.iter().zip(rates.iter_mut()).enumerate() {
                let mat = &params.materials[s.mat[k] as usize];
                s.v[k] += sm.acc * (0.5 * dt);
                s.e[k] += sm.power * dt + (sm.div - s.phi[k]) / s.m[k];
                s.phi[k] = sm.div;
                r.acc = sm.acc;
                refresh_pressure(&mut s, k, mat);
            }
        },
    );
}

/// The rates of the state as it is, for the first half kick of a run's first step (or
/// the first after the caller changed the state): the acceleration into `rates`. The
/// stiffness's energy of the state is what `phi` holds already (it is state).
pub(crate) fn prime<const D: usize, X: Executor>(
    sums: &[PairSums<D>],
    rates: &mut [AvRates<D>],
    exec: &X,
) {
    exec.run(
        (sums, rates),
        |_, (sums, rates): (&[PairSums<D>], &mut [AvRates<D>])| {
            for (sm, r) in sums.iter().zip(rates.iter_mut()) {
                r.acc = sm.acc;
            }
        },
    );
}
