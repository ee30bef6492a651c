//! Per-particle fields for plotting: the float columns of [`ParticleTable`] and derived
//! quantities (total stresses, von Mises stress, speed, radial velocity, radius), with units.

use crate::output::table::{ParticleTable, FLOAT_COLUMNS};

use super::PlotError;

/// Default h / spacing (the scene default `h_factor`).
const H_FACTOR: f64 = 1.2;

/// Fields computed from the columns: `sigma_xx` = sxx - p, `sigma_yy` = syy - p, `tau_xy` = sxy,
/// `von_mises` = sqrt(1.5 S:S), `speed` = |v|, `vr` = v·r/|r| (radial velocity about the origin)
/// and `r` = |r| (distance from the origin).
pub const DERIVED_FIELDS: [&str; 7] = [
    "sigma_xx",
    "sigma_yy",
    "tau_xy",
    "von_mises",
    "speed",
    "vr",
    "r",
];

/// Every field name [`field_values`] accepts: the float columns, then [`DERIVED_FIELDS`].
pub fn known_fields() -> Vec<String> {
    FLOAT_COLUMNS
        .iter()
        .chain(DERIVED_FIELDS.iter())
        .map(|s| s.to_string())
        .collect()
}

/// The values of field `name` for every particle of `table`.
pub fn field_values(table: &ParticleTable, name: &str) -> Result<Vec<f64>, PlotError> {
    if let Some(c) = table.float_column(name) {
        return Ok(c.to_vec());
    }
    let t = table;
    let n = t.len();
    let v: Vec<f64> = match name {
        "sigma_xx" => (0..n).map(|i| t.sxx[i] - t.p[i]).collect(),
        "sigma_yy" => (0..n).map(|i| t.syy[i] - t.p[i]).collect(),
        "tau_xy" => t.sxy.clone(),
        "von_mises" => (0..n)
            .map(|i| {
                let diag = t.sxx[i].powi(2) + t.syy[i].powi(2) + t.szz[i].powi(2);
                let off = t.sxy[i].powi(2) + t.sxz[i].powi(2) + t.syz[i].powi(2);
                (1.5 * (diag + 2.0 * off)).sqrt()
            })
            .collect(),
        "speed" => (0..n).map(|i| norm(t.vx[i], t.vy[i], t.vz[i])).collect(),
        "vr" => (0..n)
            .map(|i| {
                let r = norm(t.x[i], t.y[i], t.z[i]);
                let dot = t.x[i] * t.vx[i] + t.y[i] * t.vy[i] + t.z[i] * t.vz[i];
                if r > 0.0 {
                    dot / r
                } else {
                    0.0
                }
            })
            .collect(),
        "r" => (0..n).map(|i| norm(t.x[i], t.y[i], t.z[i])).collect(),
        _ => {
            return Err(PlotError::UnknownField {
                field: name.to_string(),
                known: known_fields(),
            })
        }
    };
    Ok(v)
}

/// The SI unit of field `name` ("" for dimensionless or unknown fields): a particle-table
/// column's from the core's table (in 3D: the plots label masses per particle), else that of a
/// field derived here.
pub fn field_unit(name: &str) -> &'static str {
    match name {
        "r" => "m",
        "speed" | "vr" => "m/s",
        "tau_xy" => "Pa",
        _ => match crate::output::meta::unit(name, 3) {
            "1" => "",
            "kg/m^3" => "kg/m³",
            u => u,
        },
    }
}

/// `name (unit)`, or just `name` when dimensionless.
pub fn field_label(name: &str) -> String {
    match field_unit(name) {
        "" => name.to_string(),
        u => format!("{name} ({u})"),
    }
}

/// The particle spacing: the median of (m/rho)^(1/dim), else of h / [`H_FACTOR`], else from the
/// bounding box; dim is 3 when any z is non-zero, else 2.
pub(crate) fn particle_spacing(t: &ParticleTable) -> f64 {
    let dim = if t.z.iter().any(|&z| z != 0.0) { 3 } else { 2 };
    let root = |v: f64| if dim == 3 { v.cbrt() } else { v.sqrt() };
    let from_volume = (0..t.len())
        .filter(|&i| t.m[i] > 0.0 && t.rho[i] > 0.0)
        .map(|i| root(t.m[i] / t.rho[i]));
    if let Some(d) = median(from_volume) {
        return d;
    }
    if let Some(h) = median(t.h.iter().copied().filter(|h| *h > 0.0)) {
        return h / H_FACTOR;
    }
    let extent = |c: &[f64]| {
        let f = c.iter().copied().filter(|v| v.is_finite());
        f.clone().fold(f64::NEG_INFINITY, f64::max) - f.fold(f64::INFINITY, f64::min)
    };
    let mut volume = extent(&t.x).max(0.0) * extent(&t.y).max(0.0);
    if dim == 3 {
        volume *= extent(&t.z).max(0.0);
    }
    let d = root(volume / t.len().max(1) as f64);
    if d.is_finite() && d > 0.0 {
        d
    } else {
        1e-3
    }
}

fn median(values: impl Iterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.filter(|v| v.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    let k = v.len() / 2;
    Some(*v.select_nth_unstable_by(k, f64::total_cmp).1)
}

fn norm(a: f64, b: f64, c: f64) -> f64 {
    (a * a + b * b + c * c).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::table::ParticleRow;

    #[test]
    fn derived_fields() {
        let mut t = ParticleTable::default();
        t.push(&ParticleRow {
            x: 3.0,
            y: 4.0,
            vx: 1.0,
            vy: 2.0,
            p: 10.0,
            sxx: 2.0,
            syy: -1.0,
            szz: -1.0,
            sxy: 0.5,
            ..ParticleRow::default()
        });
        let one = |f: &str| field_values(&t, f).unwrap()[0];
        assert_eq!(one("sigma_xx"), -8.0);
        assert_eq!(one("sigma_yy"), -11.0);
        assert_eq!(one("tau_xy"), 0.5);
        assert!((one("von_mises") - (1.5f64 * 6.5).sqrt()).abs() < 1e-12);
        assert!((one("speed") - 5f64.sqrt()).abs() < 1e-12);
        assert!((one("vr") - 11.0 / 5.0).abs() < 1e-12);
        assert_eq!(one("r"), 5.0);
        assert_eq!(one("p"), 10.0);
        let err = field_values(&t, "bogus").unwrap_err().to_string();
        assert!(err.contains("bogus") && err.contains("von_mises") && err.contains("eps_p"));
        assert_eq!(field_label("rho"), "rho (kg/m³)");
        assert_eq!(field_label("damage"), "damage");
    }
}
