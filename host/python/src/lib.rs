//! `gsph._gsph`: the extension module under the `gsph` Python package
//! (host/python/python/gsph/__init__.py wraps it; docs/python.md). Long calls release
//! the GIL and look for signals between steps (Ctrl-C raises `KeyboardInterrupt` after
//! the step in progress); fields cross as numpy arrays.

use gsph::api::{ApiError, ApiResult, Particles, Simulation as Sim};
use numpy::{IntoPyArray, PyArrayMethods, PyReadonlyArray1};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

create_exception!(
    _gsph,
    GsphError,
    PyException,
    "A gsph error (one line, naming the key, particle, step or file)."
);
create_exception!(
    _gsph,
    SceneError,
    GsphError,
    "The scene (file, text, overrides) is invalid."
);
create_exception!(
    _gsph,
    SimulationError,
    GsphError,
    "The simulation failed (a step, a neighbour overflow)."
);
create_exception!(
    _gsph,
    ArgumentError,
    GsphError,
    "A bad argument: unknown field, wrong length, non-finite value."
);
create_exception!(
    _gsph,
    OutputError,
    GsphError,
    "A file could not be read or written."
);

fn err(e: ApiError) -> PyErr {
    let msg = e.to_string();
    match e {
        ApiError::Scene(_) => SceneError::new_err(msg),
        ApiError::Simulation(_) => SimulationError::new_err(msg),
        ApiError::Argument(_) | ApiError::Stopped(_) => ArgumentError::new_err(msg),
        ApiError::Io(_) => OutputError::new_err(msg),
    }
}

/// Seconds between two looks for signals during a long call.
const SIGNAL_PERIOD: f64 = 0.02;

/// Between the steps of a long call (the GIL released): runs Python's signal handlers
/// every [`SIGNAL_PERIOD`] s; an exception from one (`KeyboardInterrupt` on Ctrl-C) is
/// kept in `raised` and stops the call after the step just taken.
fn between_steps(last: &mut std::time::Instant, raised: &mut Option<PyErr>) -> ApiResult<()> {
    if last.elapsed().as_secs_f64() < SIGNAL_PERIOD {
        return Ok(());
    }
    *last = std::time::Instant::now();
    Python::attach(|py| py.check_signals()).map_err(|e| {
        *raised = Some(e);
        ApiError::Stopped("stopped by a signal".into())
    })
}

/// The result of a long call: the exception a signal handler raised, if one stopped it.
fn after_steps<T>(r: ApiResult<T>, raised: Option<PyErr>) -> PyResult<T> {
    match (r, raised) {
        (Err(_), Some(e)) => Err(e),
        (r, _) => r.map_err(err),
    }
}

/// A simulation (see the `gsph` package for the documented wrapper).
#[pyclass(module = "gsph._gsph", name = "Simulation")]
struct PySim {
    inner: Sim,
}

#[pymethods]
impl PySim {
    /// Builds a scene file with overrides.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf, overrides: Vec<String>) -> PyResult<Self> {
        let inner = py
            .detach(|| Sim::from_file(&path, &overrides))
            .map_err(err)?;
        Ok(PySim { inner })
    }

    /// Builds scene text with overrides.
    #[staticmethod]
    fn from_text(
        py: Python<'_>,
        text: String,
        origin: String,
        overrides: Vec<String>,
    ) -> PyResult<Self> {
        let inner = py
            .detach(|| Sim::from_text(&text, &origin, &overrides))
            .map_err(err)?;
        Ok(PySim { inner })
    }

    /// Builds the caller's particles (flat float64 arrays; empty for absent).
    #[staticmethod]
    #[allow(clippy::too_many_arguments)]
    fn from_particles(
        settings: String,
        overrides: Vec<String>,
        position: PyReadonlyArray1<'_, f64>,
        velocity: PyReadonlyArray1<'_, f64>,
        density: PyReadonlyArray1<'_, f64>,
        energy: PyReadonlyArray1<'_, f64>,
        mass: PyReadonlyArray1<'_, f64>,
        material: Vec<u32>,
        spacing: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Self> {
        let parts = Particles {
            position: position.as_slice()?,
            velocity: velocity.as_slice()?,
            density: density.as_slice()?,
            energy: energy.as_slice()?,
            mass: mass.as_slice()?,
            material: &material,
            spacing: spacing.as_slice()?,
        };
        let inner = Sim::from_particles(&settings, "settings", &overrides, &parts).map_err(err)?;
        Ok(PySim { inner })
    }

    /// Continues from a checkpoint directory.
    #[staticmethod]
    fn from_checkpoint(py: Python<'_>, dir: PathBuf) -> PyResult<Self> {
        let inner = py.detach(|| Sim::from_checkpoint(&dir)).map_err(err)?;
        Ok(PySim { inner })
    }

    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    fn __len__(&self) -> usize {
        self.inner.len()
    }

    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }

    #[getter]
    fn steps(&self) -> u64 {
        self.inner.steps()
    }

    #[getter]
    fn scheme(&self) -> &'static str {
        self.inner.scheme().name()
    }

    #[getter]
    fn effects(&self) -> Vec<&'static str> {
        self.inner.effects().names().collect()
    }

    fn stable_dt(&mut self) -> PyResult<f64> {
        self.inner.stable_dt().map_err(err)
    }

    #[pyo3(signature = (dt=None))]
    fn step(&mut self, py: Python<'_>, dt: Option<f64>) -> PyResult<f64> {
        let inner = &mut self.inner;
        py.detach(|| inner.step(dt)).map_err(err)
    }

    fn advance(&mut self, py: Python<'_>, t: f64) -> PyResult<u64> {
        let inner = &mut self.inner;
        let (mut last, mut raised) = (std::time::Instant::now(), None);
        let r = py.detach(|| inner.advance_to_with(t, || between_steps(&mut last, &mut raised)));
        after_steps(r, raised)
    }

    fn run(&mut self, py: Python<'_>) -> PyResult<u64> {
        let inner = &mut self.inner;
        let (mut last, mut raised) = (std::time::Instant::now(), None);
        let r = py.detach(|| inner.run_with(|| between_steps(&mut last, &mut raised)));
        after_steps(r, raised)
    }

    /// Values per particle of a field.
    fn components(&self, name: &str) -> PyResult<usize> {
        self.inner.components(name).map_err(err)
    }

    /// A field as a new float64 array (n,) or (n, components), id order.
    fn field<'py>(&mut self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let f = self.inner.field(name).map_err(err)?;
        let (n, c) = (self.inner.len(), f.components(self.inner.dim()));
        let v = self.inner.get(name).map_err(err)?.into_pyarray(py);
        if f.is_array() {
            Ok(v.reshape([n, c])?.into_any())
        } else {
            Ok(v.into_any())
        }
    }

    /// Sets a field from a flat float64 array (id order).
    fn set_field(&mut self, name: &str, data: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        self.inner.write(name, data.as_slice()?).map_err(err)
    }

    fn ids<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.inner.ids().into_pyarray(py).into_any()
    }

    /// Sets the external acceleration from a flat float64 array (empty: none).
    fn set_acceleration(&mut self, a: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        self.inner
            .set_external_acceleration(a.as_slice()?)
            .map_err(err)
    }

    fn energy(&self) -> (f64, f64) {
        self.inner.energy()
    }

    fn momentum(&self) -> Vec<f64> {
        self.inner.momentum()[..self.inner.dim()].to_vec()
    }

    fn external_impulse(&self) -> Vec<f64> {
        self.inner.external_impulse()[..self.inner.dim()].to_vec()
    }

    /// (x, sigma_xx, exact sigma_xx or NaN) of every particle sorted by x, for scenes
    /// whose reference is a stress profile.
    fn profile<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = self.inner.profile().map_err(err)?;
        let n = rows.len();
        let flat: Vec<f64> = rows.into_iter().flatten().collect();
        Ok(flat.into_pyarray(py).reshape([n, 3])?.into_any())
    }

    fn summary_json(&self) -> String {
        serde_json::Value::Object(self.inner.summary()).to_string()
    }

    fn write_snapshot(&self, path: PathBuf) -> PyResult<()> {
        self.inner.write_snapshot(&path).map_err(err)
    }

    fn write_checkpoint(&self, dir: PathBuf) -> PyResult<()> {
        self.inner.write_checkpoint(&dir).map_err(err)
    }

    /// The series so far: (column names, float64 array (rows, columns)).
    fn series<'py>(&self, py: Python<'py>) -> PyResult<(Vec<String>, Bound<'py, PyAny>)> {
        let s = self.inner.series();
        let (rows, cols) = (s.rows.len(), s.names.len());
        let flat: Vec<f64> = s.rows.into_iter().flatten().collect();
        Ok((
            s.names,
            flat.into_pyarray(py).reshape([rows, cols])?.into_any(),
        ))
    }

    fn series_csv(&self) -> String {
        self.inner.series_csv().to_string()
    }

    fn write_series(&self, path: PathBuf) -> PyResult<()> {
        self.inner.write_series(&path).map_err(err)
    }

    fn write_snapshots(&self, dir: PathBuf) -> PyResult<()> {
        self.inner.write_snapshots(&dir).map_err(err)
    }

    fn open_snapshots(&mut self, dir: PathBuf) -> PyResult<()> {
        self.inner.open_snapshots(&dir).map_err(err)
    }

    fn append_snapshot(&mut self) -> PyResult<()> {
        self.inner.append_snapshot().map_err(err)
    }

    fn close_snapshots(&mut self) -> PyResult<()> {
        self.inner.close_snapshots().map_err(err)
    }
}

/// Runs `gsph study`: every scheme at every resolution; returns the rows as JSON and
/// writes the tables and plots into `out`.
#[pyfunction]
#[pyo3(signature = (scene, schemes, resolutions, overrides, metric, out))]
fn study_json(
    py: Python<'_>,
    scene: PathBuf,
    schemes: Vec<String>,
    resolutions: Vec<f64>,
    overrides: Vec<String>,
    metric: Option<String>,
    out: PathBuf,
) -> PyResult<String> {
    let schemes = gsph::study::parse_schemes(&schemes.join(",")).map_err(ArgumentError::new_err)?;
    let opts = gsph::study::StudyOptions {
        schemes,
        resolutions,
        overrides,
        metric,
        out,
    };
    let rows = py
        .detach(|| gsph::study::run_study(&scene, &opts))
        .map_err(GsphError::new_err)?;
    let list: Vec<serde_json::Value> = rows.iter().map(gsph::study::row_json).collect();
    Ok(serde_json::Value::Array(list).to_string())
}

/// Runs `gsph hugoniot`: a moving-window run per particle velocity; returns the points as
/// JSON and writes their profiles, the table and the plot into `out`.
#[pyfunction]
#[pyo3(signature = (scene, overrides, ups, out))]
fn hugoniot_json(
    py: Python<'_>,
    scene: PathBuf,
    overrides: Vec<String>,
    ups: Vec<f64>,
    out: PathBuf,
) -> PyResult<String> {
    let s = gsph::scene::load(Path::new(&scene), &overrides)
        .map_err(|e| SceneError::new_err(e.to_string()))?;
    let opts = gsph::window::hugoniot::HugoniotOptions {
        ups,
        ..Default::default()
    };
    let points = py
        .detach(|| {
            std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
            gsph::window::run_hugoniot(&s, &opts, &out)
        })
        .map_err(GsphError::new_err)?;
    Ok(gsph::window::hugoniot::to_json(&points).to_string())
}

#[pymodule]
fn _gsph(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<PySim>()?;
    m.add_function(wrap_pyfunction!(study_json, m)?)?;
    m.add_function(wrap_pyfunction!(hugoniot_json, m)?)?;
    m.add("GsphError", py.get_type::<GsphError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SimulationError", py.get_type::<SimulationError>())?;
    m.add("ArgumentError", py.get_type::<ArgumentError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
