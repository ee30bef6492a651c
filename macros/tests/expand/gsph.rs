// The invocation of gsph-core (core/src/dispatch.rs).
gsph_macros::specialise! {
    dims: [1, 2, 3];
    families: [av => crate::schemes::av::Av, pm => crate::schemes::pm::Pm, ts => crate::schemes::ts::Ts, tl => crate::schemes::tl::Tl];
    effects: [
        strength: STRENGTH feature "effects-strength",
        correction: CORRECTION only [pm] feature "effects-correction",
        muscl: MUSCL only [pm, ts] feature "effects-muscl",
    ];
}
