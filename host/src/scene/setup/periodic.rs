//! The periodic box against the kernel support: along a periodic axis of length `L` a
//! particle finds each neighbour by its nearest image, so every pair closer than the
//! support radius `R = support × h` is seen exactly once only when `L >= 2R` (below that a
//! neighbour's other image is also within `R` and is missed, and below `R` a particle would
//! be its own neighbour). `h = h_factor × spacing` of the coarsest body, with
//! `spacing = bodies[k].spacing / resolution_scale` as built. A length short of the minimum
//! by round-off only (1e-9 relative) passes, so `L = 2R` written in the scene is accepted.

use super::initial::InitialParticles;
use crate::scene::spec::Scene;
use crate::scene::SceneError;

/// Refuses a periodic length below `2 × support × h` (checked after [`crate::scene::validate`];
/// bodies read from a file without a `spacing` are checked once built, by
/// [`check_length_built`]).
pub(in crate::scene) fn check_length(s: &Scene) -> Result<(), SceneError> {
    check_with(s, |b| {
        let dx = s.bodies[b].spacing / s.resolution_scale;
        dx.is_finite().then_some(dx)
    })
}

/// [`check_length`] with the largest spacing of the particles of each body read from a file
/// without a `spacing` (the others were checked before they were built).
pub(super) fn check_length_built(s: &Scene, parts: &InitialParticles) -> Result<(), SceneError> {
    if s.bodies.iter().all(|b| b.spacing.is_finite()) {
        return Ok(());
    }
    check_with(s, |b| {
        let dx = s.bodies[b].spacing / s.resolution_scale;
        if dx.is_finite() {
            return Some(dx);
        }
        parts
            .body
            .iter()
            .zip(&parts.spacing)
            .filter(|(&k, _)| k as usize == b)
            .map(|(_, &d)| d)
            .reduce(f64::max)
    })
}

/// The check with `dx_of(body)`, the spacing of a body (`None`: not known yet).
fn check_with(s: &Scene, dx_of: impl Fn(usize) -> Option<f64>) -> Result<(), SceneError> {
    let Some(p) = &s.periodic else {
        return Ok(());
    };
    // the first body with the largest spacing
    let coarsest = (0..s.bodies.len()).fold(None, |best, b| {
        let Some(dx) = dx_of(b) else { return best };
        match best {
            Some((_, d)) if d >= dx => best,
            _ => Some((b, dx)),
        }
    });
    let Some((b, dx)) = coarsest else {
        return Ok(());
    };
    let support = s.kernel.support();
    let h = s.h_factor * dx;
    let min = 2.0 * support * h;
    for &a in &p.axes {
        let len = p.hi[a] - p.lo[a];
        if len < min * (1.0 - 1e-9) {
            return Err(SceneError(format!(
                "periodic.hi: the periodic length along axis {a} is {} m, below twice the kernel support, 2 x {support} h = {} m (h = h_factor {} x spacing {} m of bodies[{b}]); a particle would miss a neighbour's second image",
                short(len),
                short(min),
                s.h_factor,
                short(dx),
            )));
        }
    }
    Ok(())
}

/// `v` in `e` notation with at most 6 significant digits (`1.04e-3`, not
/// `1.0400000000000001e-3`).
fn short(v: f64) -> String {
    let s = format!("{v:.5e}");
    match s.split_once('e') {
        Some((m, e)) if m.contains('.') => {
            format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => s,
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::parse;

    const STRIP: &str = include_str!("../../../../cases/sound_cu_2d.toml");

    #[test]
    fn periodic_length_below_twice_the_support_is_refused() {
        // spacing 1e-4 m, strip 1e-3 m wide, Wendland C2 (support 2 h)
        let at = |hf: f64| parse(STRIP, "strip", &[format!("h_factor={hf}")]);
        assert!(at(1.2).is_ok());
        // 2 x 2 x 2.5 x 1e-4 = 1e-3: exactly the minimum is accepted
        assert!(at(2.5).is_ok());
        let e = at(2.6).unwrap_err().0;
        assert!(
            e.contains("periodic.hi: the periodic length along axis 1 is 1e-3 m")
                && e.contains("= 1.04e-3 m (h = h_factor 2.6 x spacing 1e-4 m of bodies[0])"),
            "{e}"
        );
        // the Gaussian-like kernel reaches 3 h
        let e = parse(
            STRIP,
            "strip",
            &["kernel=\"gaussian\"".into(), "h_factor=2".into()],
        )
        .unwrap_err()
        .0;
        assert!(e.contains("2 x 3 h = 1.2e-3 m"), "{e}");
        // resolution_scale refines the spacing, hence h
        assert!(parse(
            STRIP,
            "strip",
            &["h_factor=2.6".into(), "resolution_scale=2".into()]
        )
        .is_ok());
    }
}
