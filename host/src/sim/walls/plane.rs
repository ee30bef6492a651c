//! A wall's plane and the reflections through it of points, vectors and tensors (the
//! mirror images of [`super`]).

use crate::scene::{walls::unit, WallSpec};
use gsph_core::math::{Matrix, Sym3, Vector};

/// A wall plane.
#[derive(Clone, Debug)]
pub struct Plane<const D: usize> {
    /// A point of the plane.
    pub point: Vector<D>,
    /// Unit normal towards the particles' side.
    pub normal: Vector<D>,
    /// Coulomb friction coefficient (0: frictionless; always 0 for symmetry planes).
    pub friction: f64,
    /// A rigid wall pushes but never pulls (contact is unilateral); a symmetry plane
    /// transmits tension too.
    pub unilateral: bool,
    /// `R = I - 2 n nᵀ` in 3D (the normal padded with zeros).
    r3: [[f64; 3]; 3],
}

impl<const D: usize> Plane<D> {
    /// The plane of a wall; `None` when its normal has no direction (zero or not finite:
    /// validation refuses such a scene).
    pub(super) fn new(w: &WallSpec) -> Option<Self> {
        let n = unit(&w.normal)?;
        let normal = Vector::<D>::from_fn(|k, _| n[k]);
        let mut r3 = [[0.0; 3]; 3];
        for (a, row) in r3.iter_mut().enumerate() {
            for (b, x) in row.iter_mut().enumerate() {
                let na = if a < D { n[a] } else { 0.0 };
                let nb = if b < D { n[b] } else { 0.0 };
                *x = f64::from(u8::from(a == b)) - 2.0 * na * nb;
            }
        }
        Some(Plane {
            point: Vector::<D>::from_fn(|k, _| w.point[k]),
            normal,
            friction: w.friction,
            unilateral: w.kind == "rigid",
            r3,
        })
    }

    /// Signed distance of `x` from the plane (positive on the particles' side).
    pub fn distance(&self, x: &Vector<D>) -> f64 {
        (x - self.point).dot(&self.normal)
    }

    /// The reflection of the point `x`.
    pub fn reflect_point(&self, x: &Vector<D>) -> Vector<D> {
        x - self.normal * (2.0 * self.distance(x))
    }

    /// The reflection of the vector `v`.
    pub fn reflect(&self, v: &Vector<D>) -> Vector<D> {
        v - self.normal * (2.0 * v.dot(&self.normal))
    }

    /// `R M R` of a `D x D` matrix.
    pub(super) fn reflect_matrix(&self, m: &Matrix<D>) -> Matrix<D> {
        let r = Matrix::<D>::from_fn(|a, b| self.r3[a][b]);
        r * m * r
    }

    /// `R S R` of a symmetric 3x3 tensor.
    pub(super) fn reflect_sym(&self, s: &Sym3) -> Sym3 {
        let r = &self.r3;
        let c = |a: usize, b: usize| {
            let mut v = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    v += r[a][i] * r[b][j] * s.get(i, j);
                }
            }
            v
        };
        Sym3::new(c(0, 0), c(1, 1), c(2, 2), c(0, 1), c(0, 2), c(1, 2))
    }

    /// The gradients of the six Voigt components of a symmetric tensor, reflected as the
    /// third-order tensor `T_abc = d S_ab / d x_c` they are.
    pub(super) fn reflect_tensor_gradient(&self, g: &[Vector<D>; 6]) -> [Vector<D>; 6] {
        const VOIGT: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
        let voigt = |a: usize, b: usize| {
            VOIGT
                .iter()
                .position(|&(i, j)| (i, j) == (a.min(b), a.max(b)))
                .expect("a Voigt pair")
        };
        let r = &self.r3;
        let mut out = [Vector::<D>::zeros(); 6];
        for (k, &(a, b)) in VOIGT.iter().enumerate() {
            for c in 0..D {
                let mut v = 0.0;
                for i in 0..3 {
                    for j in 0..3 {
                        let rij = r[a][i] * r[b][j];
                        if rij == 0.0 {
                            continue;
                        }
                        for l in 0..D {
                            v += rij * r[c][l] * g[voigt(i, j)][l];
                        }
                    }
                }
                out[k][c] = v;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane3(n: [f64; 3]) -> Plane<3> {
        Plane::new(&WallSpec {
            point: vec![0.0, 0.0, 0.0],
            normal: n.to_vec(),
            kind: "rigid".into(),
            friction: 0.0,
        })
        .expect("a normal with a direction")
    }

    #[test]
    fn reflections_are_involutions_and_match_the_matrix_form() {
        let pl = plane3([1.0, 2.0, -0.5]);
        let x = Vector::<3>::new(0.3, -0.7, 1.1);
        assert!((pl.reflect_point(&pl.reflect_point(&x)) - x).norm() < 1e-15);
        assert!((pl.distance(&pl.reflect_point(&x)) + pl.distance(&x)).abs() < 1e-15);
        let s = Sym3::new(1.0, 2.0, 3.0, 0.4, -0.5, 0.6);
        let back = pl.reflect_sym(&pl.reflect_sym(&s));
        for (a, b) in back.to_array().iter().zip(s.to_array()) {
            assert!((a - b).abs() < 1e-14);
        }
        // R S R keeps the invariants
        let r = pl.reflect_sym(&s);
        assert!((r.trace() - s.trace()).abs() < 1e-14);
        assert!((r.von_mises() - s.von_mises()).abs() < 1e-13);
        // a gradient of a tensor: involution too
        let g: [Vector<3>; 6] =
            core::array::from_fn(|k| Vector::<3>::new(k as f64, 1.0 - k as f64, 0.5 * k as f64));
        let gg = pl.reflect_tensor_gradient(&pl.reflect_tensor_gradient(&g));
        for k in 0..6 {
            assert!((gg[k] - g[k]).norm() < 1e-13);
        }
    }

    #[test]
    fn an_axis_plane_flips_the_normal_components_only() {
        let pl = plane3([1.0, 0.0, 0.0]);
        let s = pl.reflect_sym(&Sym3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0));
        assert_eq!(s.to_array(), [1.0, 2.0, 3.0, -4.0, -5.0, 6.0]);
        let v = pl.reflect(&Vector::<3>::new(1.0, 2.0, 3.0));
        assert_eq!(v, Vector::<3>::new(-1.0, 2.0, 3.0));
        // d s_xy / dx is even in x (both flip), d s_xy / dy is odd
        let mut g = [Vector::<3>::zeros(); 6];
        g[3] = Vector::<3>::new(1.0, 1.0, 1.0);
        let r = pl.reflect_tensor_gradient(&g);
        assert_eq!(r[3], Vector::<3>::new(1.0, -1.0, -1.0));
    }
}
