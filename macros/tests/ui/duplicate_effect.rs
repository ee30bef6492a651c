gsph_macros::specialise! {
    dims: [2];
    families: [pm => crate::Pm];
    effects: [
        strength: STRENGTH,
        periodic: PERIODIC,
        strength: STRENGTH2,
    ];
}

fn main() {}
