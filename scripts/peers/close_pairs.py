"""Where are the close pairs of a gsph rings run, and in what stress state?

    .venv-peers/bin/python scripts/peers/close_pairs.py out/peers/dx_5e-4/gsph_av/full/snapshots.h5 --dx 5e-4

For the last snapshot (or --time T): the pairs nearer than 0.75 dx, how many join particles of
the same ring, where their centres lie, and the principal stresses of sigma = S - p I (tension
positive) of the particles in them. Artificial stress acts only along tensile principal
directions, so a close pair whose particles are compressed both ways is not the tensile
instability but the compressive pairing of the cubic spline (its gradient peaks at q = 2/3,
r = dx at h = 1.5 dx, and falls for nearer neighbours), which artificial stress cannot
prevent.
"""

import argparse
import json

import h5py
import numpy as np
from scipy.spatial import cKDTree


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("snapshots")
    ap.add_argument("--dx", type=float, required=True)
    ap.add_argument("--time", type=float)
    a = ap.parse_args()
    f = h5py.File(a.snapshots, "r")
    keys = sorted(k for k in f.keys() if k.startswith("step"))
    if a.time is not None:
        keys.sort(key=lambda k: abs(f[k].attrs["time"] - a.time))
    g = f[keys[-1] if a.time is None else keys[0]]
    x = g["position"][:, :2]
    ids = g["id"][:]
    body = (ids >= len(ids) // 2).astype(int)  # the left ring's particles come first
    p, sxx, syy, sxy = (g[k][:] for k in ("p", "sxx", "syy", "sxy"))
    pairs = np.array(sorted(cKDTree(x).query_pairs(0.75 * a.dx)), dtype=int).reshape(-1, 2)
    idx = np.unique(pairs.ravel())
    mean = (sxx + syy) / 2 - p
    rad = np.sqrt(((sxx - syy) / 2) ** 2 + sxy**2)
    s1 = mean + rad
    mid = 0.5 * (x[pairs[:, 0]] + x[pairs[:, 1]]) if len(pairs) else np.zeros((0, 2))
    out = {
        "time": float(g.attrs["time"]),
        "close_pairs": int(len(pairs)),
        "particles_in_them": int(len(idx)),
        "fraction_of_particles": len(idx) / len(x),
        "same_ring": int((body[pairs[:, 0]] == body[pairs[:, 1]]).sum()),
        "centre_x_range": [float(mid[:, 0].min()), float(mid[:, 0].max())] if len(mid) else None,
        "centre_abs_y_range": [float(abs(mid[:, 1]).min()), float(abs(mid[:, 1]).max())]
        if len(mid)
        else None,
        "compressed_both_ways": float((s1[idx] < 0).mean()) if len(idx) else None,
        "in_compression_p_gt_0": float((p[idx] > 0).mean()) if len(idx) else None,
        "median_largest_principal_Pa": float(np.median(s1[idx])) if len(idx) else None,
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
