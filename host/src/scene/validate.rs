//! Semantic checks of a deserialised scene. Each failure is one line naming the key.

pub(crate) use super::checks::num;
use super::checks::{dims, fail, finite, non_negative, positive, R};
use super::spec::*;
pub use super::validate_parts::resolve_poisson;
use super::validate_parts::{material_known, validate_model, validate_shape};
use gsph_core::schemes::options::{OptionKey, Range};

/// Most materials, and most bodies, in a scene (particles store both indices as `u16`).
pub const MAX_COUNT: usize = u16::MAX as usize + 1;

/// Most snapshot intervals (`output.snapshots`): each snapshot time cuts the step that
/// reaches it, so a huge count makes every step a snapshot (and the run never ends).
pub const MAX_SNAPSHOTS: usize = 100_000;
/// Most series samples (`output.series`): the series takes at most one row per step, but
/// the driver walks the sample times one by one, so a huge count stalls every step.
pub const MAX_SERIES: usize = 10_000_000;

/// Checks the scene.
pub fn validate(s: &Scene) -> R {
    validate_with(s, true)
}

/// As [`validate`] for a scene whose particles the caller gives (the library's
/// `Simulation::from_particles`): `bodies` must be absent.
pub fn validate_settings(s: &Scene) -> R {
    if !s.bodies.is_empty() {
        return fail(
            "bodies",
            "the particles come from the caller's arrays; leave `bodies` out of the settings",
        );
    }
    if s.window.is_some() {
        return fail(
            "window",
            "the moving window feeds particles from `bodies`; it cannot run on the caller's particles",
        );
    }
    if s.resolution_scale != 1.0 {
        return fail(
            "resolution_scale",
            "the particles come from the caller's arrays; there is no lattice to refine",
        );
    }
    validate_with(s, false)
}

/// The scene's checks, in order (the first failure is reported): each a named check of
/// one part or one cross-key rule; the models check their own parameters.
fn validate_with(s: &Scene, bodies_required: bool) -> R {
    check_run_time(s)?;
    check_artificial_stress(s)?;
    check_numerics(s)?;
    check_output(s)?;
    check_options(s)?;
    check_periodic(s)?;
    check_materials(s)?;
    check_bodies(s, bodies_required)?;
    check_monitor(s)?;
    check_window_and_reference(s)?;
    check_total_lagrangian(s)
}

/// What scheme `tl` does not run with yet: its pairs are those of the reference
/// configuration, fixed for the run, and the parts below would add or move pairs.
fn check_total_lagrangian(s: &Scene) -> R {
    if s.scheme != gsph_core::schemes::Scheme::Tl {
        return Ok(());
    }
    if s.periodic.is_some() {
        return fail(
            "periodic",
            "not yet with scheme tl (its reference neighbours do not wrap across the box)",
        );
    }
    if let Some(k) = s.walls.iter().position(|w| w.kind == "rigid") {
        return fail(
            &format!("walls[{k}].type"),
            "rigid is not yet with scheme tl (a rigid wall lets go of a particle by removing its mirror, which changes the particle's reference neighbourhood and F at once: a Taylor bar gained 69 % of its energy); symmetry planes work",
        );
    }
    if s.window.is_some() {
        return fail(
            "window",
            "not with scheme tl (the window feeds and drops particles; tl's reference neighbours are fixed)",
        );
    }
    Ok(())
}

/// The dimension, the end time, the resolution, the time step.
fn check_run_time(s: &Scene) -> R {
    if !(1..=3).contains(&s.dim) {
        return fail("dim", format!("must be 1, 2 or 3 (got {})", s.dim));
    }
    positive("t_end", s.t_end)?;
    positive("resolution_scale", s.resolution_scale)?;
    if let Some(cfl) = s.cfl {
        positive("cfl", cfl)?;
        if cfl > 1.0 {
            return fail("cfl", format!("must be at most 1 (got {})", num(cfl)));
        }
    }
    if let Some(dt) = s.dt {
        positive("dt", dt)?;
        if dt > s.t_end {
            return fail(
                "dt",
                format!(
                    "a fixed time step longer than t_end = {} (got {})",
                    num(s.t_end),
                    num(dt)
                ),
            );
        }
        if s.cfl.is_some() {
            return fail(
                "dt",
                "a fixed time step and `cfl` exclude each other (remove one of them)",
            );
        }
    }
    Ok(())
}

/// Artificial stress: its epsilon and exponent.
fn check_artificial_stress(s: &Scene) -> R {
    if let Some(e) = s.options.artificial_stress {
        positive("options.artificial_stress", e)?;
        if e > 1.0 {
            return fail(
                "options.artificial_stress",
                format!(
                    "must be at most 1 (got {}; Gray, Monaghan & Swift use 0.3)",
                    num(e)
                ),
            );
        }
    }
    if let Some(n) = s.options.artificial_stress_exponent {
        if s.options.artificial_stress.is_none() {
            return fail(
                "options.artificial_stress_exponent",
                "read only with options.artificial_stress (set its epsilon too)",
            );
        }
        if !(1..=16).contains(&n) {
            return fail(
                "options.artificial_stress_exponent",
                format!("must be between 1 and 16 (got {n}; Gray, Monaghan & Swift use 4)"),
            );
        }
    }
    Ok(())
}

/// The smoothing-length factor and the capacities.
fn check_numerics(s: &Scene) -> R {
    if !(0.5..=100.0).contains(&s.h_factor) {
        return fail(
            "h_factor",
            format!(
                "must be between 0.5 and 100 (got {}); below 0.5 a particle has no neighbours",
                num(s.h_factor)
            ),
        );
    }
    non_negative("skin", s.skin)?;
    if s.neighbor_capacity == Some(0) {
        return fail("neighbor_capacity", "must be at least 1");
    }
    if s.max_particles == Some(0) {
        return fail("max_particles", "must be at least 1");
    }
    if s.max_steps == Some(0) {
        return fail("max_steps", "must be at least 1");
    }
    Ok(())
}

/// The output schedule and checkpoints.
fn check_output(s: &Scene) -> R {
    if s.output.snapshots == 0 {
        return fail(
            "output.snapshots",
            "must be at least 1 (initial and final state)",
        );
    }
    if s.output.snapshots > MAX_SNAPSHOTS {
        return fail(
            "output.snapshots",
            format!(
                "at most {MAX_SNAPSHOTS} (got {}): every snapshot time ends a step, so more would make each step a snapshot and the run endless",
                s.output.snapshots
            ),
        );
    }
    if s.output.series == Some(0) {
        return fail("output.series", "must be at least 1");
    }
    if let Some(n) = s.output.series.filter(|&n| n > MAX_SERIES) {
        return fail(
            "output.series",
            format!("at most {MAX_SERIES} (got {n}; the series takes at most one row per step)"),
        );
    }
    if s.output.checkpoint_steps == Some(0) {
        return fail("output.checkpoint_steps", "must be at least 1");
    }
    if let Some(v) = s.output.checkpoint_seconds {
        if !(v.is_finite() && v > 0.0) {
            return fail(
                "output.checkpoint_seconds",
                format!("must be positive (got {})", num(v)),
            );
        }
    }
    if s.window.is_some()
        && (s.output.checkpoint_steps.is_some() || s.output.checkpoint_seconds.is_some())
    {
        return fail(
            "output.checkpoint_steps",
            "checkpoints are not supported for moving-window scenes",
        );
    }
    Ok(())
}

/// The smallest ratio of a solid's shear modulus to its bulk modulus at the reference
/// state (rubber's is about 1e-3).
pub const MIN_SHEAR_TO_BULK: f64 = 1e-8;

/// The `[options]` keys: read by the scheme (the core says), in range.
fn check_options(s: &Scene) -> R {
    let o = &s.options;
    if let Some((key, why)) = super::applies::inapplicable(o, s.scheme).into_iter().next() {
        return fail(key, why);
    }
    // the keys of the transverse Riemann problems: there are none in 1D or without strength
    // the rule the effects follow (`sim::resolve_effects`): a material has strength as
    // its model says, a material without a `strength` key by its shear modulus
    let no_strength = !s.materials.is_empty()
        && (s.materials.iter()).all(|m| !super::materials::material_of(m).has_strength());
    for (key, set) in [
        (
            "options.transverse_dissipation",
            o.transverse_dissipation.is_some(),
        ),
        ("options.objective", o.objective.is_some()),
    ] {
        if set && s.dim == 1 {
            return fail(
                key,
                "not read in 1D (uniaxial strain has no transverse waves)",
            );
        }
        if set && no_strength {
            return fail(
                key,
                "not read without strength (no material has a strength model, so no transverse waves)",
            );
        }
    }
    // the halo carries the specific volume's slopes with the other gradients, which a
    // scene without strength, correction or MUSCL does not exchange; the interpolation
    // stands in for artificial stress against the tensile instability of solids
    if o.specific_volume.is_some() && no_strength {
        return fail(
            "options.specific_volume",
            "not read without strength (no material has a strength model; it stands in for artificial stress in solids)",
        );
    }
    // the stiffness's scale is the shear modulus
    if o.hourglass.is_some() && no_strength {
        return fail(
            "options.hourglass",
            "not read without strength (no material has a shear modulus to scale the stiffness)",
        );
    }
    // the ranges of the options table
    for key in OptionKey::ALL {
        if let Some(v) = o.number(key) {
            match key.range() {
                Range::Positive => positive(key.path(), v)?,
                Range::NonNegative => non_negative(key.path(), v)?,
                Range::Any => finite(key.path(), v)?,
            }
        }
    }
    Ok(())
}

/// Periodic boundaries.
fn check_periodic(s: &Scene) -> R {
    if let Some(p) = &s.periodic {
        dims("periodic.lo", &p.lo, s.dim)?;
        dims("periodic.hi", &p.hi, s.dim)?;
        if p.axes.is_empty() {
            return fail("periodic.axes", "must list at least one axis");
        }
        for (k, &a) in p.axes.iter().enumerate() {
            if a >= s.dim {
                return fail(
                    &format!("periodic.axes[{k}]"),
                    format!("axis {a} does not exist in {}D", s.dim),
                );
            }
            if p.hi[a] <= p.lo[a] {
                return fail(
                    "periodic.hi",
                    format!("must exceed periodic.lo along axis {a}"),
                );
            }
        }
    }
    super::walls::validate(s)?;
    Ok(())
}

/// The materials: names, densities, moduli; each model checks its own parameters.
fn check_materials(s: &Scene) -> R {
    if s.materials.is_empty() {
        return fail("materials", "at least one material is required");
    }
    if s.materials.len() > MAX_COUNT {
        return fail("materials", format!("at most {MAX_COUNT} materials"));
    }
    for (k, m) in s.materials.iter().enumerate() {
        let key = format!("materials[{k}]");
        if s.materials[..k].iter().any(|o| o.name == m.name) {
            return fail(
                &format!("{key}.name"),
                format!("duplicate material name `{}`", m.name),
            );
        }
        positive(&format!("{key}.rho0"), m.rho0)?;
        non_negative(&format!("{key}.shear_modulus"), m.shear_modulus)?;
        // within the ranges of real materials (gsph_core::material::params::ranges)
        validate_model(&key, {
            use gsph_core::material::params::{physical, ranges::*};
            physical("rho0", m.rho0, DENSITY, "kg/m^3")
                .and_then(|()| physical("shear_modulus", m.shear_modulus, MODULUS, "Pa"))
                .and_then(|()| match m.tensile_strength {
                    Some(t) => physical("tensile_strength", t, STRESS, "Pa"),
                    None => Ok(()),
                })
        })?;
        validate_model(&format!("{key}.eos"), m.eos.check())?;
        // a shear modulus far below the bulk modulus makes the transverse Riemann
        // problems divide rounding residuals of the tractions by an impedance near zero
        // (the pm family's density went NaN at G = 1e-25 Pa with K = 7e10 Pa): below
        // 1e-8 K (no solid comes near: rubber's G/K is about 1e-3) the material is a fluid
        let bulk = m.rho0 * super::materials::material_of(m).eos(m.rho0, 0.0).c2;
        if m.shear_modulus > 0.0 && m.shear_modulus < MIN_SHEAR_TO_BULK * bulk {
            return fail(
                &format!("{key}.shear_modulus"),
                format!(
                    "must be 0 (a fluid) or at least {MIN_SHEAR_TO_BULK:e} of the bulk modulus at rho0 (K = {} Pa): shear waves slower than that are a fluid's (got {})",
                    num(bulk),
                    num(m.shear_modulus)
                ),
            );
        }
        if let Some(t) = m.tensile_strength {
            positive(&format!("{key}.tensile_strength"), t)?;
            if matches!(m.strength, Some(Strength::Jh1(_))) {
                return fail(
                    &format!("{key}.tensile_strength"),
                    "JH1 has its own tensile limit (strength.tensile_limit)",
                );
            }
        }
        match &m.strength {
            Some(Strength::Fluid) if m.shear_modulus > 0.0 => {
                return fail(
                    &format!("{key}.strength"),
                    "a fluid must have shear_modulus = 0",
                );
            }
            Some(Strength::Fluid) | None => {}
            Some(_) if m.shear_modulus <= 0.0 && m.poisson_ratio.is_none() => {
                return fail(
                    &format!("{key}.shear_modulus"),
                    "must be positive for a material with strength",
                );
            }
            Some(strength) => validate_model(&format!("{key}.strength"), strength.check())?,
        }
    }
    Ok(())
}

/// The monitored quantities.
fn check_monitor(s: &Scene) -> R {
    if let Some(bf) = s.monitor.as_ref().and_then(|m| m.back_face.as_ref()) {
        material_known(s, "monitor.back_face.material", &bf.material)?;
        if bf.axis >= s.dim {
            return fail(
                "monitor.back_face.axis",
                format!("must be below dim = {} (got {})", s.dim, bf.axis),
            );
        }
        finite("monitor.back_face.position", bf.position)?;
        if bf.normal != 1.0 && bf.normal != -1.0 {
            return fail(
                "monitor.back_face.normal",
                format!("must be 1 or -1 (got {})", bf.normal),
            );
        }
    }
    if let Some(f) = s.monitor.as_ref().and_then(|m| m.close_pairs) {
        if !(f > 0.0 && f < 1.0) {
            return fail(
                "monitor.close_pairs",
                format!(
                    "a fraction of the lattice spacing between 0 and 1 (got {})",
                    num(f)
                ),
            );
        }
    }
    if let Some(fr) = s.monitor.as_ref().and_then(|m| m.front.as_ref()) {
        if fr.axis >= s.dim {
            return fail(
                "monitor.front.axis",
                format!("must be below dim = {} (got {})", s.dim, fr.axis),
            );
        }
        positive("monitor.front.velocity", fr.velocity)?;
        if let Some(b) = fr.bin {
            positive("monitor.front.bin", b)?;
        }
        if let Some(b) = fr.behind {
            positive("monitor.front.behind", b)?;
        }
        if let Some(f) = fr.fit_from {
            if !(0.0..1.0).contains(&f) {
                return fail(
                    "monitor.front.fit_from",
                    format!("must lie in [0, 1) (got {f})"),
                );
            }
        }
    }
    Ok(())
}

/// The moving window and the exact reference.
fn check_window_and_reference(s: &Scene) -> R {
    if let Some(w) = &s.window {
        w.geometry(s)?;
    }
    match &s.reference {
        Some(ReferenceSpec::FlyerPlate {
            material,
            impact_velocity,
            interface,
        }) => {
            material_known(s, "reference.material", material)?;
            finite("reference.impact_velocity", *impact_velocity)?;
            finite("reference.interface", *interface)?;
        }
        Some(ReferenceSpec::ElasticPlasticRiemann {
            material,
            sigma1,
            interface,
            x_left,
        }) => {
            material_known(s, "reference.material", material)?;
            finite("reference.sigma1", *sigma1)?;
            finite("reference.interface", *interface)?;
            finite("reference.x_left", *x_left)?;
        }
        Some(ReferenceSpec::SoundWave {
            material,
            amplitude,
            k,
            center,
        }) => {
            material_known(s, "reference.material", material)?;
            finite("reference.amplitude", *amplitude)?;
            positive("reference.k", *k)?;
            finite("reference.center", *center)?;
        }
        Some(ReferenceSpec::ShellCollapse {
            material,
            center,
            r_inner,
            r_outer,
            v0,
        }) => {
            material_known(s, "reference.material", material)?;
            if s.dim != 2 {
                return fail("reference", "shell_collapse is a 2D reference");
            }
            dims("reference.center", center, s.dim)?;
            positive("reference.r_inner", *r_inner)?;
            positive("reference.r_outer", *r_outer)?;
            if r_outer <= r_inner {
                return fail("reference.r_outer", "must exceed r_inner");
            }
            non_negative("reference.v0", *v0)?;
        }
        None => {}
    }
    Ok(())
}

/// The bodies: each one's material, spacing, shape, lattice and motion.
fn check_bodies(s: &Scene, bodies_required: bool) -> R {
    if bodies_required && s.bodies.is_empty() {
        return fail("bodies", "at least one body is required");
    }
    if s.bodies.len() > MAX_COUNT {
        return fail("bodies", format!("at most {MAX_COUNT} bodies"));
    }
    for (k, b) in s.bodies.iter().enumerate() {
        let key = format!("bodies[{k}]");
        check_body(s, &key, b)?;
        check_lattice(s, &key, b)?;
        check_motion(s, &key, b)?;
    }
    Ok(())
}

/// A body's material, spacing, shape, jitter and pores (`key`: `bodies[k]`).
fn check_body(s: &Scene, key: &str, b: &BodySpec) -> R {
    material_known(s, &format!("{key}.material"), &b.material)?;
    let from_file = matches!(b.shape, ShapeSpec::Particles { .. });
    if b.spacing.is_nan() && !from_file {
        return fail(
            &format!("{key}.spacing"),
            "missing (this key is required; only a `particles` body whose file has an `m` column may leave it out)",
        );
    }
    if !b.spacing.is_nan() {
        positive(&format!("{key}.spacing"), b.spacing)?;
    }
    validate_shape(&format!("{key}.shape"), &b.shape, s.dim)?;
    if from_file {
        if s.resolution_scale != 1.0 {
            return fail(
                "resolution_scale",
                format!(
                    "{key} is read from a file (shape `particles`): there is no lattice to refine; keep resolution_scale = 1 (got {})",
                    num(s.resolution_scale)
                ),
            );
        }
        if b.jitter != 0.0 {
            return fail(
                &format!("{key}.jitter"),
                "not for a `particles` body (its positions come from the file)",
            );
        }
    }
    if !(b.jitter >= 0.0 && b.jitter < 0.5) {
        return fail(
            &format!("{key}.jitter"),
            format!(
                "must lie in [0, 0.5) (a fraction of the spacing; got {})",
                num(b.jitter)
            ),
        );
    }
    if let Some(p) = &b.pores {
        if s.dim == 1 {
            return fail(&format!("{key}.pores"), "pores need 2 or 3 dimensions");
        }
        super::pores::validate(&format!("{key}.pores"), p, s.dim)?;
    }
    Ok(())
}

/// A body's lattice and lattice origin.
fn check_lattice(s: &Scene, key: &str, b: &BodySpec) -> R {
    match b.lattice.as_deref() {
        None | Some("square") => {}
        Some("polar") => {
            if !matches!(b.shape, ShapeSpec::Disc { .. } | ShapeSpec::Annulus { .. }) || s.dim != 2
            {
                return fail(
                    &format!("{key}.lattice"),
                    "polar lattices exist for 2D discs and annuli only",
                );
            }
        }
        Some(other) => {
            return fail(
                &format!("{key}.lattice"),
                format!("unknown lattice `{other}` (known: square, polar)"),
            )
        }
    }
    check_layout(s, key, b)?;
    if let Some(o) = &b.lattice_origin {
        let k = format!("{key}.lattice_origin");
        let r_out = match b.shape {
            ShapeSpec::Disc { radius, .. } => radius,
            ShapeSpec::Annulus { r_outer, .. } => r_outer,
            _ => return fail(&k, "a lattice origin is for discs and annuli only"),
        };
        if b.lattice.as_deref() == Some("polar") {
            return fail(&k, "a lattice origin is for the square lattice only");
        }
        if o.len() != s.dim {
            return fail(
                &k,
                format!("must have {} components (got {})", s.dim, o.len()),
            );
        }
        if let Some(v) = o.iter().find(|v| !(v.is_finite() && v.abs() <= r_out)) {
            return fail(
                &k,
                format!("{v} must lie within the outer radius {r_out} of the centre"),
            );
        }
    }
    Ok(())
}

/// A body's layout and its relaxation's iterations.
fn check_layout(s: &Scene, key: &str, b: &BodySpec) -> R {
    let k = format!("{key}.layout");
    match b.layout.as_deref() {
        None | Some("lattice") => {
            if b.relax_iterations.is_some() {
                return fail(
                    &format!("{key}.relax_iterations"),
                    "only with layout = \"relaxed\" (the lattice is not relaxed)",
                );
            }
        }
        Some("relaxed") => {
            if s.dim == 1 {
                return fail(&k, "a relaxed layout needs 2 or 3 dimensions (a 1D lattice already ends half a spacing inside its segment)");
            }
            if matches!(b.shape, ShapeSpec::Particles { .. }) {
                return fail(&k, "a particle file's layout is left as given");
            }
            if matches!(b.shape, ShapeSpec::Box { .. }) {
                return fail(&k, "a box's lattice already fits it (its sites sit at the centres of equal cells, the surface rows half a cell inside): there is nothing to relax");
            }
            if b.pores.is_some() {
                return fail(&k, "not with pores (the relaxation sees the shape's surface only and would close them)");
            }
            if let Some(n) = b.relax_iterations {
                if !(1..=100_000).contains(&n) {
                    return fail(
                        &format!("{key}.relax_iterations"),
                        format!("must lie in 1..=100000 (got {n})"),
                    );
                }
            }
        }
        Some(other) => {
            return fail(
                &k,
                format!("unknown layout `{other}` (known: lattice, relaxed)"),
            )
        }
    }
    Ok(())
}

/// A body's initial velocity and state.
fn check_motion(s: &Scene, key: &str, b: &BodySpec) -> R {
    match &b.velocity {
        Some(VelocitySpec::Uniform { value }) => {
            dims(&format!("{key}.velocity.value"), value, s.dim)?
        }
        Some(VelocitySpec::Radial { v0, r_ref, center }) => {
            finite(&format!("{key}.velocity.v0"), *v0)?;
            positive(&format!("{key}.velocity.r_ref"), *r_ref)?;
            dims(&format!("{key}.velocity.center"), center, s.dim)?;
        }
        Some(VelocitySpec::Rotation {
            omega,
            center,
            twist_height,
        }) => {
            if s.dim == 1 {
                return fail(
                    &format!("{key}.velocity"),
                    "a rotation needs a plane: use it in 2D or 3D",
                );
            }
            finite(&format!("{key}.velocity.omega"), *omega)?;
            dims(&format!("{key}.velocity.center"), center, s.dim)?;
            if let Some(h) = twist_height {
                if s.dim != 3 {
                    return fail(
                        &format!("{key}.velocity.twist_height"),
                        "a twist varies along z: use it in 3D",
                    );
                }
                positive(&format!("{key}.velocity.twist_height"), *h)?;
            }
        }
        Some(VelocitySpec::Cantilever {
            root,
            length,
            tip,
            axis,
            direction,
            k,
        }) => {
            if s.dim == 1 {
                return fail(
                    &format!("{key}.velocity"),
                    "a beam bends in a plane: use it in 2D or 3D",
                );
            }
            dims(&format!("{key}.velocity.root"), root, s.dim)?;
            positive(&format!("{key}.velocity.length"), *length)?;
            finite(&format!("{key}.velocity.tip"), *tip)?;
            positive(&format!("{key}.velocity.k"), *k)?;
            for (name, a) in [("axis", *axis), ("direction", *direction)] {
                if a >= s.dim {
                    return fail(
                        &format!("{key}.velocity.{name}"),
                        format!("axis {a} does not exist in {}D", s.dim),
                    );
                }
            }
            if axis == direction {
                return fail(
                    &format!("{key}.velocity.direction"),
                    format!("must differ from the beam's axis {axis}"),
                );
            }
        }
        Some(VelocitySpec::Pulse {
            amplitude,
            k: kk,
            center,
            axis,
        }) => {
            finite(&format!("{key}.velocity.amplitude"), *amplitude)?;
            positive(&format!("{key}.velocity.k"), *kk)?;
            finite(&format!("{key}.velocity.center"), *center)?;
            if *axis >= s.dim {
                return fail(
                    &format!("{key}.velocity.axis"),
                    format!("axis {axis} does not exist in {}D", s.dim),
                );
            }
        }
        None => {}
    }
    match &b.initial {
        Some(InitialSpec::UniaxialStress { sigma_xx }) => {
            finite(&format!("{key}.initial.sigma_xx"), *sigma_xx)?
        }
        Some(InitialSpec::Density { rho, e }) => {
            positive(&format!("{key}.initial.rho"), *rho)?;
            finite(&format!("{key}.initial.e"), *e)?;
        }
        None => {}
    }
    Ok(())
}
