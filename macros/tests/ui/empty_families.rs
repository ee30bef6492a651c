gsph_macros::specialise! {
    dims: [2];
    families: [];
    effects: [
        strength: STRENGTH,
    ];
}

fn main() {}
