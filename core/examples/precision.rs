//! What double precision buys (issue 28 item 4): the flyer plate of seed 000 §4.1 (the
//! firmware's case, `ts1` with strength and plasticity, one thread, the portable loops)
//! stepped with `gsph-core` alone at several resolutions, in the precision this build's
//! `Real` has (`f64`, or `f32` with the feature `f32`), and measured against the exact
//! solution ([`gsph_core::exact::FlyerPlate`]) as `gsph study` measures the flyer plate:
//! the mean |sigma_xx - exact| over the particles, relative to the final stress.
//!
//! ```text
//! cargo run --release -p gsph-core --example precision --no-default-features \
//!     --features dim1,scheme-ts,effects-strength [--features f32] -- [N ...]
//! ```
//!
//! Prints one CSV row per particle count N (default 200 400 800 1600; the plate is
//! [0, 1] cm, the left half the flyer): `precision,n,steps,l1_error_relative,
//! energy_rel_error,peak_sigma_xx_pa,step_seconds,us_per_particle_step`. The time is that of
//! the step function alone (the O(N²) neighbour search before each step is left out: it
//! is the same code in both precisions and not the solver's). `scripts/precision.sh`
//! builds both precisions and runs them in interleaved rounds.

// `as f64` widens `Real` in the `f32` build and is the identity in the `f64` one
#![allow(clippy::unnecessary_cast)]

use gsph_core::dispatch::select_1d;
use gsph_core::effects::EffectSet;
use gsph_core::exact::{FlyerPlate, FlyerPlateParams};
use gsph_core::exec::Serial;
use gsph_core::kernel::Kernel;
use gsph_core::material::eos::Hugoniot;
use gsph_core::material::{Material, Strength};
use gsph_core::math::{Real, Sym3, Vector};
use gsph_core::neighbors::{build_naive, NeighborList, Periodic};
use gsph_core::schemes::*;
use gsph_core::state::*;
use std::time::Instant;

/// The precision of `Real` in this build.
const PRECISION: &str = if core::mem::size_of::<Real>() == 4 {
    "f32"
} else {
    "f64"
};

/// Plate length, m (seed 000: [0, 1] cm, the interface at 0.5 cm).
const LENGTH: f64 = 0.01;
/// Neighbour capacity per particle (2h = 2.4 spacings: four neighbours, more under
/// compression).
const CAP: usize = 8;
/// The step's effects: the firmware's specialisation.
const EFFECTS: EffectSet = EffectSet::STRENGTH.union(EffectSet::PLASTICITY);

/// One run's result.
struct Row {
    steps: u32,
    l1_relative: f64,
    energy_rel_error: f64,
    peak_sigma: f64,
    seconds: f64,
}

fn material() -> Material {
    let p = FlyerPlateParams::seed000();
    Material {
        rho0: p.rho0,
        eos: gsph_core::material::Eos::Hugoniot(Hugoniot {
            rho0: p.rho0,
            c0: p.c0,
            s1: p.s1,
        }),
        shear_modulus: p.shear_modulus,
        strength: Strength::VonMises {
            yield_stress: p.yield_stress,
        },
        tensile_strength: Real::INFINITY,
    }
}

fn run(n: usize, sol: &FlyerPlate) -> Result<Row, String> {
    let mat = material();
    let mats = [mat];
    let dx = (LENGTH / n as f64) as Real;
    let v0 = sol.params().impact_velocity;
    let mut x: Vec<Vector<1>> = (0..n)
        .map(|i| Vector::<1>::new((i as Real + 0.5) * dx))
        .collect();
    let mut v: Vec<Vector<1>> = (0..n)
        .map(|i| Vector::<1>::new(if i < n / 2 { v0 } else { 0.0 }))
        .collect();
    let m = vec![mat.rho0 * dx; n];
    let mt = vec![0u16; n];
    let mut rho = vec![mat.rho0; n];
    let mut e = vec![0.0; n];
    let eos = mat.eos(mat.rho0, 0.0);
    let mut p = vec![eos.p; n];
    let mut c = vec![gsph_core::math::real::sqrt(eos.c2); n];
    let mut cl = vec![mat.c_long(mat.rho0, eos.c2); n];
    let mut h = vec![1.2 * dx; n];
    let mut s = vec![Sym3::ZERO; n];
    let mut eps_p = vec![0.0; n];
    let mut sums = vec![PairSums::<1>::default(); n];
    let mut nb = vec![0u32; NeighborList::storage_len(n, CAP)];
    let mut geom = vec![PairGeom::<1>::default(); n * CAP / 2];
    let mut star = vec![TsStar { u: 0.0, p: 0.0 }; n * CAP / 2];
    let mut aux = vec![
        Aux {
            inv_rho: 0.0,
            vol: 0.0,
            ct: 0.0,
        };
        n
    ];
    let step = select_1d::<Serial>(Family::Ts, EFFECTS.kernel_part())
        .ok_or("this build lacks dim1, scheme-ts and effects-strength")?;
    let t_end: Real = 0.5e-6;
    if t_end > sol.valid_until(0.0, LENGTH as Real) {
        return Err("the exact solution does not hold until t_end".into());
    }
    let (mut t, mut steps, mut seconds) = (0.0 as Real, 0u32, 0.0f64);
    let mut e0 = None;
    while t < t_end {
        let mut list = NeighborList::new(CAP, n, &mut nb).map_err(|e| format!("{e:?}"))?;
        let hh: &[Real] = &h;
        build_naive(
            &x,
            &Periodic::none(),
            |i, j| 2.0 * 0.5 * (hh[i] + hh[j]),
            &mut list,
        )
        .map_err(|e| format!("neighbours: {e:?}"))?;
        let mut sys = System::builder()
            .x(&mut x)
            .v(&mut v)
            .m(&m)
            .mat(&mt)
            .rho(&mut rho)
            .e(&mut e)
            .p(&mut p)
            .c(&mut c)
            .cl(&mut cl)
            .h(&mut h)
            .s(&mut s)
            .eps_p(&mut eps_p)
            .build()
            .expect("every field a run stores");
        let energy = total_energy(&sys);
        e0.get_or_insert(energy);
        let dt = stable_dt(&sys, 0.5).min(t_end - t);
        let params = StepParams {
            dt,
            materials: &mats,
            kernel: Kernel::CubicSpline,
            h_factor: 1.2,
            periodic: Periodic::none(),
            nbrs: list.view(),
            options: SchemeOptions::default(),
            effects: EFFECTS,
            simd: gsph_core::simd::SimdLevel::BASELINE,
        };
        let pairs = list.view().unordered_pairs();
        let mut ws = Workspace {
            sums: &mut sums,
            grad: &mut [],
            grad_stress: &mut [],
            corr: &mut [],
            hg: &mut [],
            av: &mut [],
            art: &mut [],
            rec: &mut [],
            fac: &mut [],
            aux: &mut aux,
            geom: &mut geom[..pairs],
            ts_star: &mut star[..pairs],
            pm_star: &mut [],
            primed: false,
        };
        let t0 = Instant::now();
        step(
            &mut sys,
            &mut ws,
            &params,
            &Serial,
            &mut gsph_core::halo::NoHalo,
        )
        .map_err(|e| format!("step {}: {e}", steps + 1))?;
        seconds += t0.elapsed().as_secs_f64();
        check_finite(&sys).map_err(|e| format!("step {}: {e}", steps + 1))?;
        t += dt;
        steps += 1;
    }
    let sys = System::builder()
        .x(&mut x)
        .v(&mut v)
        .m(&m)
        .mat(&mt)
        .rho(&mut rho)
        .e(&mut e)
        .p(&mut p)
        .c(&mut c)
        .cl(&mut cl)
        .h(&mut h)
        .s(&mut s)
        .eps_p(&mut eps_p)
        .build()
        .expect("every field a run stores");
    let e1 = total_energy(&sys) as f64;
    let e0 = e0.map_or(e1, |e| e as f64);
    // the error as `gsph study` measures the flyer plate, summed in f64 in both builds
    let (mut sum, mut peak) = (0.0f64, 0.0f64);
    for i in 0..n {
        let sxx = (sys.s[i].xx - sys.p[i]) as f64;
        let exact = sol.sample(sys.x[i].x, t).0 as f64;
        sum += (sxx - exact).abs();
        peak = peak.min(sxx);
    }
    Ok(Row {
        steps,
        l1_relative: sum / n as f64 / (sol.final_stress() as f64).abs(),
        energy_rel_error: (e1 - e0) / e0,
        peak_sigma: peak,
        seconds,
    })
}

fn main() {
    let sizes: Vec<usize> = {
        let args: Vec<String> = std::env::args().skip(1).collect();
        if args.is_empty() {
            vec![200, 400, 800, 1600]
        } else {
            match args.iter().map(|a| a.parse::<usize>()).collect() {
                Ok(v) => v,
                Err(_) => {
                    eprintln!("precision: the arguments are particle counts, e.g. 200 400 800");
                    std::process::exit(2);
                }
            }
        }
    };
    let sol = match FlyerPlate::new(FlyerPlateParams::seed000()) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("precision: exact solution: {e}");
            std::process::exit(1);
        }
    };
    println!("precision,n,steps,l1_error_relative,energy_rel_error,peak_sigma_xx_pa,step_seconds,us_per_particle_step");
    for n in sizes {
        if n < 4 || n % 2 != 0 {
            eprintln!("precision: N = {n}: an even count of at least 4");
            std::process::exit(2);
        }
        match run(n, &sol) {
            Ok(r) => println!(
                "{PRECISION},{n},{},{:.6e},{:.3e},{:.6e},{:.4},{:.4}",
                r.steps,
                r.l1_relative,
                r.energy_rel_error,
                r.peak_sigma,
                r.seconds,
                r.seconds * 1e6 / (r.steps as f64 * n as f64)
            ),
            Err(e) => {
                eprintln!("precision: N = {n}: {e}");
                std::process::exit(1);
            }
        }
    }
}
