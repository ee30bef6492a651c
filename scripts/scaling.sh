#!/usr/bin/env bash
# Cost per particle-step against problem size and thread count (issue 14 item 6;
# docs/performance.md): cases/rings.toml in every scheme at 4,416 / 17,592 / 70,320
# particles on one thread, and at 17,592 (or --big: 70,320) on 1 and N threads, timed by
# gsph's own clock over the stepping (summary.json wall_s; the [monitor] is switched off,
# one snapshot at the end). Prints a markdown table and writes it to out/scaling/scaling.md.
#
#   scripts/scaling.sh [--threads N] [--schemes "av ts2"] [--reps R] [--big]
#
# Steps per run: 2,000 at 4,416 particles, 1,000 at 17,592, 500 at 70,320 (the step is
# fixed, dt = 1e-8 s). The lists do not age alike: their skin is a fraction of h, which
# halves with each size step while particles move as far per step, so a larger ring
# rebuilds about twice as often (the rebuild column gives all three sizes). Each figure is
# the least of R runs (default 1). About 10 minutes for all schemes on 2 cores.
# GSPH overrides the binary (default target/release/gsph, built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
THREADS=$(getconf _NPROCESSORS_ONLN)
SCHEMES="av pm ts1 ts2 tkc"
REPS=1
BIG=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --threads) THREADS=${2:?--threads needs a count}; shift ;;
    --schemes) SCHEMES=${2:?--schemes needs a list}; shift ;;
    --reps) REPS=${2:?--reps needs a count}; shift ;;
    --big) BIG=1 ;;
    -h|--help) sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
    *) echo "scaling: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
GSPH=${GSPH:-$ROOT/target/release/gsph}
if [[ ! -x $GSPH ]]; then
  echo "scaling: building gsph (cargo build --release -p gsph)" >&2
  cargo build --release -q -p gsph
fi
OUT=$ROOT/out/scaling
mkdir -p "$OUT"

# us SCHEME SCALE STEPS THREADS -> "us_per_particle_step bytes_per_particle rebuilds ns_per_pair"
us() {
  local best="" line
  for _ in $(seq "$REPS"); do
    "$GSPH" run cases/rings.toml --set "scheme=$1" --set "resolution_scale=$2" \
      --set "max_steps=$3" --set output.snapshots=1 --unset monitor --threads "$4" --quiet \
      --out "$OUT/run" >/dev/null 2>"$OUT/err" || { echo "failed: $(tail -1 "$OUT/err")"; return; }
    line=$(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
print("%.3f %d %.0f %.2f" % (d["wall_s"] / d["particles"] / d["steps"] * 1e6,
    d["bytes_per_particle"], 1000 * d["neighbor_rebuilds"] / d["steps"],
    d["wall_s"] / d["pair_interactions"] * 1e9))
' "$OUT/run/summary.json")
    if [[ -z $best ]] || awk -v a="${line%% *}" -v b="${best%% *}" 'BEGIN { exit !(a < b) }'; then
      best=$line
    fi
  done
  echo "$best"
}

big_scale=1
[[ $BIG -eq 1 ]] && big_scale=0.5
big_steps=1000
[[ $BIG -eq 1 ]] && big_steps=500
rows=()
for s in $SCHEMES; do
  echo "scaling: $s" >&2
  read -r a _ ra pa < <(us "$s" 0.5 2000 1)
  read -r b bytes rb pb < <(us "$s" 1 1000 1)
  read -r c _ rc pc < <(us "$s" 2 500 1)
  t1=$b
  [[ $BIG -eq 1 ]] && read -r t1 _ _ _ < <(us "$s" "$big_scale" "$big_steps" 1)
  read -r tn _ _ _ < <(us "$s" "$big_scale" "$big_steps" "$THREADS")
  rows+=("$(awk -v s="$s" -v a="$a" -v b="$b" -v c="$c" -v t1="$t1" -v tn="$tn" \
    -v by="$bytes" -v ra="$ra" -v rb="$rb" -v rc="$rc" -v pa="$pa" -v pb="$pb" -v pc="$pc" 'function spread(x, y, z,  lo, hi) {
      lo = x; hi = x; if (y < lo) lo = y; if (z < lo) lo = z; if (y > hi) hi = y; if (z > hi) hi = z
      return 100 * (hi / lo - 1) }
    BEGIN {
      printf "| %s | %.3f | %.3f | %.3f | %+.0f %% | %.2f / %.2f / %.2f | %+.0f %% | %.3f | %.3f | %.2f | %d | %s / %s / %s |",
        s, a, b, c, spread(a, b, c), pa, pb, pc, spread(pa, pb, pc), t1, tn, t1 / tn, by, ra, rb, rc }')")
done
n_big=17,592
[[ $BIG -eq 1 ]] && n_big=70,320
{
  echo "# Cost per particle-step: size and threads ($(date -u +%F), $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1), $(getconf _NPROCESSORS_ONLN) cores, gsph $(git rev-parse --short HEAD))"
  echo
  echo "cases/rings.toml (artificial stress on, monitor off), µs per particle-step; spread = largest/smallest − 1 over the three sizes; ns per pair = wall time over the neighbour-list entries stepped (thinner rings have more surface, so fewer neighbours per particle: 31 at 4,416, 35 at 70,320); threads at $n_big particles."
  echo
  echo "| scheme | 4,416 (1 thread) | 17,592 | 70,320 | spread | ns per pair at the three sizes | spread | $n_big, 1 thread | $THREADS threads | speed-up | bytes/particle (17,592) | rebuilds per 1,000 steps at the three sizes |"
  echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  printf '%s\n' "${rows[@]}"
} >"$OUT/scaling.md"
cat "$OUT/scaling.md"
