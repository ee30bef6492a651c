//! Turns bodies into particles: lattices clipped to shapes, initial velocity and state.

use super::import;
pub use super::initial::InitialParticles;
use crate::scene::materials::material_of;
use crate::scene::spec::*;
use crate::scene::SceneError;
use gsph_core::material::{Material, Strength};
use gsph_core::math::Sym3;

pub use crate::memory::MAX_PARTICLES;
/// Most lattice cells the bounding box of the particles may span (at the finest spacing):
/// the neighbour search keeps a grid over that box.
pub const MAX_CELLS: f64 = (1u64 << 30) as f64;
/// Most neighbour-list entries (particles times capacity, 4 bytes each).
pub const MAX_NEIGHBOR_ENTRIES: f64 = (1u64 << 32) as f64;

/// `v <= limit`, false for NaN.
fn at_most(v: f64, limit: f64) -> bool {
    v <= limit
}

/// Builds the particles once and checks that the run fits in memory (see [`MAX_PARTICLES`],
/// [`MAX_CELLS`], [`MAX_NEIGHBOR_ENTRIES`]). Errors name the key.
pub fn check_build(scene: &Scene) -> Result<(), SceneError> {
    // the relaxation moves particles within their shape and keeps their count: the checks
    // need the lattice only
    let parts = build(scene, false, false)?;
    // bodies read from a file without a `spacing`: the periodic length against the
    // spacing their particles have
    super::periodic::check_length_built(scene, &parts)?;
    check_particles(scene, &parts)
}

/// Refuses particles spread over more neighbour-search cells, or needing more
/// neighbour-list entries, than the limits allow.
pub fn check_particles(scene: &Scene, parts: &InitialParticles) -> Result<(), SceneError> {
    let dim = scene.dim;
    let finest = parts.spacing.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut cells = 1.0;
    for a in 0..dim {
        let (lo, hi) = parts
            .x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                (l.min(p[a]), h.max(p[a]))
            });
        cells *= (hi - lo) / finest + 1.0;
    }
    if !at_most(cells, MAX_CELLS) {
        return Err(SceneError(format!(
            "bodies: the particles span {cells:.2e} cells of the finest spacing {finest:e} m (limit {MAX_CELLS:.2e}); are bodies far apart or a spacing too fine?"
        )));
    }
    let capacity = scene
        .neighbor_capacity
        .unwrap_or_else(|| crate::neighbors::default_capacity(dim, scene.kernel, scene.h_factor));
    let entries = parts.len() as f64 * capacity as f64;
    if !at_most(entries, MAX_NEIGHBOR_ENTRIES) {
        return Err(SceneError(format!(
            "neighbor_capacity: {} particles x {capacity} neighbours is {entries:.2e} list entries (limit {MAX_NEIGHBOR_ENTRIES:.2e})",
            parts.len()
        )));
    }
    crate::memory::check_lists_fit(parts.len(), capacity, crate::memory::available())
        .map_err(SceneError)?;
    Ok(())
}

/// Builds the particles of every body (relaxing the `relaxed` layouts, silently: what the
/// relaxation did is in [`InitialParticles::layout`]).
pub fn build_particles(scene: &Scene) -> Result<InitialParticles, SceneError> {
    build(scene, true, false)
}

/// [`build_particles`], with the relaxation's progress lines on stderr (MPI rank 0) if
/// `report`: a run's progress display (`gsph run` without `--quiet`).
pub fn build_particles_reporting(
    scene: &Scene,
    report: bool,
) -> Result<InitialParticles, SceneError> {
    build(scene, true, report)
}

fn build(scene: &Scene, relax: bool, report: bool) -> Result<InitialParticles, SceneError> {
    let mut out = InitialParticles {
        dim: scene.dim,
        ..Default::default()
    };
    let mut total = 0.0;
    let limit = scene.particle_limit();
    for (b, body) in scene.bodies.iter().enumerate() {
        let key = format!("bodies[{b}]");
        let mi = scene
            .materials
            .iter()
            .position(|m| m.name == body.material)
            .expect("validated: material exists");
        let mat = material_of(&scene.materials[mi]);
        let dx = body.spacing / scene.resolution_scale;
        let polar = body.lattice.as_deref() == Some("polar");
        let shape_key = format!("{key}.shape");
        // a file is opened (a CSV file's rows counted, an STL surface read) before the
        // particles are counted against the limits
        let (source, count_key) = match &body.shape {
            ShapeSpec::Particles { file, step, .. } => {
                let src = import::open_particles(&shape_key, file, *step, scene.dim, limit)
                    .map_err(SceneError)?;
                total += src.rows() as f64;
                (Source::File(src), format!("{key}.shape.file"))
            }
            ShapeSpec::Stl {
                file,
                scale,
                offset,
            } => {
                let offset = offset.as_deref().map_or([0.0; 3], |o| [o[0], o[1], o[2]]);
                let mesh = import::read_stl(&shape_key, file, *scale, offset, limit)
                    .map_err(SceneError)?;
                total += mesh.sites(dx);
                (Source::Mesh(mesh), format!("{key}.spacing"))
            }
            _ => {
                total += sites(scene.dim, &body.shape, dx, polar);
                (Source::Lattice, format!("{key}.spacing"))
            }
        };
        check_count(scene, &key, &count_key, &source, dx, total)?;
        let mut mesh = None;
        let mut pts = match source {
            Source::File(src) => {
                file_body(&mut out, scene, b, mi, &mat, src)?;
                continue;
            }
            Source::Mesh(m) => mesh.insert(m).fill(dx),
            Source::Lattice => lattice(
                scene.dim,
                &body.shape,
                dx,
                polar,
                body.lattice_origin.as_deref(),
            ),
        };
        let full: f64 = pts.iter().map(|p| p.1).sum();
        if let Some(pores) = &body.pores {
            pts.retain(|(x, _)| !super::pores::inside(pores, x));
        }
        out.porosity
            .push(full / pts.iter().map(|p| p.1).sum::<f64>().max(f64::MIN_POSITIVE));
        if pts.is_empty() {
            return Err(SceneError(format!(
                "{key}: the shape holds no particle at spacing {dx:e} m (spacing / resolution_scale); the shape must be at least half a spacing across"
            )));
        }
        if relax && body.layout.as_deref() == Some("relaxed") {
            let line = relaxed(scene, b, dx, mesh.as_ref(), &mut pts, report);
            out.layout.push(line);
        }
        push_sites(&mut out, scene, b, mi, &mat, dx, pts)?;
    }
    crate::scene::validate_parts::check_step_count(scene)?;
    Ok(out)
}

/// Relaxes the sites `pts` of body `b` (spacing `dx`; `mesh`: an STL body's surface)
/// against its shape's signed distance, with (if `report`) a progress line on stderr
/// (rank 0) at the progress interval, and returns what it did as a line for the run log.
fn relaxed(
    scene: &Scene,
    b: usize,
    dx: f64,
    mesh: Option<&import::Mesh>,
    pts: &mut [([f64; 3], f64)],
    report: bool,
) -> String {
    use super::relax;
    use std::time::Instant;
    let body = &scene.bodies[b];
    let iterations = body.relax_iterations.unwrap_or(relax::DEFAULT_ITERATIONS);
    let surface = super::sdf::Surface::of(&body.shape, scene.dim, mesh, relax::reach(dx))
        .expect("validated: a relaxed body has a surface");
    let mut x: Vec<[f64; 3]> = pts.iter().map(|p| p.0).collect();
    let show = report && crate::dist_rank() == 0;
    let start = Instant::now();
    let mut last = start;
    let every = crate::progress::interval();
    let mut progress = |k: usize, residual: f64| {
        if show && (k == 1 || last.elapsed() >= every) && k < iterations {
            last = Instant::now();
            eprintln!(
                "gsph: bodies[{b}]: relaxing the layout: iteration {k} of {iterations}, imbalance {residual:.2e}, elapsed {}",
                crate::progress::hms(start.elapsed().as_secs_f64())
            );
        }
    };
    let r = relax::relax(scene.dim, &mut x, dx, &surface, iterations, &mut progress);
    for (p, y) in pts.iter_mut().zip(x) {
        p.0 = y;
    }
    let line = format!(
        "bodies[{b}]: relaxed layout, {} particles, {} iterations in {}: surface roughness {:.3} -> {:.3} spacings, imbalance {:.2e} -> {:.2e}, nearest pair {:.3} spacings",
        pts.len(),
        iterations,
        crate::progress::hms(start.elapsed().as_secs_f64()),
        r.roughness[0],
        r.roughness[1],
        r.residual[0],
        r.residual[1],
        r.nearest
    );
    if show {
        eprintln!("gsph: {line}");
    }
    line
}

/// Appends the lattice sites `pts` (position, volume) of body `b` of material `mi`, in the
/// body's initial state.
fn push_sites(
    out: &mut InitialParticles,
    scene: &Scene,
    b: usize,
    mi: usize,
    mat: &Material,
    dx: f64,
    pts: Vec<([f64; 3], f64)>,
) -> Result<(), SceneError> {
    let body = &scene.bodies[b];
    let key = format!("bodies[{b}]");
    let (rho, e, s) = initial_state(mat, body.initial.as_ref())
        .map_err(|msg| SceneError(format!("{key}.initial: {msg}")))?;
    for (x, vol) in pts {
        let x = jittered(x, scene.dim, body.jitter * dx, out.x.len() as u64);
        out.v.push(velocity(body.velocity.as_ref(), &x));
        out.x0.push(x);
        out.x.push(x);
        out.m.push(rho * vol);
        out.rho.push(rho);
        out.e.push(e);
        out.s.push(s);
        out.mat.push(mi as u16);
        out.body.push(b as u16);
        out.spacing.push(dx);
        out.eps_p.push(0.0);
        out.damage.push(0.0);
        out.temp.push(mat.initial_temperature());
    }
    Ok(())
}

/// Refuses a scene whose particles up to and including this body (`total`, about) exceed
/// the scene's particle limit or the memory of this machine, naming the key that sets the
/// count (`count_key`: the body's spacing or its particle file).
fn check_count(
    scene: &Scene,
    key: &str,
    count_key: &str,
    source: &Source,
    dx: f64,
    total: f64,
) -> Result<(), SceneError> {
    let limit = scene.particle_limit();
    if !at_most(total, limit as f64) {
        let lim = limit as f64;
        return Err(SceneError(match source {
            Source::File(src) => format!(
                "{count_key}: the file holds {} particles, about {total:.2e} with the bodies before it, more than the limit {lim:.0e} (`max_particles` raises it)",
                src.rows()
            ),
            _ => format!(
                "{key}.spacing: spacing {dx:e} m (spacing / resolution_scale) makes about {total:.2e} particles, more than the limit {lim:.0e} (`max_particles` raises it)"
            ),
        }));
    }
    let each = crate::memory::bytes_per_particle(scene.dim, scene.kernel, scene.h_factor);
    crate::memory::check_fits(each, total, crate::memory::available(), count_key)
        .map_err(SceneError)?;
    Ok(())
}

/// Where the particles of a body come from.
enum Source {
    /// A lattice clipped to a primitive shape.
    Lattice,
    /// A particle file (shape `particles`).
    File(import::ParticleSource),
    /// A closed STL surface filled with a lattice (shape `stl`).
    Mesh(import::Mesh),
}

/// Appends the particles of body `b`, read from a file (`super::import`).
fn file_body(
    out: &mut InitialParticles,
    scene: &Scene,
    b: usize,
    mi: usize,
    mat: &Material,
    src: import::ParticleSource,
) -> Result<(), SceneError> {
    let body = &scene.bodies[b];
    let key = format!("bodies[{b}]");
    let ShapeSpec::Particles { file_material, .. } = &body.shape else {
        unreachable!("a particles body")
    };
    let f = import::read_particles(&format!("{key}.shape"), src, scene.dim, *file_material)
        .map_err(SceneError)?;
    let initial = match &body.initial {
        Some(i) => Some(
            initial_state(mat, Some(i))
                .map_err(|msg| SceneError(format!("{key}.initial: {msg}")))?,
        ),
        None => None,
    };
    let name = &scene.materials[mi].name;
    let mut ps =
        import::file_body(&f, &key, body, scene.dim, mat, name, initial).map_err(SceneError)?;
    let full: f64 = ps.iter().map(|p| p.m / p.rho).sum();
    if let Some(pores) = &body.pores {
        ps.retain(|p| !super::pores::inside(pores, &p.x));
    }
    let kept: f64 = ps.iter().map(|p| p.m / p.rho).sum();
    out.porosity.push(full / kept.max(f64::MIN_POSITIVE));
    if ps.is_empty() {
        return Err(SceneError(format!(
            "{key}: the body holds no particle (every particle of its file lies in a pore)"
        )));
    }
    for p in ps {
        out.v.push(match &body.velocity {
            Some(_) => velocity(body.velocity.as_ref(), &p.x),
            None => p.v,
        });
        out.x0.push(p.x0.unwrap_or(p.x));
        out.x.push(p.x);
        out.m.push(p.m);
        out.rho.push(p.rho);
        out.e.push(p.e);
        out.s.push(p.s);
        out.mat.push(mi as u16);
        out.body.push(b as u16);
        out.spacing.push(p.spacing);
        out.eps_p.push(p.eps_p);
        out.damage.push(p.damage);
        out.temp.push(p.temperature);
    }
    Ok(())
}

/// splitmix64 (Steele, Lea & Flood 2014): a well-mixed 64-bit hash of `z`.
fn splitmix64(z: u64) -> u64 {
    let mut z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// `x` moved by a uniform amount in `[-amount, amount)` along each of the first `dim` axes,
/// drawn from [`splitmix64`] keyed by the particle index (the same scene always gives the
/// same particles; the initial velocity is evaluated at the moved position).
fn jittered(mut x: [f64; 3], dim: usize, amount: f64, index: u64) -> [f64; 3] {
    if amount > 0.0 {
        for (a, xa) in x.iter_mut().enumerate().take(dim) {
            let r = splitmix64(index.wrapping_mul(3).wrapping_add(a as u64));
            // 53 random bits -> [0, 1)
            let u = (r >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            *xa += amount * (2.0 * u - 1.0);
        }
    }
    x
}

/// Number of lattice sites [`lattice`] visits for a shape (an upper bound on its particles;
/// infinite or NaN where `dx` is absurdly small). Bodies from files are counted from them.
fn sites(dim: usize, shape: &ShapeSpec, dx: f64, polar: bool) -> f64 {
    match shape {
        ShapeSpec::Particles { .. } | ShapeSpec::Stl { .. } => {
            unreachable!("counted from the file")
        }
        ShapeSpec::Segment { min, max } => (max - min) / dx,
        ShapeSpec::Box { min, max } => (0..dim).map(|a| (max[a] - min[a]) / dx + 1.0).product(),
        ShapeSpec::Cylinder { radius, length, .. } => {
            (2.0 * (radius / dx).round().max(1.0)).powi(2) * (length / dx + 1.0)
        }
        ShapeSpec::Disc { radius: r, .. } | ShapeSpec::Annulus { r_outer: r, .. } => {
            if polar {
                std::f64::consts::PI * (r / dx + 1.0).powi(2)
            } else {
                (2.0 * (r / dx).ceil() + 2.0).powi(dim as i32)
            }
        }
    }
}

/// Lattice points inside a shape with their volumes (length in 1D, area in 2D). A shape
/// less than half a spacing across along some axis holds none.
fn lattice(
    dim: usize,
    shape: &ShapeSpec,
    dx: f64,
    polar: bool,
    origin: Option<&[f64]>,
) -> Vec<([f64; 3], f64)> {
    let mut pts = Vec::new();
    match shape {
        ShapeSpec::Particles { .. } | ShapeSpec::Stl { .. } => {
            unreachable!("bodies from files are built by `super::import`")
        }
        ShapeSpec::Segment { min, max } => {
            let n = ((max - min) / dx).round() as usize;
            let d = (max - min) / n as f64;
            for k in 0..n {
                pts.push(([min + (k as f64 + 0.5) * d, 0.0, 0.0], d));
            }
        }
        ShapeSpec::Box { min, max } => {
            let n: Vec<usize> = (0..dim)
                .map(|a| ((max[a] - min[a]) / dx).round() as usize)
                .collect();
            let d: Vec<f64> = (0..dim).map(|a| (max[a] - min[a]) / n[a] as f64).collect();
            let vol: f64 = d.iter().product();
            let nz = if dim == 3 { n[2] } else { 1 };
            for kz in 0..nz {
                for ky in 0..n[1] {
                    for kx in 0..n[0] {
                        let mut x = [0.0; 3];
                        x[0] = min[0] + (kx as f64 + 0.5) * d[0];
                        x[1] = min[1] + (ky as f64 + 0.5) * d[1];
                        if dim == 3 {
                            x[2] = min[2] + (kz as f64 + 0.5) * d[2];
                        }
                        pts.push((x, vol));
                    }
                }
            }
        }
        ShapeSpec::Cylinder {
            base,
            axis,
            radius,
            length,
            quarter,
        } => cylinder_sites(&mut pts, base, *axis, *radius, *length, *quarter, dx),
        ShapeSpec::Disc { center, radius } => {
            if polar {
                polar_rings(&mut pts, center, 0.0, *radius, dx);
            } else if let Some(o) = origin {
                node_clip(&mut pts, dim, center, o, 0.0, *radius, dx);
            } else {
                square_clip(&mut pts, dim, center, 0.0, *radius, dx);
            }
        }
        ShapeSpec::Annulus {
            center,
            r_inner,
            r_outer,
        } => {
            if polar {
                polar_rings(&mut pts, center, *r_inner, *r_outer, dx);
            } else if let Some(o) = origin {
                node_clip(&mut pts, dim, center, o, *r_inner, *r_outer, dx);
            } else {
                square_clip(&mut pts, dim, center, *r_inner, *r_outer, dx);
            }
        }
    }
    pts
}

/// The sites of a cylinder (see [`ShapeSpec::Cylinder`]): `2 m` sites of `r / m` across
/// each transverse axis (`m = round(r / dx)`), `round(length / dx)` along the axis, the
/// transverse ones kept where `r² < radius²` (and on the positive side with `quarter`).
fn cylinder_sites(
    pts: &mut Vec<([f64; 3], f64)>,
    base: &[f64],
    axis: usize,
    radius: f64,
    length: f64,
    quarter: bool,
    dx: f64,
) {
    let m = (radius / dx).round().max(1.0) as i64;
    let dt = radius / m as f64;
    let na = ((length / dx).round() as i64).max(1);
    let da = length / na as f64;
    let (t1, t2) = ((axis + 1) % 3, (axis + 2) % 3);
    let from = if quarter { 0 } else { -m };
    for ka in 0..na {
        for k2 in from..m {
            for k1 in from..m {
                let (u, v) = ((k1 as f64 + 0.5) * dt, (k2 as f64 + 0.5) * dt);
                if u * u + v * v >= radius * radius {
                    continue;
                }
                let mut x = [0.0; 3];
                x[axis] = base[axis] + (ka as f64 + 0.5) * da;
                x[t1] = base[t1] + u;
                x[t2] = base[t2] + v;
                pts.push((x, dt * dt * da));
            }
        }
    }
}

/// Cartesian lattice with a node at `c + o`: sites `o + i dx` relative to the centre
/// (i = 0 … round((r_out − o)/dx) − 1 per axis, the half-open extent `[o, r_out)`), kept
/// where `r_in² <= r² < r_out²`. The squares are compared, with the offsets formed as
/// `o + i dx`, as the peers' colliding-rings scripts do, so that the same sites are kept
/// to the last bit (17,592 particles for their two rings at dx = 5e-4).
fn node_clip(
    pts: &mut Vec<([f64; 3], f64)>,
    dim: usize,
    c: &[f64],
    o: &[f64],
    r_in: f64,
    r_out: f64,
    dx: f64,
) {
    let n = |a: usize| ((r_out - o[a]) / dx).round() as i64;
    clip_sites(
        pts,
        dim,
        c,
        dx,
        |a| 0..n(a),
        |a, i| o[a] + i as f64 * dx,
        |r2| r_in * r_in <= r2 && r2 < r_out * r_out,
    );
}

/// Cartesian lattice, offset by half a spacing from the centre, clipped to r_in <= r < r_out.
fn square_clip(
    pts: &mut Vec<([f64; 3], f64)>,
    dim: usize,
    c: &[f64],
    r_in: f64,
    r_out: f64,
    dx: f64,
) {
    let n = (r_out / dx).ceil() as i64 + 1;
    clip_sites(
        pts,
        dim,
        c,
        dx,
        |_| -n..n,
        |_, k| (k as f64 + 0.5) * dx,
        |r2| {
            let r = r2.sqrt();
            r >= r_in && r < r_out
        },
    );
}

/// The sites `c + (off(0, kx), off(1, ky), off(2, kz))` for k in `range(axis)` on the
/// axes the dimension has, each of volume `dx^dim`, where `keep(r²)` of the offset holds.
fn clip_sites(
    pts: &mut Vec<([f64; 3], f64)>,
    dim: usize,
    c: &[f64],
    dx: f64,
    range: impl Fn(usize) -> std::ops::Range<i64>,
    off: impl Fn(usize, i64) -> f64,
    keep: impl Fn(f64) -> bool,
) {
    let vol = dx.powi(dim as i32);
    let axis = |a: usize| if a < dim { range(a) } else { 0..1 };
    let at = |a: usize, k: i64| if a < dim { off(a, k) } else { 0.0 };
    for kz in axis(2) {
        for ky in axis(1) {
            for kx in axis(0) {
                let d = [at(0, kx), at(1, ky), at(2, kz)];
                if keep(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) {
                    let mut x = [0.0; 3];
                    for a in 0..dim {
                        x[a] = c[a] + d[a];
                    }
                    pts.push((x, vol));
                }
            }
        }
    }
}

/// Concentric rings of particles (2D): ring k at r_k = r_in + (k + 1/2) dr with
/// round(2 pi r_k / dr) particles, each carrying the area of its ring sector.
fn polar_rings(pts: &mut Vec<([f64; 3], f64)>, c: &[f64], r_in: f64, r_out: f64, dx: f64) {
    let nr = ((r_out - r_in) / dx).round() as usize;
    let dr = (r_out - r_in) / nr as f64;
    for k in 0..nr {
        let r = r_in + (k as f64 + 0.5) * dr;
        let nt = ((2.0 * std::f64::consts::PI * r / dr).round() as usize).max(1);
        let area =
            std::f64::consts::PI * ((r + 0.5 * dr).powi(2) - (r - 0.5 * dr).powi(2)) / nt as f64;
        let shift = if k % 2 == 1 { 0.5 } else { 0.0 };
        for j in 0..nt {
            let th = (j as f64 + shift) * 2.0 * std::f64::consts::PI / nt as f64;
            pts.push(([c[0] + r * th.cos(), c[1] + r * th.sin(), 0.0], area));
        }
    }
}

fn velocity(spec: Option<&VelocitySpec>, x: &[f64; 3]) -> [f64; 3] {
    let mut v = [0.0; 3];
    match spec {
        None => {}
        Some(VelocitySpec::Uniform { value }) => v[..value.len()].copy_from_slice(value),
        Some(VelocitySpec::Radial { v0, r_ref, center }) => {
            let mut d = [0.0; 3];
            for a in 0..center.len() {
                d[a] = x[a] - center[a];
            }
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if r > 0.0 {
                for a in 0..3 {
                    v[a] = v0 * r_ref / r * d[a] / r;
                }
            }
        }
        Some(VelocitySpec::Rotation {
            omega,
            center,
            twist_height,
        }) => {
            let w = match twist_height {
                Some(h) => omega * (std::f64::consts::PI * (x[2] - center[2]) / (2.0 * h)).sin(),
                None => *omega,
            };
            v[0] = -w * (x[1] - center[1]);
            v[1] = w * (x[0] - center[0]);
        }
        Some(VelocitySpec::Pulse {
            amplitude,
            k,
            center,
            axis,
        }) => {
            let s = x[*axis] - center;
            v[*axis] = amplitude * (-k * s * s).exp();
        }
        Some(VelocitySpec::Cantilever {
            root,
            length,
            tip,
            axis,
            direction,
            k,
        }) => {
            let xi = (x[*axis] - root[*axis]) / length;
            if xi > 0.0 {
                v[*direction] = tip * crate::scene::spec::cantilever_mode(*k, xi);
            }
        }
    }
    v
}

/// Initial (rho, e, deviator) of a body.
fn initial_state(mat: &Material, init: Option<&InitialSpec>) -> Result<(f64, f64, Sym3), String> {
    match init {
        None => Ok((mat.rho0, 0.0, Sym3::ZERO)),
        Some(InitialSpec::Density { rho, e }) => Ok((*rho, *e, Sym3::ZERO)),
        Some(InitialSpec::UniaxialStress { sigma_xx }) => {
            let sxx_of = |rho: f64| -> f64 {
                let elastic = -(4.0 * mat.shear_modulus / 3.0) * (rho / mat.rho0).ln();
                match mat.strength {
                    Strength::Fluid => 0.0,
                    Strength::Elastic => elastic,
                    Strength::VonMises { yield_stress } => {
                        elastic.clamp(-2.0 * yield_stress / 3.0, 2.0 * yield_stress / 3.0)
                    }
                    // quasi-static loading at room temperature: the initial yield stress A
                    Strength::JohnsonCook(jc) => elastic.clamp(-2.0 * jc.a / 3.0, 2.0 * jc.a / 3.0),
                    // the intact strength at zero pressure bounds the deviator
                    Strength::Jh1(jh) => {
                        let y = jh.intact_strength(0.0);
                        elastic.clamp(-2.0 * y / 3.0, 2.0 * y / 3.0)
                    }
                }
            };
            let sigma = |rho: f64| -mat.eos(rho, 0.0).p + sxx_of(rho) - sigma_xx;
            let (mut lo, mut hi) = (mat.rho0 * 0.2, mat.rho0 * 5.0);
            if sigma(lo) * sigma(hi) > 0.0 {
                return Err(format!("no density between {lo:.4e} and {hi:.4e} kg/m³ gives sigma_xx = {sigma_xx:e} Pa"));
            }
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if sigma(lo) * sigma(mid) <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let rho = 0.5 * (lo + hi);
            let sxx = sxx_of(rho);
            Ok((
                rho,
                0.0,
                Sym3::new(sxx, -0.5 * sxx, -0.5 * sxx, 0.0, 0.0, 0.0),
            ))
        }
    }
}
