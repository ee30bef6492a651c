"""(KE+SE)/E0 of the breathing ring against time, every scheme, from scripts/elastic.sh's
runs (out/elastic/runs/breathing-DX-SCHEME-DISSIPATION/series.csv); or, with `plate`, the
clamped oscillating plate's (out/elastic/runs/plate-SCALE-SCHEME-VARIANT/) at each
resolution, beside SPHinXsys's kinetic-energy peaks (its UL solver with the hourglass
penalty; docs/notes/issue46_peers.md).

    python scripts/elastic_plot.py [DX] [OUT.png]      (default 1e-3, docs/elastic/breathing.png)
    python scripts/elastic_plot.py plate [OUT.png]     (default docs/elastic/plate.png)
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

if len(sys.argv) > 1 and sys.argv[1] == "plate":
    # the peer's kinetic-energy peaks (SPHinXsys UL + GNOG, regression file Run_0)
    PEER_T = [0.142, 0.284, 0.427, 0.570, 0.713, 0.857]
    PEER_KE = [0.9922, 0.9892, 0.9869, 0.9851, 0.9824, 0.9793]
    out = Path(sys.argv[2] if len(sys.argv) > 2 else "docs/elastic/plate.png")
    runs = Path("out/elastic/runs")
    fig, axes = plt.subplots(1, 3, figsize=(14, 4), sharey=True)
    for ax, scheme in zip(axes, ["ts2", "tkc", "pm"]):
        for scale, style in [(1, "-"), (2, "--"), (4, ":")]:
            for variant, color in [("full", "C0"), ("stiff", "C1"), ("stiff_full", "C2")]:
                path = runs / f"plate-{scale}-{scheme}-{variant}" / "series.csv"
                if not path.exists():
                    continue
                rows = list(csv.DictReader(open(path)))
                t = [float(r["t"]) for r in rows]
                e = [float(r["mechanical_energy_ratio"]) for r in rows]
                ax.plot(t, e, style, color=color, lw=1, label=f"{variant}, H/{10 * scale}")
        ax.plot(PEER_T, PEER_KE, "ks", ms=4, label="SPHinXsys UL, KE peaks")
        ax.set_title(scheme)
        ax.set_xlabel("t (s)")
        ax.set_ylim(0, 1.3)
        ax.axhline(1.0, color="k", lw=0.5)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("(KE + SE) / E0")
    fig.suptitle("Clamped oscillating plate (cases/plate_oscillating.toml)")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    print(out)
    sys.exit(0)

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
