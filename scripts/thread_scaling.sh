#!/usr/bin/env bash
# Thread scaling on a many-core machine (issue 28 item 6; docs/performance.md): the
# colliding rings at 70,320 particles (cases/rings.toml, resolution_scale 2, artificial
# stress on, monitor off) in every scheme and the 2D steel->SiC impact (51,200
# particles, ts2), each at 1, 2, 4, 8, 16 threads (THREADS), timed by gsph's own clock
# over the stepping (summary.json wall_s). ROUNDS interleaved rounds (each runs every
# case and thread count once); the speed-up t(1)/t(n) is the median of the per-round
# ratios. Prints a Markdown table; rows also in $OUT/rows.csv.
#
#   scripts/thread_scaling.sh          env: THREADS="1 2 4 8 16" ROUNDS=2 STEPS=80
#                                           SCHEMES="av pm ts1 ts2 tkc" OUT GSPH
#
# GSPH is the command that runs gsph (default target/release/gsph); on a machine without
# this one's libraries it can be a carried loader, e.g.
# GSPH=".dev/lib/ld-linux-x86-64.so.2 --library-path .dev/lib .dev/gsph".
set -euo pipefail
cd "$(dirname "$0")/.."
THREADS=${THREADS:-"1 2 4 8 16"}
ROUNDS=${ROUNDS:-2}
STEPS=${STEPS:-80}
SCHEMES=${SCHEMES:-"av pm ts1 ts2 tkc"}
OUT=${OUT:-out/thread_scaling}
read -r -a GSPH_CMD <<<"${GSPH:-target/release/gsph}"
mkdir -p "$OUT"
echo "round,case,scheme,threads,particles,steps,wall_s" >"$OUT/rows.csv"

# one CASE SCHEME THREADS ROUND ARGS...: one run, a row in rows.csv
one() {
  local case=$1 scheme=$2 t=$3 r=$4 scene=$5
  shift 5
  "${GSPH_CMD[@]}" run "$scene" --set "scheme=$scheme" --set "max_steps=$STEPS" \
    --set output.snapshots=1 --unset monitor --threads "$t" --quiet --out "$OUT/run" "$@" \
    >/dev/null 2>"$OUT/err" || { echo "$case $scheme $t: $(tail -1 "$OUT/err")" >&2; return 0; }
  python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
print(",".join(sys.argv[2:]) + ",%d,%d,%.4f" % (d["particles"], d["steps"], d["wall_s"]))
' "$OUT/run/summary.json" "$r" "$case" "$scheme" "$t" >>"$OUT/rows.csv"
}

for r in $(seq "$ROUNDS"); do
  for s in $SCHEMES; do
    for t in $THREADS; do
      echo "round $r: rings $s, $t threads" >&2
      one rings "$s" "$t" "$r" cases/rings.toml --set resolution_scale=2
    done
  done
  for t in $THREADS; do
    echo "round $r: impact ts2, $t threads" >&2
    one impact ts2 "$t" "$r" cases/steel_sic_impact.toml
  done
done

python3 - "$OUT/rows.csv" "$THREADS" <<'PY'
import csv, statistics, sys, os
rows = list(csv.DictReader(open(sys.argv[1])))
threads = [int(t) for t in sys.argv[2].split()]
cases = []
for r in rows:
    k = (r["case"], r["scheme"])
    if k not in cases:
        cases.append(k)
model = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
flags = next((l.split(":", 1)[1].split() for l in open("/proc/cpuinfo") if l.startswith("flags")), [])
simd = ", ".join(f for f in ("avx2", "fma", "avx512f") if f in flags)
print(f"{model} ({simd}), {os.cpu_count()} logical CPUs: µs per particle-step at 1 thread, then speed-up t(1)/t(n) (median of per-round ratios) and efficiency.")
print()
print("| case | scheme | particles | µs/particle-step, 1 thread | " + " | ".join(f"{t} threads" for t in threads[1:]) + " |")
print("| --- | --- | ---: | ---: | " + " | ".join("---:" for _ in threads[1:]) + " |")
for case, scheme in cases:
    sel = [r for r in rows if (r["case"], r["scheme"]) == (case, scheme)]
    by = {}
    for r in sel:
        by.setdefault(r["round"], {})[int(r["threads"])] = float(r["wall_s"])
    n, steps = int(sel[0]["particles"]), int(sel[0]["steps"])
    t1 = statistics.median(v[1] for v in by.values() if 1 in v)
    cells = []
    for t in threads[1:]:
        ratios = [v[1] / v[t] for v in by.values() if 1 in v and t in v]
        if ratios:
            s = statistics.median(ratios)
            cells.append(f"{s:.2f} ({100 * s / t:.0f} %)")
        else:
            cells.append("–")
    print(f"| {case} | {scheme} | {n:,} | {1e6 * t1 / (n * steps):.3f} | " + " | ".join(cells) + " |")
PY
