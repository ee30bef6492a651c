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
/// name: Type, kind, storage, access, "unit", "description", {
///     api("api name" [more aliases], write|read, range)
///     out[column "description", ...]
///     init(required | optional "default")   (only on the fields initial particles carry)
/// };
/// ```
///
/// - `kind`: how the field transforms under a reflection (a wall's mirror image):
///   `point` (a position), `vector`, `tensor` (a symmetric 3x3 tensor) or `scalar`;
/// - `storage`: the name of the [`EffectSet`](crate::effects::EffectSet) constant whose
///   effect stores the field (`HYDRO`: every run; `effects.contains(EffectSet::HYDRO)` is
///   always true); a run without it stores an empty array;
/// - `access`: `mut` (a step writes it), `ref` (a step only reads it) or `keep` (the
///   host carries it with the particle, permutes, mirrors, checkpoints and outputs it,
///   but no step sees it: it is not a field of [`System`](crate::state::System));
/// - `unit`: the SI unit (`"1"`: dimensionless, `""`: a label such as an index); masses
///   and volumes follow the dimension (in 2D per unit length out of the plane, in 1D per
///   unit cross-section area);
/// - `api`: the field's name in the library API (`gsph::api`, the C ABI, Python), further
///   aliases besides the field's own name, whether a caller may write it, and the range a
///   written value must lie in (`any` finite value, `positive`, `nonnegative`, `fraction`:
///   in [0, 1]);
/// - `out`: the columns of `final.csv` and of the snapshots' particle tables, with their
///   meaning: one per component (a point or vector has three, padded with 0 below 3D; a
///   tensor six, `xx yy zz xy xz yz`; a scalar one), or none.
/// - `Type` may name `D` (the dimension), `Vector`, `Real` and `Sym3` of [`crate::math`],
///   which the callback's expansion site must have in scope.
///
/// The callback receives the parenthesised arguments first, then the rows.
/// `particle_fields!(step cb { args })` passes only the rows a step sees (all but `keep`).
#[macro_export]
macro_rules! particle_fields {
    (step $cb:ident { $($args:tt)* }) => {
        $crate::particle_fields! { @rows ($crate::__step_rows) ($cb ($($args)*) []) }
    };
    ($cb:ident { $($args:tt)* }) => {
        $crate::particle_fields! { @rows ($cb) (($($args)*)) }
    };
    (@rows ($($mac:tt)*) ($($pre:tt)*)) => {
        $($mac)*! {
            $($pre)*
            x: Vector<D>, point, HYDRO, mut, "m", "Position", {
                api("position" [], write, any)
                out[x "position x", y "position y (0 in 1D)", z "position z (0 in 1D and 2D)"]
                init(required)
            };
            v: Vector<D>, vector, HYDRO, mut, "m/s", "Velocity", {
                api("velocity" [], write, any)
                out[vx "velocity x", vy "velocity y (0 in 1D)", vz "velocity z (0 in 1D and 2D)"]
                init(required)
            };
            m: Real, scalar, HYDRO, ref, "kg", "Mass (in 2D per unit length out of the plane, kg/m; in 1D per unit cross-section area, kg/m^2)", {
                api("mass" [], write, positive)
                out[m "particle mass (kg/m^2 in 1D: per unit area; kg/m in 2D: per unit length)"]
                init(required)
            };
            mat: u16, scalar, HYDRO, ref, "", "Material index into `StepParams::materials`", {
                api("material" [], read, any)
                out[]
                init(required)
            };
            rho: Real, scalar, HYDRO, mut, "kg/m^3", "Density", {
                api("density" [], write, positive)
                out[rho "density"]
                init(required)
            };
            p: Real, scalar, HYDRO, mut, "Pa", "Pressure, positive in compression (kept consistent with rho, e by the EOS)", {
                api("pressure" [], read, any)
                out[p "pressure, positive in compression (sigma = -p I + S)"]
            };
            e: Real, scalar, HYDRO, mut, "J/kg", "Specific internal energy", {
                api("energy" [], write, any)
                out[e "specific internal energy"]
                init(required)
            };
            c: Real, scalar, HYDRO, mut, "m/s", "Bulk sound speed (from the EOS)", {
                api("sound_speed" [], read, any)
                out[]
            };
            cl: Real, scalar, HYDRO, mut, "m/s", "Longitudinal sound speed `sqrt(c^2 + 4G/(3 rho))`", {
                api("longitudinal_sound_speed" [], read, any)
                out[]
            };
            s: Sym3, tensor, STRENGTH, mut, "Pa", "Stress deviator S (full 3x3)", {
                api("deviator" [], write, any)
                out[
                    sxx "stress deviator S_xx (not the stress: sigma_xx = sxx - p)",
                    syy "stress deviator S_yy (sigma_yy = syy - p)",
                    szz "stress deviator S_zz (sigma_zz = szz - p)",
                    sxy "stress deviator S_xy (= sigma_xy)",
                    sxz "stress deviator S_xz (= sigma_xz)",
                    syz "stress deviator S_yz (= sigma_yz)"
                ]
                init(required)
            };
            eps_p: Real, scalar, PLASTICITY, mut, "1", "Equivalent plastic strain", {
                api("plastic_strain" [], write, nonnegative)
                out[eps_p "equivalent plastic strain"]
                init(optional "0")
            };
            damage: Real, scalar, DAMAGE, mut, "1", "Damage in [0, 1]", {
                api("damage" [], write, fraction)
                out[damage "damage in [0, 1]"]
                init(optional "0")
            };
            temp: Real, scalar, HEAT, mut, "K", "Temperature", {
                api("temperature" [], write, positive)
                out[temperature "temperature"]
                init(optional "the material's initial temperature")
            };
            h: Real, scalar, HYDRO, mut, "m", "Smoothing length `h = h_factor (m/rho)^(1/D)`", {
                api("h" [smoothing_length], write, positive)
                out[h "smoothing length"]
            };
            x0: Vector<D>, point, HYDRO, keep, "m", "Reference position: where the particle was created (the reference configuration of `det_f`)", {
                api("reference_position" [], read, any)
                out[
                    x0 "reference (initial) position x",
                    y0 "reference (initial) position y (0 in 1D)",
                    z0 "reference (initial) position z (0 in 1D and 2D)"
                ]
                init(optional "its position")
            };
            hg: Vector<D>, vector, HOURGLASS, mut, "m", "Hourglass displacement: the particle's displacement away from the affine motion of its neighbours, integrated in time and rotated with the spin (`schemes::hourglass`)", {
                api("hourglass_displacement" [], write, any)
                out[
                    hgx "hourglass displacement x (effect hourglass; its stored energy is xi G V |d|^2/(2 h^2))",
                    hgy "hourglass displacement y (0 in 1D)",
                    hgz "hourglass displacement z (0 in 1D and 2D)"
                ]
            };
            xr: Vector<D>, point, REFERENCE, mut, "m", "Reference position of the total-Lagrangian scheme `tl`: where the particle was at the start of the run; its kernel, neighbours and gradient correction stay fixed there (`schemes::tl`)", {
                api("tl_reference_position" [], read, any)
                out[]
            };
            vr: Real, scalar, REFERENCE, ref, "m^3", "Reference volume `m/rho` of the particle in tl's reference configuration (in 2D per unit length, m^2; in 1D per unit area, m)", {
                api("tl_reference_volume" [], read, positive)
                out[]
            };
            phi: Real, scalar, REFERENCE, mut, "J", "The energy tl's hourglass stiffness stores in the particle's pairs, `sum_j k_ij |F_i dX_ij - dx_ij|^2 / 2` (part of its internal energy; J/m in 2D, J/m^2 in 1D)", {
                api("tl_hourglass_energy" [], read, any)
                out[phi "energy stored by tl's hourglass stiffness (scheme tl; part of the internal energy)"]
            };
        }
    };
}

/// Filters the rows of [`particle_fields!`](crate::particle_fields) to those a step sees
/// (access `mut` or `ref`), then calls the callback with them.
#[doc(hidden)]
#[macro_export]
macro_rules! __step_rows {
    ($cb:ident $args:tt [$($kept:tt)*]) => {
        $cb! { $args $($kept)* }
    };
    ($cb:ident $args:tt [$($kept:tt)*] $name:ident: $ty:ty, $kind:ident, $when:ident, keep, $unit:literal, $doc:literal, $io:tt; $($rest:tt)*) => {
        $crate::__step_rows! { $cb $args [$($kept)*] $($rest)* }
    };
    ($cb:ident $args:tt [$($kept:tt)*] $name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt; $($rest:tt)*) => {
        $crate::__step_rows! { $cb $args [$($kept)* $name: $ty, $kind, $when, $acc, $unit, $doc, $io;] $($rest)* }
    };
}

/// Calls `$cb! { ($($args)*) ROWS }` with the table of per-particle quantities derived
/// from the state for output, one row each:
///
/// ```text
/// name: "unit", "description", { api(...) out[...] };
/// ```
///
/// with `api` and `out` as in [`particle_fields!`](crate::particle_fields) (`api` always
/// `read`). They are not state: the host computes each from the particles when it writes
/// or hands them out, by the function of the same name in `gsph::sim::derived`.
#[macro_export]
macro_rules! derived_fields {
    ($cb:ident { $($args:tt)* }) => {
        $cb! {
            ($($args)*)
            det_f: "1", "Determinant of the deformation gradient F = dx/dx0 from the current and reference positions", {
                api("det_f" [], read, any)
                out[det_f "det F, F = dx/dx0 from the positions and reference positions (corrected SPH gradient); rho0/rho while volume follows density"]
            };
        }
    };
}

/// The names of the per-particle fields, in table order.
pub const FIELD_NAMES: &[&str] = {
    macro_rules! names {
        (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
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
