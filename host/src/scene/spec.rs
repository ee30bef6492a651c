//! The scene schema (serde). Units are SI; every field is documented in `cases/README.md`.

pub use super::material_spec::{Eos, MaterialSpec, Strength};
pub use gsph_core::kernel::Kernel;
pub use gsph_core::schemes::options::SceneOptions;
pub use gsph_core::schemes::Scheme;
use serde::{Deserialize, Serialize};

pub(super) fn one() -> f64 {
    1.0
}
/// The CFL number when a scene sets neither `cfl` nor `dt`.
pub const DEFAULT_CFL: f64 = 0.5;
fn default_h_factor() -> f64 {
    1.2
}
fn default_skin() -> f64 {
    0.1
}
/// `spacing` left out of a body (see [`BodySpec::spacing`]).
fn no_spacing() -> f64 {
    f64::NAN
}
fn default_snapshots() -> usize {
    10
}
fn default_kernel() -> Kernel {
    Kernel::CubicSpline
}

/// A whole scene.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Case name (defaults to the file stem).
    #[serde(default)]
    pub name: Option<String>,
    /// Free text.
    #[serde(default)]
    pub description: Option<String>,
    /// Dimension: 1 (uniaxial strain), 2 (plane strain) or 3.
    pub dim: usize,
    /// Scheme: av, pm, ts1, ts2, tkc.
    pub scheme: Scheme,
    /// End time, s.
    pub t_end: f64,
    /// Factor on the number of particles along each axis (spacing / factor).
    #[serde(default = "one")]
    pub resolution_scale: f64,
    /// CFL number on h / (c_l + |v|) (default [`DEFAULT_CFL`]; excludes `dt`).
    #[serde(default)]
    pub cfl: Option<f64>,
    /// A fixed time step, s, instead of the CFL-controlled one (excludes `cfl`; a step
    /// longer than the CFL-1 limit h / (c_l + |v|) stops the run).
    #[serde(default)]
    pub dt: Option<f64>,
    /// Keep every particle's smoothing length at its initial `h_factor (m/rho)^(1/dim)`.
    #[serde(default)]
    pub constant_h: bool,
    /// Kernel: cubic_spline (default), wendland_c2, gaussian.
    #[serde(default = "default_kernel")]
    pub kernel: Kernel,
    /// Smoothing length factor: h = h_factor (m/rho)^(1/dim) (seed 004's theta is h_factor/2).
    #[serde(default = "default_h_factor")]
    pub h_factor: f64,
    /// Neighbour list capacity per particle (default by dimension and kernel).
    #[serde(default)]
    pub neighbor_capacity: Option<usize>,
    /// Relative skin of the neighbour lists.
    #[serde(default = "default_skin")]
    pub skin: f64,
    /// Stop after this many steps (safety net).
    #[serde(default)]
    pub max_steps: Option<u64>,
    /// Most particles the scene may have, and so rows of a particle file or facets of an
    /// STL file it reads (default [`crate::memory::MAX_PARTICLES`], 1e8); memory is
    /// checked separately.
    #[serde(default)]
    pub max_particles: Option<u64>,
    /// Scheme options.
    #[serde(default)]
    pub options: OptionsSpec,
    /// Output schedule.
    #[serde(default)]
    pub output: OutputSpec,
    /// Periodic boundaries.
    #[serde(default)]
    pub periodic: Option<PeriodicSpec>,
    /// Rigid walls and symmetry planes ([`super::walls`]).
    #[serde(default)]
    pub walls: Vec<super::walls::WallSpec>,
    /// Materials.
    pub materials: Vec<MaterialSpec>,
    /// Bodies.
    pub bodies: Vec<BodySpec>,
    /// Exact or analytic reference of the case.
    #[serde(default)]
    pub reference: Option<ReferenceSpec>,
    /// Quantities recorded during the run (series columns and summary keys).
    #[serde(default)]
    pub monitor: Option<MonitorSpec>,
    /// A moving observation window (seed 004 §3): see [`super::WindowSpec`].
    #[serde(default)]
    pub window: Option<super::WindowSpec>,
    /// Where each of `materials` came from, in the same order (not a scene key): `scene`
    /// (written in the scene), `library NAME` (the material library, `cases/materials/`),
    /// `include FILE`, with the keys the scene overrode or removed (`super::library`).
    #[serde(skip)]
    pub material_sources: Vec<String>,
}

/// Quantities recorded during a run.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MonitorSpec {
    /// The free back face of a target, for its peak (spall) velocity: the particles of
    /// `material` that start within one lattice spacing of the plane `x[axis] = position`.
    /// Series column `back_face_velocity` (their largest velocity component along `axis`,
    /// signed so that motion away from the target is positive); summary key
    /// `back_face_velocity_peak` (its maximum over the run).
    #[serde(default)]
    pub back_face: Option<BackFaceSpec>,
    /// A wave front moving along +`axis`: see [`FrontSpec`].
    #[serde(default)]
    pub front: Option<FrontSpec>,
    /// The centre-of-mass velocity of each body: series columns `body{k}_vx`, `_vy`,
    /// `_vz` (as many as the dimension), summary keys of the same names.
    #[serde(default)]
    pub bodies: bool,
    /// The elastic strain energy `sum V (p²/(2K) + S:S/(4G))` (K = rho0 c0² and G of each
    /// material at its reference state): series column and summary key `strain_energy`.
    #[serde(default)]
    pub strain_energy: bool,
    /// Kinetic plus elastic strain energy against its initial value (a freely vibrating or
    /// spinning elastic body keeps it; what a scheme dissipates is lost from it): series
    /// columns and summary keys `mechanical_energy` (J) and `mechanical_energy_ratio`.
    #[serde(default)]
    pub mechanical_energy: bool,
    /// Angular momentum about the z axis through the origin, `sum m (x v_y - y v_x)`
    /// (kg m²/s; per unit length in 2D): series column and summary key
    /// `angular_momentum_z`, and its change over the initial value `angular_momentum_change`
    /// ((L - L0)/|L0|).
    #[serde(default)]
    pub angular_momentum: bool,
    /// Pairs nearer than this fraction of the lattice spacing (the clumping of the tensile
    /// instability; 0 < f < 1): series columns `close_fraction` (the fraction of particles
    /// with such a neighbour) and `min_distance` (the nearest pair over the spacing);
    /// summary keys of the same names at the end and `close_fraction_max`,
    /// `min_distance_min` over the samples.
    #[serde(default)]
    pub close_pairs: Option<f64>,
    /// A rod standing on a wall (the Taylor test): series columns and summary keys
    /// `rod_length` and `rod_impact_diameter` (`crate::monitor::rod`).
    #[serde(default)]
    pub rod: Option<RodSpec>,
}

/// A rod whose axis is `axis` through `base`, standing on the plane `x[axis] = base[axis]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodSpec {
    /// Centre of the impact face at the start, m (3 components).
    pub base: Vec<f64>,
    /// The rod's axis: 0, 1 or 2.
    pub axis: usize,
}

/// The position of a wave front driven from the low end of `axis`: particles are binned
/// along `axis` (bins `bin` wide, default two spacings of the finest body) and the front is
/// the far end of the first run of bins (from the low end) whose mean velocity along `axis`
/// reaches `velocity`. Series column `front_position`; summary
/// keys `front_speed` (least-squares slope over the samples after `fit_from` of the run,
/// default 0.5), `behind_front_velocity` and `ahead_front_velocity` (mean particle velocity
/// along `axis` over `behind` m, default 10 bins, behind and ahead of the front at the end).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrontSpec {
    /// Axis of propagation (0 = x).
    #[serde(default)]
    pub axis: usize,
    /// Velocity threshold that marks the front, m/s (e.g. half the particle velocity).
    pub velocity: f64,
    /// Bin width, m.
    #[serde(default)]
    pub bin: Option<f64>,
    /// Fraction of t_end after which the front speed is fitted.
    #[serde(default)]
    pub fit_from: Option<f64>,
    /// Length behind the front over which the particle velocity is averaged, m.
    #[serde(default)]
    pub behind: Option<f64>,
}

/// A back face (see [`MonitorSpec::back_face`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackFaceSpec {
    /// Material of the target.
    pub material: String,
    /// Axis normal to the face (0 = x).
    #[serde(default)]
    pub axis: usize,
    /// Position of the face along `axis`, m.
    pub position: f64,
    /// Direction of the outward normal along `axis`: +1 or -1 (default +1).
    #[serde(default = "one")]
    pub normal: f64,
}

impl Scene {
    /// The CFL number (the scene's, or [`DEFAULT_CFL`]).
    pub fn cfl(&self) -> f64 {
        self.cfl.unwrap_or(DEFAULT_CFL)
    }

    /// Most particles the scene may have (`max_particles`, default
    /// [`crate::memory::MAX_PARTICLES`]).
    pub fn particle_limit(&self) -> usize {
        self.max_particles
            .map_or(crate::memory::MAX_PARTICLES, |n| {
                usize::try_from(n).unwrap_or(usize::MAX)
            })
    }

    /// Deserialises from a TOML table. The error is one line, `KEY: cause` (the key path
    /// as in `materials[0].rho0`), or the bare cause at the top level.
    pub fn deserialize_table(t: toml::Table) -> Result<Scene, String> {
        super::de::from_table(t).map_err(|e| e.to_string())
    }
}

/// Scheme options: the core's [`SceneOptions`] (each key is read by some schemes only and
/// refused for the others, see `scene::applies`; absent keys take the scheme's default).
pub type OptionsSpec = SceneOptions;

/// Output schedule.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Number of snapshot intervals (snapshots at t = 0, t_end/N, ..., t_end).
    #[serde(default = "default_snapshots")]
    pub snapshots: usize,
    /// Number of diagnostic samples (time series) over the run.
    #[serde(default)]
    pub series: Option<usize>,
    /// Write a checkpoint every this many steps (`gsph run`; docs/checkpoint.md).
    #[serde(default)]
    pub checkpoint_steps: Option<u64>,
    /// Write a checkpoint every this many seconds of wall time.
    #[serde(default)]
    pub checkpoint_seconds: Option<f64>,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            snapshots: default_snapshots(),
            series: None,
            checkpoint_steps: None,
            checkpoint_seconds: None,
        }
    }
}

/// Periodic boundaries: a box `[lo, hi)` on the listed axes (0 = x, 1 = y, 2 = z).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PeriodicSpec {
    /// Axes that are periodic.
    pub axes: Vec<usize>,
    /// Lower corner (all dims).
    pub lo: Vec<f64>,
    /// Upper corner (all dims).
    pub hi: Vec<f64>,
}

/// A body: a shape filled with a lattice of particles of one material.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Material name.
    pub material: String,
    /// Shape.
    pub shape: ShapeSpec,
    /// Lattice spacing, m (divided by `resolution_scale`). Required, except for a
    /// `particles` body whose file has an `m` column (each particle's spacing is then
    /// `(m/rho)^(1/dim)`); left out, it reads as NaN.
    #[serde(default = "no_spacing")]
    pub spacing: f64,
    /// Lattice: square (cartesian) or polar (concentric rings; disc and annulus only).
    #[serde(default)]
    pub lattice: Option<String>,
    /// Layout: `lattice` (the lattice as built, the default) or `relaxed` (the lattice
    /// relaxed against the shape's signed distance, so that its surface row follows the
    /// shape: a body-fitted layout; 2D and 3D shapes, not a particle file; see
    /// `setup::relax`).
    #[serde(default)]
    pub layout: Option<String>,
    /// Iterations of the `relaxed` layout (default `setup::relax::DEFAULT_ITERATIONS`).
    #[serde(default)]
    pub relax_iterations: Option<usize>,
    /// Square lattice of a disc or annulus with a node at this point relative to the
    /// centre, m: sites at `center + lattice_origin + i spacing` (i = 0, 1, … up to the
    /// half-open extent `[lattice_origin, r_outer)` on each axis), kept where
    /// `r_inner² <= r² < r_outer²`, as the peers' colliding-rings case builds its rings
    /// (`lattice_origin = [-r_outer, -r_outer]`). Default: sites offset half a spacing from
    /// the centre.
    #[serde(default)]
    pub lattice_origin: Option<Vec<f64>>,
    /// Initial velocity field.
    #[serde(default)]
    pub velocity: Option<VelocitySpec>,
    /// Initial mechanical state (default: unstressed at rho0).
    #[serde(default)]
    pub initial: Option<InitialSpec>,
    /// Pores cut out of the lattice (porous samples, seed 004 §4).
    #[serde(default)]
    pub pores: Option<PoresSpec>,
    /// A driven body (a piston): its particles keep their initial velocity and move at
    /// exactly that velocity for the whole run, whatever acts on them (external work:
    /// energy is not conserved).
    #[serde(default)]
    pub driven: bool,
    /// Random displacement of every particle from its lattice site, as a fraction of the
    /// spacing (0 <= jitter < 0.5): each coordinate moves by a uniform amount in
    /// [-jitter, jitter) spacings, from a deterministic generator keyed by particle index.
    #[serde(default)]
    pub jitter: f64,
}

/// Circular (2D) or spherical (3D) pores repeated on a periodic cell: a particle is removed
/// when its centre lies within `radius` of a pore centre or of any periodic image of one.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PoresSpec {
    /// Period of the pore pattern along each axis, m.
    pub cell: Vec<f64>,
    /// Pore centres within one cell, m (relative to `origin`).
    pub centers: Vec<Vec<f64>>,
    /// Pore radius, m.
    pub radius: f64,
    /// Corner of the first cell, m (default: the origin).
    #[serde(default)]
    pub origin: Option<Vec<f64>>,
}

/// Shapes.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// 1D interval [min, max].
    Segment {
        /// Lower end, m.
        min: f64,
        /// Upper end, m.
        max: f64,
    },
    /// Axis-aligned box (2D/3D).
    Box {
        /// Lower corner, m.
        min: Vec<f64>,
        /// Upper corner, m.
        max: Vec<f64>,
    },
    /// Circular cylinder along a coordinate axis (3D): a Cartesian lattice with an even
    /// number of sites across each diameter (the axis lies between sites, so a quarter
    /// model's symmetry planes do too), kept inside the radius; `quarter = true` keeps the
    /// sites on the positive side of both transverse axes through `base` (a quarter model
    /// with two symmetry planes, whose sites are exactly those of the whole cylinder).
    Cylinder {
        /// Centre of the base face, m.
        base: Vec<f64>,
        /// The cylinder's axis: 0, 1 or 2 (x, y, z).
        axis: usize,
        /// Radius, m.
        radius: f64,
        /// Length along `axis` from the base, m.
        length: f64,
        /// Keep only the quadrant on the positive side of the transverse axes.
        #[serde(default)]
        quarter: bool,
    },
    /// Disc (2D) or ball (3D).
    Disc {
        /// Centre, m.
        center: Vec<f64>,
        /// Radius, m.
        radius: f64,
    },
    /// Annulus (2D).
    Annulus {
        /// Centre, m.
        center: Vec<f64>,
        /// Inner radius, m.
        r_inner: f64,
        /// Outer radius, m.
        r_outer: f64,
    },
    /// Particles read from a file (relative to the scene file): a CSV file with a header
    /// naming its columns (`x` and as many of `y`, `z` as the dimension needs; optional
    /// state columns; `final.csv` of a run is one), or a `snapshots.h5` of a run. The body's
    /// `velocity` and `initial`, where given, replace the file's columns. See
    /// `super::import` and cases/README.md.
    Particles {
        /// The file.
        file: String,
        /// The step of the snapshot to read from an HDF5 file (default: its last).
        #[serde(default)]
        step: Option<u64>,
        /// Only the rows whose `material` column is this index (the material's position
        /// in the scene that wrote the file). Required when the file holds several.
        #[serde(default)]
        file_material: Option<u32>,
    },
    /// A closed triangulated surface read from an STL file (ASCII or binary; relative to
    /// the scene file), 3D only: the box lattice over its bounding box at `spacing`, kept
    /// inside the surface. Vertices are placed at `scale * vertex + offset`.
    Stl {
        /// The file.
        file: String,
        /// Factor on the file's coordinates (e.g. 1e-3 for a file in millimetres).
        #[serde(default = "one")]
        scale: f64,
        /// Translation after scaling, m (default none).
        #[serde(default)]
        offset: Option<Vec<f64>>,
    },
}

/// Initial velocity fields.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum VelocitySpec {
    /// Uniform velocity, m/s.
    Uniform {
        /// Components.
        value: Vec<f64>,
    },
    /// Radial `v = v0 r_ref / r e_r` (negative v0: inward).
    Radial {
        /// Speed at r_ref, m/s.
        v0: f64,
        /// Reference radius, m.
        r_ref: f64,
        /// Centre, m.
        center: Vec<f64>,
    },
    /// Rigid rotation about the z axis through `center`: `v = omega e_z × (x - center)`
    /// (2D and 3D); with `twist_height = H` (3D) a twist instead, the angular velocity
    /// `omega sin(pi (z - center_z) / (2 H))` growing from 0 at `z = center_z` (Lee, Gil,
    /// Ghavamian & Bonet's twisting column).
    Rotation {
        /// Angular velocity, rad/s (positive: counter-clockwise seen from +z).
        omega: f64,
        /// A point of the axis, m (its x and y; its z is the twist's base).
        center: Vec<f64>,
        /// The twist's height H, m (3D; absent: a rigid rotation).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        twist_height: Option<f64>,
    },
    /// Gaussian pulse along an axis: `v_axis = amplitude exp(-k (x - center)²)`.
    Pulse {
        /// Amplitude, m/s.
        amplitude: f64,
        /// k, 1/m².
        k: f64,
        /// Centre coordinate along the axis, m.
        center: f64,
        /// Axis (0 = x).
        #[serde(default)]
        axis: usize,
    },
    /// The first bending mode of a cantilever clamped at `root` (SPHinXsys's oscillating
    /// plate): along the beam axis `axis`, at `xi = (x_axis - root_axis)/length`, the
    /// deflection velocity `v_direction = tip phi(xi)` for `xi > 0` (0 behind the root),
    /// `phi(xi) = [M (cos k xi - cosh k xi) - N (sin k xi - sinh k xi)] / Q`,
    /// `M = sin k + sinh k`, `N = cos k + cosh k`, `Q = 2 (cos k sinh k - sin k cosh k)`,
    /// so that `phi(0) = phi'(0) = 0` (clamped) and `phi(1) = 1` (the tip moves at `tip`);
    /// `k = 1.875` (the root of `1 + cos k cosh k = 0`) is the first mode (2D and 3D).
    Cantilever {
        /// A point of the clamped face, m.
        root: Vec<f64>,
        /// Length of the free beam, m.
        length: f64,
        /// Velocity of the tip, m/s.
        tip: f64,
        /// The beam's axis (default 0, x).
        #[serde(default)]
        axis: usize,
        /// The axis the beam bends along (default 1, y).
        #[serde(default = "axis_y")]
        direction: usize,
        /// The mode's wave number `k L` (default 1.875, the first mode).
        #[serde(default = "first_cantilever_mode")]
        k: f64,
    },
}

fn axis_y() -> usize {
    1
}

fn first_cantilever_mode() -> f64 {
    1.875
}

/// `phi(xi)` of [`VelocitySpec::Cantilever`]: the cantilever mode of wave number `k`,
/// 1 at the tip (`xi = 1`), 0 with zero slope at the root (`xi = 0`).
pub fn cantilever_mode(k: f64, xi: f64) -> f64 {
    let (m, n) = (k.sin() + k.sinh(), k.cos() + k.cosh());
    let q = 2.0 * (k.cos() * k.sinh() - k.sin() * k.cosh());
    let kx = k * xi;
    (m * (kx.cos() - kx.cosh()) - n * (kx.sin() - kx.sinh())) / q
}

/// Initial mechanical states.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum InitialSpec {
    /// The state reached by uniaxial-strain compression (along x) to `sigma_xx`
    /// (tension positive): density and deviator from the EOS and the strength model.
    UniaxialStress {
        /// Target sigma_xx, Pa.
        sigma_xx: f64,
    },
    /// Given density and specific internal energy, no deviator.
    Density {
        /// Density, kg/m³.
        rho: f64,
        /// Specific internal energy, J/kg.
        #[serde(default)]
        e: f64,
    },
}

/// The exact or analytic reference of a case (what `l1_error` etc. are measured against).
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ReferenceSpec {
    /// Seed 000 §4.1: symmetric impact of identical elastic–plastic plates.
    FlyerPlate {
        /// Material of both plates (Hugoniot EOS, von Mises).
        material: String,
        /// Flyer velocity, m/s.
        impact_velocity: f64,
        /// Initial interface position, m.
        interface: f64,
    },
    /// Seed 004 §2.1.1: elastic–plastic Riemann problem with a free left end.
    ElasticPlasticRiemann {
        /// Material (logarithmic EOS, von Mises).
        material: String,
        /// Left stress sigma1, Pa.
        sigma1: f64,
        /// Initial discontinuity position, m.
        interface: f64,
        /// Free left end of the bar, m.
        x_left: f64,
    },
    /// Seed 004 §2.1.2: a Gaussian velocity pulse `amplitude exp(-k (x - center)²)` in a
    /// linear elastic solid splits into two half-amplitude pulses at c_l.
    SoundWave {
        /// Material (linear EOS, elastic).
        material: String,
        /// Pulse amplitude, m/s.
        amplitude: f64,
        /// Width parameter k, 1/m².
        k: f64,
        /// Initial centre, m (along x).
        center: f64,
    },
    /// Collapse of a cylindrical shell (2D): incompressible rigid-plastic stopping radii
    /// and radius history (ring of seed 000 §4.2, Verney cylinder of seed 004 §2.1.3).
    ShellCollapse {
        /// Material (von Mises; its rho0 and yield stress enter the solution).
        material: String,
        /// Axis of the shell, m.
        center: Vec<f64>,
        /// Initial inner radius, m.
        r_inner: f64,
        /// Initial outer radius, m.
        r_outer: f64,
        /// Initial inward speed at the inner radius, m/s.
        v0: f64,
    },
}
