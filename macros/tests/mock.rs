//! Compile-pass test of `specialise!`: the generated code compiles against mock modules
//! laid out like gsph-core's (`crate::effects`, `crate::exec`, `crate::state`,
//! `crate::schemes`), and dispatch picks the right specialisation.
//!
//! The generated `#[cfg(feature = ..)]` gates are evaluated against the features of this
//! package (gsph-macros), which declares them for this test only (see macros/Cargo.toml).
//! Its default features compile some specialisations and leave others out (dim1,
//! scheme-av and effects-periodic are off); every expectation below reads the features
//! with `cfg!`, so the test holds for any feature selection (`--all-features` included).
//!
//! Warnings are errors, so the generated code must not warn (unused variables, ...). Only
//! when the features compile no pm step are the mock's own items dead code.
#![deny(warnings)]
#![cfg_attr(not(all(feature = "dim2", feature = "scheme-pm")), allow(dead_code))]

mod effects {
    /// The compile-time effect set (mock of gsph-core's).
    pub trait Effects: Copy + 'static {
        const STRENGTH: bool;
        const PLASTICITY: bool;
        const MUSCL: bool;
        const PERIODIC: bool;
        const SET: EffectSet;
    }

    /// The run-time effect set (mock of gsph-core's).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct EffectSet(pub u16);

    impl EffectSet {
        pub const HYDRO: EffectSet = EffectSet(0);
        pub const STRENGTH: EffectSet = EffectSet(1);
        pub const PLASTICITY: EffectSet = EffectSet(2);
        pub const MUSCL: EffectSet = EffectSet(4);
        pub const PERIODIC: EffectSet = EffectSet(8);

        pub const fn union(self, o: EffectSet) -> EffectSet {
            EffectSet(self.0 | o.0)
        }
    }
}

mod halo {
    pub trait Halo<const D: usize> {}

    pub struct NoHalo;

    impl<const D: usize> Halo<D> for NoHalo {}
}

mod exec {
    pub trait Executor {}

    pub struct Serial;

    impl Executor for Serial {}
}

mod state {
    use crate::effects::EffectSet;
    use crate::schemes::scheme::Family;

    /// What a step was called with: dimension, family, effect set and the four constants.
    pub type Call = (usize, Family, EffectSet, [bool; 4]);

    /// The mock particle system records the steps run on it.
    pub struct System<'a, const D: usize> {
        pub calls: &'a mut Vec<Call>,
    }

    #[derive(Debug)]
    pub enum StepError {}
}

mod schemes {
    use crate::effects::Effects;
    use crate::exec::Executor;
    use crate::state::{StepError, System};
    use scheme::Family;
    use workspace::{StepParams, Workspace};

    pub mod workspace {
        use core::marker::PhantomData;

        pub struct Workspace<'a, const D: usize>(pub PhantomData<&'a ()>);

        pub struct StepParams<'a, const D: usize>(pub PhantomData<&'a ()>);
    }

    pub mod scheme {
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Family {
            Av,
            Pm,
            Ts,
        }
    }

    pub mod family {
        pub use super::{SchemeFamily, StepFn};
    }

    pub trait SchemeFamily {
        fn checked_step<const D: usize, E: Effects, X: Executor>(
            sys: &mut System<'_, D>,
            ws: &mut Workspace<'_, D>,
            params: &StepParams<'_, D>,
            exec: &X,
            halo: &mut dyn crate::halo::Halo<D>,
        ) -> Result<(), StepError>;
    }

    pub type StepFn<const D: usize, X> = fn(
        &mut System<'_, D>,
        &mut Workspace<'_, D>,
        &StepParams<'_, D>,
        &X,
        &mut dyn crate::halo::Halo<D>,
    ) -> Result<(), StepError>;

    /// Records `(D, family, E::SET, E's constants)` instead of stepping.
    fn record<const D: usize, E: Effects>(
        sys: &mut System<'_, D>,
        family: Family,
    ) -> Result<(), StepError> {
        let consts = [E::STRENGTH, E::PLASTICITY, E::MUSCL, E::PERIODIC];
        sys.calls.push((D, family, E::SET, consts));
        Ok(())
    }

    macro_rules! mock_family {
        ($module:ident, $ty:ident) => {
            pub mod $module {
                #[allow(dead_code)] // when its `scheme-*` feature is off
                pub struct $ty;

                impl super::SchemeFamily for $ty {
                    fn checked_step<const D: usize, E: super::Effects, X: super::Executor>(
                        sys: &mut super::System<'_, D>,
                        _: &mut super::Workspace<'_, D>,
                        _: &super::StepParams<'_, D>,
                        _: &X,
                        _: &mut dyn crate::halo::Halo<D>,
                    ) -> Result<(), super::StepError> {
                        super::record::<D, E>(sys, super::Family::$ty)
                    }
                }
            }
        };
    }

    mock_family!(av, Av);
    mock_family!(pm, Pm);
    mock_family!(ts, Ts);
}

gsph_macros::specialise! {
    dims: [1, 2];
    families: [
        av => crate::schemes::av::Av,
        pm => crate::schemes::pm::Pm,
        ts => crate::schemes::ts::Ts,
    ];
    effects: [
        strength: STRENGTH feature "effects-strength",
        plasticity: PLASTICITY requires strength feature "effects-strength",
        muscl: MUSCL only [pm, ts] feature "effects-muscl",
        periodic: PERIODIC feature "effects-periodic",
    ];
}

use core::marker::PhantomData;

use effects::EffectSet;
use exec::Serial;
use schemes::scheme::Family;
use schemes::workspace::{StepParams, Workspace};
use state::{Call, System};

/// Runs a selected 2D step on a fresh mock system and returns what it recorded.
fn run_2d(step: schemes::StepFn<2, Serial>) -> Vec<Call> {
    let mut calls = Vec::new();
    let mut sys = System::<2> { calls: &mut calls };
    step(
        &mut sys,
        &mut Workspace(PhantomData),
        &StepParams(PhantomData),
        &Serial,
        &mut halo::NoHalo,
    )
    .unwrap();
    calls
}

const SP: EffectSet = EffectSet::STRENGTH.union(EffectSet::PLASTICITY);

#[test]
fn selects_the_requested_specialisation() {
    let step = select_2d::<Serial>(Family::Pm, SP);
    let compiled = cfg!(all(
        feature = "dim2",
        feature = "scheme-pm",
        feature = "effects-strength"
    ));
    assert_eq!(step.is_some(), compiled);
    if let Some(step) = step {
        assert_eq!(
            run_2d(step),
            [(2, Family::Pm, SP, [true, true, false, false])]
        );
    }

    let sm = EffectSet::STRENGTH.union(EffectSet::MUSCL);
    let step = select_2d::<Serial>(Family::Ts, sm);
    let compiled = cfg!(all(
        feature = "dim2",
        feature = "scheme-ts",
        feature = "effects-strength",
        feature = "effects-muscl"
    ));
    assert_eq!(step.is_some(), compiled);
    if let Some(step) = step {
        assert_eq!(
            run_2d(step),
            [(2, Family::Ts, sm, [true, false, true, false])]
        );
    }
}

#[cfg(all(feature = "dim2", feature = "scheme-pm", feature = "effects-strength"))]
#[test]
fn named_step_functions_can_be_called_directly() {
    assert_eq!(
        run_2d(step_2d_pm_strength::<Serial>),
        [(
            2,
            Family::Pm,
            EffectSet::STRENGTH,
            [true, false, false, false]
        )]
    );
    assert_eq!(<FxStrengthPlasticity as effects::Effects>::SET, SP);
}

#[test]
fn invalid_combinations_are_never_selected() {
    // MUSCL is `only [pm, ts]`; plasticity without strength is not closed; bit 9 is unknown.
    assert!(select_2d::<Serial>(Family::Av, EffectSet::MUSCL).is_none());
    assert!(select_2d::<Serial>(Family::Pm, EffectSet::PLASTICITY).is_none());
    assert!(select_2d::<Serial>(Family::Pm, EffectSet(1 << 9)).is_none());
    assert!(select_1d::<Serial>(Family::Av, EffectSet::MUSCL).is_none());
}

#[test]
fn feature_gates_decide_what_is_compiled() {
    let av = select_2d::<Serial>(Family::Av, EffectSet::HYDRO);
    assert_eq!(
        av.is_some(),
        cfg!(all(feature = "dim2", feature = "scheme-av"))
    );
    let periodic = select_2d::<Serial>(Family::Pm, EffectSet::PERIODIC);
    assert_eq!(
        periodic.is_some(),
        cfg!(all(
            feature = "dim2",
            feature = "scheme-pm",
            feature = "effects-periodic"
        ))
    );
    let one_d = select_1d::<Serial>(Family::Pm, EffectSet::HYDRO);
    assert_eq!(
        one_d.is_some(),
        cfg!(all(feature = "dim1", feature = "scheme-pm"))
    );
}

#[test]
fn catalogue_lists_every_specialisation() {
    // Closed sets of {strength, plasticity}: hydro, s, s+p (3); times periodic (6); times
    // muscl for pm and ts only: av 6, pm 12, ts 12, so 30 per dimension and 60 in all.
    assert_eq!(CATALOGUE.len(), 60);
    for (family, n) in [(Family::Av, 6), (Family::Pm, 12), (Family::Ts, 12)] {
        assert_eq!(
            CATALOGUE
                .iter()
                .filter(|s| s.dim == 2 && s.family == family)
                .count(),
            n
        );
    }
    for s in CATALOGUE {
        let selected = match s.dim {
            1 => select_1d::<Serial>(s.family, s.effects).is_some(),
            _ => select_2d::<Serial>(s.family, s.effects).is_some(),
        };
        assert_eq!(selected, s.compiled, "{}", s.name);
    }
    let names: Vec<_> = CATALOGUE.iter().map(|s| s.name).collect();
    assert!(names.contains(&"step_1d_av_hydro"));
    assert!(names.contains(&"step_2d_ts_strength_plasticity_muscl_periodic"));
    let first = &CATALOGUE[0];
    assert_eq!(
        (first.dim, first.family, first.effects),
        (1, Family::Av, EffectSet::HYDRO)
    );
}
