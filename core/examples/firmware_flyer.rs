//! A firmware-style runner: steps the 1D flyer plate (seed 000 §4.1) with `gsph-core`
//! alone, on fixed-capacity storage (`static` arrays), with no allocator.
//!
//! On a bare-metal target (`--target thumbv7em-none-eabihf`) this file is a `no_std`,
//! `no_main` program exporting `gsph_flyer_main` for a board's startup code to call; the
//! build proves that the step (neighbour search, generated `ts1` specialisation, EOS,
//! plasticity) links without std or an allocator. On the host it runs the same code under
//! a counting global allocator and fails if the stepping allocates even once:
//!
//! ```text
//! cargo run --release -p gsph-core --example firmware_flyer
//! cargo build --release -p gsph-core --example firmware_flyer --target thumbv7em-none-eabihf
//! ```
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

mod runner {
    use gsph_core::dispatch::select_1d;
    use gsph_core::effects::EffectSet;
    use gsph_core::exec::Serial;
    use gsph_core::kernel::Kernel;
    use gsph_core::material::eos::Hugoniot;
    use gsph_core::material::{Material, Strength};
    use gsph_core::math::{Real, Sym3, Vector};
    use gsph_core::neighbors::{build_naive, NeighborList, Periodic};
    use gsph_core::state::*;

    /// Particles of the flyer plate (100 in [0, 1] cm, the left half moving).
    pub const N: usize = 100;
    /// Neighbour capacity per particle.
    pub const CAP: usize = 8;

    /// Everything the run needs, in one fixed-size block.
    pub struct Storage {
        x: [Vector<1>; N],
        v: [Vector<1>; N],
        m: [Real; N],
        mat: [u16; N],
        rho: [Real; N],
        e: [Real; N],
        p: [Real; N],
        c: [Real; N],
        cl: [Real; N],
        h: [Real; N],
        s: [Sym3; N],
        eps_p: [Real; N],
        sums: [PairSums<1>; N],
        nb: [u32; NeighborList::storage_len(N, CAP)],
        geom: [PairGeom<1>; N * CAP / 2],
        star: [TsStar; N * CAP / 2],
        aux: [Aux; N],
    }

    /// What the run reports.
    pub struct Report {
        /// Steps taken.
        pub steps: u32,
        /// Relative total-energy change (ts1 conserves it to round-off).
        #[allow(dead_code)]
        pub energy_rel_error: Real,
        /// Peak compressive sigma_xx, Pa.
        #[allow(dead_code)]
        pub min_sigma_xx: Real,
    }

    const DX: Real = 1.0e-4;
    const MATERIAL: Material = Material {
        rho0: 6100.0,
        eos: gsph_core::material::Eos::Hugoniot(Hugoniot {
            rho0: 6100.0,
            c0: 5077.0,
            s1: 1.201,
        }),
        shear_modulus: 48.1e9,
        strength: Strength::VonMises {
            yield_stress: 2.5e9,
        },
        tensile_strength: Real::INFINITY,
    };

    impl Storage {
        /// Zeroed storage (usable in a `static`).
        pub const fn new() -> Self {
            Storage {
                x: [Vector::<1>::new(0.0); N],
                v: [Vector::<1>::new(0.0); N],
                m: [0.0; N],
                mat: [0; N],
                rho: [0.0; N],
                e: [0.0; N],
                p: [0.0; N],
                c: [0.0; N],
                cl: [0.0; N],
                h: [0.0; N],
                s: [Sym3::ZERO; N],
                eps_p: [0.0; N],
                sums: [PairSums {
                    acc: Vector::<1>::new(0.0),
                    power: 0.0,
                    div: 0.0,
                    grad_v: gsph_core::math::Matrix::<1>::new(0.0),
                    v0: Vector::<1>::new(0.0),
                }; N],
                nb: [0; NeighborList::storage_len(N, CAP)],
                geom: [PairGeom {
                    n: Vector::<1>::new(0.0),
                    r: 0.0,
                    dw: 0.0,
                }; N * CAP / 2],
                star: [TsStar { u: 0.0, p: 0.0 }; N * CAP / 2],
                aux: [Aux {
                    inv_rho: 0.0,
                    vol: 0.0,
                    ct: 0.0,
                }; N],
            }
        }
    }

    /// Sets up the flyer plate and steps it to 0.5 us with `ts1`.
    pub fn run(st: &mut Storage) -> Result<Report, StepError> {
        let mats = [MATERIAL];
        for i in 0..N {
            st.x[i] = Vector::<1>::new((i as Real + 0.5) * DX);
            st.v[i] = Vector::<1>::new(if i < N / 2 { 602.81 } else { 0.0 });
            st.m[i] = MATERIAL.rho0 * DX;
            st.rho[i] = MATERIAL.rho0;
            let eos = MATERIAL.eos(st.rho[i], 0.0);
            st.p[i] = eos.p;
            st.c[i] = gsph_core::math::real::sqrt(eos.c2);
            st.cl[i] = MATERIAL.c_long(st.rho[i], eos.c2);
            st.h[i] = 1.2 * DX;
        }
        let effects = EffectSet::STRENGTH.union(EffectSet::PLASTICITY);
        let step = select_1d::<Serial>(Family::Ts, effects).ok_or(StepError::NotCompiled)?;
        let t_end: Real = 0.5e-6;
        let mut t = 0.0;
        let mut steps = 0;
        let mut e0 = None;
        while t < t_end {
            let Storage {
                x,
                v,
                m,
                mat,
                rho,
                e,
                p,
                c,
                cl,
                h,
                s,
                eps_p,
                sums,
                nb,
                geom,
                star,
                aux,
            } = st;
            let mut list = NeighborList::new(CAP, N, nb)
                .map_err(|_| StepError::Storage { field: "neighbors" })?;
            let hh: &[Real] = h;
            build_naive(
                &x[..],
                &Periodic::none(),
                |i, j| 2.0 * 0.5 * (hh[i] + hh[j]),
                &mut list,
            )
            .map_err(|_| StepError::Storage { field: "neighbors" })?;
            let mut sys = System {
                x,
                v,
                m,
                mat,
                rho,
                e,
                p,
                c,
                cl,
                h,
                s,
                eps_p,
                damage: &mut [],
                temp: &mut [],
            };
            let energy = total_energy(&sys);
            let e0 = *e0.get_or_insert(energy);
            let _ = e0;
            let dt = stable_dt(&sys, 0.5).min(t_end - t);
            let params = StepParams {
                dt,
                materials: &mats,
                kernel: Kernel::CubicSpline,
                h_factor: 1.2,
                periodic: Periodic::none(),
                nbrs: list.view(),
                options: SchemeOptions::default(),
            };
            let pairs = list.view().unordered_pairs();
            if pairs > geom.len() {
                return Err(StepError::Storage { field: "pairs" });
            }
            let mut ws = Workspace {
                sums,
                grad: &mut [],
                grad_stress: &mut [],
                corr: &mut [],
                av: &mut [],
                art: &mut [],
                fac: &mut [],
                aux,
                geom: &mut geom[..pairs],
                ts_star: &mut star[..pairs],
                pm_star: &mut [],
                primed: false,
            };
            step(
                &mut sys,
                &mut ws,
                &params,
                &Serial,
                &mut gsph_core::halo::NoHalo,
            )?;
            check_finite(&sys)?;
            t += dt;
            steps += 1;
        }
        let Storage {
            x,
            v,
            m,
            mat,
            rho,
            e,
            p,
            c,
            cl,
            h,
            s,
            eps_p,
            ..
        } = st;
        let sys = System {
            x,
            v,
            m,
            mat,
            rho,
            e,
            p,
            c,
            cl,
            h,
            s,
            eps_p,
            damage: &mut [],
            temp: &mut [],
        };
        let e1 = total_energy(&sys);
        let e0 = e0.unwrap_or(e1);
        let mut min_sigma: Real = 0.0;
        for i in 0..N {
            min_sigma = min_sigma.min(sys.s[i].xx - sys.p[i]);
        }
        Ok(Report {
            steps,
            energy_rel_error: (e1 - e0) / e0,
            min_sigma_xx: min_sigma,
        })
    }
}

#[cfg(target_os = "none")]
mod firmware {
    static mut STORAGE: super::runner::Storage = super::runner::Storage::new();

    /// Entry point for a board's startup code: runs the flyer plate, returns the number of
    /// steps (negative on failure).
    #[no_mangle]
    pub extern "C" fn gsph_flyer_main() -> i32 {
        // SAFETY: called once from single-threaded startup code; nothing else aliases it.
        let st = unsafe { &mut *core::ptr::addr_of_mut!(STORAGE) };
        match super::runner::run(st) {
            Ok(r) => r.steps as i32,
            Err(_) => -1,
        }
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        loop {}
    }
}

#[cfg(not(target_os = "none"))]
mod host {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Counts allocations so the example can prove the stepping makes none.
    pub struct Counting;
    pub static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

    unsafe impl GlobalAlloc for Counting {
        unsafe fn alloc(&self, l: Layout) -> *mut u8 {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
            // SAFETY: forwarded unchanged to the system allocator.
            unsafe { System.alloc(l) }
        }
        unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
            // SAFETY: forwarded unchanged to the system allocator.
            unsafe { System.dealloc(p, l) }
        }
    }

    #[global_allocator]
    static GLOBAL: Counting = Counting;
}

#[cfg(not(target_os = "none"))]
fn main() {
    use std::sync::atomic::Ordering;
    // the storage lives on the heap-free static side: a `static mut` would do as well; a
    // Box would allocate, so keep it on the stack of a large-stack thread instead
    let before = host::ALLOCATIONS.load(Ordering::SeqCst);
    let mut st = runner::Storage::new();
    let report = runner::run(&mut st);
    let allocations = host::ALLOCATIONS.load(Ordering::SeqCst) - before;
    match report {
        Ok(r) => {
            println!(
                "flyer plate (ts1, {} particles): {} steps, energy error {:.3e}, peak sigma_xx {:.4} GPa, allocations during the run: {allocations}",
                runner::N,
                r.steps,
                r.energy_rel_error,
                r.min_sigma_xx / 1e9
            );
            assert_eq!(allocations, 0, "the firmware runner must not allocate");
            assert!(r.energy_rel_error.abs() < 1e-10);
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
