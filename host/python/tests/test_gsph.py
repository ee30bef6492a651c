"""Tests of the gsph Python package (run by scripts/python.sh, part of `make test`).

The numbers are checked against the `gsph` command: GSPH_BIN (default
target/release/gsph) runs the same scene and the package must reproduce its final.csv
byte for byte.
"""

import csv
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import gsph

ROOT = pathlib.Path(__file__).resolve().parents[3]
CASES = ROOT / "cases"
GSPH_BIN = os.environ.get("GSPH_BIN", str(ROOT / "target" / "release" / "gsph"))


def gsph_run(scene, out, *overrides):
    cmd = [GSPH_BIN, "run", str(scene), "--out", str(out), "--quiet"]
    for o in overrides:
        cmd += ["--set", o]
    subprocess.run(cmd, check=True)
    return out


def test_flyer_plate_run_equals_the_cli(tmp_path):
    sim = gsph.Scene.from_file(CASES / "flyer_plate.toml").build()
    steps = sim.run()
    sim.write_snapshot(tmp_path / "py.csv")
    cli = gsph_run(CASES / "flyer_plate.toml", tmp_path / "cli")
    assert (tmp_path / "py.csv").read_bytes() == (cli / "final.csv").read_bytes()
    summary = sim.summary()
    assert summary["steps"] == steps > 0
    assert abs(summary["energy_rel_error"]) < 1e-10
    # the peak stress read from the numpy fields equals the CLI's
    s, p = sim.field("deviator"), sim.field("pressure")
    rows = list(csv.DictReader(open(cli / "final.csv")))
    cli_peak = min(float(r["sxx"]) - float(r["p"]) for r in rows)
    assert np.min(s[:, 0] - p) == cli_peak


def test_fields_shapes_and_order():
    sim = gsph.Scene.from_file(CASES / "flyer_plate.toml").build()
    n = len(sim)
    assert sim.field("position").shape == (n, 1)
    assert sim.field("deviator").shape == (n, 6)
    assert sim.field("rho").shape == (n,)
    assert list(sim.ids()) == list(range(n))
    x = sim.field("x")[:, 0]
    assert np.all(np.diff(x) > 0)  # built left to right, returned in id order
    sim.step()
    sim.step()
    # after steps (and a Morton renumbering) the id order still holds
    assert list(sim.ids()) == list(range(n))


def test_writing_density_updates_pressure():
    sim = gsph.Scene.from_file(CASES / "flyer_plate.toml").build()
    rho = sim.field("density")
    p0 = sim.field("pressure").copy()
    rho[:10] *= 1.01
    sim.set_field("density", rho)
    p1 = sim.field("pressure")
    assert np.all(p1[:10] > p0[:10]) and np.array_equal(p1[10:], p0[10:])


def test_errors_are_exceptions_with_gsph_messages(tmp_path):
    with pytest.raises(gsph.SceneError, match="materials"):
        gsph.Scene.from_file(CASES / "flyer_plate.toml", {"materials.0.rho0": -1.0}).build()
    with pytest.raises(gsph.SceneError, match="cannot read scene"):
        gsph.Scene.from_file(tmp_path / "missing.toml").build()
    sim = gsph.Scene.from_file(CASES / "flyer_plate.toml", {"scheme": "ts1"}).build()
    assert sim.scheme == "ts1"
    with pytest.raises(gsph.ArgumentError, match="unknown field `nope`"):
        sim.field("nope")
    with pytest.raises(gsph.ArgumentError, match="not simulated by this scene .*damage model"):
        sim.field("damage")
    with pytest.raises(gsph.ArgumentError, match="read-only"):
        sim.set_field("pressure", np.zeros(len(sim)))
    with pytest.raises(gsph.ArgumentError, match=r"density: shape \(3,\)"):
        sim.set_field("density", np.ones(3))
    with pytest.raises(gsph.ArgumentError, match="not finite"):
        bad = sim.field("rho")
        bad[5] = math.nan
        sim.set_field("rho", bad)
    with pytest.raises(gsph.ArgumentError, match="dt"):
        sim.step(-1.0)
    assert issubclass(gsph.SceneError, gsph.GsphError)


def test_particles_from_numpy_and_the_momentum_budget():
    settings = """
dim = 2
scheme = "ts2"
t_end = 1.0
[[materials]]
name = "al"
rho0 = 2785.0
shear_modulus = 27.6e9
eos = { type = "mie_gruneisen", c0 = 5328.0, s1 = 1.338, gamma0 = 2.0 }
strength = { type = "von_mises", yield_stress = 0.3e9 }
"""
    dx = 1e-3
    gx, gy = np.meshgrid((np.arange(30) + 0.5) * dx, (np.arange(12) + 0.5) * dx)
    pos = np.column_stack([gx.ravel(), gy.ravel()])
    n = len(pos)
    sim = gsph.Simulation.from_particles(settings, pos, np.zeros(n, int), dx,
                                         velocity=np.tile([40.0, 0.0], (n, 1)))
    assert len(sim) == n and sim.dim == 2
    m = sim.field("mass")
    assert np.allclose(m, 2785.0 * dx * dx)
    p0 = sim.momentum()
    applied = np.zeros(2)
    for _ in range(50):
        y = sim.field("position")[:, 1]
        a = np.column_stack([1e5 * y / y.max(), -5e4 * np.ones(n)])
        sim.set_acceleration(a)
        dt = sim.step()
        applied += (m[:, None] * a).sum(axis=0) * dt
    change = sim.momentum() - p0
    assert np.allclose(change, applied, rtol=1e-10, atol=0)
    assert np.allclose(sim.external_impulse(), applied, rtol=1e-12, atol=0)
    with pytest.raises(gsph.ArgumentError, match="particles.spacing"):
        gsph.Simulation.from_particles(settings, pos, np.zeros(n, int), -1.0)
    # a (dim, n) array is refused, not read with its components mixed
    with pytest.raises(gsph.ArgumentError, match=r"acceleration: shape \(2, 360\)"):
        sim.set_acceleration(np.zeros((2, n)))
    with pytest.raises(gsph.ArgumentError, match="material: must be integers"):
        gsph.Simulation.from_particles(settings, pos, np.full(n, 0.5), dx)
    with pytest.raises(gsph.SceneError, match="bodies"):
        gsph.Simulation.from_particles(
            settings + '[[bodies]]\nmaterial = "al"\nshape = { type = "box", min = [0, 0], max = [1e-2, 1e-2] }\nspacing = 1e-3\n',
            pos, np.zeros(n, int), dx)


def test_checkpoint_continues_bitwise(tmp_path):
    scene = gsph.Scene.from_file(CASES / "flyer_plate.toml")
    whole = scene.build()
    whole.advance(0.2e-6)  # the same steps as the checkpointed run: both land on 0.2 us
    whole.advance(0.4e-6)
    half = scene.build()
    half.advance(0.2e-6)
    half.write_checkpoint(tmp_path / "ck")
    again = gsph.Simulation.from_checkpoint(tmp_path / "ck")
    assert again.steps == half.steps
    again.advance(0.4e-6)
    for name in ["position", "velocity", "density", "energy", "deviator", "plastic_strain"]:
        assert np.array_equal(again.field(name), whole.field(name)), name


def test_profile_against_the_exact_solution():
    sim = gsph.Scene.from_file(CASES / "flyer_plate.toml").build()
    sim.run()
    prof = sim.profile()
    assert prof.shape == (len(sim), 3)
    assert np.all(np.diff(prof[:, 0]) >= 0)
    held = ~np.isnan(prof[:, 2])
    l1 = np.mean(np.abs(prof[held, 1] - prof[held, 2]))
    assert l1 == pytest.approx(sim.summary()["l1_error"], rel=1e-12)


def test_study_from_python(tmp_path):
    rows = gsph.study(CASES / "flyer_plate.toml", schemes=["ts1"], resolutions=[0.5, 1.0],
                      out=tmp_path / "study")
    assert [r["resolution"] for r in rows] == [0.5, 1.0]
    assert all(r["scheme"] == "ts1" and math.isfinite(r["error"]) for r in rows)
    # finer is more accurate on the flyer plate
    assert rows[1]["error"] < rows[0]["error"]
    assert (tmp_path / "study").is_dir()


def test_hugoniot_from_python_refuses_a_scene_without_window(tmp_path):
    with pytest.raises(gsph.GsphError, match="window"):
        gsph.hugoniot(CASES / "flyer_plate.toml", [300.0], out=tmp_path / "h")
