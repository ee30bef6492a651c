//! Robust bracketed scalar root finding (Brent's method), always terminating.

use super::error::ExactError;
use crate::math::real::{abs, min};
use crate::math::Real;

/// Iteration cap; Brent converges in far fewer steps on the smooth monotone functions used
/// here, and bisection alone would reach round-off from any f64 bracket in ~1100 steps.
const MAX_ITER: usize = 300;

/// Root of `f` in `[a, b]` by Brent's method (inverse quadratic interpolation, secant and
/// bisection safeguards).
///
/// `f(a)` and `f(b)` must be finite and of opposite sign (or one of them zero), otherwise
/// [`ExactError::NoRootBracket`] naming `what` is returned. The iterate is accepted once
/// the bracket half-width is below `2 eps |x| + xtol / 2`; at most [`MAX_ITER`] function
/// evaluations are made, so the call always terminates.
pub(crate) fn brent<F: FnMut(Real) -> Real>(
    mut f: F,
    a: Real,
    b: Real,
    xtol: Real,
    what: &'static str,
) -> Result<Real, ExactError> {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if !(fa.is_finite() && fb.is_finite()) || (fa > 0.0) == (fb > 0.0) && fa != 0.0 && fb != 0.0 {
        return Err(ExactError::NoRootBracket { what });
    }
    if fa == 0.0 {
        return Ok(a);
    }
    let (mut c, mut fc) = (b, fb);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..MAX_ITER {
        if (fb > 0.0) == (fc > 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if abs(fc) < abs(fb) {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * Real::EPSILON * abs(b) + 0.5 * xtol;
        let xm = 0.5 * (c - b);
        if abs(xm) <= tol || fb == 0.0 {
            return Ok(b);
        }
        if abs(e) >= tol && abs(fa) > abs(fb) {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = abs(p);
            if 2.0 * p < min(3.0 * xm * q - abs(tol * q), abs(e * q)) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if abs(d) > tol {
            d
        } else if xm > 0.0 {
            tol
        } else {
            -tol
        };
        fb = f(b);
        if !fb.is_finite() {
            // The function left its finite range inside the bracket: give up.
            return Err(ExactError::NoRootBracket { what });
        }
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_root_finds_sqrt2_and_rejects_bad_bracket() {
        let r = brent(|x| x * x - 2.0, 0.0, 2.0, 0.0, "sqrt2").unwrap();
        assert!(abs(r - crate::math::real::sqrt(2.0)) < 1e-15);
        assert_eq!(
            brent(|x| x * x + 1.0, -1.0, 1.0, 0.0, "none"),
            Err(ExactError::NoRootBracket { what: "none" })
        );
        // A discontinuous sign change still terminates at the jump.
        let j = brent(|x| if x < 0.3 { -1.0 } else { 1.0 }, 0.0, 1.0, 0.0, "step").unwrap();
        assert!(abs(j - 0.3) < 1e-12);
    }
}
