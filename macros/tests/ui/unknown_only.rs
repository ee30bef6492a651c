gsph_macros::specialise! {
    dims: [2];
    families: [pm => crate::Pm, ts => crate::Ts];
    effects: [
        muscl: MUSCL only [pm, tkc],
    ];
}

fn main() {}
