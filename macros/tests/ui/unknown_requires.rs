gsph_macros::specialise! {
    dims: [2];
    families: [pm => crate::Pm];
    effects: [
        strength: STRENGTH,
        plasticity: PLASTICITY requires strenght,
    ];
}

fn main() {}
