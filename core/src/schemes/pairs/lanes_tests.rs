//! The vectorised loops against the portable ones, bit for bit.

extern crate std;

use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::math::{Lcg, Real, Vector};
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::schemes::options::SchemeOptions;
use crate::schemes::pairs::geometry_pass;
use crate::schemes::workspace::StepParams;
use crate::simd::SimdLevel;
use crate::state::PairGeom;
use std::format;
use std::vec;
use std::vec::Vec;

#[derive(Clone, Copy, Debug)]
struct Hydro;
impl Effects for Hydro {
    const STRENGTH: bool = false;
    const CORRECTION: bool = false;
    const MUSCL: bool = false;
    const SET: EffectSet = EffectSet::HYDRO;
}

/// The pair geometry and artificial-stress factors of `n` jittered particles with
/// scattered smoothing lengths (some pairs of the lists lie outside the support, some
/// particles have a partial last group of four) at `simd`; `periodic`: in a box periodic
/// along x, with pairs across its faces.
fn geometry<const D: usize>(
    simd: SimdLevel,
    kernel: Kernel,
    exponent: Option<u32>,
    seed: u64,
    periodic: bool,
) -> (Vec<PairGeom<D>>, Vec<Real>) {
    const CAP: usize = 96;
    let side = match D {
        1 => 40,
        2 => 9,
        _ => 4,
    };
    let n = (0..D).fold(1, |a, _| a * side);
    let mut rng = Lcg(seed);
    let x: Vec<Vector<D>> = (0..n)
        .map(|i| {
            let mut c = i;
            Vector::<D>::from_fn(|_, _| {
                let k = c % side;
                c /= side;
                1e-3 * (k as Real + 0.3 * (rng.unit() - 0.5)) - 0.01
            })
        })
        .collect();
    let h: Vec<Real> = (0..n).map(|_| 1e-3 * (1.0 + 0.6 * rng.unit())).collect();
    let mut boxed = Periodic::<D>::none();
    if periodic {
        // positions 1e-3 (k +- 0.15) - 0.01, k below `side`
        boxed.lo[0] = -0.0105;
        boxed.len[0] = 1e-3 * side as Real;
        boxed.axes[0] = true;
    }
    let mut storage = vec![0u32; NeighborList::storage_len(n, CAP)];
    let mut list = NeighborList::new(CAP, n, &mut storage).unwrap();
    let hmax = h.iter().cloned().fold(0.0, Real::max);
    build_naive(&x, &boxed, |_, _| 1.2 * kernel.support() * hmax, &mut list).unwrap();
    let mut options = SchemeOptions::default();
    let mut effects = EffectSet::HYDRO;
    if periodic {
        effects = effects.union(EffectSet::PERIODIC);
        let across = (0..n).any(|i| {
            list.view()
                .of(i)
                .iter()
                .any(|&j| (x[i][0] - x[j as usize][0]).abs() > 0.5 * boxed.len[0])
        });
        assert!(across, "{D}D: no pair across the periodic faces");
    }
    if let Some(e) = exponent {
        options.artificial_stress = 0.3;
        options.artificial_stress_exponent = e;
        effects = effects.union(EffectSet::ARTIFICIAL_STRESS);
    }
    let params = StepParams {
        dt: 0.0,
        materials: &[],
        kernel,
        h_factor: 1.5,
        periodic: boxed,
        nbrs: list.view(),
        options,
        effects,
        simd,
    };
    let pairs = list.view().unordered_pairs();
    let mut geom = vec![PairGeom::<D>::default(); pairs];
    let mut fac = vec![0.0; if exponent.is_some() { pairs } else { 0 }];
    geometry_pass::<D, Hydro, Serial>(&x, &h, &params, &mut geom, &mut fac, &Serial);
    assert!(
        geom.iter().any(|g| g.r == 0.0),
        "some pairs outside the support"
    );
    assert!(geom.iter().filter(|g| g.r > 0.0).count() > pairs / 4);
    (geom, fac)
}

fn bits<const D: usize>(g: &[PairGeom<D>]) -> Vec<u64> {
    g.iter()
        .flat_map(|g| {
            g.n.iter()
                .chain([&g.r, &g.dw])
                .map(|v| v.to_bits())
                .collect::<Vec<_>>()
        })
        .collect()
}

fn same_geometry<const D: usize>() {
    for level in crate::simd::tested_levels() {
        same_geometry_at::<D>(level);
    }
}

fn same_geometry_at<const D: usize>(level: SimdLevel) {
    for kernel in [Kernel::CubicSpline, Kernel::WendlandC2, Kernel::Gaussian] {
        for exponent in [None, Some(4), Some(0), Some(3)] {
            for (seed, periodic) in [1, 2, 3].into_iter().flat_map(|s| [(s, false), (s, true)]) {
                let base = geometry::<D>(SimdLevel::BASELINE, kernel, exponent, seed, periodic);
                let (g0, f0) = base;
                let (g1, f1) = geometry::<D>(level, kernel, exponent, seed, periodic);
                let at = level.get();
                let case = format!("{at} {kernel} {D}D {exponent:?} seed {seed} {periodic}");
                assert_eq!(bits(&g0), bits(&g1), "{case}");
                let fb = |f: &[Real]| f.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(fb(&f0), fb(&f1), "{case}");
            }
        }
    }
}

#[test]
fn vectorised_pair_geometry_is_bitwise_the_portable_one_1d() {
    same_geometry::<1>();
}

#[test]
fn vectorised_pair_geometry_is_bitwise_the_portable_one_2d() {
    same_geometry::<2>();
}

#[test]
fn vectorised_pair_geometry_is_bitwise_the_portable_one_3d() {
    same_geometry::<3>();
}
