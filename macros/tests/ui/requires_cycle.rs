gsph_macros::specialise! {
    dims: [2];
    families: [pm => crate::Pm];
    effects: [
        damage: DAMAGE requires heat,
        heat: HEAT requires damage,
    ];
}

fn main() {}
