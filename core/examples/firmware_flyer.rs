//! A firmware-style runner: steps the 1D flyer plate (seed 000 §4.1) with `gsph-core`
//! alone, on fixed-capacity storage (`static` arrays), with no allocator.
//!
//! On a bare-metal target (`--target thumbv7em-none-eabihf`) this file is a bootable
//! `no_std`, `no_main` firmware for QEMU's `mps2-an386` board (Cortex-M4F): the runtime
//! (vector table, reset handler, semihosting) is `core/firmware/rt.rs` and the memory
//! layout `core/firmware/mps2_an386.ld`; it prints the result over semihosting and exits
//! with a non-zero status on failure. On the host it runs the same code under a counting
//! global allocator and fails if the stepping allocates even once. `scripts/firmware.sh`
//! builds and runs both (f64 and `f32`) and compares them with the host and the CLI:
//!
//! ```text
//! cargo run --release -p gsph-core --example firmware_flyer
//! cargo rustc -p gsph-core --release --example firmware_flyer --target thumbv7em-none-eabihf \
//!     --no-default-features --features dim1,scheme-ts,effects-strength \
//!     -- -C link-arg=-Tcore/firmware/mps2_an386.ld
//! qemu-system-arm -M mps2-an386 -nographic -semihosting-config enable=on,target=native \
//!     -kernel target/thumbv7em-none-eabihf/release/examples/firmware_flyer
//! ```
//!
//! The particle count is `GSPH_FIRMWARE_N` at build time (default 100; the left half is
//! the flyer), so the largest run that fits a RAM budget can be built.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

mod runner {
    use core::fmt;
    use gsph_core::dispatch::{select_1d, CATALOGUE};
    use gsph_core::effects::EffectSet;
    use gsph_core::exec::Serial;
    use gsph_core::kernel::Kernel;
    use gsph_core::material::eos::Hugoniot;
    use gsph_core::material::{Material, Strength};
    use gsph_core::math::{Real, Sym3, Vector};
    use gsph_core::neighbors::{build_naive, NeighborList, Periodic};
    use gsph_core::schemes::*;
    use gsph_core::state::*;

    /// Particles of the flyer plate (spacing 0.1 mm, the left half moving): 100 (the plate
    /// of `cases/flyer_plate.toml`, [0, 1] cm) unless `GSPH_FIRMWARE_N` is set at build time.
    pub const N: usize = match option_env!("GSPH_FIRMWARE_N") {
        Some(s) => parse_count(s),
        None => 100,
    };

    const fn parse_count(s: &str) -> usize {
        let b = s.as_bytes();
        let mut n: usize = 0;
        let mut i = 0;
        while i < b.len() {
            assert!(b[i].is_ascii_digit(), "GSPH_FIRMWARE_N: not a number");
            n = n * 10 + (b[i] - b'0') as usize;
            i += 1;
        }
        assert!(n >= 2, "GSPH_FIRMWARE_N: at least 2 particles");
        n
    }

    /// The precision of `Real` in this build.
    pub const PRECISION: &str = if core::mem::size_of::<Real>() == 4 {
        "f32"
    } else {
        "f64"
    };

    /// Bound on the relative energy error of a sound run: ts1 conserves total energy up to
    /// round-off (measured: a few machine epsilons, 3e-16 in f64 and 9e-7 in f32).
    pub const ENERGY_TOLERANCE: Real = 1.0e3 * Real::EPSILON;

    /// The effects of the run: the step is `select_1d(Family::Ts, EFFECTS.kernel_part())`.
    const EFFECTS: EffectSet = EffectSet::STRENGTH.union(EffectSet::PLASTICITY);

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
        pub energy_rel_error: Real,
        /// Peak compressive sigma_xx, Pa.
        pub min_sigma_xx: Real,
    }

    /// The result line, the same on the host and the firmware: the numbers in their
    /// shortest round-trip form, so that runs can be compared bit for bit.
    pub fn write_report(w: &mut impl fmt::Write, r: &Report) -> fmt::Result {
        write!(
            w,
            "flyer plate (ts1, {N} particles, {PRECISION}): {} steps, energy error {:e}, peak sigma_xx {:.6} GPa ({:e} Pa)",
            r.steps,
            r.energy_rel_error,
            r.min_sigma_xx / 1e9,
            r.min_sigma_xx
        )
    }

    /// The step function the run selects (the catalogue entry of `select_1d`'s arguments)
    /// and how many specialisations this build contains.
    pub fn write_kernel(w: &mut impl fmt::Write) -> fmt::Result {
        let name = CATALOGUE
            .iter()
            .find(|s| s.dim == 1 && s.family == Family::Ts && s.effects == EFFECTS.kernel_part())
            .map_or("none", |s| s.name);
        let compiled = CATALOGUE.iter().filter(|s| s.compiled).count();
        write!(
            w,
            "kernel {name} (this build contains {compiled} of {} specialisations)",
            CATALOGUE.len()
        )
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
        let step =
            select_1d::<Serial>(Family::Ts, EFFECTS.kernel_part()).ok_or(StepError::NotCompiled)?;
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
            let mut sys = System::builder()
                .x(x)
                .v(v)
                .m(m)
                .mat(mat)
                .rho(rho)
                .e(e)
                .p(p)
                .c(c)
                .cl(cl)
                .h(h)
                .s(s)
                .eps_p(eps_p)
                .build()?;
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
                effects: EFFECTS,
                simd: gsph_core::simd::SimdLevel::BASELINE,
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
                hg: &mut [],
                av: &mut [],
                art: &mut [],
                rec: &mut [],
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
        let sys = System::builder()
            .x(x)
            .v(v)
            .m(m)
            .mat(mat)
            .rho(rho)
            .e(e)
            .p(p)
            .c(c)
            .cl(cl)
            .h(h)
            .s(s)
            .eps_p(eps_p)
            .build()
            .expect("every field a run stores");
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
#[path = "../firmware/rt.rs"]
mod rt;

#[cfg(target_os = "none")]
mod firmware {
    use super::{rt, runner};
    use core::fmt::Write;

    /// The run's storage: `.bss`, sized by `N` (its symbol size gives the bytes per
    /// particle to `scripts/firmware.sh`).
    #[no_mangle]
    static mut GSPH_STORAGE: runner::Storage = runner::Storage::new();

    /// Called by the reset handler: runs the flyer plate, prints the result line, the
    /// kernel, the memory and the time over semihosting, and exits (status 1 on failure).
    #[no_mangle]
    extern "C" fn gsph_main() -> ! {
        // SAFETY: called once by the reset handler; nothing else aliases the storage.
        let st = unsafe { &mut *core::ptr::addr_of_mut!(GSPH_STORAGE) };
        let mut out = rt::Console::new();
        let t0 = rt::host_ns();
        let report = runner::run(st);
        let t1 = rt::host_ns();
        let r = match report {
            Ok(r) => r,
            Err(e) => {
                let _ = writeln!(out, "error: {e}");
                drop(out);
                rt::exit(false)
            }
        };
        let _ = runner::write_report(&mut out, &r);
        let _ = writeln!(out);
        let _ = runner::write_kernel(&mut out);
        let _ = writeln!(out);
        let (used, reserved) = rt::stack_use();
        let _ = writeln!(
            out,
            "memory storage {} bytes, stack used {used} of {reserved} bytes",
            core::mem::size_of::<runner::Storage>()
        );
        if let (Some(t0), Some(t1)) = (t0, t1) {
            let _ = writeln!(out, "time stepping {} us of host time", (t1 - t0) / 1000);
        }
        let ok = r.energy_rel_error.abs() < runner::ENERGY_TOLERANCE && used < reserved;
        if !ok {
            let _ = writeln!(out, "error: energy error or stack use out of bounds");
        }
        drop(out);
        rt::exit(ok)
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
    // the storage lives on the stack of the main thread: a Box would allocate
    let before = host::ALLOCATIONS.load(Ordering::SeqCst);
    let mut st = runner::Storage::new();
    let report = runner::run(&mut st);
    let allocations = host::ALLOCATIONS.load(Ordering::SeqCst) - before;
    match report {
        Ok(r) => {
            let mut line = String::new();
            runner::write_report(&mut line, &r).expect("formatting a String");
            println!("{line}, allocations during the run: {allocations}");
            line.clear();
            runner::write_kernel(&mut line).expect("formatting a String");
            println!("{line}");
            assert_eq!(allocations, 0, "the firmware runner must not allocate");
            assert!(r.energy_rel_error.abs() < runner::ENERGY_TOLERANCE);
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
