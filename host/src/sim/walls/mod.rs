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
//! the same ghosts. How they are made, numbered and bounded: `images.rs`.
//!
//! Under MPI (feature `mpi`) the mirrors sit after the other ranks' ghosts and image
//! those too, so an owned particle sees every mirror it would see in one process (a
//! mirror within reach of a particle images a particle within reach of it, which this
//! rank holds); `Both` refreshes the ranks' ghosts first, then the mirrors from them.

mod images;
mod plane;

pub use plane::Plane;

use super::Sim;
use crate::scene::WallSpec;
use gsph_core::halo::{Exchange, Fields, GhostWorkspace, Halo};
use gsph_core::math::{Sym3, Vector};
use gsph_core::state::System;

/// The planes of a scene and the mirror ghosts of the current neighbour lists.
#[derive(Clone, Debug, Default)]
pub struct Mirrors<const D: usize> {
    /// The planes.
    pub planes: Vec<Plane<D>>,
    /// Each ghost's source and plane, in ghost order (ghost `k` is particle `first + k`;
    /// the source of a corner image is an earlier ghost).
    pub map: Vec<(usize, usize)>,
    /// The first mirror: after the owned particles (and under MPI the other ranks'
    /// ghosts).
    pub first: usize,
    /// Neighbour-list reach at the last rebuild: a released ghost is put this far again
    /// behind its plane, out of every kernel's support.
    pub reach: f64,
    /// Particles found behind a plane after a step and put back (this rank's).
    pub crossings: u64,
    /// Kinetic energy turned into heat by wall friction, J (per unit area in 1D, per
    /// unit thickness in 2D; this rank's).
    pub friction_work: f64,
}

impl<const D: usize> Mirrors<D> {
    /// The planes of `walls`; the error names a wall whose normal has no direction.
    pub fn new(walls: &[WallSpec]) -> Result<Self, String> {
        let planes = walls
            .iter()
            .enumerate()
            .map(|(k, w)| {
                Plane::new(w).ok_or_else(|| {
                    format!("walls[{k}].normal: has no direction (zero or not finite)")
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(Mirrors {
            planes,
            ..Default::default()
        })
    }

    /// True without planes.
    pub fn is_empty(&self) -> bool {
        self.planes.is_empty()
    }
}

/// A scratch record's image through a wall: each field by its kind in the core's table
/// ([`gsph_core::scratch_records!`]: a vector reflected, a matrix `R M R`, a scalar or a
/// flag unchanged).
trait Mirror<const D: usize> {
    /// The image through `pl`.
    fn mirror(&self, pl: &plane::Plane<D>) -> Self;
}

/// A field's image by its kind.
macro_rules! mirror_field {
    (vector, $pl:expr, $v:expr) => {
        $pl.reflect(&$v)
    };
    (matrix, $pl:expr, $v:expr) => {
        $pl.reflect_matrix(&$v)
    };
    (scalar, $pl:expr, $v:expr) => {
        $v
    };
    (flag, $pl:expr, $v:expr) => {
        $v
    };
}

macro_rules! scratch_mirrors {
    (() $($rec:ident $rdoc:literal { $($f:ident: $ty:ty = $default:expr, $kind:ident, $doc:literal;)* })*) => {
        $(
            impl<const D: usize> Mirror<D> for gsph_core::state::$rec<D> {
                fn mirror(&self, pl: &plane::Plane<D>) -> Self {
                    gsph_core::state::$rec { $($f: mirror_field!($kind, pl, self.$f),)* }
                }
            }
        )*
    };
}
gsph_core::scratch_records!(scratch_mirrors {});

impl<const D: usize> Halo<D> for Mirrors<D> {
    fn refresh(&mut self, exchange: &Exchange, sys: &mut System<'_, D>, ws: GhostWorkspace<'_, D>) {
        let f = exchange.fields;
        for (k, &(o, w)) in self.map.iter().enumerate() {
            let g = self.first + k;
            let pl = &self.planes[w];
            if f.contains(Fields::X) {
                sys.x[g] = pl.reflect_point(&sys.x[o]);
                // tl's pairs see the reference positions: its mirrors carry theirs
                if !sys.xr.is_empty() {
                    sys.xr[g] = pl.reflect_point(&sys.xr[o]);
                }
                if pl.unilateral && !pressed(pl, sys, o) {
                    // released: out of reach, the particle sees a free surface
                    sys.x[g] -= pl.normal * (4.0 * self.reach);
                    if !sys.xr.is_empty() {
                        sys.xr[g] -= pl.normal * (4.0 * self.reach);
                    }
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
                ws.grad[g] = ws.grad[o].mirror(pl);
            }
            if f.contains(Fields::GRAD_STRESS) && !ws.grad_stress.is_empty() {
                ws.grad_stress[g] = pl.reflect_tensor_gradient(&ws.grad_stress[o]);
            }
            if f.contains(Fields::CORR) && !ws.corr.is_empty() {
                ws.corr[g] = ws.corr[o].mirror(pl);
            }
            if f.contains(Fields::HOURGLASS) && !ws.hg.is_empty() {
                ws.hg[g] = ws.hg[o].mirror(pl);
            }
        }
    }
}

/// The fields [`pressed`] reads of a mirror's source.
#[cfg(feature = "mpi")]
const PRESSED: Fields =
    Fields(Fields::V.0 | Fields::RHO.0 | Fields::P.0 | Fields::CL.0 | Fields::S.0);

/// The MPI ghosts, then the mirrors (feature `mpi`): an exchange that moves the ghosts
/// (`x`) also brings what a rigid wall's release test reads of them ([`PRESSED`]), so a
/// mirror of another rank's particle is released exactly when one process would release
/// it.
#[cfg(feature = "mpi")]
pub(crate) struct Both<'a, const D: usize> {
    /// The ranks' ghosts.
    pub dist: &'a mut crate::dist::Dist<D>,
    /// The walls' mirrors.
    pub mirrors: &'a mut Mirrors<D>,
}

#[cfg(feature = "mpi")]
impl<const D: usize> Halo<D> for Both<'_, D> {
    fn refresh(&mut self, exchange: &Exchange, sys: &mut System<'_, D>, ws: GhostWorkspace<'_, D>) {
        let mut wide = *exchange;
        if exchange.fields.contains(Fields::X) && self.mirrors.planes.iter().any(|p| p.unilateral) {
            wide.fields = wide.fields.with(PRESSED);
        }
        let GhostWorkspace {
            grad,
            grad_stress,
            corr,
            hg,
        } = ws;
        self.dist.refresh(
            &wide,
            sys,
            GhostWorkspace {
                grad: &mut *grad,
                grad_stress: &mut *grad_stress,
                corr: &mut *corr,
                hg: &mut *hg,
            },
        );
        self.mirrors.refresh(
            exchange,
            sys,
            GhostWorkspace {
                grad,
                grad_stress,
                corr,
                hg,
            },
        );
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

impl<const D: usize> Sim<D> {
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
impl<const D: usize> Sim<D> {
    /// Particles put back from behind a plane and the work of wall friction, summed over
    /// the MPI ranks (collective under MPI).
    pub fn wall_totals(&self) -> (u64, f64) {
        #[cfg(feature = "mpi")]
        if self.dist.is_some() {
            return (
                crate::dist::all_sum_u64(self.mirrors.crossings),
                crate::dist::all_sum_f64(self.mirrors.friction_work),
            );
        }
        (self.mirrors.crossings, self.mirrors.friction_work)
    }
}
