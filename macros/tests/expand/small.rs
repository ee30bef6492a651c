// One dimension, one family, three effects: small enough to read in full.
gsph_macros::specialise! {
    dims: [2];
    families: [pm => crate::schemes::pm::Pm];
    effects: [
        strength: STRENGTH feature "effects-strength",
        plasticity: PLASTICITY requires strength feature "effects-strength",
        periodic: PERIODIC feature "effects-periodic",
    ];
}
