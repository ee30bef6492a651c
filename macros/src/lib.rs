//! Procedural macros of gsph: compile-time specialisation of the schemes.
//!
//! The physics is written once, generic over `const D: usize`, a scheme family
//! (`SchemeFamily`) and an effect set (`E: Effects`). This crate generates only the wiring:
//! a marker type per effect set, a named monomorphic step function per (dimension, family,
//! effect set), a dispatch function per dimension and a catalogue. See [`specialise!`].
//!
//! Layout (after serde_derive and pest): [`specialise!`] calls `expand::specialise`, which
//! parses the input into a validated `model::Model` and generates code from it with
//! `quote`. Expansion snapshots live in `tests/expand/` (regenerate with
//! `UPDATE_EXPAND=1 cargo test -p gsph-macros`), compile-fail tests in `tests/ui/`.

mod expand;
mod model;
#[cfg(test)]
mod tests;

/// Generates the specialisations of gsph's schemes.
///
/// Invoked once, inside gsph-core (`core/src/dispatch.rs`):
///
/// ```ignore
/// gsph_macros::specialise! {
///     dims: [1, 2, 3];
///     families: [av => crate::schemes::av::Av, pm => crate::schemes::pm::Pm];
///     effects: [
///         strength: STRENGTH feature "effects-strength",
///         plasticity: PLASTICITY requires strength feature "effects-strength",
///         muscl: MUSCL only [pm] feature "effects-muscl",
///     ];
/// }
/// ```
///
/// An *effect set* is a subset of the effects closed under `requires`; it is valid for a
/// family if every member with an `only [..]` clause lists that family. The macro
/// generates, in the invoking module:
///
/// - per effect set valid for some family, a marker type `Fx{Names}` (`FxHydro` for the
///   empty set, `FxStrengthPlasticity`, ...) implementing `crate::effects::Effects`;
/// - per (dimension, family, valid set), `step_{d}d_{family}_{effects|hydro}`, calling
///   `<Family as crate::schemes::SchemeFamily>::checked_step::<D, Fx.., X>`, gated by
///   `#[cfg(all(feature = "dim{d}", feature = "scheme-{family}", <effect features>))]`;
/// - per dimension, `select_{d}d(family, effects) -> Option<StepFn<D, X>>`;
/// - `Specialisation` and `CATALOGUE`, every specialisation with whether it is compiled.
///
/// Unknown or duplicate names, dimensions outside `1..=3`, empty lists and `requires`
/// cycles are compile errors pointing at the offending token.
#[proc_macro]
pub fn specialise(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand::specialise(input.into()).into()
}
