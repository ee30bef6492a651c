"""The package runs what the command line runs (issue 25, items 5 and 6), checked against
the `gsph` command (GSPH_BIN, default target/release/gsph):

- Ctrl-C during `run()` or `advance()` raises KeyboardInterrupt after the step in progress
  (it used to arrive when the run ended), and the simulation goes on and checkpoints;
- every scene of cases/ and cases/hard/ builds and steps (a [window] scene is refused in
  one line naming the command that runs it);
- a scene with a [monitor] and output.series records the CLI's series.csv byte for byte,
  also as arrays, and writes the CLI's snapshots.h5 + snapshots.xdmf;
- overrides unset keys, as `gsph run --unset`.
"""

import os
import pathlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import gsph

ROOT = pathlib.Path(__file__).resolve().parents[3]
CASES = ROOT / "cases"
GSPH_BIN = os.environ.get("GSPH_BIN", str(ROOT / "target" / "release" / "gsph"))

# a long run in a child process: prints "ready DT", then, on KeyboardInterrupt, the
# monotonic time it arrived and the steps taken; then steps on and checkpoints
CHILD = r"""
import sys, time, gsph
scene, call, ck = sys.argv[1:4]
sim = gsph.Scene.from_file(scene, {"t_end": 1e-2, "output.snapshots": 1}).build()
print("ready", sim.stable_dt(), flush=True)
try:
    sim.run() if call == "run" else sim.advance(1e-2)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic(), sim.steps, flush=True)
steps = sim.steps
sim.step()
assert sim.steps == steps + 1
sim.write_checkpoint(ck)
assert gsph.Simulation.from_checkpoint(ck).steps == steps + 1
print("usable", flush=True)
"""


@pytest.mark.parametrize("call", ["run", "advance"])
def test_ctrl_c_interrupts_a_long_call_after_its_step(tmp_path, call):
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, str(CASES / "flyer_plate.toml"), call, str(tmp_path / "ck")],
        stdout=subprocess.PIPE, text=True)
    try:
        ready = child.stdout.readline().split()
        assert ready[0] == "ready", ready
        total_steps = 1e-2 / float(ready[1])  # the run's length, roughly
        time.sleep(0.5)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=20)
    finally:
        child.kill()
    lines = out.split("\n")
    assert lines[0].startswith("interrupted"), out
    _, at, steps = lines[0].split()
    assert float(at) - sent < 1.0, f"KeyboardInterrupt {float(at) - sent:.2f} s after SIGINT"
    assert 0 < int(steps) < 0.5 * total_steps
    assert lines[1] == "usable" and child.returncode == 0


def scene_files():
    return sorted(list(CASES.glob("*.toml")) + list((CASES / "hard").glob("*.toml")))


def test_the_scene_list_is_whole():
    assert len(scene_files()) >= 15


@pytest.mark.parametrize("path", scene_files(), ids=lambda p: p.relative_to(CASES).as_posix())
def test_every_bundled_scene_builds_and_steps(path):
    windowed = "\n[window]" in path.read_text()
    scene = gsph.Scene.from_file(path, {"resolution_scale": 0.5, "output.snapshots": 1})
    if windowed:
        with pytest.raises(gsph.SceneError) as e:
            scene.build()
        assert str(e.value) == (
            f"window: the moving window ([window]) is not run by the library; run this scene "
            f"with `gsph run {path}` (its Hugoniot with `gsph hugoniot {path}`)")
        return
    sim = scene.build()
    assert sim.step() > 0 and sim.steps == 1
    assert len(sim.series()["t"]) >= 1


SCENE = CASES / "steel_sic_impact.toml"
SETS = {"resolution_scale": 0.1, "t_end": 2e-6, "output.snapshots": 4, "output.series": 50}


def test_monitor_series_and_snapshots_equal_gsph_run(tmp_path):
    cmd = [GSPH_BIN, "run", str(SCENE), "--out", str(tmp_path / "cli"), "--quiet"]
    for k, v in SETS.items():
        cmd += ["--set", f"{k}={v}"]
    subprocess.run(cmd, check=True)
    sim = gsph.Scene.from_file(SCENE, SETS).build()
    sim.open_snapshots(tmp_path / "lib")
    sim.run()
    sim.close_snapshots()
    sim.write_series(tmp_path / "lib" / "series.csv")
    cli = (tmp_path / "cli" / "series.csv").read_bytes()
    assert (tmp_path / "lib" / "series.csv").read_bytes() == cli
    assert sim.series_csv().encode() == cli
    series = sim.series()
    names = cli.decode().split("\n")[0].split(",")
    assert list(series) == names and names[-1] == "back_face_velocity"
    rows = np.loadtxt(tmp_path / "cli" / "series.csv", delimiter=",", skiprows=1)
    for k, name in enumerate(names):
        assert np.array_equal(series[name], rows[:, k], equal_nan=True), name
    assert sim.summary()["back_face_velocity_peak"] == np.max(series["back_face_velocity"])
    # the snapshot pair: complete, the CLI's frames, drawn by `gsph plot particles`
    assert "complete" in (tmp_path / "lib" / "snapshots.xdmf").read_text()
    subprocess.run([GSPH_BIN, "plot", "particles", str(tmp_path / "lib"), "--out",
                    str(tmp_path / "eps_p.png")], check=True)
    assert (tmp_path / "eps_p.png").stat().st_size > 0
    h5py = pytest.importorskip("h5py")
    with h5py.File(tmp_path / "lib" / "snapshots.h5") as a, \
            h5py.File(tmp_path / "cli" / "snapshots.h5") as b:
        groups = sorted(g for g in a if g.startswith("step_"))
        assert groups == sorted(g for g in b if g.startswith("step_")) and len(groups) == 5
        for g in groups:
            for d in ["position", "velocity", "stress", "p", "eps_p"]:
                assert np.array_equal(a[g][d][()], b[g][d][()]), (g, d)


def test_write_snapshots_one_frame_and_errors(tmp_path):
    sim = gsph.Scene.from_file(CASES / "flyer_plate.toml").build()
    sim.step()
    sim.write_snapshots(tmp_path / "one")
    assert (tmp_path / "one" / "snapshots.h5").is_file()
    assert "complete" in (tmp_path / "one" / "snapshots.xdmf").read_text()
    with pytest.raises(gsph.ArgumentError, match="write_snapshot writes CSV"):
        sim.write_snapshot(tmp_path / "x.h5")
    with pytest.raises(gsph.ArgumentError, match="no snapshot file is open"):
        sim.append_snapshot()
    # a time already passed is refused (issue 45), not 0 steps
    with pytest.raises(gsph.ArgumentError, match="lies before the simulation's time"):
        sim.advance(-1)


def test_overrides_unset_keys():
    with_ref = gsph.Scene.from_file(CASES / "flyer_plate.toml").build()
    assert "l1_error" in with_ref.summary()
    for scene in [gsph.Scene.from_file(CASES / "flyer_plate.toml", unset=["reference"]),
                  gsph.Scene.from_file(CASES / "flyer_plate.toml", {"reference": None}),
                  gsph.Scene.from_file(CASES / "flyer_plate.toml", ["unset:reference"])]:
        assert scene.overrides == ["unset:reference"]
        assert "l1_error" not in scene.build().summary()
    with pytest.raises(gsph.SceneError, match="^--unset nope: "):
        gsph.Scene.from_file(CASES / "flyer_plate.toml", unset="nope").build()
