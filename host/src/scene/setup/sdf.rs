//! Signed distances to the bodies' surfaces (negative inside, in m), for the relaxed layout
//! ([`super::relax`]): exact for the primitive shapes, the nearest facet for an STL surface.

use super::stl::Mesh;
use crate::scene::spec::ShapeSpec;

/// The surface of a body's shape.
#[derive(Debug, Clone)]
pub(super) enum Surface {
    /// Axis-aligned box over the first `dim` axes.
    Box {
        lo: [f64; 3],
        hi: [f64; 3],
        dim: usize,
    },
    /// Disc (2D) or ball (3D).
    Ball { c: [f64; 3], r: f64, dim: usize },
    /// Annulus (2D).
    Annulus { c: [f64; 3], ri: f64, ro: f64 },
    /// Circular cylinder along `axis`; `quarter`: cut by the planes through `base` normal
    /// to the two transverse axes (a quarter model's symmetry planes read as surfaces: the
    /// relaxation's surface term there is the mirror image's).
    Cylinder {
        base: [f64; 3],
        axis: usize,
        r: f64,
        len: f64,
        quarter: bool,
    },
    /// A closed triangulated surface.
    Mesh(MeshDistance),
}

fn pad(v: &[f64]) -> [f64; 3] {
    let mut o = [0.0; 3];
    o[..v.len().min(3)].copy_from_slice(&v[..v.len().min(3)]);
    o
}

fn len(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Signed distance to an axis-aligned box of half sizes `half` about the origin, over
/// the first `dim` axes of `q` (the point relative to the centre).
fn box_distance(q: [f64; 3], half: [f64; 3], dim: usize) -> f64 {
    let mut out2 = 0.0;
    let mut inside = f64::NEG_INFINITY;
    for a in 0..dim {
        let d = q[a].abs() - half[a];
        out2 += d.max(0.0) * d.max(0.0);
        inside = inside.max(d);
    }
    out2.sqrt() + inside.min(0.0)
}

impl Surface {
    /// The surface of `shape` in `dim` dimensions (`None` for a particle file and a 1D
    /// segment, whose layouts are never relaxed), with the mesh of an STL body.
    pub(super) fn of(
        shape: &ShapeSpec,
        dim: usize,
        mesh: Option<&Mesh>,
        reach: f64,
    ) -> Option<Self> {
        Some(match shape {
            ShapeSpec::Box { min, max } => Surface::Box {
                lo: pad(min),
                hi: pad(max),
                dim,
            },
            ShapeSpec::Disc { center, radius } => Surface::Ball {
                c: pad(center),
                r: *radius,
                dim,
            },
            ShapeSpec::Annulus {
                center,
                r_inner,
                r_outer,
            } => Surface::Annulus {
                c: pad(center),
                ri: *r_inner,
                ro: *r_outer,
            },
            ShapeSpec::Cylinder {
                base,
                axis,
                radius,
                length,
                quarter,
            } => Surface::Cylinder {
                base: pad(base),
                axis: *axis,
                r: *radius,
                len: *length,
                quarter: *quarter,
            },
            ShapeSpec::Stl { .. } => Surface::Mesh(MeshDistance::new(mesh?, reach)),
            ShapeSpec::Segment { .. } | ShapeSpec::Particles { .. } => return None,
        })
    }

    /// Signed distance of `x` to the surface, m (negative inside). For a mesh, points
    /// farther than its reach from every facet read as deep inside (`-reach`).
    pub(super) fn phi(&self, x: &[f64; 3]) -> f64 {
        match self {
            Surface::Box { lo, hi, dim } => {
                let c = [
                    (lo[0] + hi[0]) / 2.0,
                    (lo[1] + hi[1]) / 2.0,
                    (lo[2] + hi[2]) / 2.0,
                ];
                let half = [
                    (hi[0] - lo[0]) / 2.0,
                    (hi[1] - lo[1]) / 2.0,
                    (hi[2] - lo[2]) / 2.0,
                ];
                box_distance(sub(*x, c), half, *dim)
            }
            Surface::Ball { c, r, dim } => {
                let mut d = sub(*x, *c);
                d[*dim..].iter_mut().for_each(|v| *v = 0.0);
                len(d) - r
            }
            Surface::Annulus { c, ri, ro } => {
                let rr = ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2)).sqrt();
                (rr - ro).max(ri - rr)
            }
            Surface::Cylinder {
                base,
                axis,
                r,
                len: l,
                quarter,
            } => {
                let (t1, t2) = ((axis + 1) % 3, (axis + 2) % 3);
                let (u, v) = (x[t1] - base[t1], x[t2] - base[t2]);
                let radial = (u * u + v * v).sqrt() - r;
                let along = (x[*axis] - base[*axis] - l / 2.0).abs() - l / 2.0;
                // the distance in the (radial, axial) half-plane
                let mut d = (radial.max(0.0).powi(2) + along.max(0.0).powi(2)).sqrt()
                    + radial.max(along).min(0.0);
                if *quarter {
                    d = d.max(-u).max(-v);
                }
                d
            }
            Surface::Mesh(m) => m.phi(x),
        }
    }

    /// The outward unit normal at `x` (the gradient of [`Surface::phi`] by central
    /// differences `eps` wide over the first `dim` axes; zero where it vanishes).
    pub(super) fn normal(&self, x: &[f64; 3], dim: usize, eps: f64) -> [f64; 3] {
        let mut g = [0.0; 3];
        for (a, ga) in g.iter_mut().enumerate().take(dim) {
            let (mut p, mut m) = (*x, *x);
            p[a] += eps;
            m[a] -= eps;
            *ga = (self.phi(&p) - self.phi(&m)) / (2.0 * eps);
        }
        let n = len(g);
        if n > 0.0 {
            g.map(|v| v / n)
        } else {
            g
        }
    }
}

/// Distances to a mesh: its facets binned on a grid of cells `reach` wide, each facet in
/// every cell its bounding box, grown by `reach`, touches.
#[derive(Debug, Clone)]
pub(super) struct MeshDistance {
    tris: Vec<[[f64; 3]; 3]>,
    normals: Vec<[f64; 3]>,
    lo: [f64; 3],
    cell: f64,
    n: [usize; 3],
    start: Vec<u32>,
    items: Vec<u32>,
    reach: f64,
}

impl MeshDistance {
    fn new(mesh: &Mesh, reach: f64) -> Self {
        let lo = mesh.lo.map(|v| v - 2.0 * reach);
        let hi = mesh.hi.map(|v| v + 2.0 * reach);
        let mut cell = reach;
        // at most about 2^24 cells
        let count = |c: f64| -> [usize; 3] {
            [0, 1, 2].map(|a| (((hi[a] - lo[a]) / c).ceil() as usize).max(1))
        };
        while count(cell).iter().map(|&k| k as f64).product::<f64>() > (1u64 << 24) as f64 {
            cell *= 2.0;
        }
        let n = count(cell);
        let at = |a: usize, v: f64| (((v - lo[a]) / cell).floor().max(0.0) as usize).min(n[a] - 1);
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (k, t) in mesh.tris.iter().enumerate() {
            let mut c0 = [0usize; 3];
            let mut c1 = [0usize; 3];
            for a in 0..3 {
                let mn = t[0][a].min(t[1][a]).min(t[2][a]) - reach;
                let mx = t[0][a].max(t[1][a]).max(t[2][a]) + reach;
                c0[a] = at(a, mn);
                c1[a] = at(a, mx);
            }
            for z in c0[2]..=c1[2] {
                for y in c0[1]..=c1[1] {
                    for x in c0[0]..=c1[0] {
                        pairs.push((((z * n[1] + y) * n[0] + x) as u32, k as u32));
                    }
                }
            }
        }
        pairs.sort_unstable();
        let mut start = vec![0u32; n[0] * n[1] * n[2] + 1];
        for &(c, _) in &pairs {
            start[c as usize + 1] += 1;
        }
        for c in 0..n[0] * n[1] * n[2] {
            start[c + 1] += start[c];
        }
        let normals = mesh
            .tris
            .iter()
            .map(|t| {
                let nn = cross(sub(t[1], t[0]), sub(t[2], t[0]));
                let l = len(nn);
                if l > 0.0 {
                    nn.map(|v| v / l)
                } else {
                    nn
                }
            })
            .collect();
        MeshDistance {
            tris: mesh.tris.clone(),
            normals,
            lo,
            cell,
            n,
            start,
            items: pairs.into_iter().map(|p| p.1).collect(),
            reach,
        }
    }

    /// The facets within `reach` of `x`, as at most three planes (`Piece::Plane`), nearest
    /// first: facets whose normals lie within 45 degrees of a nearer one's count as that
    /// one (a curved surface's tessellation reads as one smooth piece; a polyhedron's edges
    /// and corners as their faces).
    fn planes_near(&self, x: &[f64; 3]) -> Vec<Piece> {
        let Some(flat) = self.cell_of(x) else {
            return Vec::new();
        };
        let mut near: Vec<(f64, u32)> = self.items
            [self.start[flat] as usize..self.start[flat + 1] as usize]
            .iter()
            .map(|&t| {
                (
                    len(sub(*x, closest_on_triangle(x, &self.tris[t as usize]))),
                    t,
                )
            })
            .filter(|(d, _)| *d < self.reach)
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let cos = 45f64.to_radians().cos();
        let mut out: Vec<[f64; 3]> = Vec::new();
        let mut pieces = Vec::new();
        for (_, t) in near {
            let n = self.normals[t as usize];
            if len(n) == 0.0 || out.iter().any(|m| dot(*m, n) > cos) {
                continue;
            }
            out.push(n);
            pieces.push(Piece::Plane {
                n,
                o: dot(n, self.tris[t as usize][0]),
            });
            if pieces.len() == 3 {
                break;
            }
        }
        pieces
    }

    fn cell_of(&self, x: &[f64; 3]) -> Option<usize> {
        let mut c = [0usize; 3];
        for a in 0..3 {
            let k = ((x[a] - self.lo[a]) / self.cell).floor();
            if !(k >= 0.0 && (k as usize) < self.n[a]) {
                return None;
            }
            c[a] = k as usize;
        }
        Some((c[2] * self.n[1] + c[1]) * self.n[0] + c[0])
    }

    /// Signed distance: to the nearest facet within `reach`, its sign that of the offset
    /// along that facet's outward normal (of the facets equally near, the one the offset is
    /// most nearly normal to); `-reach` (deep inside) where no facet is that near.
    fn phi(&self, x: &[f64; 3]) -> f64 {
        let Some(flat) = self.cell_of(x) else {
            // outside the grid: far outside the surface
            return self.reach;
        };
        let (mut best, mut sign, mut along) = (f64::INFINITY, -1.0, 0.0);
        for &t in &self.items[self.start[flat] as usize..self.start[flat + 1] as usize] {
            let p = closest_on_triangle(x, &self.tris[t as usize]);
            let off = sub(*x, p);
            let d = len(off);
            let a = if d > 0.0 {
                dot(off, self.normals[t as usize]) / d
            } else {
                0.0
            };
            let nearer = d < best * (1.0 - 1e-12);
            let tie = !nearer && d <= best * (1.0 + 1e-12) && a.abs() > along;
            if nearer || tie {
                best = d;
                along = a.abs();
                sign = if a > 0.0 { 1.0 } else { -1.0 };
            }
        }
        if best > self.reach {
            -self.reach
        } else {
            sign * best
        }
    }
}

/// `a + t d`.
fn along(a: [f64; 3], d: [f64; 3], t: f64) -> [f64; 3] {
    [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]]
}

/// The point of triangle `t` nearest to `p` (Ericson, Real-Time Collision Detection §5.1.5).
fn closest_on_triangle(p: &[f64; 3], t: &[[f64; 3]; 3]) -> [f64; 3] {
    let (a, b, c) = (t[0], t[1], t[2]);
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(*p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(*p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return along(a, ab, d1 / (d1 - d3));
    }
    let cp = sub(*p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return along(a, ac, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    [
        a[0] + ab[0] * v + ac[0] * w,
        a[1] + ab[1] * v + ac[1] * w,
        a[2] + ab[2] * v + ac[2] * w,
    ]
}

/// One smooth piece of a primitive surface, whose solid is the intersection of its pieces'
/// insides: its own signed distance and the mirror image across it (the relaxation's
/// ghosts, composed across the pieces that meet at an edge or corner).
#[derive(Debug, Clone, Copy)]
pub(super) enum Piece {
    /// `n·x <= o` inside (`n` a unit vector).
    Plane { n: [f64; 3], o: f64 },
    /// Inside (`outside = false`: `|x - c| <= r`) or outside (`outside = true`) a circle
    /// (dim 2), sphere (dim 3) or, with `axis`, a cylinder about `c` along that axis.
    Round {
        c: [f64; 3],
        r: f64,
        axis: Option<usize>,
        dim: usize,
        outside: bool,
    },
}

impl Piece {
    /// The offset from the centre (or axis) and its length.
    fn radial(c: &[f64; 3], axis: Option<usize>, dim: usize, x: &[f64; 3]) -> ([f64; 3], f64) {
        let mut d = sub(*x, *c);
        d[dim..].iter_mut().for_each(|v| *v = 0.0);
        if let Some(a) = axis {
            d[a] = 0.0;
        }
        (d, len(d))
    }

    /// Signed distance (negative inside the piece).
    pub(super) fn phi(&self, x: &[f64; 3]) -> f64 {
        match *self {
            Piece::Plane { n, o } => dot(n, *x) - o,
            Piece::Round {
                c,
                r,
                axis,
                dim,
                outside,
            } => {
                let (_, rho) = Piece::radial(&c, axis, dim, x);
                if outside {
                    r - rho
                } else {
                    rho - r
                }
            }
        }
    }

    /// The mirror image of `x` across the piece.
    pub(super) fn reflect(&self, x: &[f64; 3]) -> [f64; 3] {
        match *self {
            Piece::Plane { n, .. } => {
                let phi = self.phi(x);
                [
                    x[0] - 2.0 * phi * n[0],
                    x[1] - 2.0 * phi * n[1],
                    x[2] - 2.0 * phi * n[2],
                ]
            }
            Piece::Round {
                c, r, axis, dim, ..
            } => {
                let (d, rho) = Piece::radial(&c, axis, dim, x);
                if rho == 0.0 {
                    return *x;
                }
                let f = (2.0 * r - rho) / rho - 1.0;
                [x[0] + f * d[0], x[1] + f * d[1], x[2] + f * d[2]]
            }
        }
    }
}

impl Surface {
    /// The pieces near `x`: a primitive surface's own, a mesh's facets within reach of `x`
    /// as planes ([`MeshDistance::planes_near`]).
    pub(super) fn pieces_near(&self, x: &[f64; 3], all: &[Piece]) -> Vec<Piece> {
        match self {
            Surface::Mesh(m) => m.planes_near(x),
            _ => all.to_vec(),
        }
    }

    /// The pieces of a primitive surface (empty for a mesh: see [`Surface::pieces_near`]).
    pub(super) fn pieces(&self) -> Vec<Piece> {
        let unit = |a: usize, s: f64| {
            let mut n = [0.0; 3];
            n[a] = s;
            n
        };
        match *self {
            Surface::Box { lo, hi, dim } => (0..dim)
                .flat_map(|a| {
                    [
                        Piece::Plane {
                            n: unit(a, 1.0),
                            o: hi[a],
                        },
                        Piece::Plane {
                            n: unit(a, -1.0),
                            o: -lo[a],
                        },
                    ]
                })
                .collect(),
            Surface::Ball { c, r, dim } => vec![Piece::Round {
                c,
                r,
                axis: None,
                dim,
                outside: false,
            }],
            Surface::Annulus { c, ri, ro } => vec![
                Piece::Round {
                    c,
                    r: ro,
                    axis: None,
                    dim: 2,
                    outside: false,
                },
                Piece::Round {
                    c,
                    r: ri,
                    axis: None,
                    dim: 2,
                    outside: true,
                },
            ],
            Surface::Cylinder {
                base,
                axis,
                r,
                len: l,
                quarter,
            } => {
                let mut p = vec![
                    Piece::Round {
                        c: base,
                        r,
                        axis: Some(axis),
                        dim: 3,
                        outside: false,
                    },
                    Piece::Plane {
                        n: unit(axis, 1.0),
                        o: base[axis] + l,
                    },
                    Piece::Plane {
                        n: unit(axis, -1.0),
                        o: -base[axis],
                    },
                ];
                if quarter {
                    for t in [(axis + 1) % 3, (axis + 2) % 3] {
                        p.push(Piece::Plane {
                            n: unit(t, -1.0),
                            o: -base[t],
                        });
                    }
                }
                p
            }
            Surface::Mesh(_) => Vec::new(),
        }
    }
}
