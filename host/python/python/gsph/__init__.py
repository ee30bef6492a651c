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
OutputError. Long calls (build, step, advance, run, study, hugoniot) release the GIL.
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


def _overrides(overrides):
    """`{"key": value}` or ["key=value", ...] as the list `gsph run --set` takes."""
    if overrides is None:
        return []
    if isinstance(overrides, dict):
        out = []
        for k, v in overrides.items():
            if isinstance(v, bool):
                v = "true" if v else "false"
            elif isinstance(v, float):
                v = repr(v)
            out.append(f"{k}={v}")
        return out
    return [str(o) for o in overrides]


def _flat(a):
    """`a` as a contiguous float64 vector (empty for None)."""
    if a is None:
        return _np.zeros(0)
    return _np.ascontiguousarray(a, dtype=_np.float64).ravel()


class Scene:
    """A scene file or text with overrides. `build()` validates and builds it."""

    def __init__(self, text=None, path=None, overrides=None):
        if (text is None) == (path is None):
            raise ArgumentError("Scene: give exactly one of text and path")
        self.text = text
        self.path = None if path is None else os.fspath(path)
        self.overrides = _overrides(overrides)

    @classmethod
    def from_file(cls, path, overrides=None):
        """A scene file (TOML) with overrides: a dict {"key": value} or ["key=value"]."""
        return cls(path=path, overrides=overrides)

    @classmethod
    def from_text(cls, text, overrides=None):
        """Scene text (TOML, as a scene file) with overrides."""
        return cls(text=text, overrides=overrides)

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
                       density=None, energy=None, mass=None, overrides=None):
        """The caller's particles: `settings` is scene text without bodies; `position`
        (n, dim); `material` (n,) indices into the settings' materials; `spacing` one
        value or (n,); the rest optional (rest, rho0, 0, density * spacing**dim)."""
        mat = [int(m) for m in _np.asarray(material).ravel()]
        raw = _gsph.Simulation.from_particles(
            settings, _overrides(overrides), _flat(position),
            _flat(velocity), _flat(density),
            _flat(energy), _flat(mass), mat,
            _flat(spacing))
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
        """Steps to time `t` (the last step shortened to land on it); returns steps."""
        return self._raw.advance(float(t))

    def run(self):
        """Runs to t_end through the snapshot times, as `gsph run`; returns steps."""
        return self._raw.run()

    def field(self, name):
        """A field as a new float64 array in particle-id order: position, velocity, mass,
        density, pressure, energy, sound_speed, deviator, plastic_strain, damage,
        temperature, h, material (or x, v, m, rho, p, e, c, s, eps_p, temp)."""
        return self._raw.field(name)

    def set_field(self, name, values):
        """Sets a writable field (id order; all values checked before any is written)."""
        self._raw.set_field(name, _flat(values))

    def ids(self):
        """Particle ids, in the order of every field."""
        return self._raw.ids()

    def set_acceleration(self, a):
        """External acceleration, m/s², shape (n, dim), applied in every following step
        (half before, half after it) until set again; None removes it."""
        self._raw.set_acceleration(_flat(a))

    def energy(self):
        """(kinetic, internal) energy, J."""
        return self._raw.energy()

    def momentum(self):
        """Total momentum (dim components)."""
        return _np.array(self._raw.momentum())

    def external_impulse(self):
        """Momentum added by the external accelerations so far, sum m a dt."""
        return _np.array(self._raw.external_impulse())

    def summary(self):
        """The summary now, as a dict (the keys of `gsph run`'s summary.json that need
        no history, the reference's measures, the external impulse and work)."""
        return json.loads(self._raw.summary_json())

    def write_snapshot(self, path):
        """Writes the state as a CSV file with the columns of final.csv."""
        self._raw.write_snapshot(os.fspath(path))

    def write_checkpoint(self, directory):
        """Writes a checkpoint that `Simulation.from_checkpoint` continues from."""
        self._raw.write_checkpoint(os.fspath(directory))

    def __repr__(self):
        return (f"<gsph.Simulation {self.dim}D {self.scheme}, {len(self)} particles, "
                f"t={self.time:.4e} s, {self.steps} steps>")


def study(scene, schemes=("ts1", "ts2"), resolutions=(0.5, 1.0, 2.0), overrides=None,
          metric=None, out="out/study"):
    """`gsph study`: error against the exact solution and wall time for every scheme at
    every resolution scale. Returns a list of dicts (scheme, resolution, particles, error,
    wall_s, steps, pair_interactions, energy_rel_error, pareto); writes tables and plots
    into `out`."""
    rows = _gsph.study_json(os.fspath(scene), list(schemes), [float(r) for r in resolutions],
                            _overrides(overrides), metric, os.fspath(out))
    return json.loads(rows)


def hugoniot(scene, ups, overrides=None, out="out/hugoniot"):
    """`gsph hugoniot`: the moving-window Hugoniot of a porous-material scene at the
    particle velocities `ups` (m/s). Returns a list of dicts (up, us, sigma_behind, ...);
    writes profiles, hugoniot.csv and the plot into `out`."""
    pts = _gsph.hugoniot_json(os.fspath(scene), _overrides(overrides),
                              [float(u) for u in ups], os.fspath(out))
    return json.loads(pts)
