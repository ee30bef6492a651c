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
//! A second table measures what the run-time flags (plasticity, damage, heat, periodic,
//! artificial stress: `gsph_core::effects`) cost when they are OFF, the price of compiling 42
//! steps instead of one per effect set. On the elastic block (no flag on) each scheme's
//! step is run as the dispatch table has it (every flag read at run time) and as
//! instantiations that compile one flag out, or all of them
//! (`gsph_core::effects::Effects::RUNTIME`), swapped into the same simulation. Each round
//! runs every variant for `OFF_STEPS` steps from the same state, in an order that rotates
//! between rounds; the table gives the median over `OFF_ROUNDS` rounds of each variant's
//! time over the dispatch table's, and checks that every variant ends in the same state,
//! bit for bit (a flag that is off changes nothing).
//!
//! Run: `cargo bench -p gsph --bench effects` (a few minutes on 2 cores, after the build).

use criterion::{Criterion, SamplingMode};
use gsph::exec::Rayon;
use gsph::scene::{build_particles, parse};
use gsph::sim::Sim;
use gsph_core::effects::{EffectSet, Effects};
use gsph_core::schemes::{av::Av, pm::Pm, ts::Ts, SchemeFamily, StepFn};
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

/// Steps each variant runs per round of the flags-off table.
const OFF_STEPS: u64 = 40;
/// Rounds of the flags-off table.
const OFF_ROUNDS: usize = 9;

/// A step instantiation: the compiled effects of a scheme (`S`trength, `C`orrection,
/// `M`USCL) with the run-time flags `R` read (the others compiled out).
#[derive(Clone, Copy, Debug)]
struct Variant<const S: bool, const C: bool, const M: bool, const R: u16>;

impl<const S: bool, const C: bool, const M: bool, const R: u16> Effects for Variant<S, C, M, R> {
    const STRENGTH: bool = S;
    const CORRECTION: bool = C;
    const MUSCL: bool = M;
    const SET: EffectSet = EffectSet(
        (if S { EffectSet::STRENGTH.0 } else { 0 })
            | (if C { EffectSet::CORRECTION.0 } else { 0 })
            | (if M { EffectSet::MUSCL.0 } else { 0 }),
    );
    const RUNTIME: EffectSet = EffectSet(R);
}

const ALL: u16 = EffectSet::RUNTIME.0;
const NO_PLASTICITY: u16 = ALL & !EffectSet::PLASTICITY.0;
const NO_DAMAGE: u16 = ALL & !EffectSet::DAMAGE.0;
const NO_HEAT: u16 = ALL & !EffectSet::HEAT.0;
const NO_PERIODIC: u16 = ALL & !EffectSet::PERIODIC.0;
const NO_ART: u16 = ALL & !EffectSet::ARTIFICIAL_STRESS.0;

/// The variants of one scheme's step (compiled effects `S`, `C`, `M`): the label and the
/// step, the dispatch table's first.
fn variants<F: SchemeFamily, const S: bool, const C: bool, const M: bool>(
) -> Vec<(&'static str, StepFn<2, Rayon>)> {
    vec![
        (
            "every flag read (the dispatch table)",
            F::step::<2, Variant<S, C, M, ALL>, Rayon>,
        ),
        (
            "plasticity compiled out",
            F::step::<2, Variant<S, C, M, NO_PLASTICITY>, Rayon>,
        ),
        (
            "damage compiled out",
            F::step::<2, Variant<S, C, M, NO_DAMAGE>, Rayon>,
        ),
        (
            "heat compiled out",
            F::step::<2, Variant<S, C, M, NO_HEAT>, Rayon>,
        ),
        (
            "periodic compiled out",
            F::step::<2, Variant<S, C, M, NO_PERIODIC>, Rayon>,
        ),
        (
            "artificial stress compiled out",
            F::step::<2, Variant<S, C, M, NO_ART>, Rayon>,
        ),
        (
            "every flag compiled out",
            F::step::<2, Variant<S, C, M, 0>, Rayon>,
        ),
    ]
}

/// The flags-off table of one scheme: `(label, median time over the dispatch table's)`.
fn flags_off(scheme: &str, variants: &[(&'static str, StepFn<2, Rayon>)]) -> Vec<(String, f64)> {
    let mut sets = overrides("+ strength");
    sets.push(format!("scheme={scheme}"));
    let scene = parse(&base_scene(), "effects", &sets).unwrap_or_else(|e| panic!("{e}"));
    let mut parts = build_particles(&scene).unwrap_or_else(|e| panic!("{e}"));
    let k = 2.0 * std::f64::consts::PI / (WAVELENGTH * SPACING);
    for (x, v) in parts.x.iter().zip(parts.v.iter_mut()) {
        for a in 0..2 {
            v[a] = AMPLITUDE * ((k * x[a]).sin() + 0.5 * (k * x[1 - a]).sin());
        }
    }
    let mut base = Sim::<2>::new(&scene, &parts).unwrap_or_else(|e| panic!("{e}"));
    let dt = base.stable_dt(0.5);
    base.step(dt).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        base.effects.without(EffectSet::COMPILED),
        EffectSet::HYDRO,
        "{scheme}: a run-time flag is on"
    );
    let n = variants.len();
    let mut ratios = vec![Vec::new(); n];
    let mut finals: Vec<Option<Vec<f64>>> = vec![None; n];
    for round in 0..OFF_ROUNDS {
        let mut t = vec![0.0; n];
        for q in 0..n {
            let v = (q + round) % n;
            let mut sim = base.clone();
            sim.replace_step(variants[v].1);
            let t0 = Instant::now();
            for _ in 0..OFF_STEPS {
                sim.step(dt).unwrap_or_else(|e| panic!("{e}"));
            }
            t[v] = t0.elapsed().as_secs_f64();
            let state: Vec<f64> = sim
                .x
                .iter()
                .flat_map(|x| [x[0], x[1]])
                .chain(sim.e.clone())
                .collect();
            match &finals[v] {
                None => finals[v] = Some(state),
                Some(s) => assert!(s == &state, "{scheme}: a variant is not repeatable"),
            }
        }
        for v in 0..n {
            ratios[v].push(t[v] / t[0]);
        }
    }
    for v in 1..n {
        assert!(
            finals[v] == finals[0],
            "{scheme}: `{}` ends in another state than the dispatch table's step",
            variants[v].0
        );
    }
    variants
        .iter()
        .zip(ratios)
        .map(|((label, _), mut r)| {
            r.sort_by(f64::total_cmp);
            (label.to_string(), r[r.len() / 2])
        })
        .collect()
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

    // what the run-time flags cost when they are off
    let tables = pool.install(|| {
        [
            ("av", flags_off("av", &variants::<Av, true, false, false>())),
            (
                "ts2",
                flags_off("ts2", &variants::<Ts, true, false, true>()),
            ),
            ("tkc", flags_off("tkc", &variants::<Pm, true, true, true>())),
        ]
    });
    println!(
        "\nRun-time flags when off: the elastic block ({} particles, one thread, {OFF_STEPS} steps a round), median over {OFF_ROUNDS} rounds of the time over the dispatch table's step (every flag read). A variant below 1 is what the flag costs when off:\n",
        N * N
    );
    println!("| variant | av | ts2 | tkc |");
    println!("| --- | ---: | ---: | ---: |");
    for (k, (label, _)) in tables[0].1.iter().enumerate() {
        println!(
            "| {label} | {:.3} | {:.3} | {:.3} |",
            tables[0].1[k].1, tables[1].1[k].1, tables[2].1[k].1
        );
    }
    println!("\nEvery variant ended each scheme's run in the same state, bit for bit.");
}
