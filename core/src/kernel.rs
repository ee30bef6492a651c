//! Smoothing kernels `W(r, h) = sigma_D / h^D f(q)`, `q = r / h`, and their radial
//! derivatives `dW/dr = sigma_D / h^(D+1) f'(q)`.
//!
//! * Cubic B-spline M4 (Monaghan & Lattanzio 1985; Monaghan 1992 eq 2.6), support `2h`:
//!   `f = 1 - 3/2 q² + 3/4 q³` for `q < 1`, `f = 1/4 (2 - q)³` for `1 <= q < 2`;
//!   `sigma_1 = 2/3`, `sigma_2 = 10/(7 pi)`, `sigma_3 = 1/pi`.
//! * Wendland C2 (Wendland 1995; Dehnen & Aly 2012 table 1, rescaled to support `2h`):
//!   1D `f = (1 - q/2)³ (3/2 q + 1)`, `sigma_1 = 5/8`;
//!   2D/3D `f = (1 - q/2)⁴ (2q + 1)`, `sigma_2 = 7/(4 pi)`, `sigma_3 = 21/(16 pi)`.
//! * Gaussian-like, support `3h`: `f = exp(-q²) - exp(-9)` for `q < 3`, shifted so that
//!   `W` is continuous (zero) at the support. Its integral over `q` space is
//!   `I_1 = sqrt(pi) erf(3) - 6 e^-9`, `I_2 = pi (1 - 10 e^-9)`,
//!   `I_3 = pi^(3/2) erf(3) - 42 pi e^-9` (from `int_0^a q² e^(-q²) dq =
//!   sqrt(pi)/4 erf(a) - a/2 e^(-a²)`), and `sigma_D = 1 / I_D`. The constants are
//!   precomputed literals (40-digit arithmetic, correctly rounded to f64) and a unit test
//!   checks them against the erf formula.
//!
//! Units: `r`, `h` in m; `W` in m^-D; `dW/dr` in m^-(D+1).
use crate::math::{real, Real, Vector, PI};

/// `exp(-9)`: the shift that makes the Gaussian-like kernel vanish at `q = 3`.
const EXP_M9: f64 = 0.000_123_409_804_086_679_56;
/// `1 / (sqrt(pi) erf(3) - 6 e^-9)`: 1D Gaussian-like normalisation.
const GAUSS_SIGMA_1: f64 = 0.564_437_851_340_717_6;
/// `1 / (pi (1 - 10 e^-9))`: 2D Gaussian-like normalisation.
const GAUSS_SIGMA_2: f64 = 0.318_703_197_175_042_36;
/// `1 / (pi^(3/2) erf(3) - 42 pi e^-9)`: 3D Gaussian-like normalisation.
const GAUSS_SIGMA_3: f64 = 0.180_117_822_102_568_58;

/// Smoothing kernel shape. Support radius is `support() * h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// Cubic B-spline (M4), support 2h.
    CubicSpline,
    /// Wendland C2, support 2h.
    WendlandC2,
    /// Gaussian-like: truncated Gaussian, support 3h.
    Gaussian,
}

impl Kernel {
    /// Every kernel, in the order messages list them.
    pub const ALL: [Kernel; 3] = [Kernel::CubicSpline, Kernel::WendlandC2, Kernel::Gaussian];

    /// The scene name.
    pub const fn name(self) -> &'static str {
        match self {
            Kernel::CubicSpline => "cubic_spline",
            Kernel::WendlandC2 => "wendland_c2",
            Kernel::Gaussian => "gaussian",
        }
    }

    /// The kernel of a scene name.
    pub fn from_name(name: &str) -> Option<Kernel> {
        Kernel::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Support radius in units of h (dimensionless): 2 for the cubic spline and Wendland
    /// C2, 3 for the Gaussian-like kernel.
    pub const fn support(self) -> Real {
        match self {
            Kernel::CubicSpline | Kernel::WendlandC2 => 2.0,
            Kernel::Gaussian => 3.0,
        }
    }

    /// Dimensionless normalisation `sigma_D` such that `int W d^D x = 1` with
    /// `W = sigma_D / h^D f(q)` (see the module doc for the constants and their origin).
    ///
    /// Panics if `dim` is not 1, 2 or 3.
    #[inline(always)]
    pub const fn sigma(self, dim: usize) -> Real {
        match (self, dim) {
            (Kernel::CubicSpline, 1) => 2.0 / 3.0,
            (Kernel::CubicSpline, 2) => 10.0 / (7.0 * PI),
            (Kernel::CubicSpline, 3) => 1.0 / PI,
            (Kernel::WendlandC2, 1) => 5.0 / 8.0,
            (Kernel::WendlandC2, 2) => 7.0 / (4.0 * PI),
            (Kernel::WendlandC2, 3) => 21.0 / (16.0 * PI),
            (Kernel::Gaussian, 1) => GAUSS_SIGMA_1 as Real,
            (Kernel::Gaussian, 2) => GAUSS_SIGMA_2 as Real,
            (Kernel::Gaussian, 3) => GAUSS_SIGMA_3 as Real,
            _ => panic!("kernel dimension must be 1, 2 or 3"),
        }
    }

    /// The dimensionless shape `f(q)` and its derivative `f'(q)` (module doc), both zero
    /// for `q >= support()`.
    ///
    /// Lane twin: `shape` in `core/src/simd/ops.rs` (the cubic spline and Wendland C2;
    /// held bitwise equal by `schemes/pairs/lanes_tests.rs`).
    #[inline(always)]
    fn shape<const D: usize>(self, q: Real) -> (Real, Real) {
        match self {
            Kernel::CubicSpline => {
                if q < 1.0 {
                    (1.0 - q * q * (1.5 - 0.75 * q), q * (2.25 * q - 3.0))
                } else if q < 2.0 {
                    let t = 2.0 - q;
                    (0.25 * t * t * t, -0.75 * t * t)
                } else {
                    (0.0, 0.0)
                }
            }
            Kernel::WendlandC2 => {
                if q < 2.0 {
                    let t = 1.0 - 0.5 * q;
                    let t2 = t * t;
                    if D == 1 {
                        // f = t³ (1.5 q + 1), f' = -3 q t²
                        (t2 * t * (1.5 * q + 1.0), -3.0 * q * t2)
                    } else {
                        // f = t⁴ (2 q + 1), f' = -5 q t³
                        (t2 * t2 * (2.0 * q + 1.0), -5.0 * q * t2 * t)
                    }
                } else {
                    (0.0, 0.0)
                }
            }
            Kernel::Gaussian => {
                if q < 3.0 {
                    let g = real::exp(-q * q);
                    // max(): no negative round-off just inside the support
                    (real::max(g - EXP_M9 as Real, 0.0), -2.0 * q * g)
                } else {
                    (0.0, 0.0)
                }
            }
        }
    }

    /// The kernel's second moment in units of `h^2`: `<r^2>/h^2 = int (r/h)^2 W d^D x`
    /// (cubic spline: 1/3, 31/49, 9/10 in 1D, 2D, 3D), by Simpson's rule on each unit
    /// interval of `q` (the piecewise kernels' breakpoints), 256 panels each (to 1e-10). D times the
    /// variance of one coordinate under `W`: the width `schemes::pm::volume` gives
    /// the Gaussian that stands for the kernel in Inutsuka's pair integrals.
    pub fn second_moment<const D: usize>(self) -> Real {
        let measure = |q: Real| match D {
            1 => 2.0,
            2 => 2.0 * PI * q,
            _ => 4.0 * PI * q * q,
        };
        let g = |q: Real| self.shape_value::<D>(q) * q * q * measure(q);
        const PANELS: usize = 256;
        let mut total = 0.0;
        let mut lo = 0.0;
        while lo < self.support() {
            let dq = 1.0 / PANELS as Real;
            let mut s = g(lo) + g(lo + 1.0);
            for k in 1..PANELS {
                s += g(lo + k as Real * dq) * if k % 2 == 1 { 4.0 } else { 2.0 };
            }
            total += s * dq / 3.0;
            lo += 1.0;
        }
        total * self.sigma(D)
    }

    /// The dimensionless shape `f(q)` of `W = sigma_D / h^D f(q)` (zero for
    /// `q >= support()`): ratios of kernel values at one `h` need only this.
    #[inline(always)]
    pub fn shape_value<const D: usize>(self, q: Real) -> Real {
        self.shape::<D>(q).0
    }

    /// Kernel value `W(r, h) = sigma_D / h^D f(r/h)` in m^-D (`r >= 0`, `h > 0` in m).
    #[inline]
    pub fn w<const D: usize>(self, r: Real, h: Real) -> Real {
        self.w_dw::<D>(r, h).0
    }

    /// Radial derivative `dW/dr (r, h) = sigma_D / h^(D+1) f'(r/h)` in m^-(D+1)
    /// (non-positive).
    #[inline]
    pub fn dw<const D: usize>(self, r: Real, h: Real) -> Real {
        self.w_dw::<D>(r, h).1
    }

    /// `(W, dW/dr)` at once (units as in [`Kernel::w`] and [`Kernel::dw`]); one division
    /// and one shape evaluation, for the pair loop.
    #[inline]
    pub fn w_dw<const D: usize>(self, r: Real, h: Real) -> (Real, Real) {
        // compare in r so that W(r >= support * h) is exactly zero despite rounding of r/h
        if r >= self.support() * h {
            return (0.0, 0.0);
        }
        let inv_h = 1.0 / h;
        let q = r * inv_h;
        let (f, df) = self.shape::<D>(q);
        let norm = self.sigma(D) * real::powi(inv_h, D as u32);
        (norm * f, norm * inv_h * df)
    }

    /// The shape `f(r/h)` and `dW/dr (r, h)` at once (zero at and beyond the support): the
    /// pair geometry needs the slope, the artificial stress the ratio of shapes.
    #[inline(always)]
    pub fn shape_dw<const D: usize>(self, r: Real, h: Real) -> (Real, Real) {
        if r >= self.support() * h {
            return (0.0, 0.0);
        }
        let inv_h = 1.0 / h;
        let (f, df) = self.shape::<D>(r * inv_h);
        let norm = self.sigma(D) * real::powi(inv_h, D as u32);
        (f, norm * inv_h * df)
    }

    /// grad_i W(x_i - x_j) given `rij = x_i - x_j` and `r = |rij| > 0` (m^-(D+1)):
    /// `dW/dr rij / r`.
    pub fn gradient<const D: usize>(self, rij: &Vector<D>, r: Real, h: Real) -> Vector<D> {
        rij * (self.dw::<D>(r, h) / r)
    }
}

/// The scene name.
impl core::fmt::Display for Kernel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::*;

    const ALL: [Kernel; 3] = [Kernel::CubicSpline, Kernel::WendlandC2, Kernel::Gaussian];
    const H: Real = 0.37;

    /// Composite Simpson rule of `g` over `[a, b]` with `n` (even) intervals.
    fn simpson(g: impl Fn(Real) -> Real, a: Real, b: Real, n: usize) -> Real {
        let dx = (b - a) / n as Real;
        let mut s = g(a) + g(b);
        for i in 1..n {
            let c = if i % 2 == 1 { 4.0 } else { 2.0 };
            s += c * g(a + i as Real * dx);
        }
        s * dx / 3.0
    }

    fn dim_of<const D: usize>() -> usize {
        D
    }

    /// int W d^D x with the radial measure 2 dr, 2 pi r dr, 4 pi r² dr, split at the
    /// breakpoints of the piecewise kernels (q = 1, 2).
    fn integral<const D: usize>(k: Kernel) -> Real {
        let measure = |r: Real| match dim_of::<D>() {
            1 => 2.0,
            2 => 2.0 * PI * r,
            _ => 4.0 * PI * r * r,
        };
        let g = |r: Real| k.w::<D>(r, H) * measure(r);
        let mut total = 0.0;
        let mut lo = 0.0;
        let mut hi = 1.0;
        while lo < k.support() {
            total += simpson(g, lo * H, hi * H, 2000);
            lo = hi;
            hi += 1.0;
        }
        total
    }

    /// The second moment matches the cubic spline's closed forms and, for the others, an
    /// independent quadrature of `r^2 W` on 2000 panels per unit interval.
    #[test]
    fn second_moment_matches_closed_forms_and_a_fine_quadrature() {
        let cs = Kernel::CubicSpline;
        assert!((cs.second_moment::<1>() - 1.0 / 3.0).abs() < 1e-10);
        assert!((cs.second_moment::<2>() - 31.0 / 49.0).abs() < 1e-10);
        assert!((cs.second_moment::<3>() - 0.9).abs() < 1e-10);
        fn fine<const D: usize>(k: Kernel) -> Real {
            let measure = |r: Real| match dim_of::<D>() {
                1 => 2.0,
                2 => 2.0 * PI * r,
                _ => 4.0 * PI * r * r,
            };
            let g = |r: Real| k.w::<D>(r, H) * measure(r) * r * r;
            let mut total = 0.0;
            let mut lo = 0.0;
            while lo < k.support() {
                total += simpson(g, lo * H, (lo + 1.0) * H, 2000);
                lo += 1.0;
            }
            total / (H * H)
        }
        for k in [Kernel::WendlandC2, Kernel::Gaussian] {
            assert!(
                (k.second_moment::<1>() - fine::<1>(k)).abs() < 1e-9,
                "{k:?}"
            );
            assert!(
                (k.second_moment::<2>() - fine::<2>(k)).abs() < 1e-9,
                "{k:?}"
            );
            assert!(
                (k.second_moment::<3>() - fine::<3>(k)).abs() < 1e-9,
                "{k:?}"
            );
        }
    }

    #[test]
    fn normalisation_integrates_to_one() {
        for k in ALL {
            let i = [integral::<1>(k), integral::<2>(k), integral::<3>(k)];
            for (d, v) in i.iter().enumerate() {
                assert!((v - 1.0).abs() < 1e-6, "{k:?} D={} integral {v}", d + 1);
            }
        }
    }

    #[test]
    fn gaussian_constants_match_erf_formula() {
        let e9 = real::exp(-9.0);
        assert!((EXP_M9 as Real - e9).abs() <= 1e-18);
        let sp = real::sqrt(PI);
        let i1 = sp * real::erf(3.0) - 6.0 * e9;
        let i2 = PI * (1.0 - 10.0 * e9);
        let i3 = PI * sp * real::erf(3.0) - 42.0 * PI * e9;
        for (d, i) in [(1, i1), (2, i2), (3, i3)] {
            let s = Kernel::Gaussian.sigma(d);
            assert!((s * i - 1.0).abs() < 1e-14, "D={d}: {s} vs 1/{i}");
        }
    }

    #[test]
    fn sigma_is_const_and_matches_literals() {
        const S: Real = Kernel::CubicSpline.sigma(2);
        assert_eq!(S, 10.0 / (7.0 * PI));
        assert_eq!(Kernel::CubicSpline.sigma(1), 2.0 / 3.0);
        assert_eq!(Kernel::WendlandC2.sigma(3), 21.0 / (16.0 * PI));
        // W(0) by hand: cubic 3D is 1/(pi h³), Wendland 1D is 5/(8 h).
        assert!((Kernel::CubicSpline.w::<3>(0.0, 0.5) - 8.0 / PI).abs() < 1e-12);
        assert!((Kernel::WendlandC2.w::<1>(0.0, 0.5) - 1.25).abs() < 1e-15);
        // cubic 1D at q = 1: sigma f = 2/3 * 1/4 = 1/6, h = 0.5 -> 1/3.
        assert!((Kernel::CubicSpline.w::<1>(0.5, 0.5) - 1.0 / 3.0).abs() < 1e-15);
    }

    fn check_dw<const D: usize>(k: Kernel) {
        let n = 300;
        let max_dw = (0..n)
            .map(|i| k.dw::<D>(k.support() * H * i as Real / n as Real, H).abs())
            .fold(0.0, Real::max);
        let d = 1e-5 * H;
        for i in 1..n {
            let r = k.support() * H * (i as Real + 0.37) / n as Real;
            let q = r / H;
            // skip the breakpoints of the piecewise shapes and the support edge
            if [1.0, 2.0, 3.0].iter().any(|b| (q - b).abs() < 1e-3) || r >= k.support() * H {
                continue;
            }
            let fd = (k.w::<D>(r + d, H) - k.w::<D>(r - d, H)) / (2.0 * d);
            let an = k.dw::<D>(r, H);
            let scale = an.abs().max(1e-3 * max_dw);
            assert!(
                (fd - an).abs() <= 1e-6 * scale,
                "{k:?} D={D} q={q}: fd {fd} vs dw {an}"
            );
            assert_eq!(k.w_dw::<D>(r, H), (k.w::<D>(r, H), an));
        }
    }

    #[test]
    fn dw_matches_finite_difference() {
        for k in ALL {
            check_dw::<1>(k);
            check_dw::<2>(k);
            check_dw::<3>(k);
        }
    }

    fn check_shape<const D: usize>(k: Kernel) {
        let s = k.support() * H;
        for r in [s, s * (1.0 + 1e-12), 1.5 * s, 10.0 * s] {
            assert_eq!(k.w::<D>(r, H), 0.0);
            assert_eq!(k.dw::<D>(r, H), 0.0);
        }
        let mut prev = k.w::<D>(0.0, H);
        assert!(prev > 0.0);
        assert_eq!(k.dw::<D>(0.0, H), 0.0);
        for i in 1..=4000 {
            let r = 1.2 * s * i as Real / 4000.0;
            let (w, dw) = k.w_dw::<D>(r, H);
            assert!(w >= 0.0, "{k:?} D={D} r={r}: W = {w} < 0");
            assert!(w <= prev, "{k:?} D={D} r={r}: W increases");
            assert!(dw <= 0.0, "{k:?} D={D} r={r}: dW/dr = {dw} > 0");
            prev = w;
        }
        // continuity at the support: W just inside is tiny
        assert!(k.w::<D>(s * (1.0 - 1e-9), H) < 1e-10 * k.w::<D>(0.0, H));
    }

    #[test]
    fn compact_support_non_negative_non_increasing() {
        for k in ALL {
            check_shape::<1>(k);
            check_shape::<2>(k);
            check_shape::<3>(k);
        }
    }

    fn check_gradient<const D: usize>(k: Kernel, pts: &[[Real; 3]]) {
        let d = 1e-6 * H;
        for p in pts {
            let x = Vector::<D>::from_fn(|a, _| p[a] * H);
            let r = x.norm();
            let g = k.gradient::<D>(&x, r, H);
            let gmax = g.norm();
            for a in 0..D {
                let mut xp = x;
                let mut xm = x;
                xp[a] += d;
                xm[a] -= d;
                let fd = (k.w::<D>(xp.norm(), H) - k.w::<D>(xm.norm(), H)) / (2.0 * d);
                assert!(
                    (fd - g[a]).abs() <= 1e-6 * gmax,
                    "{k:?} D={D} x={p:?} comp {a}: fd {fd} vs {}",
                    g[a]
                );
            }
        }
    }

    #[test]
    fn gradient_matches_finite_difference_2d_3d() {
        let pts = [
            [0.3, 0.2, -0.1],
            [-0.7, 0.5, 0.4],
            [1.1, -0.6, 0.3],
            [0.05, 1.3, -0.8],
            [-1.2, -0.9, 0.2],
        ];
        for k in ALL {
            check_gradient::<2>(k, &pts);
            check_gradient::<3>(k, &pts);
        }
        // the gradient points from j to i with dW/dr < 0: it points back towards j
        let x = Vector::<2>::new(0.5 * H, 0.0);
        assert!(Kernel::CubicSpline.gradient::<2>(&x, 0.5 * H, H)[0] < 0.0);
    }
}
