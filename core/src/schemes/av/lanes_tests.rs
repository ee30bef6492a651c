//! `av`'s vectorised pair loop against the portable one, bit for bit: every rate of every
//! particle.

extern crate std;

use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::math::{Matrix, Real};
use crate::schemes::av::pairs::rates;
use crate::schemes::av::record_len;
use crate::schemes::av::records::AvRates;
use crate::schemes::options::SchemeOptions;
use crate::schemes::star_tests::{scene, with_pairs};
use crate::schemes::workspace::{StepParams, Workspace};
use crate::simd::SimdLevel;
use crate::state::{Aux, System};
use std::vec;
use std::vec::Vec;

macro_rules! effects {
    ($name:ident, $strength:expr, $set:expr) => {
        #[derive(Clone, Copy, Debug)]
        struct $name;
        impl Effects for $name {
            const STRENGTH: bool = $strength;
            const CORRECTION: bool = false;
            const MUSCL: bool = false;
            const SET: EffectSet = $set;
        }
    };
}
effects!(
    Solid,
    true,
    EffectSet::STRENGTH.union(EffectSet::ARTIFICIAL_STRESS)
);
effects!(SolidPlain, true, EffectSet::STRENGTH);
effects!(Fluid, false, EffectSet::ARTIFICIAL_STRESS);

/// The rates of every particle by `av`'s pair loop with `params` (records given or not).
fn all_rates<const D: usize, E: Effects>(
    sys: &System<'_, D>,
    params: &StepParams<'_, D>,
    records: bool,
) -> Vec<AvRates<D>> {
    let n = sys.x.len();
    let mut av = vec![AvRates::<D>::default(); n];
    let mut art = vec![Matrix::<D>::zeros(); n];
    let mut aux = vec![Aux::default(); n];
    // stale values the loop must overwrite, not read
    let mut rec = vec![Real::NAN; if records { n * record_len(D) } else { 0 }];
    let mut ws = Workspace {
        sums: &mut [],
        grad: &mut [],
        grad_stress: &mut [],
        corr: &mut [],
        hg: &mut [],
        av: &mut av,
        art: &mut art,
        rec: &mut rec,
        geom: &mut [],
        fac: &mut [],
        aux: &mut aux,
        ts_star: &mut [],
        pm_star: &mut [],
        primed: false,
    };
    rates::<D, E, Serial>(sys, &mut ws, params, &Serial);
    av
}

fn bits<const D: usize>(r: &AvRates<D>) -> Vec<u64> {
    let mut b: Vec<u64> = r.acc.iter().map(|x| x.to_bits()).collect();
    b.extend([r.de, r.drho, r.rate].map(|x| x.to_bits()));
    b.extend(r.ds.to_array().map(|x| x.to_bits()));
    b
}

/// Every particle's rates at `level` (records given) against the baseline and against
/// `level` without records (the portable loop): asserts every bit equal, and that nine
/// particles in ten have a finite, non-zero acceleration to compare; `periodic`: in a box
/// periodic along x, with pairs across its faces.
fn same_rates<const D: usize, E: Effects>(
    level: SimdLevel,
    kernel: Kernel,
    seed: u64,
    periodic: bool,
) {
    let mut sc = scene::<D>(seed);
    if periodic {
        sc.periodic_along_x();
    }
    // no zero densities (the star tests' fallback case): here their infinite 1/rho
    // would make every neighbour's rates NaN, and the comparison toothless
    for r in sc.rho.iter_mut().filter(|r| **r == 0.0) {
        *r = 6100.0;
    }
    let options = SchemeOptions {
        av_alpha: 1.0,
        av_beta: 2.0,
        ..SchemeOptions::default()
    };
    with_pairs::<D, E>(level, &mut sc, options, |sys, params, _| {
        if periodic {
            // some pairs lie across the box's faces: their minimum image is not x_i - x_j
            let len = params.periodic.len[0];
            let across = (0..sys.x.len()).any(|i| {
                let row = params.nbrs.of(i);
                row.iter()
                    .any(|&j| (sys.x[i][0] - sys.x[j as usize][0]).abs() > 0.5 * len)
            });
            assert!(across, "{D}D: no pair across the periodic faces");
        }
        let vectorised = StepParams { kernel, ..*params };
        let base = StepParams {
            simd: SimdLevel::BASELINE,
            ..vectorised
        };
        let want = all_rates::<D, E>(sys, &base, true);
        let got = all_rates::<D, E>(sys, &vectorised, true);
        let portable = all_rates::<D, E>(sys, &vectorised, false);
        let at = level.get();
        for (i, ((w, g), p)) in want.iter().zip(&got).zip(&portable).enumerate() {
            assert_eq!(
                bits(w),
                bits(p),
                "{at} {D}D {kernel} seed {seed}: particle {i}"
            );
            assert_eq!(
                bits(w),
                bits(g),
                "{at} {D}D {kernel} seed {seed}: particle {i}: {w:?} against {g:?}"
            );
        }
        // the loop met what it must handle: viscosity, artificial stress, failed
        // particles (damage 1) and pairs outside the support
        let moving = want
            .iter()
            .filter(|r| r.acc.norm() > 0.0 && r.acc.norm().is_finite())
            .count();
        assert!(moving > want.len() * 9 / 10, "{moving} of {}", want.len());
    });
}

fn all<const D: usize>() {
    for level in crate::simd::tested_levels() {
        for seed in 1..4 {
            for kernel in [Kernel::CubicSpline, Kernel::WendlandC2, Kernel::Gaussian] {
                for periodic in [false, true] {
                    same_rates::<D, Solid>(level, kernel, seed, periodic);
                    same_rates::<D, SolidPlain>(level, kernel, seed, periodic);
                    same_rates::<D, Fluid>(level, kernel, seed, periodic);
                }
            }
        }
    }
}

#[test]
fn vectorised_av_rates_are_bitwise_the_portable_ones_1d() {
    all::<1>();
}
#[test]
fn vectorised_av_rates_are_bitwise_the_portable_ones_2d() {
    all::<2>();
}
#[test]
fn vectorised_av_rates_are_bitwise_the_portable_ones_3d() {
    all::<3>();
}
