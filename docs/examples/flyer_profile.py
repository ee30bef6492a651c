"""The flyer plate from Python: run the scene, plot sigma_xx against the exact solution.

    python docs/examples/flyer_profile.py [OUT.png]

Notebook-style: each block below is one cell (docs/python.md walks through it).
"""
import os
import sys

import matplotlib.pyplot as plt
import numpy as np

import gsph

# %% Build the scene from the bundled file, with ts1 and ts2 side by side.
sims = {}
for scheme in ["ts1", "ts2"]:
    sim = gsph.Scene.from_file("cases/flyer_plate.toml", {"scheme": scheme}).build()
    steps = sim.run()  # the steps `gsph run` takes
    sims[scheme] = sim
    s = sim.summary()
    print(f"{scheme}: {len(sim)} particles, {steps} steps, t = {sim.time:.3e} s, "
          f"L1 error {s['l1_error'] / 1e9:.4f} GPa, energy error {s['energy_rel_error']:.1e}")

# %% sigma_xx of every particle against the exact solution (Connolly et al. 2013 §4.1).
fig, ax = plt.subplots(figsize=(7, 4))
for scheme, sim in sims.items():
    x, sxx, exact = sim.profile().T
    ax.plot(x * 100, sxx / 1e9, ".", ms=4, label=scheme)
x, _, exact = sims["ts2"].profile().T
held = ~np.isnan(exact)
ax.plot(x[held] * 100, exact[held] / 1e9, "k-", lw=1, label="exact")
ax.set_xlabel("x (cm)")
ax.set_ylabel(r"$\sigma_{xx}$ (GPa)")
ax.set_title(f"Flyer plate at t = {sims['ts2'].time * 1e6:.2f} µs")
ax.legend()
fig.tight_layout()

# %% Peak stress from the numpy fields, and the picture.
p = sims["ts2"].field("pressure")
s = sims["ts2"].field("deviator")
print(f"peak compressive sigma_xx (ts2): {np.min(s[:, 0] - p) / 1e9:.4f} GPa")
out = sys.argv[1] if len(sys.argv) > 1 else "flyer_profile.png"
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
fig.savefig(out, dpi=120)
print(f"wrote {out}")
