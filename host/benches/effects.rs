//! What each effect costs (DESIGN §5): time per step and bytes per particle of one 2D scene
//! as effects are added one at a time, all in the `pm` family so that only the effect
//! changes between rows.
//!
//! The scene is a uniform 2D block (`N` x `N` particles, cubic spline, h_factor 1.2) of an
//! aluminium-like material with a Mie–Grüneisen EOS, carrying a standing-wave velocity field
//! (amplitude `AMPLITUDE`, wavelength `WAVELENGTH` spacings, longitudinal plus transverse) so
//! that every pair has a real velocity and stress jump. [`ROWS`] lists the effect sets: each
//! row is the scene of an earlier row (or the base scene) plus `--set` overrides, so rows for
//! further effects (heat, damage) are appended by adding an entry, e.g.
//! `Row { label: "+ heat", extends: Some("+ plasticity"), set: &["materials.0.strength={ type = \"johnson_cook\", ... }"] }`.
//! The periodic row wraps y with period equal to the block height, so the particles near the
//! y faces get neighbours across the boundary (more pairs per step than the free block:
//! that is part of the cost of the effect, and the table prints pairs per step).
//!
//! Timing: a rayon pool of ONE thread (the per-step cost of the effect, not the scaling).
//! dt is the CFL 0.5 step of the initial state. The block is rebuilt (untimed) every
//! `MAX_STEPS` steps, so particles move a few hundredths of a spacing and the neighbour
//! lists built before timing are never rebuilt inside it (rebuilds in timed steps are counted
//! and printed on stderr). Only `sim.step` is timed. Bytes per particle are
//! `Sim::bytes_per_particle` (state, workspace and neighbour lists allocated for the set).
//!
//! At the end a Markdown table is printed on stdout: effect set, time per step, microseconds
//! per particle-step, ratio to hydro-only, bytes per particle, ratio, pairs per step. Time
//! per step is the mean over all timed steps of the row (warm-up included).
//!
//! Run: `cargo bench -p gsph --bench effects` (under a minute on 2 cores, after the build).

use criterion::{Criterion, SamplingMode};
use gsph::scene::{build_particles, parse};
use gsph::sim::Sim;
use std::time::{Duration, Instant};

/// Particles along each axis.
const N: usize = 80;
/// Lattice spacing, m.
const SPACING: f64 = 1.0e-4;
/// Velocity amplitude of the standing wave, m/s.
const AMPLITUDE: f64 = 5.0;
/// Wavelength of the standing wave, in spacings (divides `N`, so the field is periodic).
const WAVELENGTH: f64 = 16.0;
/// Steps before the block is rebuilt (bounds drift and neighbour-list staleness).
const MAX_STEPS: u64 = 40;

/// One row of the table: an effect set, as the scene of an earlier row plus overrides.
struct Row {
    /// Label in the table (the effect added).
    label: &'static str,
    /// The row whose scene this one extends (`None`: the base, hydro-only scene).
    extends: Option<&'static str>,
    /// `--set KEY=VALUE` overrides applied on top of that scene.
    set: &'static [&'static str],
}

/// The effect sets measured, in order; the first is the baseline of the ratios.
const ROWS: &[Row] = &[
    Row {
        label: "hydro",
        extends: None,
        set: &[],
    },
    Row {
        label: "+ strength",
        extends: Some("hydro"),
        set: &[
            "materials.0.shear_modulus=27.6e9",
            "materials.0.strength={ type = \"elastic\" }",
        ],
    },
    Row {
        label: "+ plasticity",
        extends: Some("+ strength"),
        // Low enough that part of the block yields within the timed steps.
        set: &["materials.0.strength={ type = \"von_mises\", yield_stress = 1.0e7 }"],
    },
    Row {
        label: "+ correction",
        extends: Some("+ plasticity"),
        set: &["options.correction=true"],
    },
    Row {
        label: "+ muscl (= tkc)",
        extends: Some("+ correction"),
        set: &["options.muscl=true", "options.limiter=minmod"],
    },
    Row {
        label: "+ periodic (y)",
        extends: Some("+ muscl (= tkc)"),
        set: &[
            "periodic.axes=[1]",
            "periodic.lo=[0.0, 0.0]",
            // N * SPACING: the block height.
            "periodic.hi=[8.0e-3, 8.0e-3]",
        ],
    },
    // Monaghan's artificial stress (cases/rings.toml's eps = 0.3, n = 4) on the elastic block.
    Row {
        label: "+ artificial stress",
        extends: Some("+ strength"),
        set: &["options.artificial_stress=0.3"],
    },
    // Heat and damage replace the von Mises model of "+ plasticity" (they come with their
    // strength models): Johnson–Cook (seed 000 table 4 steel, yield lowered so that the
    // block yields) tracks temperature; JH1 (table 4 SiC, strengths lowered likewise)
    // accumulates damage.
    Row {
        label: "+ heat (Johnson-Cook)",
        extends: Some("+ strength"),
        set: &["materials.0.strength={ type = \"johnson_cook\", a = 1.0e7, b = 1.0e8, n = 0.65, c = 0.07, m = 1.0, t_room = 298.0, t_melt = 1673.0, specific_heat = 440.0, taylor_quinney = 0.9 }"],
    },
    Row {
        label: "+ damage (JH1)",
        extends: Some("+ strength"),
        set: &["materials.0.strength={ type = \"jh1\", sigma_i1 = 1.0e7, p1 = 2.5e9, sigma_i2 = 1.7e7, p2 = 10.0e9, sigma_f_max = 1.3e6, c_f = 0.4, tensile_limit = -0.75e9, eps_f_max = 0.8, p_max = 99.75e9, c = 0.009 }"],
    },
];

/// The base scene: a hydro-only (fluid) block, scheme pm.
fn base_scene() -> String {
    let len = N as f64 * SPACING;
    format!(
        r#"
name = "effects_2d"
dim = 2
scheme = "pm"
t_end = 1.0
cfl = 0.5
kernel = "cubic_spline"
h_factor = 1.2

[[materials]]
name = "aluminium"
rho0 = 2785.0
eos = {{ type = "mie_gruneisen", c0 = 5328.0, s1 = 1.338, gamma0 = 2.0 }}

[[bodies]]
material = "aluminium"
shape = {{ type = "box", min = [0.0, 0.0], max = [{len:e}, {len:e}] }}
spacing = {SPACING:e}
"#
    )
}

/// All overrides of a row (those of the rows it extends first).
fn overrides(label: &str) -> Vec<String> {
    let row = ROWS
        .iter()
        .find(|r| r.label == label)
        .unwrap_or_else(|| panic!("no row `{label}`"));
    let mut out = row.extends.map(overrides).unwrap_or_default();
    out.extend(row.set.iter().map(|s| s.to_string()));
    out
}

/// Builds the block of a row with the standing-wave velocity field, and takes one (priming)
/// step with the returned dt.
fn block(row: &Row) -> (Sim<2>, f64) {
    let scene = parse(&base_scene(), "effects", &overrides(row.label))
        .unwrap_or_else(|e| panic!("{}: {e}", row.label));
    let mut parts = build_particles(&scene).unwrap_or_else(|e| panic!("{e}"));
    let k = 2.0 * std::f64::consts::PI / (WAVELENGTH * SPACING);
    for (x, v) in parts.x.iter().zip(parts.v.iter_mut()) {
        for a in 0..2 {
            v[a] = AMPLITUDE * ((k * x[a]).sin() + 0.5 * (k * x[1 - a]).sin());
        }
    }
    let mut sim = Sim::<2>::new(&scene, &parts).unwrap_or_else(|e| panic!("{e}"));
    let dt = sim.stable_dt(0.5);
    sim.step(dt).unwrap_or_else(|e| panic!("{e}"));
    (sim, dt)
}

/// What one row measured.
struct Measured {
    effects: String,
    ms_per_step: f64,
    bytes: usize,
    pairs: u64,
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("rayon pool");
    let mut group = c.benchmark_group("effects_2d");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(1000));
    let mut measured = Vec::new();
    for row in ROWS {
        let (mut sim, dt) = block(row);
        let pairs = sim.pair_interactions; // one step so far
        let (mut timed, mut steps, mut rebuilds) = (Duration::ZERO, 0u64, 0u64);
        group.bench_function(row.label, |b| {
            pool.install(|| {
                b.iter_custom(|iters| {
                    let mut time = Duration::ZERO;
                    for _ in 0..iters {
                        if sim.step > MAX_STEPS {
                            sim = block(row).0;
                        }
                        let r = sim.rebuilds;
                        let t0 = Instant::now();
                        sim.step(dt).unwrap_or_else(|e| panic!("{e}"));
                        time += t0.elapsed();
                        rebuilds += sim.rebuilds - r;
                    }
                    (timed, steps) = (timed + time, steps + iters);
                    time
                })
            })
        });
        let yielded = sim.eps_p.iter().filter(|&&e| e > 0.0).count();
        eprintln!(
            "{}: effects {}, {} particles, {pairs} pairs/step, dt {dt:.3e} s, {steps} timed steps, {rebuilds} list rebuilds in them, {yielded} particles yielded (last block)",
            row.label,
            sim.effects,
            sim.len()
        );
        measured.push(Measured {
            effects: sim.effects.to_string(),
            ms_per_step: timed.as_secs_f64() * 1e3 / steps.max(1) as f64,
            bytes: sim.bytes_per_particle(),
            pairs,
        });
    }
    group.finish();
    c.final_summary();

    let base = &measured[0];
    println!(
        "\nEffect costs, 2D pm family, {} particles, one rayon thread:\n",
        N * N
    );
    println!("| effect set | time/step (ms) | us/particle-step | / hydro | bytes/particle | / hydro | pairs/step |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (row, m) in ROWS.iter().zip(&measured) {
        println!(
            "| {} (`{}`) | {:.2} | {:.3} | {:.2} | {} | {:.2} | {} |",
            row.label,
            m.effects,
            m.ms_per_step,
            m.ms_per_step * 1e3 / (N * N) as f64,
            m.ms_per_step / base.ms_per_step,
            m.bytes,
            m.bytes as f64 / base.bytes as f64,
            m.pairs
        );
    }
}
