#!/usr/bin/env bash
# Full-size validation runs (not part of CI): the figures and tables of the seeds.
# Writes everything under out/validation/. Takes about 30 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cargo build --release -p gsph
g=target/release/gsph
o=out/validation
mkdir -p "$o"

echo "== seed 000 table 2: energy error of each scheme on the flyer plate"
$g study cases/flyer_plate.toml --schemes av,pm,ts1,ts2 --resolutions 1 --metric energy_rel_error --out "$o/energy_table"
for s in av pm ts1 ts2; do
  $g run cases/flyer_plate.toml --set scheme=$s --out "$o/flyer_$s" --quiet
  $g plot profile "$o/flyer_$s"
done

echo "== seed 004 fig 2b (1D): L1(sigma_xx) against resolution, elastic-plastic Riemann problem"
$g study cases/riemann_al.toml --schemes av,pm,ts1,ts2 --resolutions 1,2,4,8 --out "$o/riemann_study"

echo "== seed 000 §4.2: collapsing ring, ts2 at 8,172 and 23,780 particles"
for r in 1 1.7127; do
  d="$o/ring_ts2_$r"
  $g run cases/ring_collapse.toml --set resolution_scale=$r --out "$d"
  $g plot particles "$d" --field eps_p
  $g plot particles "$d" --field tau_xy
  $g plot series "$d" --columns inner_radius,outer_radius,inner_radius_exact,outer_radius_exact --y-label "radius (m)"
done
for s in ts1 av; do
  d="$o/ring_${s}_1"
  $g run cases/ring_collapse.toml --set scheme=$s --out "$d"
  $g plot particles "$d" --field eps_p
done
echo "validation outputs in $o"
