"""(KE+SE)/E0 of the breathing ring against time, every scheme, from scripts/elastic.sh's
runs (out/elastic/runs/breathing-DX-SCHEME-DISSIPATION/series.csv).

    python scripts/elastic_plot.py [DX] [OUT.png]      (default 1e-3, docs/elastic/breathing.png)
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

dx = sys.argv[1] if len(sys.argv) > 1 else "1e-3"
out = Path(sys.argv[2] if len(sys.argv) > 2 else "docs/elastic/breathing.png")
runs = Path("out/elastic/runs")
fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
for ax, diss in zip(axes, ["full", "compression"]):
    for scheme in ["av", "ts1", "ts2", "tkc", "pm"]:
        d = "none" if scheme == "av" else diss
        path = runs / f"breathing-{dx}-{scheme}-{d}" / "series.csv"
        if not path.exists():
            continue
        rows = list(csv.DictReader(open(path)))
        t = [float(r["t"]) * 1e6 for r in rows]
        e = [float(r["mechanical_energy_ratio"]) for r in rows]
        ax.plot(t, e, label=scheme if scheme != "av" else "av (no Riemann solver)")
    ax.set_title(f"options.dissipation = {diss}")
    ax.set_xlabel("t (µs)")
    ax.set_ylim(0, 1.5)
    ax.axhline(1.0, color="k", lw=0.5)
    ax.grid(alpha=0.3)
axes[0].set_ylabel("(KE + SE) / E0")
axes[0].legend()
fig.suptitle(f"Free breathing ring (cases/ring_breathing.toml), dx = {dx} m")
fig.tight_layout()
out.parent.mkdir(parents=True, exist_ok=True)
fig.savefig(out, dpi=110)
print(out)
