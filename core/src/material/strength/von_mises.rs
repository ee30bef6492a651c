//! Von Mises radial return (elastic–perfectly plastic, associated flow).
//!
//! # Derivation
//!
//! The elastic predictor of a step gives the trial deviator `S_tr = S_n + 2G de` (`de` the
//! deviatoric strain increment, plus the Jaumann rotation). With associated flow the plastic
//! strain increment is `de_p = dl N`, `N = (3/2) S / sigma_vm` (so that the equivalent
//! plastic strain `sqrt(2/3 de_p:de_p) = dl`), and the corrected deviator is
//! `S = S_tr - 2G de_p`. Since `N` is parallel to `S_tr` (backward Euler), `S = k S_tr`, and
//! the consistency condition `sigma_vm(S) = Y` gives the radial return
//!
//! ```text
//! k = Y / sigma_tr,   sigma_tr = sqrt(3/2 S_tr:S_tr),   d_eps_p = dl = (sigma_tr - Y) / (3G).
//! ```
//!
//! # Plastic work
//!
//! The plastic work per unit volume reported is `W_p = S : de_p = Y d_eps_p`, evaluated with
//! the returned deviator (exactly `S_returned : de_p`, since `de_p = (S_tr - S)/(2G)` and
//! `S:S_tr = (2/3) Y sigma_tr`). It is the dissipation of perfect plasticity, whose stress
//! stays on the yield surface during plastic flow. The other natural choice, the elastic
//! energy released by the return `(S_tr:S_tr - S:S)/(4G) = (sigma_tr + Y)/2 d_eps_p` (the
//! mean of trial and returned deviator contracted with `de_p`), agrees to first order in the
//! overshoot `sigma_tr - Y`; the difference `(sigma_tr - Y) d_eps_p / 2` is the error of the
//! elastic predictor, not a dissipation.
use super::return_map::ReturnMap;
use crate::math::real::max;
use crate::math::{Real, Sym3};

/// Von Mises radial return of a trial deviator onto the yield surface `sigma_vm = yield_stress`.
///
/// `s_trial` is the full symmetric 3x3 trial deviator (tension positive), `yield_stress` the
/// current flow stress `Y` (Pa) and `shear_modulus` `G` (Pa). If
/// `sigma_vm = sqrt(3/2 S:S) <= Y` the state is elastic and returned unchanged; otherwise
/// `S = S_trial Y / sigma_vm` (coaxial, on the yield surface), `d_eps_p = (sigma_vm - Y)/(3G)`
/// and `plastic_work = Y d_eps_p` (see the module documentation for the derivation and the
/// choice of the plastic work).
///
/// Edge cases: `Y = +inf` never yields; a negative or NaN `Y` is taken as zero (no shear
/// strength: the deviator is removed); a `G` that is not positive (or NaN) reports no
/// plastic strain and no work, as no elastic strain can be attributed; `G = +inf` gives
/// `d_eps_p = 0`. A non-finite trial deviator is returned unchanged.
pub fn radial_return(s_trial: Sym3, yield_stress: Real, shear_modulus: Real) -> ReturnMap {
    let sigma_vm = s_trial.von_mises();
    let y = max(yield_stress, 0.0); // NaN or negative -> 0
    if sigma_vm.is_nan() || sigma_vm <= y {
        return ReturnMap::elastic(s_trial);
    }
    let s = s_trial * (y / sigma_vm);
    let d_eps_p = if shear_modulus > 0.0 {
        (sigma_vm - y) / (3.0 * shear_modulus)
    } else {
        0.0
    };
    ReturnMap {
        s,
        d_eps_p,
        plastic_work: y * d_eps_p,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::math::Lcg;

    /// A random deviator with components up to `scale`.
    fn deviator(g: &mut Lcg, scale: Real) -> Sym3 {
        let a = [(); 6].map(|_| scale * g.next());
        Sym3::from_array(a).deviator()
    }

    #[test]
    fn plastic_return_lies_on_the_yield_surface_and_is_coaxial() {
        let mut g = Lcg(2);
        let (y, gm) = (3e8, 2.6e10);
        for _ in 0..500 {
            let st = deviator(&mut g, 2e9);
            let svm = st.von_mises();
            if svm <= y {
                continue;
            }
            let m = radial_return(st, y, gm);
            assert!((m.s.von_mises() - y).abs() < 1e-12 * y);
            assert!(m.s.trace().abs() < 1e-6);
            // coaxial: S = k S_trial with 0 < k < 1 component-wise
            let k = m.s.ddot(&st) / st.ddot(&st);
            assert!(k > 0.0 && k < 1.0 && (m.s - st * k).max_abs() < 1e-12 * svm);
            // consistency 3G d_eps_p = sigma_trial - Y, plastic work non-negative
            assert!((3.0 * gm * m.d_eps_p - (svm - y)).abs() < 1e-12 * svm);
            assert!(m.d_eps_p > 0.0 && m.plastic_work >= 0.0);
            // W_p = S_returned : de_p with de_p = (S_trial - S)/(2G)
            let de_p = (st - m.s) * (0.5 / gm);
            assert!((m.s.ddot(&de_p) - m.plastic_work).abs() < 1e-10 * m.plastic_work);
        }
    }

    #[test]
    fn elastic_states_are_untouched() {
        let st = Sym3::new(1e8, -0.4e8, -0.6e8, 2e7, -1e7, 3e7);
        let y = st.von_mises();
        for yy in [y, 1.5 * y, Real::INFINITY] {
            assert_eq!(radial_return(st, yy, 2.6e10), ReturnMap::elastic(st));
        }
        // infinite yield stress never yields, however large the trial deviator
        let big = st * 1e20;
        assert_eq!(radial_return(big, Real::INFINITY, 1.0).s, big);
        assert_eq!(
            radial_return(Sym3::ZERO, 0.0, 1e10),
            ReturnMap::elastic(Sym3::ZERO)
        );
    }

    /// 1D uniaxial strain: a strain increment de along x gives the deviatoric increment
    /// 2G (2/3, -1/3, -1/3) de, so S_xx = -2 S_yy = -2 S_zz and sigma_vm = 3/2 |S_xx|: the
    /// deviator saturates at |S_xx| = 2Y/3 (the out-of-plane S_zz is essential).
    #[test]
    fn uniaxial_strain_saturates_at_two_thirds_of_the_yield_stress() {
        let (y, gm) = (2.9e8, 2.76e10);
        for sign in [-1.0, 1.0] {
            let mut s = Sym3::ZERO;
            let mut eps_p = 0.0;
            let de = sign * 1e-4;
            for step in 0..400 {
                s += Sym3::new(
                    2.0 * gm * 2.0 / 3.0 * de,
                    -2.0 * gm / 3.0 * de,
                    -2.0 * gm / 3.0 * de,
                    0.0,
                    0.0,
                    0.0,
                );
                let m = radial_return(s, y, gm);
                s = m.s;
                eps_p += m.d_eps_p;
                assert!((s.xx + 2.0 * s.yy).abs() < 1e-6 && (s.yy - s.zz).abs() < 1e-6);
                if step > 100 {
                    assert!((s.xx.abs() - 2.0 * y / 3.0).abs() < 1e-12 * y);
                    assert_eq!(s.xx.signum(), sign);
                }
            }
            // first yield at |e_xx| = Y/(2G) (sigma_vm = 2G |e_xx|); afterwards the plastic
            // strain tensor grows as (2/3, -1/3, -1/3) de, whose equivalent is (2/3)|de|
            let elastic = y / (2.0 * gm);
            assert!(
                (eps_p - 2.0 / 3.0 * (400.0 * 1e-4 - elastic)).abs() < 1e-12,
                "{eps_p}"
            );
        }
    }

    #[test]
    fn plastic_work_agrees_with_released_elastic_energy_to_first_order() {
        let (y, gm) = (1e8, 1e10);
        let dir = Sym3::new(2.0, -1.0, -1.0, 0.5, 0.0, -0.3).deviator();
        let dir = dir * (1.0 / dir.von_mises());
        for eta in [1e-1, 1e-2, 1e-3, 1e-4] {
            let st = dir * (y * (1.0 + eta));
            let m = radial_return(st, y, gm);
            let released = (st.ddot(&st) - m.s.ddot(&m.s)) / (4.0 * gm);
            // released / W_p = (sigma + Y)/(2Y): relative difference eta/2 -> 0
            let rel = (released - m.plastic_work) / m.plastic_work;
            assert!(
                rel > 0.0 && (rel - 0.5 * eta).abs() < 1e-6 * eta,
                "{eta}: {rel}"
            );
        }
    }

    #[test]
    fn extreme_shear_moduli_and_degenerate_inputs() {
        let st = Sym3::new(3e9, -1e9, -2e9, 5e8, 0.0, 0.0);
        let svm = st.von_mises();
        for gm in [1e3, 1e6, 1e12, 1e18, 1e30] {
            let m = radial_return(st, 1e8, gm);
            assert!((m.s.von_mises() - 1e8).abs() < 1e-12 * 1e8);
            assert!((m.d_eps_p * 3.0 * gm - (svm - 1e8)).abs() < 1e-12 * svm);
            assert!(m.d_eps_p.is_finite() && m.plastic_work.is_finite() && m.plastic_work >= 0.0);
        }
        let m = radial_return(st, 1e8, Real::INFINITY);
        assert_eq!((m.d_eps_p, m.plastic_work), (0.0, 0.0));
        let m = radial_return(st, 1e8, 0.0);
        assert!(m.s.is_finite() && m.d_eps_p == 0.0 && m.plastic_work == 0.0);
        for bad_y in [0.0, -5.0, Real::NAN] {
            let m = radial_return(st, bad_y, 1e10);
            assert_eq!(m.s, Sym3::ZERO);
            assert!((m.d_eps_p - svm / 3e10).abs() < 1e-12 && m.plastic_work == 0.0);
        }
    }
}
