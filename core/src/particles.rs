//! The per-particle state, declared once (issue 26 part 2).
//!
//! [`particle_fields!`](crate::particle_fields) holds the table of the fields a particle
//! carries from step to step: name, element type, when it is stored, whether a step writes
//! it, its SI unit and a description. Code that must touch every field is generated from
//! the table by a callback macro instead of being written out per field: the core's
//! [`System`](crate::state::System) (its slices, `reborrow`, `check_storage` and the split
//! of the executors), and in the host the loops over the particle arrays.
//!
//! The table's order is the order of the fields wherever they are listed (the struct, the
//! loops, and so the host's formats that follow it).
//!
//! # Adding a field
//!
//! A row here, and the physics that reads or writes it. Every loop generated from the table
//! picks it up; code that builds a [`System`](crate::state::System) by hand (the firmware
//! example, tests) names it.

/// Calls `$cb! { ($($args)*) ROWS }` with the table of per-particle fields, one row each:
///
/// ```text
/// name: Type, kind, storage, access, "unit", "description";
/// ```
///
/// - `kind`: how the field transforms under a reflection (a wall's mirror image):
///   `point` (a position), `vector`, `tensor` (a symmetric 3x3 tensor) or `scalar`;
/// - `storage`: the name of the [`EffectSet`](crate::effects::EffectSet) constant whose
///   effect stores the field (`HYDRO`: every run; `effects.contains(EffectSet::HYDRO)` is
///   always true); a run without it stores an empty array;
/// - `access`: `mut` (a step writes it) or `ref` (a step only reads it);
/// - `unit`: the SI unit (`""`: dimensionless or an index); masses and volumes follow
///   the dimension (in 2D per unit length out of the plane, in 1D per unit
///   cross-section area);
/// - `Type` may name `D` (the dimension), `Vector`, `Real` and `Sym3` of [`crate::math`],
///   which the callback's expansion site must have in scope.
///
/// The callback receives the parenthesised arguments first, then the rows.
#[macro_export]
macro_rules! particle_fields {
    ($cb:ident { $($args:tt)* }) => {
        $cb! {
            ($($args)*)
            x: Vector<D>, point, HYDRO, mut, "m", "Position";
            v: Vector<D>, vector, HYDRO, mut, "m/s", "Velocity";
            m: Real, scalar, HYDRO, ref, "kg", "Mass (in 2D per unit length out of the plane, kg/m; in 1D per unit cross-section area, kg/m²)";
            mat: u16, scalar, HYDRO, ref, "", "Material index into `StepParams::materials`";
            rho: Real, scalar, HYDRO, mut, "kg/m³", "Density";
            e: Real, scalar, HYDRO, mut, "J/kg", "Specific internal energy";
            p: Real, scalar, HYDRO, mut, "Pa", "Pressure (kept consistent with rho, e by the EOS)";
            c: Real, scalar, HYDRO, mut, "m/s", "Bulk sound speed (from the EOS)";
            cl: Real, scalar, HYDRO, mut, "m/s", "Longitudinal sound speed `sqrt(c² + 4G/(3 rho))`";
            h: Real, scalar, HYDRO, mut, "m", "Smoothing length `h = h_factor (m/rho)^(1/D)`";
            s: Sym3, tensor, STRENGTH, mut, "Pa", "Stress deviator S (full 3x3)";
            eps_p: Real, scalar, PLASTICITY, mut, "", "Equivalent plastic strain";
            damage: Real, scalar, DAMAGE, mut, "", "Damage in [0, 1]";
            temp: Real, scalar, HEAT, mut, "K", "Temperature";
        }
    };
}

/// The names of the per-particle fields, in table order.
pub const FIELD_NAMES: &[&str] = {
    macro_rules! names {
        (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal;)*) => {
            &[$(stringify!($name)),*]
        };
    }
    crate::particle_fields!(names {})
};

#[cfg(test)]
mod tests {
    use super::FIELD_NAMES;

    #[test]
    fn the_table_lists_each_field_once() {
        let mut names = FIELD_NAMES.to_vec();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), FIELD_NAMES.len());
        assert_eq!(FIELD_NAMES[0], "x");
    }
}
