//! The input of `specialise!` parsed into a small, validated model.
//!
//! ```text
//! dims: [1, 2, 3];
//! families: [av => crate::schemes::av::Av, pm => crate::schemes::pm::Pm];
//! effects: [
//!     strength: STRENGTH feature "effects-strength",
//!     plasticity: PLASTICITY requires strength feature "effects-strength",
//!     muscl: MUSCL only [pm] feature "effects-muscl",
//! ];
//! ```
//!
//! The three sections may come in any order, each exactly once. An effect is
//! `name: CONST` followed by optional clauses, each at most once: `requires name` (or
//! `requires [a, b]`), `only [family, ..]` and `feature "cargo-feature"`.
//!
//! Every error is a [`syn::Error`] spanned at the user's offending token.

use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{bracketed, Ident, LitInt, LitStr, Path, Token};

/// At most this many effects: a set is a bit mask, like `EffectSet(u16)` in gsph-core.
pub const MAX_EFFECTS: usize = 16;

/// The validated input of `specialise!`.
pub struct Model {
    /// Dimensions, each in `1..=3`, in declaration order.
    pub dims: Vec<usize>,
    /// Scheme families, in declaration order.
    pub families: Vec<Family>,
    /// Effects, in declaration order (bit `i` of an [`EffectSet`] is `effects[i]`).
    pub effects: Vec<Effect>,
}

/// A scheme family: `name => path`.
pub struct Family {
    /// Lower-case name (`pm`), used in function names and `scheme-{name}` features.
    pub name: Ident,
    /// The type implementing `SchemeFamily`.
    pub path: Path,
}

/// One effect declaration.
pub struct Effect {
    /// Lower-case name (`strength`), used in type and function names.
    pub name: Ident,
    /// The constant naming it in `Effects` and `EffectSet` (`STRENGTH`).
    pub konst: Ident,
    /// Indices of the effects it requires.
    pub requires: Vec<usize>,
    /// Indices of the families it is restricted to (`None`: every family).
    pub only: Option<Vec<usize>>,
    /// The Cargo feature that compiles specialisations containing it.
    pub feature: Option<LitStr>,
}

/// A set of effects as a bit mask over [`Model::effects`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct EffectSet(pub u32);

/// One specialisation: a dimension, a family and an effect set valid for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Specialisation {
    /// The dimension.
    pub dim: usize,
    /// Index into [`Model::families`].
    pub family: usize,
    /// The effect set.
    pub set: EffectSet,
}

impl EffectSet {
    /// True if effect `i` is in the set.
    pub fn contains(self, i: usize) -> bool {
        self.0 & (1 << i) != 0
    }
}

impl Model {
    /// Indices of the effects in `set`, in declaration order.
    pub fn members(&self, set: EffectSet) -> impl Iterator<Item = &Effect> + '_ {
        self.effects
            .iter()
            .enumerate()
            .filter(move |(i, _)| set.contains(*i))
            .map(|(_, e)| e)
    }

    /// True if `set` holds everything its members require.
    pub fn is_closed(&self, set: EffectSet) -> bool {
        self.effects
            .iter()
            .enumerate()
            .filter(|(i, _)| set.contains(*i))
            .all(|(_, e)| e.requires.iter().all(|&r| set.contains(r)))
    }

    /// True if `set` is closed and every member restricted by `only` lists `family`.
    pub fn is_valid_for(&self, set: EffectSet, family: usize) -> bool {
        self.is_closed(set)
            && self
                .members(set)
                .all(|e| e.only.as_ref().is_none_or(|o| o.contains(&family)))
    }

    /// The effect sets valid for at least one family, by increasing bit mask
    /// (so the empty set, hydro only, comes first).
    pub fn sets(&self) -> Vec<EffectSet> {
        (0..1u32 << self.effects.len())
            .map(EffectSet)
            .filter(|&s| (0..self.families.len()).any(|f| self.is_valid_for(s, f)))
            .collect()
    }

    /// Every (dim, family, valid set), ordered by dim, then family, then set.
    pub fn specialisations(&self) -> Vec<Specialisation> {
        let sets = self.sets();
        let mut out = Vec::new();
        for &dim in &self.dims {
            for family in 0..self.families.len() {
                for &set in sets.iter().filter(|&&s| self.is_valid_for(s, family)) {
                    out.push(Specialisation { dim, family, set });
                }
            }
        }
        out
    }

    /// The features of the members of `set`, deduplicated, in declaration order.
    pub fn features(&self, set: EffectSet) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for f in self.members(set).filter_map(|e| e.feature.as_ref()) {
            if !out.contains(&f.value()) {
                out.push(f.value());
            }
        }
        out
    }
}

/// Finds `name` in `known`, or reports `what` unknown at `name`.
fn lookup(known: &[&Ident], name: &Ident, what: &str) -> syn::Result<usize> {
    known
        .iter()
        .position(|k| *k == name)
        .ok_or_else(|| syn::Error::new(name.span(), format!("unknown {what} `{name}`")))
}

/// Reports the second of two equal names.
fn check_unique<'a>(names: impl IntoIterator<Item = &'a Ident>, what: &str) -> syn::Result<()> {
    let mut seen: Vec<&Ident> = Vec::new();
    for n in names {
        if seen.contains(&n) {
            return Err(syn::Error::new(n.span(), format!("duplicate {what} `{n}`")));
        }
        seen.push(n);
    }
    Ok(())
}

/// A bracketed, comma-separated list that must not be empty.
fn non_empty_list<T>(
    input: ParseStream,
    what: &str,
    item: fn(ParseStream) -> syn::Result<T>,
) -> syn::Result<Vec<T>> {
    let content;
    let bracket = bracketed!(content in input);
    let list = Punctuated::<T, Token![,]>::parse_terminated_with(&content, item)?;
    if list.is_empty() {
        return Err(syn::Error::new(
            bracket.span.join(),
            format!("{what} must not be empty"),
        ));
    }
    Ok(list.into_iter().collect())
}

/// An effect as written, before its names are resolved.
struct RawEffect {
    name: Ident,
    konst: Ident,
    requires: Vec<Ident>,
    only: Option<Vec<Ident>>,
    feature: Option<LitStr>,
}

impl Parse for RawEffect {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name: Ident = input.parse()?;
        if name == "hydro" {
            return Err(syn::Error::new(
                name.span(),
                "`hydro` names the empty effect set",
            ));
        }
        input.parse::<Token![:]>()?;
        let mut e = RawEffect {
            name,
            konst: input.parse()?,
            requires: Vec::new(),
            only: None,
            feature: None,
        };
        let mut seen: Vec<Ident> = Vec::new();
        while !input.is_empty() && !input.peek(Token![,]) {
            let clause: Ident = input.parse()?;
            if seen.contains(&clause) {
                return Err(syn::Error::new(
                    clause.span(),
                    format!("duplicate `{clause}` clause"),
                ));
            }
            match clause.to_string().as_str() {
                "requires" if input.peek(syn::token::Bracket) => {
                    e.requires = non_empty_list(input, "`requires`", Ident::parse)?;
                }
                "requires" => e.requires = vec![input.parse()?],
                "only" => e.only = Some(non_empty_list(input, "`only`", Ident::parse)?),
                "feature" => e.feature = Some(input.parse()?),
                _ => {
                    let msg = format!("expected `requires`, `only` or `feature`, found `{clause}`");
                    return Err(syn::Error::new(clause.span(), msg));
                }
            }
            seen.push(clause);
        }
        Ok(e)
    }
}

/// `name => path`.
fn parse_family(input: ParseStream) -> syn::Result<Family> {
    let name = input.parse()?;
    input.parse::<Token![=>]>()?;
    Ok(Family {
        name,
        path: input.parse()?,
    })
}

impl Parse for Model {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let (mut dims, mut families, mut effects) = (None, None, None);
        while !input.is_empty() {
            let section: Ident = input.parse()?;
            input.parse::<Token![:]>()?;
            let duplicate =
                || syn::Error::new(section.span(), format!("duplicate section `{section}`"));
            match section.to_string().as_str() {
                "dims" if dims.is_some() => return Err(duplicate()),
                "dims" => dims = Some(non_empty_list(input, "`dims`", LitInt::parse)?),
                "families" if families.is_some() => return Err(duplicate()),
                "families" => families = Some(non_empty_list(input, "`families`", parse_family)?),
                "effects" if effects.is_some() => return Err(duplicate()),
                "effects" => effects = Some(non_empty_list(input, "`effects`", RawEffect::parse)?),
                _ => {
                    let msg =
                        format!("expected `dims`, `families` or `effects`, found `{section}`");
                    return Err(syn::Error::new(section.span(), msg));
                }
            }
            input.parse::<Token![;]>()?;
        }
        let missing =
            |s: &str| syn::Error::new(Span::call_site(), format!("missing section `{s}`"));
        let dims = dims.ok_or_else(|| missing("dims"))?;
        let families = families.ok_or_else(|| missing("families"))?;
        let effects = effects.ok_or_else(|| missing("effects"))?;
        Model::resolve(dims, families, effects)
    }
}

impl Model {
    /// Checks names and dimensions and resolves names to indices.
    fn resolve(dims: Vec<LitInt>, families: Vec<Family>, raw: Vec<RawEffect>) -> syn::Result<Self> {
        let mut dim_values = Vec::new();
        for lit in &dims {
            let d: usize = lit.base10_parse()?;
            if !(1..=3).contains(&d) {
                return Err(syn::Error::new(
                    lit.span(),
                    format!("dimension {d} is not in 1..=3"),
                ));
            }
            if dim_values.contains(&d) {
                return Err(syn::Error::new(
                    lit.span(),
                    format!("duplicate dimension {d}"),
                ));
            }
            dim_values.push(d);
        }
        check_unique(families.iter().map(|f| &f.name), "family")?;
        check_unique(raw.iter().map(|e| &e.name), "effect")?;
        check_unique(raw.iter().map(|e| &e.konst), "effect constant")?;
        if raw.len() > MAX_EFFECTS {
            let msg = format!("at most {MAX_EFFECTS} effects are supported");
            return Err(syn::Error::new(raw[MAX_EFFECTS].name.span(), msg));
        }
        let family_names: Vec<&Ident> = families.iter().map(|f| &f.name).collect();
        let effect_names: Vec<&Ident> = raw.iter().map(|e| &e.name).collect();
        let mut effects = Vec::new();
        for e in &raw {
            check_unique(&e.requires, "required effect")?;
            let requires = e
                .requires
                .iter()
                .map(|r| lookup(&effect_names, r, "effect"))
                .collect::<syn::Result<_>>()?;
            let only = match &e.only {
                None => None,
                Some(names) => {
                    check_unique(names, "family")?;
                    Some(
                        names
                            .iter()
                            .map(|f| lookup(&family_names, f, "family"))
                            .collect::<syn::Result<_>>()?,
                    )
                }
            };
            effects.push(Effect {
                name: e.name.clone(),
                konst: e.konst.clone(),
                requires,
                only,
                feature: e.feature.clone(),
            });
        }
        check_acyclic(&effects, &raw)?;
        Ok(Model {
            dims: dim_values,
            families,
            effects,
        })
    }
}

/// Rejects a `requires` cycle, spanned at the name that closes it.
fn check_acyclic(effects: &[Effect], raw: &[RawEffect]) -> syn::Result<()> {
    /// Depth-first search; `state[i]`: 0 unvisited, 1 on the current path, 2 done.
    fn visit(i: usize, effects: &[Effect], raw: &[RawEffect], state: &mut [u8]) -> syn::Result<()> {
        state[i] = 1;
        for (k, &r) in effects[i].requires.iter().enumerate() {
            match state[r] {
                1 => {
                    let at = &raw[i].requires[k];
                    let msg = format!(
                        "`requires` cycle: `{}` requires `{at}`, which (in turn) requires `{}`",
                        raw[i].name, raw[i].name
                    );
                    return Err(syn::Error::new(at.span(), msg));
                }
                0 => visit(r, effects, raw, state)?,
                _ => {}
            }
        }
        state[i] = 2;
        Ok(())
    }
    let mut state = vec![0u8; effects.len()];
    for i in 0..effects.len() {
        if state[i] == 0 {
            visit(i, effects, raw, &mut state)?;
        }
    }
    Ok(())
}
