"""gsph: Godunov SPH for solids under shock and impact, from Python.

    import gsph
    scene = gsph.Scene.from_file("cases/flyer_plate.toml", {"scheme": "ts1"})
    sim = scene.build()
    sim.run()                      # the steps `gsph run` takes
    p = sim.field("pressure")      # numpy array, particle-id order
    print(sim.summary()["energy_rel_error"])

Fields come back as new numpy arrays (copies): the solver renumbers particles in memory
(Morton order) at every neighbour-list rebuild, so no field is stored in id order and a
view would silently change meaning after the next step. Scalars are shape (n,), vectors
(n, dim), the deviator (n, 6) in the order xx, yy, zz, xy, xz, yz.

Errors are exceptions derived from gsph.GsphError carrying gsph's one-line message:
SceneError (names the key), SimulationError (names step and particle), ArgumentError,
OutputError. Long calls (build, step, advance, run, study, hugoniot) release the GIL;
Ctrl-C during run() or advance() raises KeyboardInterrupt after the step in progress,
and the simulation can go on (or be checkpointed) from there.
"""

import json
import os

import numpy as _np

from . import _gsph
from ._gsph import (
    ArgumentError,
    GsphError,
    OutputError,
    SceneError,
    SimulationError,
)

__version__ = _gsph.__version__
__all__ = [
    "Scene",
    "Simulation",
    "study",
    "hugoniot",
    "GsphError",
    "SceneError",
    "SimulationError",
    "ArgumentError",
    "OutputError",
]


def _overrides(overrides, unset=None):
    """`{"key": value}` or ["key=value", ...] as the list `gsph run --set` takes; a value
    None in the dict, a "unset:key" in the list and each key of `unset` remove the key
    (`gsph run --unset key`)."""
    out = []
    if isinstance(overrides, dict):
        for k, v in overrides.items():
            if v is None:
                out.append(f"unset:{k}")
                continue
            if isinstance(v, bool):
                v = "true" if v else "false"
            elif isinstance(v, float):
                v = repr(v)
            out.append(f"{k}={v}")
    elif overrides is not None:
        out = [str(o) for o in overrides]
    if isinstance(unset, str):
        unset = [unset]
    out += [f"unset:{k}" for k in (unset or [])]
    return out


def _flat(a):
    """`a` as a contiguous float64 vector (empty for None)."""
    if a is None:
        return _np.zeros(0)
    return _np.ascontiguousarray(a, dtype=_np.float64).ravel()


def _shaped(a, name, n, c):
    """`a` (shape (n, c), or (n,) when c is 1) as a contiguous float64 vector; any other
    shape is refused (a (c, n) array would be read with its components mixed)."""
    arr = _np.asarray(a, dtype=_np.float64)
    if arr.shape != (n, c) and not (c == 1 and arr.shape == (n,)):
        want = f"({n}, {c})" + (f" or ({n},)" if c == 1 else "")
        raise ArgumentError(f"{name}: shape {arr.shape}, {want} needed")
    return _np.ascontiguousarray(arr).ravel()


def _indices(a, name):
    """Material indices: non-negative integers, refused otherwise (never truncated)."""
    arr = _np.asarray(a).ravel()
    if arr.dtype.kind not in "iu":
        if arr.dtype.kind != "f" or not _np.all(_np.isfinite(arr) & (arr == _np.floor(arr))):
            raise ArgumentError(f"{name}: must be integers (got dtype {arr.dtype})")
    if _np.any(arr < 0):
        raise ArgumentError(f"{name}: must not be negative")
    return [int(m) for m in arr]


class Scene:
    """A scene file or text with overrides. `build()` validates and builds it."""

    def __init__(self, text=None, path=None, overrides=None, unset=None):
        if (text is None) == (path is None):
            raise ArgumentError("Scene: give exactly one of text and path")
        self.text = text
        self.path = None if path is None else os.fspath(path)
        self.overrides = _overrides(overrides, unset)

    @classmethod
    def from_file(cls, path, overrides=None, unset=None):
        """A scene file (TOML) with overrides: a dict {"key": value} or ["key=value"]
        (as `gsph run --set`); `unset` lists keys to remove (as `gsph run --unset`), as
        does a value None in the dict."""
        return cls(path=path, overrides=overrides, unset=unset)

    @classmethod
    def from_text(cls, text, overrides=None, unset=None):
        """Scene text (TOML, as a scene file) with overrides and keys to unset."""
        return cls(text=text, overrides=overrides, unset=unset)

    def build(self):
        """Validates the scene and builds its particles: a `Simulation`."""
        if self.path is not None:
            raw = _gsph.Simulation.from_file(self.path, self.overrides)
        else:
            raw = _gsph.Simulation.from_text(self.text, "scene text", self.overrides)
        return Simulation(raw)

    def __repr__(self):
        src = self.path if self.path is not None else "<text>"
        return f"Scene({src!r}, overrides={self.overrides!r})"


class Simulation:
    """A running simulation. Build one with `Scene.build()`, `Simulation.from_particles`
    or `Simulation.from_checkpoint`."""

    def __init__(self, raw):
        self._raw = raw

    @classmethod
    def from_particles(cls, settings, position, material, spacing, velocity=None,
                       density=None, energy=None, mass=None, overrides=None, unset=None):
        """The caller's particles: `settings` is scene text without bodies; `position`
        (n, dim); `material` (n,) indices into the settings' materials; `spacing` one
        value or (n,); the rest optional (rest, rho0, 0, density * spacing**dim)."""
        mat = _indices(material, "material")
        n = len(mat)
        pos = _np.asarray(position, dtype=_np.float64)
        dim = 1 if pos.ndim == 1 else (pos.shape[1] if pos.ndim == 2 else -1)
        vec = lambda a, name: None if a is None else _shaped(a, name, n, dim)  # noqa: E731
        sca = lambda a, name: None if a is None else _shaped(a, name, n, 1)  # noqa: E731
        spacing = _np.asarray(spacing, dtype=_np.float64)
        raw = _gsph.Simulation.from_particles(
            settings, _overrides(overrides, unset), _shaped(pos, "position", n, max(dim, 1)),
            _flat(vec(velocity, "velocity")), _flat(sca(density, "density")),
            _flat(sca(energy, "energy")), _flat(sca(mass, "mass")), mat,
            _flat(spacing if spacing.ndim == 0 else sca(spacing, "spacing")))
        return cls(raw)

    @classmethod
    def from_checkpoint(cls, directory):
        """Continues from a checkpoint written by `write_checkpoint`."""
        return cls(_gsph.Simulation.from_checkpoint(os.fspath(directory)))

    dim = property(lambda self: self._raw.dim, doc="Dimension (1, 2, 3).")
    time = property(lambda self: self._raw.time, doc="Simulated time, s.")
    steps = property(lambda self: self._raw.steps, doc="Steps taken.")
    scheme = property(lambda self: self._raw.scheme, doc="The scheme's name.")
    effects = property(lambda self: self._raw.effects, doc="The effects simulated.")

    def __len__(self):
        return len(self._raw)

    def stable_dt(self):
        """The step the scene's rule gives now (fixed dt, or the CFL step), s."""
        return self._raw.stable_dt()

    def step(self, dt=None):
        """One step of `dt` (None: the scene's rule); returns the step taken."""
        return self._raw.step(dt)

    def advance(self, t):
        """Steps to time `t` (the last step shortened to land on it); returns steps.
        Ctrl-C raises KeyboardInterrupt after the step in progress (the state is whole)."""
        return self._raw.advance(float(t))

    def run(self):
        """Runs to t_end through the snapshot times, as `gsph run` (adding a snapshot at
        each of them while a snapshot file is open); returns steps. Ctrl-C raises
        KeyboardInterrupt after the step in progress (the state is whole)."""
        return self._raw.run()

    def field(self, name):
        """A field as a new float64 array in particle-id order: position, velocity, mass,
        material, density, pressure, energy, sound_speed, longitudinal_sound_speed,
        deviator, plastic_strain, damage, temperature, h, reference_position, det_f (or x,
        v, m, mat, rho, p, e, c, cl, s, eps_p, temp, x0); the list is gsph.api's FIELDS,
        from the core's particle table."""
        return self._raw.field(name)

    def set_field(self, name, values):
        """Sets a writable field (id order; all values checked before any is written)."""
        self._raw.set_field(name, _shaped(values, name, len(self), self._raw.components(name)))

    def ids(self):
        """Particle ids, in the order of every field."""
        return self._raw.ids()

    def set_acceleration(self, a):
        """External acceleration, m/s², shape (n, dim), applied in every following step
        (half before, half after it) until set again; None removes it."""
        self._raw.set_acceleration(
            _np.zeros(0) if a is None else _shaped(a, "acceleration", len(self), self.dim))

    def energy(self):
        """(kinetic, internal) energy, J."""
        return self._raw.energy()

    def momentum(self):
        """Total momentum (dim components)."""
        return _np.array(self._raw.momentum())

    def external_impulse(self):
        """Momentum added by the external accelerations so far, sum m a dt."""
        return _np.array(self._raw.external_impulse())

    def profile(self):
        """(n, 3) array: x, sigma_xx and the exact sigma_xx (NaN where it does not hold) of
        every particle sorted by x, for scenes whose reference is a stress profile (the
        flyer plate, the elastic-plastic Riemann problem)."""
        return self._raw.profile()

    def summary(self):
        """The summary now, as a dict (the keys of `gsph run`'s summary.json that need
        no history, the reference's measures, the external impulse and work)."""
        return json.loads(self._raw.summary_json())

    def series(self):
        """The series recorded so far (the columns of `gsph run`'s series.csv: t, step,
        dt, energies, momentum, the reference's and the [monitor]'s quantities), as a dict
        {column: float64 array}, one value per sample."""
        names, rows = self._raw.series()
        return {name: rows[:, k].copy() for k, name in enumerate(names)}

    def series_csv(self):
        """The series so far as the text of series.csv."""
        return self._raw.series_csv()

    def write_series(self, path):
        """Writes the series so far as series.csv (byte for byte `gsph run`'s for the same
        steps)."""
        self._raw.write_series(os.fspath(path))

    def write_snapshot(self, path):
        """Writes the state as a CSV file with the columns of final.csv."""
        self._raw.write_snapshot(os.fspath(path))

    def write_snapshots(self, directory):
        """Writes directory/snapshots.h5 + snapshots.xdmf (the HDF5/XDMF pair of `gsph run`,
        opened by ParaView and `gsph plot particles`) holding the state now."""
        self._raw.write_snapshots(os.fspath(directory))

    def open_snapshots(self, directory):
        """Starts the snapshot pair in `directory` with the state now as its first
        snapshot; `run()` adds one at each snapshot time of the scene, `append_snapshot()`
        one at any time, `close_snapshots()` finishes the pair (partial until then)."""
        self._raw.open_snapshots(os.fspath(directory))

    def append_snapshot(self):
        """Adds the state now to the open snapshot file."""
        self._raw.append_snapshot()

    def close_snapshots(self):
        """Finishes the open snapshot file: snapshots.h5 + snapshots.xdmf."""
        self._raw.close_snapshots()

    def write_checkpoint(self, directory):
        """Writes a checkpoint that `Simulation.from_checkpoint` continues from."""
        self._raw.write_checkpoint(os.fspath(directory))

    def __repr__(self):
        return (f"<gsph.Simulation {self.dim}D {self.scheme}, {len(self)} particles, "
                f"t={self.time:.4e} s, {self.steps} steps>")


def study(scene, schemes=("ts1", "ts2"), resolutions=(0.5, 1.0, 2.0), overrides=None,
          metric=None, out="out/study", unset=None):
    """`gsph study`: error against the exact solution and wall time for every scheme at
    every resolution scale. Returns a list of dicts (scheme, resolution, particles, error,
    wall_s, steps, pair_interactions, energy_rel_error, pareto); writes tables and plots
    into `out`."""
    rows = _gsph.study_json(os.fspath(scene), list(schemes), [float(r) for r in resolutions],
                            _overrides(overrides, unset), metric, os.fspath(out))
    return json.loads(rows)


def hugoniot(scene, ups, overrides=None, out="out/hugoniot", unset=None):
    """`gsph hugoniot`: the moving-window Hugoniot of a porous-material scene at the
    particle velocities `ups` (m/s). Returns a list of dicts (up, us, sigma_behind, ...);
    writes profiles, hugoniot.csv and the plot into `out`."""
    pts = _gsph.hugoniot_json(os.fspath(scene), _overrides(overrides, unset),
                              [float(u) for u in ups], os.fspath(out))
    return json.loads(pts)
