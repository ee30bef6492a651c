"""Metrics of the colliding elastic rings, shared by every row of scripts/peers.sh.

A run is a list of `Frame`s (particle arrays at one time). `run_metrics` gives
- KE/KE0 at 1e-5 and 5e-5 s (KE0 from the frame at t = 0, else 1/2 sum m u0^2);
- vx_L/u0: the left ring's centre-of-mass x-velocity over u0 = 0.059 c0, at 1e-5, 5e-5 s
  (the left ring is found by tag/index, never by position);
- (KE+SE)/KE0 at 5e-5 s, SE = sum_i V_i (p_i^2 / (2K) + S_i:S_i / (4G)), V_i = m_i / rho_i,
  S the full 3x3 stress deviator (szz included), p the pressure (positive in compression);
- close pairs at 5e-5 s: the fraction of particles with a neighbour nearer than 0.75 dx and
  the smallest pair distance over dx.

Readers: `read_pysph` (PySPH's *.hdf5 output folder), `read_lammps_dump` (LAMMPS dump custom
with columns id mol x y vx vy mass c_rho ... c_sig[1..4], the Cauchy stress of
smd/ulsph/stress), `read_gsph` (gsph's snapshots.h5: groups step_XXXXXX with attributes time,
step; datasets position, velocity (N x 3), id, material, m, rho, p, sxx .. syz).

Command line (all print or write JSON, except `table`):
  metrics.py measure {pysph|lammps|gsph} PATH --dx DX       -> metrics of a full run
  metrics.py timing {pysph|lammps} LOG                        -> loop seconds, steps, particles
  metrics.py row --name NAME [--timing T.json] [--measure M.json] [--us-per-step X]
                 [--particles N] [--steps S] [--wall-timing W] [--wall-full W] -o ROW.json
  metrics.py table ROW.json ...                               -> markdown table and ratios
"""

import argparse
import glob
import json
import math
import os
import re
import sys
from dataclasses import dataclass

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import case  # noqa: E402

CLOSE_FRACTION = 0.75  # "close" = nearer than 0.75 dx


@dataclass
class Frame:
    """Particle arrays at one time; stresses in Pa, `s..` the deviator, `p` the pressure
    (positive in compression); `body` 0 for the left ring, 1 for the right one."""

    time: float
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    m: np.ndarray
    rho: np.ndarray
    p: np.ndarray
    sxx: np.ndarray
    syy: np.ndarray
    szz: np.ndarray
    sxy: np.ndarray
    body: np.ndarray

    def __len__(self):
        return self.x.size


# ---------------------------------------------------------------------------- metrics

def kinetic_energy(f):
    return 0.5 * float(np.sum(f.m * (f.vx ** 2 + f.vy ** 2)))


def strain_energy(f, k=case.K, g=case.G):
    """sum V (p^2 / 2K + S:S / 4G); S:S = sxx^2 + syy^2 + szz^2 + 2 sxy^2 (2D: sxz = syz = 0)."""
    vol = f.m / f.rho
    ss = f.sxx ** 2 + f.syy ** 2 + f.szz ** 2 + 2.0 * f.sxy ** 2
    return float(np.sum(vol * (f.p ** 2 / (2.0 * k) + ss / (4.0 * g))))


def left_vx(f):
    """Centre-of-mass x-velocity of body 0 (the left ring)."""
    left = f.body == 0
    return float(np.sum(f.m[left] * f.vx[left]) / np.sum(f.m[left]))


def nearest_distances(x, y):
    """Distance from each particle to its nearest other particle."""
    pts = np.column_stack([x, y])
    try:
        from scipy.spatial import cKDTree
    except ImportError:  # brute force in chunks: O(N^2), fine for ~1e4 particles
        d = np.empty(len(pts))
        for a in range(0, len(pts), 512):
            blk = pts[a:a + 512]
            r2 = ((blk[:, None, :] - pts[None, :, :]) ** 2).sum(-1)
            r2[np.arange(len(blk)), np.arange(a, a + len(blk))] = np.inf
            d[a:a + 512] = np.sqrt(r2.min(1))
        return d
    dist, _ = cKDTree(pts).query(pts, k=2)
    return dist[:, 1]


def close_pairs(f, dx):
    """(fraction of particles with a neighbour nearer than 0.75 dx, min pair distance / dx)."""
    d = nearest_distances(f.x, f.y)
    return float(np.mean(d < CLOSE_FRACTION * dx)), float(d.min() / dx)


def frame_at(frames, t, dt=case.DT):
    """The frame nearest to time t; None if none lies within half a step (plus 1e-6 t)."""
    if not frames:
        return None
    best = min(frames, key=lambda f: abs(f.time - t))
    return best if abs(best.time - t) <= 0.5 * dt + 1e-6 * t else None


def run_metrics(frames, dx, u0=case.U0):
    """The table's accuracy numbers from a run's frames (None where a frame is missing)."""
    frames = sorted(frames, key=lambda f: f.time)
    f0 = frame_at(frames, 0.0)
    n = len(frames[0]) if frames else 0
    if f0 is not None:
        ke0 = kinetic_energy(f0)
    else:
        m = case.particles(dx)[4]
        ke0 = 0.5 * float(np.sum(m)) * u0 * u0
    out = {"particles": n, "ke0": ke0, "dx": dx}
    for t in case.T_OUT:
        key = "%.0e" % t
        f = frame_at(frames, t)
        if f is None:
            for name in ("ke", "vxl", "kese", "close", "dmin", "time"):
                out["%s@%s" % (name, key)] = None
            continue
        ke = kinetic_energy(f)
        se = strain_energy(f)
        close, dmin = close_pairs(f, dx)
        out["time@%s" % key] = f.time
        out["ke@%s" % key] = ke / ke0
        out["vxl@%s" % key] = left_vx(f) / u0
        out["kese@%s" % key] = (ke + se) / ke0
        out["close@%s" % key] = close
        out["dmin@%s" % key] = dmin
    return out


# ---------------------------------------------------------------------------- readers

def _deviator_from_cauchy(sig_xx, sig_yy, sig_zz):
    p = -(sig_xx + sig_yy + sig_zz) / 3.0
    return p, sig_xx + p, sig_yy + p, sig_zz + p


def read_pysph(dirname, array="solid"):
    """Frames of a PySPH output folder (*.hdf5 files written by pysph_rings.py)."""
    import h5py

    files = sorted(glob.glob(os.path.join(dirname, "*.hdf5")))
    if not files:
        raise FileNotFoundError("no *.hdf5 PySPH output in %s" % dirname)
    frames = []
    for fn in files:
        with h5py.File(fn, "r") as h:
            t = float(h["solver_data"].attrs["t"])
            a = h["particles"][array]["arrays"]

            def col(name):
                return np.asarray(a[name][()], dtype=float)

            if "body" in a:
                body = np.asarray(a["body"][()], dtype=int)
            else:  # the example's order: left ring first
                body = (col("gid") >= a["gid"].shape[0] // 2).astype(int)
            frames.append(Frame(
                time=t, x=col("x"), y=col("y"), vx=col("u"), vy=col("v"), m=col("m"),
                rho=col("rho"), p=col("p"), sxx=col("s00"), syy=col("s11"),
                szz=col("s22"), sxy=col("s01"), body=body))
    return frames


def read_lammps_dump(path, dt=case.DT):
    """Frames of a LAMMPS dump custom file: columns id mol x y vx vy mass c_rho and the
    Cauchy stress c_sig[1] c_sig[2] c_sig[3] c_sig[4] (xx yy zz xy, tension positive).
    mol 1 is the left ring."""
    frames = []
    with open(path) as fh:
        lines = fh.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            n = int(lines[i + 3])
            cols = lines[i + 8].split()[2:]
            assert lines[i + 8].startswith("ITEM: ATOMS"), lines[i + 8]
            data = np.loadtxt(lines[i + 9:i + 9 + n], ndmin=2)
            c = {name: data[:, k] for k, name in enumerate(cols)}
            order = np.argsort(c["id"])
            c = {k: v[order] for k, v in c.items()}
            p, sxx, syy, szz = _deviator_from_cauchy(c["c_sig[1]"], c["c_sig[2]"],
                                                     c["c_sig[3]"])
            frames.append(Frame(
                time=step * dt, x=c["x"], y=c["y"], vx=c["vx"], vy=c["vy"], m=c["mass"],
                rho=c["c_rho"], p=p, sxx=sxx, syy=syy, szz=szz, sxy=c["c_sig[4]"],
                body=(c["mol"].astype(int) - 1)))
            i += 9 + n
        else:
            i += 1
    if not frames:
        raise ValueError("no frame in LAMMPS dump %s" % path)
    return frames


def read_gsph(path, n_left=None):
    """Frames of gsph's snapshots.h5 (host/src/output/hdf5.rs): one group per snapshot,
    /step_XXXXXX, attributes time (f64) and step (u64), datasets position and velocity
    (N x 3), id and material (u32), m, rho, p, sxx, syy, szz, sxy, ... (f64; s.. the stress
    deviator, p the pressure). gsph numbers the particles body by body, so the left ring
    (body 0) is ids 0 .. n_left - 1; n_left defaults to half the particles of the first
    snapshot (the two rings are identical)."""
    import h5py

    frames = []
    with h5py.File(path, "r") as h:
        groups = sorted((g for g in h if g.startswith("step_")),
                        key=lambda g: int(h[g].attrs["step"]))
        for g in groups:
            grp = h[g]
            ids = np.asarray(grp["id"][()], dtype=np.int64)
            if n_left is None:
                n_left = ids.size // 2
            order = np.argsort(ids)
            pos = np.asarray(grp["position"][()], dtype=float)[order]
            vel = np.asarray(grp["velocity"][()], dtype=float)[order]

            def col(name):
                return np.asarray(grp[name][()], dtype=float)[order]

            frames.append(Frame(
                time=float(grp.attrs["time"]), x=pos[:, 0], y=pos[:, 1], vx=vel[:, 0],
                vy=vel[:, 1], m=col("m"), rho=col("rho"), p=col("p"), sxx=col("sxx"),
                syy=col("syy"), szz=col("szz"), sxy=col("sxy"),
                body=(ids[order] >= n_left).astype(int)))
    if not frames:
        raise ValueError("no snapshot group in %s" % path)
    return frames


READERS = {"pysph": read_pysph, "lammps": read_lammps_dump, "gsph": read_gsph}


# ---------------------------------------------------------------------------- timings

def timing_lammps(log):
    """Loop seconds, steps and atoms of the (last) LAMMPS run in a log."""
    text = open(log).read()
    m = re.findall(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                   text)
    if not m:
        raise ValueError("no 'Loop time' in %s" % log)
    loop, procs, steps, n = m[-1]
    threads = re.findall(r"with \d+ MPI tasks x (\d+) OpenMP threads", text)
    return {"loop_s": float(loop), "ranks": int(procs), "steps": int(steps),
            "particles": int(n), "threads": int(threads[-1]) if threads else None}


def timing_pysph(log, steps=None):
    """'Run took' seconds and particle count from a PySPH log (stdout or rings.log)."""
    text = open(log).read()
    run = re.findall(r"Run took: ([0-9.eE+-]+) secs", text)
    n = re.findall(r"rings: (\d+) particles", text) or re.findall(r"solid: (\d+)", text)
    if not run:
        raise ValueError("no 'Run took' in %s" % log)
    return {"loop_s": float(run[-1]), "steps": steps, "particles": int(n[-1]) if n else None,
            "ranks": 1, "threads": 1}


# ---------------------------------------------------------------------------- table

COLUMNS = [
    ("code / variant", "name", None),
    ("particles", "particles", "d"),
    ("steps timed", "steps", "d"),
    ("µs / particle-step (1 thread, median of rounds)", "us", ".3f"),
    ("rounds", "us_rounds", "rounds"),
    ("KE/KE0 @1e-5", "ke@1e-05", ".4f"),
    ("KE/KE0 @5e-5", "ke@5e-05", ".4f"),
    ("vx_L/u0 @1e-5", "vxl@1e-05", ".4f"),
    ("vx_L/u0 @5e-5", "vxl@5e-05", ".4f"),
    ("(KE+SE)/KE0 @5e-5", "kese@5e-05", ".4f"),
    ("close fraction @5e-5", "close@5e-05", ".4f"),
    ("min distance/dx @5e-5", "dmin@5e-05", ".3f"),
]


def us_of(timing, steps=None):
    """µs per particle-step of one timing run (a `timing` result)."""
    steps = timing.get("steps") or steps
    return 1e6 * timing["loop_s"] / (steps * timing["particles"])


def median(v):
    v = sorted(v)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def make_row(name, timing=None, measure=None, us=None, particles=None, steps=None,
             wall_timing=None, wall_full=None, peer=False, note=None, us_rounds=None):
    row = {"name": name, "peer": peer, "note": note, "wall_timing_s": wall_timing,
           "wall_full_s": wall_full}
    if measure:
        row.update({k: v for k, v in measure.items()})
    if timing:
        row["loop_s"] = timing["loop_s"]
        row["steps"] = timing.get("steps") or steps
        row["particles"] = timing.get("particles") or row.get("particles") or particles
        if row["steps"] and row["particles"]:
            row["us"] = 1e6 * timing["loop_s"] / (row["steps"] * row["particles"])
    if us is not None:
        row["us"] = us
    if particles is not None:
        row["particles"] = particles
    if steps is not None:
        row["steps"] = steps
    if us_rounds:
        row["us_rounds"] = us_rounds
        row["us"] = median(us_rounds)
    return row


def fmt(v, spec):
    if v is None:
        return "–"
    if spec is None:
        return str(v)
    if spec == "d":
        return "{:,}".format(int(v))
    if spec == "rounds":
        return ", ".join("%.3f" % x for x in v)
    return format(v, spec)


def table(rows):
    out = ["| " + " | ".join(c[0] for c in COLUMNS) + " |",
           "|" + "|".join("---" if c[2] is None else "---:" for c in COLUMNS) + "|"]
    for r in rows:
        out.append("| " + " | ".join(fmt(r.get(c[1]), c[2]) for c in COLUMNS) + " |")
    peers = [r for r in rows if r.get("peer") and r.get("us")]
    timed = [r for r in rows if r.get("us")]
    if peers and timed:
        out.append("")
        out.append("Speed ratios: each row's µs/particle-step over each peer's, the median of the "
                   "per-round ratios where both ran in the same rounds (< 1: faster than that "
                   "peer).")
        out.append("")
        out.append("| code / variant | " + " | ".join("/ " + p["name"] for p in peers) + " |")
        out.append("|---|" + "---:|" * len(peers))
        for r in timed:
            out.append("| %s | %s |" % (r["name"], " | ".join(
                "%.3f" % ratio(r, p) for p in peers)))
    base = [r for r in rows if r.get("us") and r.get("base")]
    if base and timed:
        b = base[0]
        out.append("")
        out.append("Over %s (median of per-round ratios; its inverse in brackets):" % b["name"])
        out.append("")
        for r in timed:
            if r is not b:
                q = ratio(r, b)
                out.append("- %s: %.3f (%.2f)" % (r["name"], q, 1.0 / q))
    walls = [r for r in rows if r.get("wall_timing_s") or r.get("wall_full_s")]
    if walls:
        out.append("")
        out.append("Wall times (whole command, incl. start-up, set-up/compilation and output): "
                   "timing run / full run to 5e-5 s.")
        out.append("")
        for r in walls:
            out.append("- %s: %s / %s" % (r["name"], fmt_s(r.get("wall_timing_s")),
                                          fmt_s(r.get("wall_full_s"))))
    notes = [r for r in rows if r.get("note")]
    if notes:
        out.append("")
        for r in notes:
            out.append("- %s: %s" % (r["name"], r["note"]))
    return "\n".join(out)


def ratio(a, b):
    """The median over rounds of a's µs over b's, round by round where both have the same
    number of rounds; else the ratio of the medians."""
    ra, rb = a.get("us_rounds"), b.get("us_rounds")
    if ra and rb and len(ra) == len(rb):
        return median([x / y for x, y in zip(ra, rb)])
    return a["us"] / b["us"]


def fmt_s(v):
    return "–" if v is None else "%.1f s" % v


# ---------------------------------------------------------------------------- CLI

def _load(path):
    if not path:
        return None
    with open(path) as fh:
        return json.load(fh)


def _dump(obj, path):
    text = json.dumps(obj, indent=1, sort_keys=True)
    if path:
        with open(path, "w") as fh:
            fh.write(text + "\n")
    else:
        print(text)


def main(argv=None):
    ap = argparse.ArgumentParser(description="colliding-rings metrics")
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("measure")
    m.add_argument("format", choices=sorted(READERS))
    m.add_argument("path")
    m.add_argument("--dx", type=float, required=True)
    m.add_argument("-o", "--out")
    t = sub.add_parser("timing")
    t.add_argument("format", choices=["pysph", "lammps"])
    t.add_argument("log")
    t.add_argument("--steps", type=int)
    t.add_argument("-o", "--out")
    r = sub.add_parser("row")
    r.add_argument("--name", required=True)
    r.add_argument("--timing")
    r.add_argument("--measure")
    r.add_argument("--us-per-step", type=float)
    r.add_argument("--particles", type=int)
    r.add_argument("--steps", type=int)
    r.add_argument("--wall-timing", type=float)
    r.add_argument("--wall-full", type=float)
    r.add_argument("--peer", action="store_true")
    r.add_argument("--note")
    r.add_argument("--base", action="store_true",
                   help="the row the others are compared with (gsph av)")
    r.add_argument("--us-rounds", help="file with one µs/particle-step per round")
    r.add_argument("-o", "--out")
    u = sub.add_parser("us", help="µs per particle-step of a timing result")
    u.add_argument("timing")
    u.add_argument("--steps", type=int)
    tb = sub.add_parser("table")
    tb.add_argument("rows", nargs="*")
    a = ap.parse_args(argv)
    if a.cmd == "measure":
        frames = READERS[a.format](a.path)
        _dump(run_metrics(frames, a.dx), a.out)
    elif a.cmd == "timing":
        res = timing_lammps(a.log) if a.format == "lammps" else timing_pysph(a.log, a.steps)
        _dump(res, a.out)
    elif a.cmd == "row":
        rounds = None
        if a.us_rounds:
            rounds = [float(x) for x in open(a.us_rounds).read().split()]
        row = make_row(a.name, _load(a.timing), _load(a.measure), a.us_per_step,
                       a.particles, a.steps, a.wall_timing, a.wall_full, a.peer, a.note,
                       rounds)
        if a.base:
            row["base"] = True
        _dump(row, a.out)
    elif a.cmd == "us":
        print("%.6f" % us_of(_load(a.timing), a.steps))
    elif a.cmd == "table":
        print(table([_load(p) for p in a.rows]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
