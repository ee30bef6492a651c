gsph_macros::specialise! {
    dims: [1, 4];
    families: [pm => crate::Pm];
    effects: [
        strength: STRENGTH,
    ];
}

fn main() {}
