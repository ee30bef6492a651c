"""gsph's snapshots opened the way ParaView opens them: VTK's XDMF reader (pip `vtk`,
vtkIOXdmf2.vtkXdmfReader) on snapshots.xdmf and snapshots.partial.xdmf of real runs
(docs/output.md). Run by scripts/python.sh, which installs vtk; skipped without it.

Checks: every snapshot is a time step with its time and particle count; the `stress`
array has 9 components and equals -p I + S from the `p` and deviator arrays; `von_mises`
is sqrt(3/2 S:S); the last snapshot agrees with final.csv (sigma_* and von_mises
columns included); a partial pair left by a stopped run opens too and says it is partial.
With h5py installed, the HDF5 datasets are also checked for units and compression.
"""

import csv
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest

xdmf2 = pytest.importorskip("vtkmodules.vtkIOXdmf2")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonExecutionModel import (  # noqa: E402
    vtkStreamingDemandDrivenPipeline as SDDP,
)

ROOT = pathlib.Path(__file__).resolve().parents[3]
CASES = ROOT / "cases"
GSPH_BIN = os.environ.get("GSPH_BIN", str(ROOT / "target" / "release" / "gsph"))

# (scene, overrides, dim): a 2D impact with strength, damage and heat, coarse and short;
# the 1D flyer plate as it is
RUNS = {
    "impact_2d": (
        "steel_sic_impact.toml",
        ["resolution_scale=0.1", "t_end=2e-6", "output.snapshots=4"],
        2,
    ),
    "flyer_1d": ("flyer_plate.toml", [], 1),
}
DEVIATOR = ["sxx", "syy", "szz", "sxy", "sxz", "syz"]


def gsph(*args):
    subprocess.run([GSPH_BIN, *map(str, args), "--quiet"], check=True)


def run(name, out, *extra):
    scene, sets, _ = RUNS[name]
    args = ["run", CASES / scene, "--out", out, *extra]
    for s in sets:
        args += ["--set", s]
    gsph(*args)
    return out


def open_xdmf(path):
    r = xdmf2.vtkXdmfReader()
    r.SetFileName(str(path))
    r.UpdateInformation()
    times = list(r.GetOutputInformation(0).Get(SDDP.TIME_STEPS()) or [])
    return r, times


def snapshot(reader, t):
    """Point arrays of the grid at time t, as numpy arrays, and the points."""
    reader.UpdateTimeStep(t)
    grid = reader.GetOutputDataObject(0)
    pd = grid.GetPointData()
    arrays = {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k))
              for k in range(pd.GetNumberOfArrays())}
    points = np.zeros((0, 3))
    if grid.GetNumberOfPoints():
        points = vtk_to_numpy(grid.GetPoints().GetData())
    return grid, arrays, points


def xdmf_times_and_sizes(path):
    text = pathlib.Path(path).read_text()
    times = [float(v) for v in re.findall(r'<Time Value="([^"]+)"/>', text)]
    sizes = [int(n) for n in re.findall(r'NumberOfElements="(\d+)"', text)]
    return text, times, sizes


def check_stress(arrays, n):
    stress = arrays["stress"]
    assert stress.shape == (n, 9), stress.shape
    p = arrays["p"]
    s = {c: arrays[c] for c in DEVIATOR}
    expect = np.stack(
        [s["sxx"] - p, s["sxy"], s["sxz"],
         s["sxy"], s["syy"] - p, s["syz"],
         s["sxz"], s["syz"], s["szz"] - p], axis=1)
    assert np.array_equal(stress, expect)
    ss = sum(s[c] ** 2 for c in DEVIATOR[:3]) + 2 * sum(s[c] ** 2 for c in DEVIATOR[3:])
    np.testing.assert_allclose(arrays["von_mises"], np.sqrt(1.5 * ss), rtol=1e-14, atol=0)
    assert arrays["velocity"].shape == (n, 3)
    for name in ["p", "eps_p", "rho", "m", "e", "damage", "temperature", "h", "id",
                 "material"]:
        assert arrays[name].shape == (n,), name


@pytest.fixture(scope="module", params=sorted(RUNS))
def finished(request, tmp_path_factory):
    out = tmp_path_factory.mktemp(request.param)
    return request.param, run(request.param, out)


def test_finished_run_opens_with_vtk(finished):
    name, out = finished
    assert not (out / "snapshots.partial.xdmf").exists()
    assert not (out / "snapshots.partial.h5").exists()
    text, xtimes, sizes = xdmf_times_and_sizes(out / "snapshots.xdmf")
    assert '<Information Name="status" Value="complete"/>' in text
    assert "PARTIAL" not in text
    reader, times = open_xdmf(out / "snapshots.xdmf")
    assert len(times) == len(xtimes) == len(sizes) >= 2
    np.testing.assert_allclose(times, xtimes, rtol=1e-15)
    assert times[0] == 0.0 and np.all(np.diff(times) > 0)
    rows = list(csv.DictReader(open(out / "final.csv")))
    for t, n in zip(times, sizes):
        grid, arrays, points = snapshot(reader, t)
        assert grid.GetNumberOfPoints() == n == len(arrays["id"])
        check_stress(arrays, n)
    # the last snapshot is the final state
    assert sizes[-1] == len(rows)
    order = np.argsort(arrays["id"])
    col = lambda c: np.array([float(r[c]) for r in rows])  # noqa: E731
    ids = col("id")
    assert np.array_equal(arrays["id"][order], ids)
    st = arrays["stress"][order]
    for k, c in [(0, "sigma_xx"), (4, "sigma_yy"), (8, "sigma_zz"), (1, "sigma_xy"),
                 (2, "sigma_xz"), (5, "sigma_yz")]:
        assert np.array_equal(st[:, k], col(c)), c
    assert np.array_equal(arrays["von_mises"][order], col("von_mises"))
    assert np.array_equal(col("sigma_xx"), col("sxx") - col("p"))
    assert np.array_equal(points[order][:, 0], col("x"))
    assert np.array_equal(arrays["eps_p"][order], col("eps_p"))
    if name == "impact_2d":
        # strength did something: the stress is not a pressure alone
        assert np.max(col("von_mises")) > 1e8 and np.max(col("eps_p")) > 0
        assert set(np.unique(arrays["material"])) == {0, 1}


def test_partial_pair_of_a_stopped_run_opens_with_vtk(tmp_path):
    out = run("impact_2d", tmp_path / "stopped", "--stop-after-steps", "15")
    assert not (out / "snapshots.xdmf").exists() and not (out / "snapshots.h5").exists()
    text, xtimes, sizes = xdmf_times_and_sizes(out / "snapshots.partial.xdmf")
    assert "<!-- PARTIAL OUTPUT" in text
    status = re.search(r'<Information Name="status" Value="([^"]+)"/>', text).group(1)
    assert status.startswith("partial: "), status
    assert "snapshots.partial.h5:/step_" in text
    reader, times = open_xdmf(out / "snapshots.partial.xdmf")
    assert len(times) == len(sizes) >= 2
    grid, arrays, _ = snapshot(reader, times[-1])
    check_stress(arrays, sizes[-1])
    # a restart finishes the run: the partial pair gives way to the complete one
    gsph("run", "--restart", out)
    assert not (out / "snapshots.partial.xdmf").exists()
    text, _, _ = xdmf_times_and_sizes(out / "snapshots.xdmf")
    assert 'Value="complete"' in text
    _, times = open_xdmf(out / "snapshots.xdmf")
    assert len(times) == 5


def test_hdf5_attributes_and_compression(finished):
    h5py = pytest.importorskip("h5py")
    name, out = finished
    scene, sets, dim = RUNS[name]
    with h5py.File(out / "snapshots.h5", "r") as f:
        assert f.attrs["dim"] == dim and f.attrs["format_version"] == 3
        assert f.attrs["scene"] == (CASES / scene).read_text()
        assert list(f.attrs["scene_overrides"]) == sets
        if name == "impact_2d":
            assert list(f.attrs["material_names"]) == ["steel", "sic"]
            assert "strength" in list(f.attrs["effects"])
        g = f[sorted(k for k in f if k.startswith("step_"))[-1]]
        assert g["stress"].shape == (len(g["id"]), 3, 3)
        assert g["stress"].attrs["units"] == "Pa"
        assert g["position"].attrs["units"] == "m"
        for ds in g.values():
            assert ds.compression == "gzip" and ds.shuffle and ds.chunks, ds.name
