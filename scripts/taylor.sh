#!/usr/bin/env bash
# The Taylor impact test (cases/taylor_copper.toml) against Wilkins & Guinan's experiment:
# av, pm and tkc at spacings D0/10, D0/20 and D0/30, the final length and impact-face diameter of
# each against the measured ones, and a picture of the final outlines.
# Writes out/taylor/{taylor.md,taylor.csv,outline_*.png}. About 25 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cargo build --release -p gsph
g=target/release/gsph
o=out/taylor
mkdir -p "$o"
outline=cases/data/taylor_wilkins_guinan_1973.csv
for r in 1 2 3; do
  for s in av pm tkc; do
    echo "== taylor_copper: $s, resolution_scale $r"
    $g run cases/taylor_copper.toml --set scheme=$s --set resolution_scale=$r --out "$o/${s}_$r" --quiet
  done
  $g plot rod "$o/av_$r" "$o/pm_$r" "$o/tkc_$r" --labels "av,pm,tkc" --outline "$outline" --out "$o/outline_$r.png"
done
python3 - "$o" <<'PY'
import json, sys, os
o = sys.argv[1]
L_exp, D_exp = 14.7964, 2 * 8.3965   # mm, cases/data/taylor_wilkins_guinan_1973.csv
rows = ["scheme,resolution_scale,particles,length_mm,length_err_pct,diameter_mm,diameter_err_pct,wall_s"]
md = ["| scheme | spacing | particles | final length (mm) | vs 14.80 | impact-face diameter (mm) | vs 16.79 | wall (s) |",
      "|---|---|---|---|---|---|---|---|"]
for r in (1, 2, 3):
    for s in ("av", "pm", "tkc"):
        j = json.load(open(os.path.join(o, f"{s}_{r}", "summary.json")))
        L, D = 1e3 * j["rod_length"], 1e3 * j["rod_impact_diameter"]
        eL, eD = 100 * (L / L_exp - 1), 100 * (D / D_exp - 1)
        n, w = j.get("particles", ""), j.get("wall_seconds", j.get("wall_s", ""))
        rows.append(f"{s},{r},{n},{L:.3f},{eL:+.1f},{D:.3f},{eD:+.1f},{w}")
        md.append(f"| {s} | D0/{10*r} | {n} | {L:.2f} | {eL:+.1f} % | {D:.2f} | {eD:+.1f} % | {w} |")
open(os.path.join(o, "taylor.csv"), "w").write("\n".join(rows) + "\n")
open(os.path.join(o, "taylor.md"), "w").write("\n".join(md) + "\n")
print("\n".join(md))
PY
