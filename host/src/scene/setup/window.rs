//! The moving window's geometry (seed 004 §3, fig 6), resolved from the `[window]` section
//! ([`WindowSpec`]) and the scene's one body.

use crate::scene::spec::{BodySpec, Scene, ShapeSpec};
use crate::scene::{SceneError, WindowSpec};

/// The window's geometry in metres, resolved from the spec and the body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowGeometry {
    /// Exit boundary x_l (particles past it are removed).
    pub x_l: f64,
    /// Entry boundary x_r.
    pub x_r: f64,
    /// Feed sample length.
    pub feed: f64,
    /// Entry region width.
    pub d_in: f64,
    /// Exit regions 1+2 width.
    pub d_out1: f64,
    /// Exit region 2 width.
    pub d_out2: f64,
    /// Lattice spacing along x as built.
    pub dx: f64,
}

fn fail<T>(key: &str, msg: impl std::fmt::Display) -> Result<T, SceneError> {
    Err(SceneError(format!("window.{key}: {msg}")))
}

fn near_integer(v: f64) -> Option<usize> {
    let r = v.round();
    ((v - r).abs() < 1e-6 * v.abs().max(1.0) && r >= 1.0).then_some(r as usize)
}

impl WindowSpec {
    /// Checks the window against its scene and resolves the geometry.
    pub fn geometry(&self, s: &Scene) -> Result<WindowGeometry, SceneError> {
        let (min, max) = self.check_setting(s)?;
        let b = &s.bodies[0];
        let len = max - min;
        let n = (len / (b.spacing / s.resolution_scale)).round().max(1.0);
        let dx = len / n;
        let feed = self.feed_length(b, len, dx)?;
        let width = |key: &str, v: Option<f64>, default: f64| -> Result<f64, SceneError> {
            let v = v.unwrap_or(default);
            if v.is_finite() && v >= 0.0 {
                Ok(v)
            } else {
                fail(key, format!("must be non-negative and finite (got {v})"))
            }
        };
        let d_in = width("d_in", self.d_in, 4.0 * dx)?;
        let d_out1 = width("d_out1", self.d_out1, 8.0 * dx)?;
        let d_out2 = width("d_out2", self.d_out2, 4.0 * dx)?;
        if d_out2 > d_out1 {
            return fail(
                "d_out2",
                "must not exceed d_out1 (region 2 lies inside region 1+2)",
            );
        }
        if d_in + d_out1 + feed >= len {
            return fail(
                "d_out1",
                format!("entry and exit regions plus one feed length must leave room in the {len:e} m window"),
            );
        }
        Ok(WindowGeometry {
            x_l: min,
            x_r: max,
            feed,
            d_in,
            d_out1,
            d_out2,
            dx,
        })
    }

    /// The scene around the window (one body, a box, periodic across the flow only) and
    /// the window's speeds and exchange interval; the body's extent along the flow.
    fn check_setting(&self, s: &Scene) -> Result<(f64, f64), SceneError> {
        if s.bodies.len() != 1 {
            return Err(SceneError(format!(
                "window: a window scene holds exactly one body, the sample (got {})",
                s.bodies.len()
            )));
        }
        let b = &s.bodies[0];
        if b.driven || b.velocity.is_some() {
            return Err(SceneError(
                "bodies[0]: a window's sample takes its velocity from the window (no `velocity`, not `driven`)".into(),
            ));
        }
        let (min, max) = match &b.shape {
            ShapeSpec::Box { min, max } => (min[0], max[0]),
            ShapeSpec::Segment { min, max } => (*min, *max),
            _ => {
                return Err(SceneError(
                    "bodies[0].shape: a window's sample must be a box (or a 1D segment)".into(),
                ))
            }
        };
        for a in 1..s.dim {
            if !s.periodic.as_ref().is_some_and(|p| p.axes.contains(&a)) {
                return Err(SceneError(format!(
                    "periodic.axes: a window must be periodic across the flow (axis {a} missing)"
                )));
            }
        }
        if s.periodic.as_ref().is_some_and(|p| p.axes.contains(&0)) {
            return Err(SceneError(
                "periodic.axes: a window's flow axis (0) cannot be periodic".into(),
            ));
        }
        if !(self.up.is_finite() && self.up >= 0.0) {
            return fail(
                "up",
                format!("must be non-negative and finite (got {})", self.up),
            );
        }
        if !(self.us.is_finite() && self.us > 0.0) {
            return fail(
                "us",
                format!("must be positive and finite (got {})", self.us),
            );
        }
        if self.every == 0 {
            return fail("every", "must be at least 1");
        }
        Ok((min, max))
    }

    /// The feed sample's length (given, else the pore cell along x, else 4 spacings): a
    /// whole number of spacings and of pore cells, and the sample at least 3 feeds long.
    fn feed_length(&self, b: &BodySpec, len: f64, dx: f64) -> Result<f64, SceneError> {
        let feed = match (self.feed, &b.pores) {
            (Some(f), _) => f,
            (None, Some(p)) => p.cell[0],
            (None, None) => 4.0 * dx,
        };
        if !(feed.is_finite() && feed > 0.0) {
            return fail("feed", format!("must be positive and finite (got {feed})"));
        }
        if near_integer(feed / dx).is_none() {
            return fail(
                "feed",
                format!(
                    "must be a whole number of lattice spacings ({feed:e} m, spacing {dx:e} m)"
                ),
            );
        }
        if b.pores
            .as_ref()
            .is_some_and(|p| near_integer(feed / p.cell[0]).is_none())
        {
            return fail("feed", "must be a whole number of pore cells along x");
        }
        match near_integer(len / feed) {
            Some(k) if k >= 3 => {}
            _ => {
                return fail(
                    "feed",
                    format!(
                        "the sample length {len:e} m must be a whole number (at least 3) of feed lengths {feed:e} m"
                    ),
                )
            }
        }
        Ok(feed)
    }
}
