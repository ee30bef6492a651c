gsph_macros::specialise! {
    dims: [2];
    families: [pm => crate::Pm, pm => crate::Tkc];
    effects: [
        strength: STRENGTH,
    ];
}

fn main() {}
