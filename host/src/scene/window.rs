//! The `[window]` section: a moving observation window (seed 004 §3, fig 6) that holds a
//! stationary shock. The window is the box of the scene's one body; material flows along
//! −x, enters through the right end from a cycled feed sample and leaves through the left.
//! Its geometry is resolved against the scene in [`super::setup::window`].

use serde::Deserialize;

/// A moving observation window. In the frame of the front, material enters at
/// `u_in = −us` and leaves at `u_out = up − us`: `us` is the shock speed relative to the
/// material ahead and `up` the particle-velocity jump.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WindowSpec {
    /// Particle-velocity jump across the wave, u_out − u_in, m/s.
    pub up: f64,
    /// Shock speed, m/s: the entry velocity is −us. `gsph run` holds it fixed;
    /// `gsph hugoniot` searches for it.
    pub us: f64,
    /// Length of the feed sample along x, m (one period of the structure; default the
    /// body's pore cell along x).
    #[serde(default)]
    pub feed: Option<f64>,
    /// Width of the entry region (velocity held at u_in), m (default 4 spacings).
    #[serde(default)]
    pub d_in: Option<f64>,
    /// Width of exit regions 1 and 2 together (velocity held at u_out), m (default 8
    /// spacings).
    #[serde(default)]
    pub d_out1: Option<f64>,
    /// Width of exit region 2 (velocity held and state frozen), m (default 4 spacings).
    #[serde(default)]
    pub d_out2: Option<f64>,
    /// Steps between particle exchanges (removal past the exit, feed through the entry);
    /// each exchange rebuilds the neighbour lists.
    #[serde(default = "default_every")]
    pub every: u64,
}

fn default_every() -> u64 {
    10
}
