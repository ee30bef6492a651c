//! Slope limiters for the MUSCL reconstruction of the `ts2` and `tkc` schemes.
//!
//! Seed 000 sec 3.3.1: the resolved gradients `dQ_i = grad Q_i · e`, `dQ_j = grad Q_j · e`
//! along the pair axis give the ratio `r_i = dQ_j / dQ_i` (and `r_j = 1/r_i`), and the
//! limited gradient is `phi(r_i) grad Q_i`. The limiters of seed 000 eq 27 are implemented:
//!
//! * Sweby(beta): `phi = max(0, min(beta r, 1), min(r, beta))`, `1 <= beta <= 2`;
//!   `minmod = Sweby(1) = max(0, min(r, 1))`, `superbee = Sweby(2)`;
//! * monotonized central: `phi = max(0, min(2r, (1+r)/2, 2))`;
//! * van Leer: `phi = (r + |r|)/(1 + |r|)`.
//!
//! All are second-order TVD (`0 <= phi <= min(2r, 2)`, `phi(1) = 1`, `phi = 0` for `r <= 0`)
//! and symmetric, `phi(r)/r = phi(1/r)` (seed 000 misprints this as `phi(r) = 1/phi(r)`), so
//! limiting the slope of i against j gives the same slope as limiting j against i: see
//! [`Limiter::limit`]. Non-finite ratios are handled: `r = NaN` (both slopes zero) gives 0
//! (first order), `r = +inf` gives the limit value of `phi` for large `r`.
use crate::math::real::{abs, max, min};
use crate::math::Real;
use core::fmt;

/// Slope limiter phi(r).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Limiter {
    /// minmod: `max(0, min(r, 1))` (Sweby with beta = 1), the most diffusive.
    Minmod,
    /// superbee: `max(0, min(2r, 1), min(r, 2))` (Sweby with beta = 2), the least
    /// diffusive; the default of the `ts2` scheme (seed 000).
    #[default]
    Superbee,
    /// Monotonized central: `max(0, min(2r, (1+r)/2, 2))`.
    MonotonizedCentral,
    /// van Leer: `(r + |r|)/(1 + |r|)`.
    VanLeer,
    /// Sweby: `max(0, min(beta r, 1), min(r, beta))` with `beta` in `[1, 2]`.
    Sweby(Real),
}

impl Limiter {
    /// phi(r), the limiter function of seed 000 eq 27 (see the module documentation).
    /// Returns 0 for `r <= 0` and for `r = NaN`.
    pub fn phi(self, r: Real) -> Real {
        // NaN and non-positive ratios give first order.
        if r.is_nan() || r <= 0.0 {
            return 0.0;
        }
        match self {
            Limiter::Minmod => sweby(1.0, r),
            Limiter::Superbee => sweby(2.0, r),
            Limiter::MonotonizedCentral => max(0.0, min(min(2.0 * r, 0.5 * (1.0 + r)), 2.0)),
            // 2r/(1+r), written as 2/(1 + 1/r) for large r so that r = inf gives 2
            Limiter::VanLeer => {
                if r <= 1.0 {
                    (r + abs(r)) / (1.0 + abs(r))
                } else {
                    2.0 / (1.0 + 1.0 / r)
                }
            }
            Limiter::Sweby(beta) => sweby(beta, r),
        }
    }

    /// The limited slope of a particle whose own resolved slope is `d_own` and whose
    /// partner's is `d_other`: `phi(d_other / d_own) d_own`, and 0 when `d_own = 0` or the
    /// slopes differ in sign. Evaluated without the division, in the closed forms
    /// `minmod(a, b)`, `maxmod(minmod(beta b, a), minmod(b, beta a))` (Sweby, superbee),
    /// `minmod(2a, (a+b)/2, 2b)` (MC) and `2ab/(a+b)` (van Leer), so the result is
    /// symmetric, `limit(a, b) == limit(b, a)`, exactly.
    ///
    /// Lane twin (superbee and minmod): `limit` in `core/src/simd/ops.rs`, held bitwise
    /// equal through the star tests (`schemes/star_tests.rs`).
    #[inline(always)]
    pub fn limit(self, d_own: Real, d_other: Real) -> Real {
        let (a, b) = (d_own, d_other);
        let same_sign = a * b > 0.0; // false for opposite signs, a zero or NaN
        if !same_sign {
            return 0.0;
        }
        // same signs: each form is sign(a) times its value on |a|, |b| (no branch on
        // which one is smaller: these branches are a coin toss in a pair loop)
        let (p, q) = (abs(a), abs(b));
        let m = match self {
            Limiter::Minmod => min(p, q),
            Limiter::Superbee => max(min(2.0 * q, p), min(q, 2.0 * p)),
            Limiter::Sweby(beta) => max(min(beta * q, p), min(q, beta * p)),
            Limiter::MonotonizedCentral => min(min(2.0 * p, 2.0 * q), 0.5 * (p + q)),
            Limiter::VanLeer => 2.0 * p * q / (p + q),
        };
        m.copysign(a)
    }

    /// Parses a limiter name (ASCII case-insensitive): `minmod`, `superbee`, `mc` (also
    /// `monotonized-central`), `vanleer` (also `van-leer`, `van_leer`), or `sweby:BETA` with
    /// `1 <= BETA <= 2`. Returns `None` for anything else.
    pub fn from_name(name: &str) -> Option<Limiter> {
        let name = name.trim();
        let is = |s: &str| name.eq_ignore_ascii_case(s);
        if is("minmod") {
            Some(Limiter::Minmod)
        } else if is("superbee") {
            Some(Limiter::Superbee)
        } else if is("mc") || is("monotonized-central") || is("monotonized_central") {
            Some(Limiter::MonotonizedCentral)
        } else if is("vanleer") || is("van-leer") || is("van_leer") {
            Some(Limiter::VanLeer)
        } else if name.len() > 6 && name.is_char_boundary(6) {
            let (head, beta) = name.split_at(6);
            if !head.eq_ignore_ascii_case("sweby:") {
                return None;
            }
            let beta: Real = beta.trim().parse().ok()?;
            (1.0..=2.0).contains(&beta).then_some(Limiter::Sweby(beta))
        } else {
            None
        }
    }
}

/// Writes the name accepted by [`Limiter::from_name`] (`sweby:BETA` for Sweby).
impl fmt::Display for Limiter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Limiter::Minmod => f.write_str("minmod"),
            Limiter::Superbee => f.write_str("superbee"),
            Limiter::MonotonizedCentral => f.write_str("mc"),
            Limiter::VanLeer => f.write_str("vanleer"),
            Limiter::Sweby(beta) => write!(f, "sweby:{beta}"),
        }
    }
}

/// Sweby's family `max(0, min(beta r, 1), min(r, beta))` for `r > 0`.
#[inline]
fn sweby(beta: Real, r: Real) -> Real {
    max(0.0, max(min(beta * r, 1.0), min(r, beta)))
}

/// Sweby's limited slope for `a b > 0`: the larger in magnitude of `minmod(beta b, a)`
/// and `minmod(b, beta a)` (both have the sign of `a`).
/// The extrapolation `ext` of one side of a pair towards its partner, bounded by half the
/// pair difference `half_jump = (Q_partner - Q_own)/2`: `minmod(ext, half_jump)`. An
/// extrapolation that points away from the partner gives 0, one that reaches past the
/// pair mean stops there. Both sides bounded this way keep the reconstructed jump of the
/// pair between zero and the particles' own jump, with the same sign, so the dissipation
/// of the pair's Riemann problem cannot turn negative.
#[inline]
pub fn bounded_extrapolation(ext: Real, half_jump: Real) -> Real {
    minmod(ext, half_jump)
}

/// minmod(a, b): 0 if `a` and `b` differ in sign (or either is zero or NaN), otherwise the
/// one of smaller magnitude (TKC eqs 14–15, seed 004).
///
/// Lane twin: `minmod` in `core/src/simd/ops.rs` (held bitwise equal through the star tests,
/// `schemes/star_tests.rs`).
#[inline(always)]
pub fn minmod(a: Real, b: Real) -> Real {
    if a > 0.0 && b > 0.0 {
        min(a, b)
    } else if a < 0.0 && b < 0.0 {
        max(a, b)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Limiter; 7] = [
        Limiter::Minmod,
        Limiter::Superbee,
        Limiter::MonotonizedCentral,
        Limiter::VanLeer,
        Limiter::Sweby(1.0),
        Limiter::Sweby(1.5),
        Limiter::Sweby(2.0),
    ];

    fn ratios() -> impl Iterator<Item = Real> {
        (-60..=60)
            .map(|k| (1.13 as Real).powi(k))
            .chain([0.5, 1.0, 2.0, 3.0, 1.0 / 3.0])
    }

    #[test]
    fn symmetry_phi_r_over_r_equals_phi_of_inverse() {
        for l in ALL {
            for r in ratios() {
                let (a, b) = (l.phi(r) / r, l.phi(1.0 / r));
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + b),
                    "{l}: r = {r}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn consistency_first_order_region_and_tvd_bounds() {
        for l in ALL {
            assert!((l.phi(1.0) - 1.0).abs() < 1e-15, "{l}");
            for r in [
                0.0,
                -0.0,
                -1e-9,
                -0.5,
                -1.0,
                -7.0,
                Real::NEG_INFINITY,
                Real::NAN,
            ] {
                assert_eq!(l.phi(r), 0.0, "{l} r = {r}");
            }
            for r in ratios().chain([Real::INFINITY]) {
                let p = l.phi(r);
                assert!(
                    p >= 0.0 && p <= (2.0 * r).min(2.0) + 1e-15,
                    "{l}: phi({r}) = {p}"
                );
            }
        }
    }

    #[test]
    fn known_values_and_sweby_end_points() {
        for r in ratios() {
            assert_eq!(Limiter::Sweby(1.0).phi(r), Limiter::Minmod.phi(r));
            assert_eq!(Limiter::Sweby(2.0).phi(r), Limiter::Superbee.phi(r));
        }
        assert_eq!(Limiter::Minmod.phi(0.5), 0.5);
        assert_eq!(Limiter::Minmod.phi(3.0), 1.0);
        assert_eq!(Limiter::Superbee.phi(0.25), 0.5);
        assert_eq!(Limiter::Superbee.phi(0.75), 1.0);
        assert_eq!(Limiter::Superbee.phi(1.5), 1.5);
        assert_eq!(Limiter::Superbee.phi(9.0), 2.0);
        assert_eq!(Limiter::MonotonizedCentral.phi(0.2), 0.4);
        assert_eq!(Limiter::MonotonizedCentral.phi(2.0), 1.5);
        assert_eq!(Limiter::MonotonizedCentral.phi(5.0), 2.0);
        assert!((Limiter::VanLeer.phi(3.0) - 1.5).abs() < 1e-15);
        assert_eq!(Limiter::VanLeer.phi(Real::INFINITY), 2.0);
    }

    #[test]
    fn limited_slope_is_symmetric_in_the_pair() {
        for l in ALL {
            for (a, b) in [
                (1.0, 2.0),
                (-3.0, -0.5),
                (1.0, -1.0),
                (0.0, 4.0),
                (2.5, 2.5),
            ] {
                let (x, y) = (l.limit(a, b), l.limit(b, a));
                assert!((x - y).abs() < 1e-14, "{l}: {a} {b}: {x} vs {y}");
            }
        }
    }

    #[test]
    fn closed_form_slopes_equal_phi_of_the_ratio() {
        for l in ALL {
            for a in [1.0, -2.5, 1e-30, 3e20] {
                for r in ratios().chain([-1.0, 0.0]) {
                    let b = r * a;
                    let want = l.phi(b / a) * a;
                    let got = l.limit(a, b);
                    assert!(
                        (got - want).abs() <= 1e-14 * want.abs(),
                        "{l}: a {a} b {b}: {got} vs {want}"
                    );
                }
            }
            assert_eq!(l.limit(0.0, 1.0), 0.0);
            assert_eq!(l.limit(1.0, Real::NAN), 0.0);
        }
    }

    #[test]
    fn bounded_extrapolation_stops_at_the_pair_mean_and_never_points_away() {
        assert_eq!(bounded_extrapolation(0.3, 0.5), 0.3);
        assert_eq!(bounded_extrapolation(0.9, 0.5), 0.5);
        assert_eq!(bounded_extrapolation(-0.9, -0.5), -0.5);
        assert_eq!(bounded_extrapolation(0.9, -0.5), 0.0);
        assert_eq!(bounded_extrapolation(0.9, 0.0), 0.0);
    }

    #[test]
    fn names_parse_and_round_trip() {
        assert_eq!(Limiter::from_name("minmod"), Some(Limiter::Minmod));
        assert_eq!(Limiter::from_name("SuperBee"), Some(Limiter::Superbee));
        assert_eq!(Limiter::from_name("mc"), Some(Limiter::MonotonizedCentral));
        assert_eq!(Limiter::from_name("vanleer"), Some(Limiter::VanLeer));
        assert_eq!(Limiter::from_name("sweby:1.5"), Some(Limiter::Sweby(1.5)));
        assert_eq!(Limiter::from_name("Sweby: 2"), Some(Limiter::Sweby(2.0)));
        for bad in [
            "",
            "sweby",
            "sweby:",
            "sweby:0.5",
            "sweby:2.5",
            "sweby:x",
            "van leer",
            "é",
        ] {
            assert_eq!(Limiter::from_name(bad), None, "{bad}");
        }
        assert_eq!(Limiter::default(), Limiter::Superbee);
        for l in ALL {
            let mut buf = heapless::String::<32>::new();
            core::fmt::write(&mut buf, format_args!("{l}")).unwrap();
            assert_eq!(Limiter::from_name(&buf), Some(l));
        }
    }

    #[test]
    fn minmod_picks_the_smaller_magnitude_of_equal_signs() {
        assert_eq!(minmod(1.0, 2.0), 1.0);
        assert_eq!(minmod(-1.0, -2.0), -1.0);
        assert_eq!(minmod(3.0, -2.0), 0.0);
        assert_eq!(minmod(0.0, 5.0), 0.0);
        assert_eq!(minmod(Real::NAN, 5.0), 0.0);
        assert_eq!(minmod(2.0, 2.0), 2.0);
    }
}
