//! Per-particle fields by name, read into and written from caller buffers in particle-id
//! order (the solver renumbers particles in memory; the caller never sees that order).

use super::{with_sim, ApiError, ApiResult, Simulation};
pub use crate::sim::values::Range;
use crate::sim::values::{range_of, Values};
use crate::sim::Sim;
use gsph_core::effects::EffectSet;
use gsph_core::state::smoothing_length;

/// What the library knows of a per-particle field: a row of the core's particle table
/// ([`gsph_core::particle_fields!`] or [`gsph_core::derived_fields!`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Info {
    /// The API name.
    pub name: &'static str,
    /// Other names accepted (the table's field name, those of `final.csv` and the scene).
    pub aliases: &'static [&'static str],
    /// The table's field name.
    pub field: &'static str,
    /// The table's kind (`point`, `vector`, `tensor`, `scalar`).
    pub kind: &'static str,
    /// Whether a caller may write it.
    pub writable: bool,
    /// The range a written value must lie in.
    pub range: Range,
    /// The effect that stores it (`HYDRO`: every run).
    pub effect: EffectSet,
    /// SI unit (`1`: dimensionless; empty: a label).
    pub unit: &'static str,
}

/// The [`Info`] of the state fields, then of the derived quantities.
macro_rules! field_infos {
    (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, {
        api($api:literal [$($alias:ident),*], $w:ident, $range:ident)
        out[$($col:ident $cdoc:literal),*]
        $(init $init:tt)?
    };)*) => {
        gsph_core::derived_fields!(derived_infos { $(Info {
            name: $api,
            aliases: &[stringify!($name), $(stringify!($alias)),*],
            field: stringify!($name),
            kind: stringify!($kind),
            writable: writable!($w),
            range: range_of!($range),
            effect: EffectSet::$when,
            unit: $unit,
        },)* });
    };
}

/// See [`field_infos`]: derived quantities are read-only scalars every run has.
macro_rules! derived_infos {
    (($($state:tt)*) $($name:ident: $unit:literal, $doc:literal, {
        api($api:literal [$($alias:ident),*], $w:ident, $range:ident)
        out[$($col:ident $cdoc:literal),*]
        $(init $init:tt)?
    };)*) => {
        /// Every field: the state fields in the order of the core's table, then the
        /// derived quantities.
        pub const FIELDS: &[Info] = &[$($state)* $(Info {
            name: $api,
            aliases: &[stringify!($name), $(stringify!($alias)),*],
            field: stringify!($name),
            kind: "scalar",
            writable: false,
            range: Range::Any,
            effect: EffectSet::HYDRO,
            unit: $unit,
        },)*];
    };
}

macro_rules! writable {
    (write) => {
        true
    };
    (read) => {
        false
    };
}

gsph_core::particle_fields!(field_infos {});

/// A per-particle field (an entry of [`FIELDS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Field(&'static Info);

impl Field {
    /// The field's name.
    pub const fn name(self) -> &'static str {
        self.0.name
    }

    /// The other names also accepted (the table's, `final.csv`'s and the scene's).
    pub fn aliases(self) -> impl Iterator<Item = &'static str> {
        let name = self.0.name;
        self.0.aliases.iter().copied().filter(move |a| *a != name)
    }

    /// What the library knows of the field.
    pub const fn info(self) -> &'static Info {
        self.0
    }

    /// The field of a name or alias.
    pub fn from_name(name: &str) -> Option<Field> {
        FIELDS
            .iter()
            .find(|f| f.name == name || f.aliases.contains(&name))
            .map(Field)
    }

    /// Values per particle in dimension `dim`.
    pub fn components(self, dim: usize) -> usize {
        match self.0.kind {
            "point" | "vector" => dim,
            "tensor" => 6,
            _ => 1,
        }
    }

    /// True for a field of several components per particle (a point, vector or tensor).
    pub fn is_array(self) -> bool {
        self.0.kind != "scalar"
    }

    /// False for the fields that follow from others (pressure, sound speeds, derived
    /// quantities) or identify a particle (material).
    pub const fn writable(self) -> bool {
        self.0.writable
    }

    /// The effect the field needs and what in a scene turns that effect on.
    fn needs(self) -> Option<(EffectSet, &'static str)> {
        let e = self.0.effect;
        let why = if e == EffectSet::STRENGTH {
            "no material has strength"
        } else if e == EffectSet::PLASTICITY {
            "no material has a yield model"
        } else if e == EffectSet::DAMAGE {
            "no material has a damage model"
        } else if e == EffectSet::HEAT {
            "no material has a thermal model"
        } else {
            return None;
        };
        Some((e, why))
    }
}

fn names() -> String {
    FIELDS.iter().map(|f| f.name).collect::<Vec<_>>().join(", ")
}

/// Copies `v` of the particles `order` into `out`, `per` values each.
fn read_into<T: Values>(v: &[T], order: &[usize], per: usize, out: &mut [f64]) {
    for (o, &i) in out.chunks_exact_mut(per).zip(order) {
        v[i].get(o);
    }
}

/// Writes `data` (`per` values each) into `v` of the particles `order`.
fn write_from<T: Values>(v: &mut [T], order: &[usize], per: usize, data: &[f64]) {
    for (x, &i) in data.chunks_exact(per).zip(order) {
        v[i].set(x);
    }
}

/// `get` and `set` over the fields of the core's table, by the table's name.
macro_rules! field_access {
    (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        /// Copies field `f` of the particles `order` (memory indices in id order) into `out`.
        fn get<const D: usize>(s: &Sim<D>, f: Field, order: &[usize], out: &mut [f64]) {
            let per = f.components(D);
            match f.0.field {
                $(stringify!($name) => read_into(&s.$name, order, per, out),)*
                derived => {
                    let v = s.derived(derived).unwrap_or_default();
                    read_into(&v, order, per, out)
                }
            }
        }

        /// Writes `data` into field `f` of the particles `order` (a writable state field).
        fn write_field<const D: usize>(s: &mut Sim<D>, f: Field, order: &[usize], data: &[f64]) {
            let per = f.components(D);
            match f.0.field {
                $(stringify!($name) => write_from(&mut s.$name, order, per, data),)*
                _ => unreachable!("read-only"),
            }
        }
    };
}

gsph_core::particle_fields!(field_access {});

/// The range a written value must lie in, as a message, or `None` when it does.
fn out_of_range(f: Field, v: f64) -> Option<&'static str> {
    f.0.range.refuses(v)
}

/// Writes `data` (id order) into field `f` of the particles `order`; positions are wrapped
/// into a periodic box, density and energy bring pressure and sound speeds along through
/// the EOS, density and mass the smoothing length.
fn set<const D: usize>(s: &mut Sim<D>, f: Field, order: &[usize], data: &[f64]) {
    write_field(s, f, order, data);
    let name = f.0.field;
    if name == "x" {
        for &i in order {
            s.x[i] = s.periodic.wrap(s.x[i]);
        }
    }
    if matches!(name, "rho" | "m") && !s.options.constant_h {
        // h follows m and rho, as the step's EOS refresh sets it
        for &i in order {
            s.h[i] = smoothing_length::<D>(s.h_factor, s.m[i], s.rho[i]);
        }
    }
    s.state_changed();
    if matches!(name, "rho" | "e") {
        for &i in order {
            let mat = s.materials[s.mat[i] as usize];
            let st = mat.eos(s.rho[i], s.e[i]);
            s.p[i] = st.p;
            s.c[i] = st.c2.max(0.0).sqrt();
            s.cl[i] = mat.c_long(s.rho[i], st.c2.max(0.0));
        }
    }
}

impl Simulation {
    /// The field of `name` (a name or alias), or the error saying it is unknown or not
    /// simulated by this scene.
    pub fn field(&self, name: &str) -> ApiResult<Field> {
        let f = Field::from_name(name).ok_or_else(|| {
            ApiError::Argument(format!("unknown field `{name}` (fields: {})", names()))
        })?;
        if let Some((effect, why)) = f.needs() {
            if !self.effects().contains(effect) {
                return Err(ApiError::Argument(format!(
                    "field `{}` is not simulated by this scene ({} scheme): {why}",
                    f.name(),
                    self.scheme().name()
                )));
            }
        }
        Ok(f)
    }

    /// Values per particle of the field `name`.
    pub fn components(&self, name: &str) -> ApiResult<usize> {
        Ok(self.field(name)?.components(self.dim()))
    }

    fn check_len(&self, f: Field, len: usize) -> ApiResult<()> {
        let want = self.len() * f.components(self.dim());
        if len != want {
            return Err(ApiError::Argument(format!(
                "field `{}`: buffer of {len} values, {want} needed ({} particles x {} components)",
                f.name(),
                self.len(),
                f.components(self.dim())
            )));
        }
        Ok(())
    }

    /// Copies the field `name` into `out` (`components` values per particle, id order).
    pub fn read(&mut self, name: &str, out: &mut [f64]) -> ApiResult<()> {
        let f = self.field(name)?;
        self.check_len(f, out.len())?;
        self.refresh_order();
        let order = &self.order.1;
        with_sim!(&self.sim, s => get(s, f, order, out));
        Ok(())
    }

    /// The field `name` as a new vector (id order).
    pub fn get(&mut self, name: &str) -> ApiResult<Vec<f64>> {
        let mut out = vec![0.0; self.len() * self.components(name)?];
        self.read(name, &mut out)?;
        Ok(out)
    }

    /// Sets the field `name` from `data` (`components` values per particle, id order).
    /// Every value is checked before any is written. Density and mass bring the smoothing
    /// length along (unless the scene has `constant_h`), density and energy the pressure
    /// and sound speeds.
    pub fn write(&mut self, name: &str, data: &[f64]) -> ApiResult<()> {
        self.check_usable()?;
        let f = self.field(name)?;
        if !f.writable() {
            return Err(ApiError::Argument(format!(
                "field `{}` is read-only (pressure and sound speed follow from density and energy through the EOS)",
                f.name()
            )));
        }
        self.check_len(f, data.len())?;
        let per = f.components(self.dim());
        if let Some((k, why)) = data
            .iter()
            .enumerate()
            .find_map(|(k, &v)| out_of_range(f, v).map(|w| (k, w)))
        {
            return Err(ApiError::Argument(format!(
                "field `{}`: value {k} (particle {}) {why} (got {:e})",
                f.name(),
                k / per,
                data[k]
            )));
        }
        self.refresh_order();
        let order = &self.order.1;
        with_sim!(&mut self.sim, s => set(s, f, order, data));
        Ok(())
    }
}
