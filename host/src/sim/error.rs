//! Why a simulation stopped or could not start.

use gsph_core::effects::EffectSet;
use gsph_core::neighbors::NeighborError;
use gsph_core::schemes::Scheme;
use gsph_core::state::StepError;

/// Why a simulation stopped or could not start. `Display` is one line.
#[derive(Debug, Clone, PartialEq)]
pub enum SimError {
    /// Neighbour lists overflowed.
    Neighbors(NeighborError),
    /// Two particles closer than half a lattice spacing.
    Overlap {
        /// First particle id.
        i: u32,
        /// Second particle id.
        j: u32,
        /// Distance, m.
        distance: f64,
        /// Where, m.
        at: [f64; 3],
    },
    /// A step failed.
    Step {
        /// Step number (1-based).
        step: u64,
        /// Time at the start of the step, s.
        t: f64,
        /// Cause.
        cause: StepError,
    },
    /// Neighbour lists overflowed when they were rebuilt during the run.
    Rebuild {
        /// Step number (1-based).
        step: u64,
        /// Time at the start of the step, s.
        t: f64,
        /// Cause.
        cause: NeighborError,
    },
    /// A fixed time step longer than the stability limit.
    TimeStep {
        /// Step number (1-based).
        step: u64,
        /// Time at the start of the step, s.
        t: f64,
        /// The fixed step, s.
        dt: f64,
        /// The CFL-1 limit, s.
        limit: f64,
        /// The particle (id) that sets the limit.
        particle: u32,
    },
    /// The CFL step fell below [`super::DT_COLLAPSE`] times the first one.
    Collapsed {
        /// Step number (1-based).
        step: u64,
        /// Time at the start of the step, s.
        t: f64,
        /// The step, s.
        dt: f64,
        /// The first step at the same CFL, s.
        first: f64,
        /// The particle (id) that sets the step.
        particle: u32,
    },
    /// The specialisation for this scene is not compiled into this build.
    NotCompiled {
        /// Dimension.
        dim: usize,
        /// Scheme.
        scheme: Scheme,
        /// Effects.
        effects: EffectSet,
    },
    /// Another MPI rank failed (its message), or a collective step of the decomposition
    /// failed here.
    Distributed(String),
    /// A wall cannot be set up (a particle starts behind it).
    Walls(String),
    /// A scene tl cannot run as it is (bodies apart at the start).
    Reference(String),
    /// The instruction-set level asked for (`GSPH_SIMD`, `--simd`) cannot run here.
    Simd(String),
    /// The scheme family cannot run an effect the scene needs.
    Unsupported {
        /// Scheme.
        scheme: Scheme,
        /// The effects it cannot run.
        effects: EffectSet,
    },
}

impl std::fmt::Display for SimError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SimError::Neighbors(e) => write!(f, "{e}"),
            SimError::Walls(e) => write!(f, "{e}"),
            SimError::Reference(e) => write!(f, "{e}"),
            SimError::Simd(e) => write!(f, "{e}"),
            SimError::Overlap { i, j, distance, at } if *distance == 0.0 => write!(
                f,
                "particles {i} and {j} are at the same point ({:.4e}, {:.4e}, {:.4e}) (a point given twice in a particle file, or two bodies overlapping?)",
                at[0], at[1], at[2]
            ),
            SimError::Overlap { i, j, distance, at } => write!(
                f,
                "particles {i} and {j} overlap: {distance:.3e} m apart at ({:.4e}, {:.4e}, {:.4e}) (less than half the lattice spacing; do two bodies overlap?)",
                at[0], at[1], at[2]
            ),
            SimError::Step { step, t, cause } => write!(f, "step {step} (t = {t:.6e} s): {cause}"),
            SimError::Rebuild { step, t, cause } => write!(f, "step {step} (t = {t:.6e} s): {cause}"),
            SimError::TimeStep { step, t, dt, limit, particle } => write!(
                f,
                "step {step} (t = {t:.6e} s): the fixed time step dt = {dt:.4e} s exceeds the stability limit h/(c_l + |v|) = {limit:.4e} s of particle {particle} (lower `dt`, or remove it for the CFL step)"
            ),
            SimError::Collapsed { step, t, dt, first, particle } => write!(
                f,
                "step {step} (t = {t:.6e} s): the time step collapsed to {dt:.4e} s, {:.1e} of the first step {first:.4e} s, set by particle {particle} (the run has gone unstable: lower `cfl`, or see docs/stability.md)",
                dt / first
            ),
            SimError::NotCompiled { dim, scheme, effects } => {
                // One line: what is missing, and the features that compile it (docs/performance.md
                // "Compile-time-selected builds").
                let (family, effects) = (scheme.family(), effects.kernel_part());
                let features = crate::specs::features(*dim, family, effects).join(",");
                let name = crate::specs::find(*dim, family, effects).map_or("", |s| s.name);
                let (n, all) = crate::specs::compiled();
                write!(
                    f,
                    "this gsph was built without the specialisation {dim}D {} ({effects}) `{name}` (it contains {n} of {all}); rebuild with `--features {features}` or the default features",
                    scheme.name()
                )
            }
            SimError::Distributed(m) => write!(f, "{m}"),
            SimError::Unsupported { scheme, effects } => write!(
                f,
                "scheme {} cannot run the effects {effects} (no build has that specialisation; the {} family supports {})",
                scheme.name(),
                crate::specs::family_name(scheme.family()),
                scheme.family().supported()
            ),
        }
    }
}

impl std::error::Error for SimError {}
