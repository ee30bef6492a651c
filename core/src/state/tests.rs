//! Tests of the state checks.

use super::*;

/// Two particles at rest with finite fields; `temp`, `damage` and `eps_p` as given (empty
/// when the effect is absent). Returns what [`check_finite`] says.
fn check(temp: &mut [Real], damage: &mut [Real], eps_p: &mut [Real]) -> Result<(), StepError> {
    let mut x = [Vector::<1>::new(0.0), Vector::<1>::new(1e-3)];
    let mut v = [Vector::<1>::zeros(); 2];
    let (mut rho, mut e, mut p) = ([2700.0; 2], [0.0; 2], [0.0; 2]);
    let (mut c, mut cl, mut h) = ([5000.0; 2], [6000.0; 2], [1e-3; 2]);
    let sys = System::<1> {
        x: &mut x,
        v: &mut v,
        m: &[2.7e-3; 2],
        mat: &[0; 2],
        rho: &mut rho,
        e: &mut e,
        p: &mut p,
        c: &mut c,
        cl: &mut cl,
        h: &mut h,
        s: &mut [],
        eps_p,
        damage,
        temp,
        hg: &mut [],
        xr: &mut [],
        vr: &[],
        phi: &mut [],
    };
    check_finite(&sys)
}

#[test]
fn check_finite_reports_temperature_damage_and_plastic_strain() {
    assert_eq!(check(&mut [], &mut [], &mut []), Ok(()));
    assert_eq!(check(&mut [298.0; 2], &mut [0.5; 2], &mut [0.1; 2]), Ok(()));
    let bad = |particle, field| Err(StepError::NonFinite { particle, field });
    assert_eq!(
        check(&mut [298.0, Real::NAN], &mut [], &mut []),
        bad(1, "temperature")
    );
    assert_eq!(
        check(&mut [298.0, Real::INFINITY], &mut [0.0; 2], &mut []),
        bad(1, "temperature")
    );
    assert_eq!(
        check(&mut [], &mut [Real::NAN, 0.0], &mut []),
        bad(0, "damage")
    );
    assert_eq!(
        check(&mut [], &mut [], &mut [0.0, Real::NAN]),
        bad(1, "plastic strain")
    );
}
