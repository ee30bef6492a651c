#!/usr/bin/env bash
# What double precision buys (issue 28 item 4; docs/performance.md): the flyer plate of
# seed 000 (ts1, strength and plasticity, one thread, the portable loops) stepped by
# core/examples/precision.rs in f64 and in f32 at several resolutions, against the exact
# solution (the error `gsph study` reports for the flyer plate: mean |sigma_xx - exact|
# relative to the final stress), in ROUNDS interleaved rounds (f64, f32, f64, f32 ...).
# Prints a Markdown table: per N the errors and energy errors of both precisions and the
# step time per particle-step, with f32/f64 as the median of the per-round ratios.
#
#   scripts/precision.sh [N ...]     env: ROUNDS=3 (default N: 200 400 800 1600 3200)
#
# Builds go to target/precision-f64 and target/precision-f32 (about 1 minute each the
# first time); the rows of every round are kept in out/precision/rows.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${ROUNDS:-3}
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(200 400 800 1600 3200)
FEATURES=dim1,scheme-ts,effects-strength
for p in f64 f32; do
  f=$FEATURES
  [[ $p == f32 ]] && f=f32,$FEATURES
  cargo build -q --release -p gsph-core --example precision --no-default-features \
    --features "$f" --target-dir "target/precision-$p"
done
mkdir -p out/precision
rows=out/precision/rows.csv
echo "round,precision,n,steps,l1_error_relative,energy_rel_error,peak_sigma_xx_pa,step_seconds,us_per_particle_step" >"$rows"
for r in $(seq "$ROUNDS"); do
  for p in f64 f32; do
    echo "round $r: $p" >&2
    "target/precision-$p/release/examples/precision" "${sizes[@]}" | tail -n +2 | sed "s/^/$r,/" >>"$rows"
  done
done
python3 - "$rows" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
print(f"CPU: {cpu}; {max(int(r['round']) for r in rows)} interleaved rounds; one thread, portable loops\n")
print("| N | steps | L1 error f64 | L1 error f32 | f32/f64 error | energy error f64 | energy error f32 | µs/particle-step f64 | f32 | f32/f64 time (median of rounds) |")
print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for n in sorted({int(r["n"]) for r in rows}):
    by = {(r["round"], r["precision"]): r for r in rows if int(r["n"]) == n}
    rounds = sorted({k[0] for k in by})
    a, b = by[(rounds[0], "f64")], by[(rounds[0], "f32")]
    ea, eb = float(a["l1_error_relative"]), float(b["l1_error_relative"])
    ta = statistics.median(float(by[(k, "f64")]["us_per_particle_step"]) for k in rounds)
    tb = statistics.median(float(by[(k, "f32")]["us_per_particle_step"]) for k in rounds)
    ratio = statistics.median(float(by[(k, "f32")]["step_seconds"]) / float(by[(k, "f64")]["step_seconds"]) for k in rounds)
    print(f"| {n} | {a['steps']} | {ea:.4e} | {eb:.4e} | {eb/ea:.4f} | {float(a['energy_rel_error']):.1e} | {float(b['energy_rel_error']):.1e} | {ta:.3f} | {tb:.3f} | {ratio:.3f} |")
PY
