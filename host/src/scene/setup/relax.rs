//! Body-fitted layouts (`layout = "relaxed"`): the body's lattice relaxed against the
//! signed distance of its surface, so that the surface row follows the shape instead of a
//! staircase.
//!
//! The relaxation is SPHinXsys's level-set particle relaxation (Zhu, Zhang & Hu, CPC 258
//! (2021) 107521) in a plain form: each iteration moves every particle along the
//! "pressure" imbalance of a uniform kernel sum,
//!
//! ```text
//! a_i = - sum_j V grad_i W_ij - n_i M(|phi_i|),     x_i += beta h² a_i,
//! ```
//!
//! where the second term stands for the neighbours the surface cuts off: for a surface
//! plane at distance `phi` with outward normal `n`, the kernel gradient integrated over
//! the outside half-space is exactly `n M(phi)` with `M` the kernel's integral over that
//! plane (divergence theorem), so a uniform layout half a spacing inside a flat surface is
//! at rest. A particle that moves closer than half a spacing to the surface is put back
//! onto the surface row (`phi = -dx/2`). Nothing else changes: the particles keep their
//! count, mass and order. Each particle's sum runs over its neighbours in the cell grid's
//! order, whatever the thread count, so the layout is the same on any number of threads
//! and ranks (each rank builds the scene's particles whole).
//!
//! Why this and not a Lloyd (CVT) iteration: it needs the signed distance only, never a
//! clipped Voronoi cell (which an STL surface in 3D would make costly), and it is the form
//! the peer whose elastic plate keeps its energy (SPHinXsys) relaxes its bodies with.

use super::sdf::{Piece, Surface};
use crate::neighbors::Grid;
use gsph_core::kernel::Kernel;
use gsph_core::math::Vector;
use gsph_core::neighbors::Periodic;
use rayon::prelude::*;

/// Iterations when a body does not set `relax_iterations`.
pub const DEFAULT_ITERATIONS: usize = 400;
/// The relaxation's kernel and its smoothing length over the spacing (SPHinXsys's).
const KERNEL: Kernel = Kernel::WendlandC2;
const H_OVER_DX: f64 = 1.3;
/// Step factor `beta` of `x += beta h² a`, and the largest move of one iteration, in
/// spacings.
const BETA: f64 = 0.4;
const MAX_MOVE: f64 = 0.1;

/// What a relaxation did (lengths in spacings).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Report {
    /// Surface roughness of the lattice before and of the layout after: the rms of
    /// `phi/dx + 1/2` over the particles within one spacing of the surface (0 for a surface
    /// row exactly half a spacing inside; a staircase's is about 0.29).
    pub roughness: [f64; 2],
    /// The rms imbalance `h |a_i|` of the first and the last iteration.
    pub residual: [f64; 2],
    /// The nearest pair after, in spacings.
    pub nearest: f64,
}

/// Relaxes the positions `x` (the first `dim` components; `dim` 2 or 3) of one body of
/// spacing `dx` against `surface` for `iterations` iterations; `progress(k, residual)`
/// after each.
pub(super) fn relax(
    dim: usize,
    x: &mut [[f64; 3]],
    dx: f64,
    surface: &Surface,
    iterations: usize,
    progress: &mut dyn FnMut(usize, f64),
) -> Report {
    match dim {
        2 => relax_d::<2>(x, dx, surface, iterations, progress),
        _ => relax_d::<3>(x, dx, surface, iterations, progress),
    }
}

/// How far from the surface the relaxation reads the signed distance (the kernel's
/// reach), m.
pub(super) fn reach(dx: f64) -> f64 {
    KERNEL.support() * H_OVER_DX * dx
}

fn pad<const D: usize>(v: &Vector<D>) -> [f64; 3] {
    let mut o = [0.0; 3];
    for a in 0..D {
        o[a] = v[a];
    }
    o
}

/// The rms of `phi/dx + 1/2` over the particles within one spacing of the surface.
pub(super) fn roughness(x: &[[f64; 3]], dx: f64, surface: &Surface) -> f64 {
    let (mut sum, mut count) = (0.0, 0usize);
    for p in x {
        let phi = surface.phi(p) / dx;
        if phi > -1.0 {
            sum += (phi + 0.5) * (phi + 0.5);
            count += 1;
        }
    }
    if count == 0 {
        0.0
    } else {
        (sum / count as f64).sqrt()
    }
}

/// The ghosts of a particle at `x`: the neighbours the surface cuts off, as mirror images
/// of `x`. A primitive surface reflects `x` across every set of the pieces within reach
/// (one piece: across a face; two or three: around an edge or a corner, the method of
/// images), keeping an image that lies outside exactly the pieces it was reflected across
/// (and outside the solid), so that the images tile the outside once near convex edges and
/// corners. A mesh's pieces are the planes of its facets within reach (at most three; see
/// `MeshDistance::planes_near`).
fn ghosts_of<const D: usize>(
    xi: &Vector<D>,
    surface: &Surface,
    pieces: &[Piece],
    reach: f64,
) -> Vec<Vector<D>> {
    let p = pad(xi);
    let unpad = |g: [f64; 3]| Vector::<D>::from_fn(|a, _| g[a]);
    let near: Vec<Piece> = surface
        .pieces_near(&p, pieces)
        .into_iter()
        .filter(|k| k.phi(&p) > -reach)
        .collect();
    let mut out = Vec::new();
    for set in 1u32..(1 << near.len()) {
        let mut g = p;
        for (k, piece) in near.iter().enumerate() {
            if set & (1 << k) != 0 {
                g = piece.reflect(&g);
            }
        }
        // outside exactly the pieces reflected across, and outside the solid (at a
        // concave edge an image across one face may land inside the other)
        let exact = near
            .iter()
            .enumerate()
            .all(|(k, piece)| (piece.phi(&g) > 0.0) == (set & (1 << k) != 0))
            && surface.phi(&g) > 0.0;
        if exact {
            out.push(unpad(g));
        }
    }
    out
}

fn relax_d<const D: usize>(
    x: &mut [[f64; 3]],
    dx: f64,
    surface: &Surface,
    iterations: usize,
    progress: &mut dyn FnMut(usize, f64),
) -> Report {
    let h = H_OVER_DX * dx;
    let reach = KERNEL.support() * h;
    let vol = dx.powi(D as i32);
    let eps = 1e-4 * dx;
    let pieces = surface.pieces();
    let before = roughness(x, dx, surface);
    let mut pos: Vec<Vector<D>> = x.iter().map(|p| Vector::from_fn(|a, _| p[a])).collect();
    let n = pos.len();
    let mut residual = [0.0; 2];
    for k in 0..iterations {
        let grid = Grid::new(&pos, reach, &Periodic::none());
        let ghosts: Vec<Vector<D>> = pos
            .par_iter()
            .map(|xi| ghosts_of::<D>(xi, surface, &pieces, reach))
            .flatten()
            .collect();
        let images = (!ghosts.is_empty()).then(|| Grid::new(&ghosts, reach, &Periodic::none()));
        let moves: Vec<(Vector<D>, f64)> = (0..n)
            .into_par_iter()
            .map(|i| {
                let xi = pos[i];
                let mut a = Vector::<D>::zeros();
                let mut add = |rij: Vector<D>| {
                    let r = rij.norm();
                    if r > 0.0 && r < reach {
                        a -= KERNEL.gradient::<D>(&rij, r, h) * vol;
                    }
                };
                grid.for_candidates(&xi, |c| {
                    if grid.sorted[c] as usize != i {
                        add(xi - grid.xs[c]);
                    }
                });
                if let Some(g) = &images {
                    g.for_candidates(&xi, |c| add(xi - g.xs[c]));
                }
                let mut step = a * (BETA * h * h);
                let len = step.norm();
                if len > MAX_MOVE * dx {
                    step *= MAX_MOVE * dx / len;
                }
                (step, h * a.norm())
            })
            .collect();
        pos.par_iter_mut()
            .zip(moves.par_iter())
            .for_each(|(xi, (step, _))| {
                let mut y = *xi + step;
                let p = pad(&y);
                let phi = surface.phi(&p);
                if phi > -0.5 * dx {
                    let nrm = surface.normal(&p, D, eps);
                    for c in 0..D {
                        y[c] -= nrm[c] * (phi + 0.5 * dx);
                    }
                }
                *xi = y;
            });
        let rms = (moves.iter().map(|m| m.1 * m.1).sum::<f64>() / n.max(1) as f64).sqrt();
        if k == 0 {
            residual[0] = rms;
        }
        residual[1] = rms;
        progress(k + 1, rms);
    }
    for (p, q) in x.iter_mut().zip(&pos) {
        *p = pad(q);
    }
    let nearest = crate::neighbors::nearest_distances(&pos, 2.0 * dx)
        .into_iter()
        .fold(f64::INFINITY, f64::min)
        / dx;
    Report {
        roughness: [before, roughness(x, dx, surface)],
        residual,
        nearest,
    }
}
