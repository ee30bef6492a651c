//! Every material parameter runs physically or is refused (issue 45 item 4): each numeric
//! key of every library material (every EOS and strength model but Murnaghan, which a
//! water added here covers), and `tensile_strength`, set in turn to 1e-300, 1e-20, 1e20,
//! 1e300 and -1, either is refused by the scene check in one line naming the key, or a
//! short 1D impact with it runs its steps and ends with every value finite.

use gsph::driver::{run, RunOptions};
use gsph::scene::library::{table_of, LIBRARY};
use gsph::scene::parse;
use toml::{Table, Value};

const VALUES: [f64; 5] = [1e-300, 1e-20, 1e20, 1e300, -1.0];

/// Batchelor's water (Murnaghan, gamma = 7), a fluid.
const WATER: &str = r#"
rho0 = 1000.0
eos = { type = "murnaghan", c0 = 1480.0, gamma = 7.0 }
"#;

/// A 1D impact of two bars of `material` at 300 m/s, 40 steps of scheme `scheme`.
fn scene(material: &Table, scheme: &str) -> String {
    let mut m = material.clone();
    m.insert("name".into(), "m".into());
    let bar = |lo: f64, v: f64| {
        toml::toml! {
            material = "m"
            shape = { type = "segment", min = lo, max = (lo + 2e-3) }
            spacing = 1e-4
            velocity = { type = "uniform", value = [v] }
        }
    };
    let mut s = toml::toml! {
        dim = 1
        t_end = 1e-3
        max_steps = 40
        [output]
        snapshots = 1
    };
    s.insert("scheme".into(), scheme.into());
    s.insert("materials".into(), Value::Array(vec![Value::Table(m)]));
    s.insert(
        "bodies".into(),
        Value::Array(vec![
            Value::Table(bar(0.0, 300.0)),
            Value::Table(bar(2e-3, 0.0)),
        ]),
    );
    toml::to_string(&s).unwrap()
}

/// The numeric keys of a material table: its own and those of its `eos` and `strength`.
fn numeric_keys(m: &Table) -> Vec<Vec<String>> {
    let mut keys = Vec::new();
    for (k, v) in m {
        match v {
            Value::Float(_) | Value::Integer(_) => keys.push(vec![k.clone()]),
            Value::Table(t) => {
                for (k2, v2) in t {
                    if matches!(v2, Value::Float(_) | Value::Integer(_)) {
                        keys.push(vec![k.clone(), k2.clone()]);
                    }
                }
            }
            _ => {}
        }
    }
    keys
}

fn set(m: &Table, key: &[String], v: f64) -> Table {
    let mut m = m.clone();
    match key {
        [k] => {
            m.insert(k.clone(), v.into());
        }
        [k, k2] => {
            m[k].as_table_mut().unwrap().insert(k2.clone(), v.into());
        }
        _ => unreachable!(),
    }
    m
}

/// What a material with `key` = `v` does: `Ok` when refused naming the key or run to
/// the end with finite values; `Err` with what went wrong.
fn verdict(m: &Table, scheme: &str, key: &[String], v: f64) -> Result<(), String> {
    let path = format!("materials[0].{}", key.join("."));
    let sc = match parse(&scene(&set(m, key, v), scheme), "sweep", &[]) {
        Err(e) if e.0.contains(&path) && !e.0.contains('\n') => return Ok(()),
        Err(e) => return Err(format!("refused without naming {path}: {e}")),
        Ok(sc) => sc,
    };
    let opts = RunOptions {
        out: None,
        progress: false,
    };
    let r = run(&sc, "sweep", &opts).map_err(|e| format!("accepted, then: {e}"))?;
    if r.summary.steps < 40 {
        return Err(format!(
            "accepted, then stopped after {} steps",
            r.summary.steps
        ));
    }
    let t = &r.table;
    let bad = t
        .float_columns()
        .iter()
        .flat_map(|c| c.iter())
        .find(|v| !v.is_finite());
    match bad {
        Some(v) => Err(format!("accepted, then a value {v}")),
        None => Ok(()),
    }
}

#[test]
fn every_material_parameter_runs_physically_or_is_refused_naming_it() {
    let mut materials: Vec<(String, Table)> = LIBRARY
        .iter()
        .map(|e| (e.name.to_string(), table_of(e).unwrap()))
        .collect();
    materials.push(("water (murnaghan)".into(), WATER.parse().unwrap()));
    let mut failures = Vec::new();
    let mut tried = 0;
    for (name, mut m) in materials {
        m.remove("name");
        if !m.contains_key("tensile_strength") && !m.to_string().contains("jh1") {
            m.insert("tensile_strength".into(), 1e9.into());
        }
        // the base material runs
        for scheme in ["ts2", "pm"] {
            verdict(&m, scheme, &["rho0".into()], m["rho0"].as_float().unwrap())
                .unwrap_or_else(|e| panic!("{name} as it is, {scheme}: {e}"));
        }
        for key in numeric_keys(&m) {
            for v in VALUES {
                for scheme in ["ts2", "pm"] {
                    tried += 1;
                    if let Err(e) = verdict(&m, scheme, &key, v) {
                        failures.push(format!("{name}: {} = {v:e} ({scheme}): {e}", key.join(".")));
                    }
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {tried}:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
