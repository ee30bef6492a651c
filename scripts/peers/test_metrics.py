"""Unit checks of scripts/peers/metrics.py on synthetic data (no peer run needed):

    .venv-peers/bin/python scripts/peers/test_metrics.py

The gsph reader is checked on a file written with h5py in the layout of
host/src/output/hdf5.rs (root attribute dim; groups /step_XXXXXX with attributes time, step;
position, velocity N x 3 f64; id, material u32; the other columns 1-D f64), the LAMMPS
reader on a dump custom file and the PySPH reader on PySPH's HDF5 layout.
"""

import os
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import case  # noqa: E402
import metrics  # noqa: E402

GSPH_SCALARS = ["id", "material", "m", "rho", "p", "e", "sxx", "syy", "szz", "sxy", "sxz",
                "syz", "eps_p", "damage", "temperature", "h"]


def synthetic(dx=1e-3, t=0.0, seed=0):
    """Both rings at dx with made-up but known velocities and stresses."""
    x, y, vx, vy, m, body = case.particles(dx)
    rng = np.random.default_rng(seed)
    n = x.size
    if t > 0:
        vx = vx * 0.5 + rng.normal(0, 10, n)
        vy = rng.normal(0, 10, n)
    rho = 1.0 + rng.uniform(-0.01, 0.01, n) * (t > 0)
    p = rng.normal(0, 1e4, n) * (t > 0)
    s = rng.normal(0, 1e4, (4, n)) * (t > 0)
    sxx, syy, sxy = s[0], s[1], s[3]
    szz = -(sxx + syy)  # a deviator
    return metrics.Frame(time=t, x=x, y=y, vx=vx, vy=vy, m=m, rho=rho, p=p, sxx=sxx,
                         syy=syy, szz=szz, sxy=sxy, body=body)


def expected(frames, dx):
    f0, f1, f5 = frames
    ke0 = 0.5 * np.sum(f0.m * (f0.vx ** 2 + f0.vy ** 2))
    ke5 = 0.5 * np.sum(f5.m * (f5.vx ** 2 + f5.vy ** 2))
    vol = f5.m / f5.rho
    ss = f5.sxx ** 2 + f5.syy ** 2 + f5.szz ** 2 + 2 * f5.sxy ** 2
    se = np.sum(vol * (f5.p ** 2 / (2 * case.K) + ss / (4 * case.G)))
    left = f1.body == 0
    vxl1 = np.sum(f1.m[left] * f1.vx[left]) / np.sum(f1.m[left]) / case.U0
    return ke5 / ke0, (ke5 + se) / ke0, vxl1


class Metrics(unittest.TestCase):
    dx = 1e-3

    def frames(self):
        return [synthetic(self.dx, 0.0), synthetic(self.dx, 1e-5, 1), synthetic(self.dx, 5e-5, 2)]

    def check(self, got, frames):
        ke5, kese5, vxl1 = expected(frames, self.dx)
        self.assertEqual(got["particles"], 4416)
        self.assertAlmostEqual(got["ke@5e-05"], ke5, places=12)
        self.assertAlmostEqual(got["kese@5e-05"], kese5, places=12)
        self.assertAlmostEqual(got["vxl@1e-05"], vxl1, places=12)
        # the lattice is untouched: nearest neighbour exactly dx, no close pair
        self.assertAlmostEqual(got["dmin@5e-05"], 1.0, places=9)
        self.assertEqual(got["close@5e-05"], 0.0)

    def test_counts(self):
        self.assertEqual([case.expected_count(d) for d in case.DX_CHOICES], [4416, 17592, 70320])
        self.assertAlmostEqual(case.C0, 4032.3891927275595, places=9)
        self.assertAlmostEqual(case.U0, 237.910962370926, places=9)

    def test_run_metrics_and_initial_state(self):
        fr = self.frames()
        got = metrics.run_metrics(fr, self.dx)
        self.check(got, fr)
        # at t = 0: vx_L / u0 = 1 exactly
        self.assertAlmostEqual(metrics.left_vx(fr[0]) / case.U0, 1.0, places=14)

    def test_close_pairs(self):
        f = synthetic(self.dx, 5e-5)
        f.y = f.y.copy()
        f.y[0] += 0.5 * self.dx  # halfway to site 1 (dx above): two particles 0.5 dx apart
        frac, dmin = metrics.close_pairs(f, self.dx)
        self.assertAlmostEqual(dmin, 0.5, places=9)
        self.assertAlmostEqual(frac, 2 / f.x.size, places=12)
        # the brute-force fallback (no scipy) agrees with the KD-tree
        d = metrics.nearest_distances(f.x, f.y)
        saved = sys.modules.get("scipy.spatial")
        sys.modules["scipy.spatial"] = None  # makes `from scipy.spatial import ...` fail
        try:
            brute = metrics.nearest_distances(f.x, f.y)
        finally:
            if saved is None:
                del sys.modules["scipy.spatial"]
            else:
                sys.modules["scipy.spatial"] = saved
        np.testing.assert_allclose(brute, d, rtol=1e-12)

    def test_gsph_reader(self):
        import h5py
        fr = self.frames()
        n = len(fr[0])
        perm = np.random.default_rng(5).permutation(n)  # gsph may reorder particles
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "snapshots.h5")
            with h5py.File(path, "w") as h:
                h.attrs.create("dim", 2, dtype=np.uint32)
                for step, f in zip([0, 1000, 5000], fr):
                    g = h.create_group("step_%06d" % step)
                    g.attrs.create("time", f.time, dtype=np.float64)
                    g.attrs.create("step", step, dtype=np.uint64)
                    z = np.zeros(n)
                    g["position"] = np.column_stack([f.x, f.y, z])[perm]
                    g["velocity"] = np.column_stack([f.vx, f.vy, z])[perm]
                    cols = {"id": np.arange(n, dtype=np.uint32),
                            "material": np.zeros(n, dtype=np.uint32), "m": f.m,
                            "rho": f.rho, "p": f.p, "sxx": f.sxx, "syy": f.syy,
                            "szz": f.szz, "sxy": f.sxy}
                    for name in GSPH_SCALARS:
                        g[name] = cols.get(name, z)[perm]
            frames = metrics.read_gsph(path)
            self.assertEqual([f.time for f in frames], [0.0, 1e-5, 5e-5])
            np.testing.assert_array_equal(frames[1].body, fr[1].body)
            self.check(metrics.run_metrics(frames, self.dx), fr)
            got = metrics.main(["measure", "gsph", path, "--dx", str(self.dx),
                                "-o", os.path.join(tmp, "m.json")])
            self.assertEqual(got, 0)

    def test_lammps_reader(self):
        fr = self.frames()
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "dump.rings")
            with open(path, "w") as fh:
                for step, f in zip([0, 1000, 5000], fr):
                    n = len(f)
                    fh.write("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%d\n" % (step, n))
                    fh.write("ITEM: BOX BOUNDS sm sm pp\n-1 1\n-1 1\n-1 1\n")
                    fh.write("ITEM: ATOMS id mol x y vx vy mass c_rho c_vol c_sig[1] "
                             "c_sig[2] c_sig[3] c_sig[4]\n")
                    sig = [f.sxx - f.p, f.syy - f.p, f.szz - f.p, f.sxy]  # Cauchy stress
                    for i in np.random.default_rng(step).permutation(n):
                        fh.write("%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g "
                                 "%.17g %.17g %.17g\n" % (
                                     i + 1, f.body[i] + 1, f.x[i], f.y[i], f.vx[i], f.vy[i],
                                     f.m[i], f.rho[i], f.m[i] / f.rho[i], sig[0][i],
                                     sig[1][i], sig[2][i], sig[3][i]))
            frames = metrics.read_lammps_dump(path)
            self.assertEqual(len(frames), 3)
            np.testing.assert_allclose(frames[2].p, fr[2].p, atol=1e-9)
            np.testing.assert_allclose(frames[2].sxx, fr[2].sxx, atol=1e-9)
            self.check(metrics.run_metrics(frames, self.dx), fr)

    def test_pysph_reader(self):
        import h5py
        fr = self.frames()
        with tempfile.TemporaryDirectory() as tmp:
            for k, f in enumerate(fr):
                with h5py.File(os.path.join(tmp, "rings_%05d.hdf5" % (1000 * k)), "w") as h:
                    h.create_group("solver_data").attrs["t"] = f.time
                    a = h.create_group("particles/solid/arrays")
                    for name, v in [("x", f.x), ("y", f.y), ("u", f.vx), ("v", f.vy),
                                    ("m", f.m), ("rho", f.rho), ("p", f.p), ("s00", f.sxx),
                                    ("s11", f.syy), ("s22", f.szz), ("s01", f.sxy),
                                    ("body", f.body)]:
                        a[name] = v
            self.check(metrics.run_metrics(metrics.read_pysph(tmp), self.dx), fr)

    def test_table(self):
        rows = [metrics.make_row("peer A", timing={"loop_s": 2.0, "steps": 1000,
                                                   "particles": 1000}, peer=True),
                metrics.make_row("code B", us=0.5, particles=1000, steps=1000)]
        self.assertAlmostEqual(rows[0]["us"], 2.0)
        t = metrics.table(rows)
        self.assertIn("| peer A | 1,000 | 1,000 | 2.000 |", t)
        self.assertIn("| code B | 0.250 |", t)


if __name__ == "__main__":
    unittest.main(verbosity=2)
