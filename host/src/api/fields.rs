//! Per-particle fields by name, read into and written from caller buffers in particle-id
//! order (the solver renumbers particles in memory; the caller never sees that order).

use super::{with_sim, ApiError, ApiResult, Simulation};
use crate::sim::Sim;
use gsph_core::effects::EffectSet;
use gsph_core::math::{Sym3, Vector};
use gsph_core::state::smoothing_length;

/// A per-particle field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// Position, m (`dim` components).
    Position,
    /// Velocity, m/s (`dim` components).
    Velocity,
    /// Mass, kg.
    Mass,
    /// Density, kg/m³ (writing it updates pressure and sound speeds through the EOS).
    Density,
    /// Pressure, Pa (read-only: it follows from density and energy).
    Pressure,
    /// Specific internal energy, J/kg (writing it updates pressure and sound speeds).
    Energy,
    /// Bulk sound speed, m/s (read-only).
    SoundSpeed,
    /// Stress deviator, Pa: 6 components `xx, yy, zz, xy, xz, yz` (materials with strength).
    Deviator,
    /// Equivalent plastic strain (materials with a yield model).
    PlasticStrain,
    /// Damage in [0, 1] (materials with a damage model).
    Damage,
    /// Temperature, K (materials with a thermal model).
    Temperature,
    /// Smoothing length, m.
    SmoothingLength,
    /// Material index (read-only; the order of `[[materials]]`).
    Material,
}

/// Every field, in the order listings show them.
pub const FIELDS: [Field; 13] = [
    Field::Position,
    Field::Velocity,
    Field::Mass,
    Field::Density,
    Field::Pressure,
    Field::Energy,
    Field::SoundSpeed,
    Field::Deviator,
    Field::PlasticStrain,
    Field::Damage,
    Field::Temperature,
    Field::SmoothingLength,
    Field::Material,
];

impl Field {
    /// The field's name.
    pub const fn name(self) -> &'static str {
        match self {
            Field::Position => "position",
            Field::Velocity => "velocity",
            Field::Mass => "mass",
            Field::Density => "density",
            Field::Pressure => "pressure",
            Field::Energy => "energy",
            Field::SoundSpeed => "sound_speed",
            Field::Deviator => "deviator",
            Field::PlasticStrain => "plastic_strain",
            Field::Damage => "damage",
            Field::Temperature => "temperature",
            Field::SmoothingLength => "h",
            Field::Material => "material",
        }
    }

    /// The short names also accepted (those of `final.csv` and the scene keys).
    pub const fn aliases(self) -> &'static [&'static str] {
        match self {
            Field::Position => &["x"],
            Field::Velocity => &["v"],
            Field::Mass => &["m"],
            Field::Density => &["rho"],
            Field::Pressure => &["p"],
            Field::Energy => &["e"],
            Field::SoundSpeed => &["c"],
            Field::Deviator => &["s"],
            Field::PlasticStrain => &["eps_p"],
            Field::Damage => &[],
            Field::Temperature => &["temp"],
            Field::SmoothingLength => &["smoothing_length"],
            Field::Material => &["mat"],
        }
    }

    /// The field of a name or alias.
    pub fn from_name(name: &str) -> Option<Field> {
        FIELDS
            .into_iter()
            .find(|f| f.name() == name || f.aliases().contains(&name))
    }

    /// Values per particle in dimension `dim`.
    pub const fn components(self, dim: usize) -> usize {
        match self {
            Field::Position | Field::Velocity => dim,
            Field::Deviator => 6,
            _ => 1,
        }
    }

    /// False for the fields that follow from others (pressure, sound speed) or identify a
    /// particle (material).
    pub const fn writable(self) -> bool {
        !matches!(self, Field::Pressure | Field::SoundSpeed | Field::Material)
    }

    /// The effect the field needs and what in a scene turns that effect on.
    const fn needs(self) -> Option<(EffectSet, &'static str)> {
        match self {
            Field::Deviator => Some((EffectSet::STRENGTH, "no material has strength")),
            Field::PlasticStrain => Some((EffectSet::PLASTICITY, "no material has a yield model")),
            Field::Damage => Some((EffectSet::DAMAGE, "no material has a damage model")),
            Field::Temperature => Some((EffectSet::HEAT, "no material has a thermal model")),
            _ => None,
        }
    }
}

fn names() -> String {
    FIELDS.map(|f| f.name()).join(", ")
}

fn sym_get(s: &Sym3, k: usize) -> f64 {
    [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz][k]
}

fn sym_set(s: &mut Sym3, k: usize, v: f64) {
    *[
        &mut s.xx, &mut s.yy, &mut s.zz, &mut s.xy, &mut s.xz, &mut s.yz,
    ][k] = v;
}

/// Copies field `f` of the particles `order` (memory indices in id order) into `out`.
fn get<const D: usize>(s: &Sim<D>, f: Field, order: &[usize], out: &mut [f64]) {
    let scalar = |v: &[f64], out: &mut [f64]| {
        for (o, &i) in out.iter_mut().zip(order) {
            *o = v[i];
        }
    };
    let vector = |v: &[Vector<D>], out: &mut [f64]| {
        for (o, &i) in out.chunks_exact_mut(D).zip(order) {
            o.copy_from_slice(v[i].as_slice());
        }
    };
    match f {
        Field::Position => vector(&s.x, out),
        Field::Velocity => vector(&s.v, out),
        Field::Mass => scalar(&s.m, out),
        Field::Density => scalar(&s.rho, out),
        Field::Pressure => scalar(&s.p, out),
        Field::Energy => scalar(&s.e, out),
        Field::SoundSpeed => scalar(&s.c, out),
        Field::PlasticStrain => scalar(&s.eps_p, out),
        Field::Damage => scalar(&s.damage, out),
        Field::Temperature => scalar(&s.temp, out),
        Field::SmoothingLength => scalar(&s.h, out),
        Field::Material => {
            for (o, &i) in out.iter_mut().zip(order) {
                *o = s.mat[i] as f64;
            }
        }
        Field::Deviator => {
            for (o, &i) in out.chunks_exact_mut(6).zip(order) {
                for (k, ok) in o.iter_mut().enumerate() {
                    *ok = sym_get(&s.s[i], k);
                }
            }
        }
    }
}

/// The range a written value must lie in, as a message, or `None` when it does.
fn out_of_range(f: Field, v: f64) -> Option<&'static str> {
    if !v.is_finite() {
        return Some("is not finite");
    }
    let bad = match f {
        Field::Mass | Field::Density | Field::SmoothingLength | Field::Temperature => v <= 0.0,
        Field::PlasticStrain => v < 0.0,
        Field::Damage => !(0.0..=1.0).contains(&v),
        _ => false,
    };
    bad.then_some(match f {
        Field::PlasticStrain => "must not be negative",
        Field::Damage => "must lie in [0, 1]",
        _ => "must be positive",
    })
}

/// Writes `data` (id order) into field `f` of the particles `order`; density and energy
/// bring pressure and sound speeds along through the EOS.
fn set<const D: usize>(s: &mut Sim<D>, f: Field, order: &[usize], data: &[f64]) {
    let scalar = |v: &mut [f64]| {
        for (&x, &i) in data.iter().zip(order) {
            v[i] = x;
        }
    };
    match f {
        Field::Position => {
            for (x, &i) in data.chunks_exact(D).zip(order) {
                s.x[i] = s.periodic.wrap(Vector::<D>::from_column_slice(x));
            }
        }
        Field::Velocity => {
            for (x, &i) in data.chunks_exact(D).zip(order) {
                s.v[i] = Vector::<D>::from_column_slice(x);
            }
        }
        Field::Mass => scalar(&mut s.m),
        Field::Density => scalar(&mut s.rho),
        Field::Energy => scalar(&mut s.e),
        Field::PlasticStrain => scalar(&mut s.eps_p),
        Field::Damage => scalar(&mut s.damage),
        Field::Temperature => scalar(&mut s.temp),
        Field::SmoothingLength => scalar(&mut s.h),
        Field::Deviator => {
            for (x, &i) in data.chunks_exact(6).zip(order) {
                for (k, &xk) in x.iter().enumerate() {
                    sym_set(&mut s.s[i], k, xk);
                }
            }
        }
        Field::Pressure | Field::SoundSpeed | Field::Material => unreachable!("read-only"),
    }
    if matches!(f, Field::Density | Field::Mass) && !s.options.constant_h {
        // h follows m and rho, as the step's EOS refresh sets it
        for &i in order {
            s.h[i] = smoothing_length::<D>(s.h_factor, s.m[i], s.rho[i]);
        }
    }
    s.state_changed();
    if matches!(f, Field::Density | Field::Energy) {
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
