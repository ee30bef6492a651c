//! Pair-loop throughput: pair interactions per second of one `Sim::step` for every scheme
//! (`av`, `pm`, `ts1`, `ts2`, `tkc`) in 1D, 2D and 3D, on one thread and on all threads.
//!
//! Each dimension steps a uniform block of the flyer-plate material (Hugoniot EOS, von Mises,
//! cubic spline, h_factor 1.2), so the specialisation is hydro + strength + plasticity (plus
//! what the scheme itself adds). The block carries a standing-wave velocity field (amplitude
//! `AMPLITUDE`, wavelength `WAVELENGTH` spacings, longitudinal plus transverse in 2D/3D), so
//! every pair has a real velocity and stress jump for the Riemann solves and limiters. dt is
//! the CFL 0.5 step of the initial state. The block is rebuilt (untimed) every `MAX_STEPS`
//! steps, so particles move at most a few hundredths of a spacing: the neighbour lists
//! (default skin 0.1) are built before timing and not rebuilt inside it (the bench counts
//! rebuilds in timed steps and prints them on stderr). Only `sim.step` is timed.
//!
//! Criterion reports elements/s = pair interactions per second (directed pairs in the lists,
//! as counted by `sim.pair_interactions`; in 3D the lists include the sqrt(6)-spacing shell
//! just outside the kernel support). Ids are `SCHEME/1t` (a rayon pool of one thread) and
//! `SCHEME/all` (a pool of all threads).
//!
//! At the end of each dimension it prints, per pool, the pair rate and the microseconds per
//! particle-step of every scheme with the ratio to av.
//!
//! Run: `cargo bench -p gsph --bench pair_loop` (under 2 minutes on 2 cores).

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use gsph::scene::{build_particles, parse};
use gsph::sim::Sim;
use std::time::{Duration, Instant};

/// Schemes compared; `av` is the baseline.
const SCHEMES: [&str; 5] = ["av", "pm", "ts1", "ts2", "tkc"];
/// Lattice spacing, m.
const SPACING: f64 = 1.0e-4;
/// Velocity amplitude of the standing wave, m/s.
const AMPLITUDE: f64 = 5.0;
/// Wavelength of the standing wave, in spacings.
const WAVELENGTH: f64 = 16.0;
/// Steps before the block is rebuilt (bounds drift, and growth in schemes that amplify it).
const MAX_STEPS: u64 = 40;

/// Particles along each axis per dimension (comparable pairs per step).
fn particles_per_axis(dim: usize) -> usize {
    match dim {
        1 => 40_000,
        2 => 90,
        _ => 14,
    }
}

/// The scene: one block of the flyer-plate material, `n` spacings along each axis.
fn scene_text(dim: usize, scheme: &str, n: usize) -> String {
    let len = n as f64 * SPACING;
    let shape = if dim == 1 {
        format!("{{ type = \"segment\", min = 0.0, max = {len:e} }}")
    } else {
        let lo = vec!["0.0"; dim].join(", ");
        let hi = vec![format!("{len:e}"); dim].join(", ");
        format!("{{ type = \"box\", min = [{lo}], max = [{hi}] }}")
    };
    format!(
        r#"
name = "pair_loop_{dim}d"
dim = {dim}
scheme = "{scheme}"
t_end = 1.0
cfl = 0.5
kernel = "cubic_spline"
h_factor = 1.2

[[materials]]
name = "metal"
rho0 = 6100.0
shear_modulus = 48.1e9
eos = {{ type = "hugoniot", c0 = 5077.0, s1 = 1.201 }}
strength = {{ type = "von_mises", yield_stress = 2.5e9 }}

[[bodies]]
material = "metal"
shape = {shape}
spacing = {SPACING:e}
"#
    )
}

/// Builds the block for `scheme` with the standing-wave velocity field, and takes one
/// (priming) step with the returned dt.
fn block<const D: usize>(scheme: &str) -> (Sim<D>, f64) {
    let text = scene_text(D, scheme, particles_per_axis(D));
    let scene = parse(&text, "pair_loop", &[]).unwrap_or_else(|e| panic!("{e}"));
    let mut parts = build_particles(&scene).unwrap_or_else(|e| panic!("{e}"));
    let k = 2.0 * std::f64::consts::PI / (WAVELENGTH * SPACING);
    for (x, v) in parts.x.iter().zip(parts.v.iter_mut()) {
        for a in 0..D {
            let shear = if D > 1 {
                0.5 * (k * x[(a + 1) % D]).sin()
            } else {
                0.0
            };
            v[a] = AMPLITUDE * ((k * x[a]).sin() + shear);
        }
    }
    let mut sim = Sim::<D>::new(&scene, &parts).unwrap_or_else(|e| panic!("{e}"));
    let dt = sim.stable_dt(0.5);
    sim.step(dt).unwrap_or_else(|e| panic!("{e}"));
    (sim, dt)
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("rayon pool")
}

fn bench_dim<const D: usize>(c: &mut Criterion) {
    let pools = [("1t", pool(1)), ("all", pool(0))];
    let mut group = c.benchmark_group(format!("pair_loop_{D}d"));
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(1000));
    // Mean pair interactions per second over all timed steps (warm-up included), per
    // (scheme, pool), for the ratios printed at the end of the group.
    let mut rates = [[0.0f64; 2]; SCHEMES.len()];
    // and microseconds per particle-step (the unit of docs/performance.md)
    let mut us_ps = [[0.0f64; 2]; SCHEMES.len()];
    for (s, scheme) in SCHEMES.into_iter().enumerate() {
        let (mut sim, dt) = block::<D>(scheme);
        let pairs = sim.pair_interactions; // one step so far
        let (mut steps, mut rebuilds) = (0u64, 0u64);
        group.throughput(Throughput::Elements(pairs));
        for (p, (label, pool)) in pools.iter().enumerate() {
            let (mut timed, mut n) = (Duration::ZERO, 0u64);
            group.bench_function(BenchmarkId::new(scheme, label), |b| {
                pool.install(|| {
                    b.iter_custom(|iters| {
                        let mut time = Duration::ZERO;
                        for _ in 0..iters {
                            if sim.step > MAX_STEPS {
                                sim = block::<D>(scheme).0;
                            }
                            let r = sim.rebuilds;
                            let t0 = Instant::now();
                            sim.step(dt).unwrap_or_else(|e| panic!("{e}"));
                            time += t0.elapsed();
                            rebuilds += sim.rebuilds - r;
                        }
                        (timed, n) = (timed + time, n + iters);
                        time
                    })
                })
            });
            steps += n;
            rates[s][p] = (pairs * n) as f64 / timed.as_secs_f64();
            us_ps[s][p] = timed.as_secs_f64() * 1e6 / (n as f64 * sim.len() as f64);
        }
        eprintln!(
            "{D}D {scheme}: {} particles, {pairs} pairs/step, dt {dt:.3e} s, {steps} timed steps, {rebuilds} list rebuilds in them",
            sim.len()
        );
    }
    group.finish();
    for (p, (label, _)) in pools.iter().enumerate() {
        let av = rates[0][p];
        let line: Vec<String> = SCHEMES
            .iter()
            .zip(&rates)
            .map(|(name, r)| format!("{name} {:.1} ({:.2})", r[p] * 1e-6, r[p] / av))
            .collect();
        eprintln!("{D}D {label}: Mpairs/s (/av): {}", line.join(", "));
        let line: Vec<String> = SCHEMES
            .iter()
            .zip(&us_ps)
            .map(|(name, u)| format!("{name} {:.3} ({:.2})", u[p], u[p] / us_ps[0][p]))
            .collect();
        eprintln!("{D}D {label}: us/particle-step (/av): {}", line.join(", "));
    }
}

fn benches(c: &mut Criterion) {
    bench_dim::<1>(c);
    bench_dim::<2>(c);
    bench_dim::<3>(c);
}

// `criterion_main!` by hand: the `criterion_group!` function would lack documentation.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    benches(&mut c);
    c.final_summary();
}
