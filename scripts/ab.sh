#!/usr/bin/env bash
# Two gsph binaries side by side (e.g. before and after a change that touches a scheme, a
# pass or the neighbour search): whether each scheme's final.csv is bitwise the same (in
# every column both binaries write) on the
# flyer plate, the 1D Riemann problem, a short 3D impact, the 2D impact with damage, the bar
# on a rigid wall, the periodic 2D Riemann strip and the rings with artificial stress, then
# the stepping wall time
# (`wall_s`) on the colliding rings (300 steps) and the 2D steel -> SiC impact (half
# resolution, 150 steps), one thread, the two binaries alternating within each round; last
# the median over rounds of new/old for each case and scheme.
#   scripts/ab.sh OLD_GSPH NEW_GSPH [REPEATS]     (about 5 minutes with 3 repeats)
# Build the old one from a worktree: git worktree add /tmp/old REV &&
#   (cd /tmp/old && cargo build --release -p gsph) and pass /tmp/old/target/release/gsph.
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2 reps=${3:-3}
o=$(mktemp -d)
# final.csv files are the same when every column both have is byte-identical (a newer
# gsph may append columns: the columns of an older one stay and keep their order)
csv_same() {
  python3 - "$1" "$2" <<'PY'
import csv, sys
a, b = (list(csv.reader(open(f))) for f in sys.argv[1:3])
common = [c for c in a[0] if c in b[0]]
ia = [a[0].index(c) for c in common]
ib = [b[0].index(c) for c in common]
ok = len(a) == len(b) and len(common) >= 22 and all(
    [ra[i] for i in ia] == [rb[j] for j in ib] for ra, rb in zip(a[1:], b[1:]))
sys.exit(0 if ok else 1)
PY
}
echo "== final.csv, old against new"
for c in flyer_plate riemann_al; do
  for s in av pm ts1 ts2 tkc; do
    for b in old new; do "${!b}" run cases/$c.toml --set scheme=$s --out "$o/${b}_${c}_$s" --quiet >/dev/null; done
    csv_same "$o/old_${c}_$s/final.csv" "$o/new_${c}_$s/final.csv" && r=identical || r=DIFFERENT
    echo "$c $s: $r"
  done
done
for b in old new; do
  "${!b}" run cases/steel_sic_impact_3d.toml --set resolution_scale=0.5 --set max_steps=40 --out "$o/${b}_3d" --quiet >/dev/null
done
csv_same "$o/old_3d/final.csv" "$o/new_3d/final.csv" && r=identical || r=DIFFERENT
echo "steel_sic_impact_3d (6,250 particles, 40 steps, ts2): $r"
# every run-time effect: damage and heat (2D impact), walls (the bar), periodic (2D
# Riemann strip), artificial stress (rings), each scheme
same() { csv_same "$o/old_$1/final.csv" "$o/new_$1/final.csv" && echo identical || echo DIFFERENT; }
for s in av pm ts1 ts2 tkc; do
  extra=(); [ "$s" = av ] && extra=(--unset options.riemann)
  for b in old new; do
    "${!b}" run cases/steel_sic_impact.toml --set scheme=$s --set resolution_scale=0.25 --set max_steps=60 "${extra[@]}" --out "$o/${b}_imp_$s" --quiet >/dev/null
    "${!b}" run cases/wall_bar.toml --set scheme=$s --set t_end=4e-6 --out "$o/${b}_wall_$s" --quiet >/dev/null
    "${!b}" run cases/riemann_al_2d.toml --set scheme=$s --set resolution_scale=0.5 --set max_steps=60 --out "$o/${b}_r2_$s" --quiet >/dev/null
    "${!b}" run cases/rings.toml --set scheme=$s --set max_steps=40 --set resolution_scale=0.5 --out "$o/${b}_ring_$s" --quiet >/dev/null
  done
  echo "steel_sic_impact 2D (damage, heat) $s: $(same imp_$s); wall_bar $s: $(same wall_$s); riemann_al_2d (periodic) $s: $(same r2_$s); rings (artificial stress) $s: $(same ring_$s)"
done
echo "== wall_s, one thread (round case scheme binary seconds)"
times=$o/times.txt
for rep in $(seq "$reps"); do
  for c in rings impact; do
    for s in av ts2 tkc; do
      # alternate which binary goes first, so neither always runs on a cooler machine
      order=(old new); (( rep % 2 == 0 )) && order=(new old)
      for b in "${order[@]}"; do
        if [ "$c" = rings ]; then
          "${!b}" run cases/rings.toml --set scheme=$s --set max_steps=300 --unset monitor \
            --set output.snapshots=1 --threads 1 --quiet --out "$o/r_${b}_$s" >/dev/null
        else
          unset_riemann=(); [ "$s" = av ] && unset_riemann=(--unset options.riemann)
          "${!b}" run cases/steel_sic_impact.toml --set scheme=$s --set resolution_scale=0.5 \
            --set max_steps=150 "${unset_riemann[@]}" --unset monitor --set output.snapshots=1 \
            --threads 1 --quiet --out "$o/r_${b}_$s" >/dev/null
        fi
        w=$(python3 -c "import json,sys;print(json.load(open(sys.argv[1]))['wall_s'])" "$o/r_${b}_$s/summary.json")
        echo "$rep $c $s $b $w" | tee -a "$times"
      done
    done
  done
done
echo "== median over rounds of new/old wall_s"
python3 - "$times" <<'PY'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
t = {(r[0], r[1], r[2], r[3]): float(r[4]) for r in rows}
for c in ("rings", "impact"):
    for s in ("av", "ts2", "tkc"):
        ratios = sorted(t[(k, c, s, "new")] / t[(k, c, s, "old")]
                        for k in {r[0] for r in rows})
        print(f"{c} {s}: new/old {statistics.median(ratios):.3f} "
              f"(rounds: {', '.join(f'{x:.3f}' for x in ratios)})")
PY
rm -rf "$o"
