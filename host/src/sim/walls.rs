//! Rigid walls and symmetry planes (`[[walls]]`) the way the Godunov schemes see a
//! boundary: every particle within the neighbour-list reach of a plane has a *mirror*
//! particle, its reflection through the plane, placed after the owned particles as a ghost
//! (the slots the MPI halo uses, [`gsph_core::halo`]). Before every pair pass that reads
//! a neighbour field, [`Mirrors`] refreshes the ghosts from their owners, reflected:
//! position and velocity through the plane, the stress deviator as `R S R` and the
//! gradients and kernel corrections likewise, with `R = I - 2 n nᵀ`. A particle and its
//! mirror then meet in a Riemann problem whose left and right states are reflections of
//! each other, so the contact velocity normal to the wall is exactly zero: the particle
//! sees a rigid, frictionless wall (in 1D an impact on the wall at v is the symmetric
//! impact of two bars at ±v, stress ρ c_l v). A symmetry plane is the same mirror: the
//! half it stands for is the reflection of the half simulated.
//!
//! A rigid wall pushes but does not pull: when the acoustic estimate of the contact
//! traction, `-σ_nn - ρ c_l v_n`, is tensile (the particle leaves the wall, or is in
//! tension across it), its mirror is put out of reach for that step, so the particle
//! sees a free surface there and a rebounding body separates.
//!
//! Friction (rigid walls with `friction = μ > 0`): after each step a particle of the
//! contact layer (within half its spacing of the plane) under compression normal to the
//! wall has its tangential velocity reduced by the Coulomb impulse `μ |σ_nn| A dt / m`
//! (at most to rest), with `A = (m/ρ)^((D-1)/D)` its face area; the kinetic energy taken
//! is added to its internal energy (frictional heating), so total energy is conserved.
//!
//! A particle that still ends a step behind a plane (it should not: the mirror pressure
//! stops it) is reflected back and its normal velocity reversed; such events are counted
//! (`wall_crossings` in summary.json).
//!
//! Ghosts are a function of the owned particles' positions at the last neighbour-list
//! rebuild (`build_x`), so a checkpoint holds owned particles only and a restart recreates
//! the same ghosts.

use super::Sim;
use crate::scene::{walls::unit, WallSpec};
use gsph_core::halo::{Exchange, Fields, GhostWorkspace, Halo};
use gsph_core::math::{Matrix, Sym3, Vector};
use gsph_core::state::System;

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
    fn new(w: &WallSpec) -> Self {
        let n = unit(&w.normal);
        let normal = Vector::<D>::from_fn(|k, _| n[k]);
        let mut r3 = [[0.0; 3]; 3];
        for (a, row) in r3.iter_mut().enumerate() {
            for (b, x) in row.iter_mut().enumerate() {
                let na = if a < D { n[a] } else { 0.0 };
                let nb = if b < D { n[b] } else { 0.0 };
                *x = f64::from(u8::from(a == b)) - 2.0 * na * nb;
            }
        }
        Plane {
            point: Vector::<D>::from_fn(|k, _| w.point[k]),
            normal,
            friction: w.friction,
            unilateral: w.kind == "rigid",
            r3,
        }
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
    fn reflect_matrix(&self, m: &Matrix<D>) -> Matrix<D> {
        let r = Matrix::<D>::from_fn(|a, b| self.r3[a][b]);
        r * m * r
    }

    /// `R S R` of a symmetric 3x3 tensor.
    fn reflect_sym(&self, s: &Sym3) -> Sym3 {
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
    fn reflect_tensor_gradient(&self, g: &[Vector<D>; 6]) -> [Vector<D>; 6] {
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

/// The planes of a scene and the mirror ghosts of the current neighbour lists.
#[derive(Clone, Debug, Default)]
pub struct Mirrors<const D: usize> {
    /// The planes.
    pub planes: Vec<Plane<D>>,
    /// Each ghost's source and plane, in ghost order (ghost `k` is particle `owned + k`;
    /// the source of a corner image is an earlier ghost).
    pub map: Vec<(usize, usize)>,
    /// The owned particles (ghosts start here).
    pub owned: usize,
    /// Neighbour-list reach at the last rebuild: a released ghost is put this far again
    /// behind its plane, out of every kernel's support.
    pub reach: f64,
    /// Particles found behind a plane after a step and put back.
    pub crossings: u64,
    /// Kinetic energy turned into heat by wall friction, J (per unit area in 1D, per
    /// unit thickness in 2D).
    pub friction_work: f64,
}

impl<const D: usize> Mirrors<D> {
    /// The planes of `walls`.
    pub fn new(walls: &[WallSpec]) -> Self {
        Mirrors {
            planes: walls.iter().map(Plane::new).collect(),
            ..Default::default()
        }
    }

    /// True without planes.
    pub fn is_empty(&self) -> bool {
        self.planes.is_empty()
    }
}

impl<const D: usize> Halo<D> for Mirrors<D> {
    fn refresh(&mut self, exchange: &Exchange, sys: &mut System<'_, D>, ws: GhostWorkspace<'_, D>) {
        let f = exchange.fields;
        for (k, &(o, w)) in self.map.iter().enumerate() {
            let g = self.owned + k;
            let pl = &self.planes[w];
            if f.contains(Fields::X) {
                sys.x[g] = pl.reflect_point(&sys.x[o]);
                if pl.unilateral && !pressed(pl, sys, o) {
                    // released: out of reach, the particle sees a free surface
                    sys.x[g] -= pl.normal * (4.0 * self.reach);
                }
            }
            if f.contains(Fields::H) {
                sys.h[g] = sys.h[o];
            }
            if f.contains(Fields::V) {
                sys.v[g] = pl.reflect(&sys.v[o]);
            }
            if f.contains(Fields::RHO) {
                sys.rho[g] = sys.rho[o];
            }
            if f.contains(Fields::P) {
                sys.p[g] = sys.p[o];
            }
            if f.contains(Fields::C) {
                sys.c[g] = sys.c[o];
            }
            if f.contains(Fields::CL) {
                sys.cl[g] = sys.cl[o];
            }
            if f.contains(Fields::S) && !sys.s.is_empty() {
                sys.s[g] = pl.reflect_sym(&sys.s[o]);
            }
            if f.contains(Fields::DAMAGE) && !sys.damage.is_empty() {
                sys.damage[g] = sys.damage[o];
            }
            if f.contains(Fields::GRAD) && !ws.grad.is_empty() {
                let s = ws.grad[o];
                let mut t = s;
                t.rho = pl.reflect(&s.rho);
                t.p = pl.reflect(&s.p);
                t.v = pl.reflect_matrix(&s.v);
                t.cl = pl.reflect(&s.cl);
                t.ct = pl.reflect(&s.ct);
                ws.grad[g] = t;
            }
            if f.contains(Fields::GRAD_STRESS) && !ws.grad_stress.is_empty() {
                ws.grad_stress[g] = pl.reflect_tensor_gradient(&ws.grad_stress[o]);
            }
            if f.contains(Fields::CORR) && !ws.corr.is_empty() {
                let mut c = ws.corr[o];
                c.l_inv = pl.reflect_matrix(&c.l_inv);
                ws.corr[g] = c;
            }
        }
    }
}

/// True when particle `o` pushes against the plane: the acoustic estimate of the normal
/// traction its mirror contact carries, `-sigma_nn - rho c_l v_n` (compression positive,
/// `v_n` the velocity along the normal), is not tensile.
fn pressed<const D: usize>(pl: &Plane<D>, sys: &System<'_, D>, o: usize) -> bool {
    let sigma_nn = normal_stress(sys.p[o], sys.s.get(o), &pl.normal);
    -sigma_nn - sys.rho[o] * sys.cl[o] * sys.v[o].dot(&pl.normal) >= 0.0
}

/// The normal Cauchy stress `n.(-p I + S).n` (tension positive; `S` absent: fluid).
fn normal_stress<const D: usize>(p: f64, s: Option<&Sym3>, n: &Vector<D>) -> f64 {
    let snn = s.map_or(0.0, |s| {
        let mut v = 0.0;
        for a in 0..D {
            for b in 0..D {
                v += n[a] * s.get(a, b) * n[b];
            }
        }
        v
    });
    -p + snn
}

/// Appends a copy of element `i` when `v` holds one element per particle so far (`n`).
fn dup<T: Copy>(v: &mut Vec<T>, i: usize, n: usize) {
    if v.len() == n && i < n {
        v.push(v[i]);
    }
}

/// Cuts `v` to `n` elements when it holds more.
fn cut<T>(v: &mut Vec<T>, n: usize) {
    v.truncate(n);
}

impl<const D: usize> Sim<D> {
    /// Removes the mirror ghosts (every per-particle array back to the owned particles).
    pub(crate) fn drop_mirrors(&mut self) {
        if self.mirrors.is_empty() || self.mirrors.map.is_empty() {
            return;
        }
        let n = self.mirrors.owned;
        cut(&mut self.ids, n);
        cut(&mut self.x, n);
        cut(&mut self.v, n);
        cut(&mut self.m, n);
        cut(&mut self.mat, n);
        cut(&mut self.rho, n);
        cut(&mut self.e, n);
        cut(&mut self.p, n);
        cut(&mut self.c, n);
        cut(&mut self.cl, n);
        cut(&mut self.h, n);
        cut(&mut self.s, n);
        cut(&mut self.eps_p, n);
        cut(&mut self.damage, n);
        cut(&mut self.temp, n);
        cut(&mut self.sums, n);
        cut(&mut self.grad, n);
        cut(&mut self.grad_stress, n);
        cut(&mut self.corr, n);
        cut(&mut self.av, n);
        cut(&mut self.art, n);
        cut(&mut self.aux, n);
        cut(&mut self.build_x, n);
        cut(&mut self.build_h, n);
        self.mirrors.map.clear();
        self.owned = n;
    }

    /// Appends the mirror of every owned particle within the neighbour-list reach of a
    /// plane at the positions of the rebuild (`build_x`, `build_h`, set for the owned
    /// particles); ids after the largest owned one.
    pub(crate) fn add_mirrors(&mut self) {
        if self.mirrors.is_empty() {
            return;
        }
        let owned = self.len();
        self.mirrors.owned = owned;
        self.owned = owned;
        let hmax = self.build_h.iter().cloned().fold(0.0, f64::max);
        let reach = self.kernel.support() * (1.0 + self.skin) * hmax;
        self.mirrors.reach = reach;
        let mut next_id = self.ids.iter().max().map_or(0, |&m| m + 1);
        // plane by plane over the particles so far: a particle near two planes also gets
        // the mirror of its mirror (the corner image a whole model would hold)
        for w in 0..self.mirrors.planes.len() {
            for i in 0..self.len() {
                let pl = &self.mirrors.planes[w];
                if pl.distance(&self.build_x[i]) >= reach {
                    continue;
                }
                let (bx, bh) = (pl.reflect_point(&self.build_x[i]), self.build_h[i]);
                let (x, v) = (pl.reflect_point(&self.x[i]), pl.reflect(&self.v[i]));
                let s = self.s.get(i).map(|s| pl.reflect_sym(s));
                let n = self.len();
                self.ids.push(next_id);
                next_id += 1;
                self.x.push(x);
                self.v.push(v);
                dup(&mut self.m, i, n);
                dup(&mut self.mat, i, n);
                dup(&mut self.rho, i, n);
                dup(&mut self.e, i, n);
                dup(&mut self.p, i, n);
                dup(&mut self.c, i, n);
                dup(&mut self.cl, i, n);
                dup(&mut self.h, i, n);
                if let Some(s) = s {
                    self.s.push(s);
                }
                dup(&mut self.eps_p, i, n);
                dup(&mut self.damage, i, n);
                dup(&mut self.temp, i, n);
                dup(&mut self.sums, i, n);
                dup(&mut self.grad, i, n);
                dup(&mut self.grad_stress, i, n);
                dup(&mut self.corr, i, n);
                dup(&mut self.av, i, n);
                dup(&mut self.art, i, n);
                dup(&mut self.aux, i, n);
                self.build_x.push(bx);
                self.build_h.push(bh);
                self.mirrors.map.push((i, w));
            }
        }
    }

    /// After a step: puts back particles found behind a plane and applies wall friction.
    pub(crate) fn enforce_walls(&mut self, dt: f64) {
        if self.mirrors.is_empty() {
            return;
        }
        let owned = self.owned;
        for w in 0..self.mirrors.planes.len() {
            let pl = self.mirrors.planes[w].clone();
            for i in 0..owned {
                let d = pl.distance(&self.x[i]);
                if d < 0.0 {
                    self.x[i] = pl.reflect_point(&self.x[i]);
                    self.v[i] = pl.reflect(&self.v[i]);
                    self.mirrors.crossings += 1;
                }
                if pl.friction == 0.0 {
                    continue;
                }
                let vol = self.m[i] / self.rho[i];
                let spacing = vol.powf(1.0 / D as f64);
                if pl.distance(&self.x[i]) >= 0.5 * spacing {
                    continue;
                }
                let n = pl.normal;
                let sigma_nn = normal_stress(self.p[i], self.s.get(i), &n);
                if sigma_nn >= 0.0 {
                    continue; // not pressed against the wall
                }
                let area = vol.powf((D as f64 - 1.0) / D as f64);
                let vt = self.v[i] - n * self.v[i].dot(&n);
                let speed = vt.norm();
                if speed == 0.0 {
                    continue;
                }
                let dv = (pl.friction * -sigma_nn * area * dt / self.m[i]).min(speed);
                let before = 0.5 * self.m[i] * self.v[i].norm_squared();
                self.v[i] -= vt * (dv / speed);
                let taken = before - 0.5 * self.m[i] * self.v[i].norm_squared();
                self.e[i] += taken / self.m[i];
                self.mirrors.friction_work += taken;
            }
        }
    }

    /// Refuses particles that start behind a plane (names the lowest such id).
    pub(crate) fn check_walls(&self) -> Result<(), String> {
        for (k, pl) in self.mirrors.planes.iter().enumerate() {
            if let Some(i) = (0..self.owned)
                .filter(|&i| pl.distance(&self.x[i]) < 0.0)
                .min_by_key(|&i| self.ids[i])
            {
                return Err(format!(
                    "walls[{k}]: particle {} starts behind the plane (distance {:e} m on the wrong side)",
                    self.ids[i],
                    -pl.distance(&self.x[i])
                ));
            }
        }
        Ok(())
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
