#!/usr/bin/env bash
# Smooth elastic motion and large strain, every scheme (issue 27): what each scheme keeps
# of a freely breathing ring's and a rigidly spinning ring's energy, the spin's angular
# momentum, the colliding rings and the Taylor test, with the Godunov schemes'
# dissipation as the seeds have it (`options.dissipation = "full"`) and only on
# compression (`"compression"`, Zhang, Hu & Adams 2017), and for pm and tkc with only the
# transverse channels on compression (`options.transverse_dissipation`), as the seeds have
# the transverse problems (`seed`: `options.objective = false`) and, for tkc, with the
# MUSCL slopes corrected at free surfaces (`slopes`: `options.corrected_slopes = true`)
# and with the umbrella scan confirming its free surfaces (`scan`: `options.surface_scan = true`);
# ts1, ts2 and tkc also with the second-order leap-frog (`leapfrog`:
# `options.integrator = "leapfrog"`, at each scene's CFL; ts2 needs CFL <= 0.25 on
# converging cases, so on the Taylor rod (0.3) its row may fail), and pm and tkc with
# Sugiura & Inutsuka's interpolated specific volumes (`volume`:
# `options.specific_volume = "interpolated"`; on the colliding rings also `volume_noas`,
# the same in place of artificial stress).
# Issue 46's hourglass stiffness (`options.hourglass = 2`): `stiff` with dissipation on
# compression only, `stiff_full` with the full dissipation, `stiff_leapfrog` with
# compression and the leap-frog (on the colliding rings in place of artificial stress).
# The breathing ring runs on the case's relaxed (body-fitted) layout (`breathing`,
# docs/layouts.md), on the clipped square lattice of issue 27 (`breathing_lattice`) and on
# a polar lattice (smooth surfaces: `breathing_polar`). SPHinXsys's clamped oscillating plate
# (`plate`, cases/plate_oscillating.toml) at H/10, H/20 and H/40 (--quick: H/10): (KE+SE)/E0
# at three periods, the period from the kinetic energy's minima and the smallest pair
# distance; `python3 scripts/elastic_plot.py plate` draws (KE+SE)/E0(t) beside the peers'.
# One Markdown table: out/elastic/table.md (rows also as out/elastic/rows.csv).
#
#   scripts/elastic.sh [--quick] [--parts breathing,breathing_lattice,breathing_polar,spin,rings,taylor,plate] [--gsph BINARY]
#
# --quick: the breathing rings at dx = 1e-3 only (no refinement) and the spin; no
#          colliding rings (each run to 2.5e-4 s takes 4-12 minutes) and no Taylor test
#          (about 10 minutes on 2 cores).
# Full: the breathing ring at dx = 2e-3, 1e-3, 5e-4 (its loss must fall on refinement),
#       the plate at H/10, H/20, H/40 (H/40: about 6,000 steps per 0.01 s, 20,800
#       particles: hours),
#       the spin, the colliding rings to 2.5e-4 s at dx = 1e-3 and 5e-4 (vx of the left
#       ring over u0, and (KE+SE)/KE0 at 5e-5 s), the Taylor rod at D0/10 and D0/20.
#       The peers' colliding-rings figures (scripts/peers.sh, out/peers/) stand beside
#       the rings rows when that table exists.
set -euo pipefail
cd "$(dirname "$0")/.."
GSPH=${GSPH:-target/release/gsph}
QUICK=0
PARTS=breathing,breathing_lattice,breathing_polar,spin,rings,taylor,plate
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) QUICK=1 ;;
    --parts) PARTS=$2; shift ;;
    --gsph) GSPH=$2; shift ;;
    *) echo "usage: scripts/elastic.sh [--quick] [--parts LIST] [--gsph BINARY]" >&2; exit 2 ;;
  esac
  shift
done
[[ -x $GSPH ]] || cargo build --release -p gsph
OUT=out/elastic
mkdir -p "$OUT"
ROWS=$OUT/rows.csv
echo "case,dx,scheme,variant,metric,value,wall_s" > "$ROWS"
SCHEMES="av ts1 ts2 tkc pm"

# run NAME SCENE SCHEME DISSIPATION ARGS... : one run into $OUT/runs/NAME
run() {
  local name=$1 scene=$2 scheme=$3 diss=$4; shift 4
  local set=(--set "scheme=$scheme")
  case $diss in
    full | compression) set+=(--set "options.dissipation=$diss") ;;
    transverse) set+=(--set "options.transverse_dissipation=compression") ;;
    seed) set+=(--set "options.objective=false") ;;
    slopes) set+=(--set "options.corrected_slopes=true") ;;
    scan) set+=(--set "options.surface_scan=true") ;;
    leapfrog) set+=(--set "options.integrator=leapfrog") ;;
    volume) set+=(--set "options.specific_volume=interpolated") ;;
    volume_noas) set+=(--set "options.specific_volume=interpolated" --unset options.artificial_stress) ;;
    stiff) set+=(--set options.hourglass=2 --set options.dissipation=compression) ;;
    stiff_full) set+=(--set options.hourglass=2) ;;
    stiff_leapfrog) set+=(--set options.hourglass=2 --set options.dissipation=compression
      --set options.integrator=leapfrog) ;;
  esac
  # the stiffness stands in for artificial stress where a scene has it (the rings)
  if [[ $diss == stiff* ]] && grep -q '^artificial_stress' "$scene"; then
    set+=(--unset options.artificial_stress)
  fi
  echo "== $name" >&2
  # a clumping variant can shrink its step for hours without collapsing it: each run
  # gets RUN_TIMEOUT seconds (default 3600) and its row is then NaN
  if ! timeout "${RUN_TIMEOUT:-3600}" "$GSPH" run "$scene" "${set[@]}" "$@" --out "$OUT/runs/$name" --quiet >&2; then
    echo "$name: failed or timed out" >&2
    return 0
  fi
}

# row CASE DX SCHEME DISS NAME KEY... : the summary keys of run NAME as rows
row() {
  local case=$1 dx=$2 scheme=$3 diss=$4 name=$5; shift 5
  python3 - "$OUT/runs/$name/summary.json" "$case" "$dx" "$scheme" "$diss" "$@" >> "$ROWS" <<'PY'
import json, sys
path, case, dx, scheme, diss, *keys = sys.argv[1:]
try:
    d = json.load(open(path))
except OSError:
    d = {}
for k in keys:
    v = d.get(k, float("nan"))
    print(f"{case},{dx},{scheme},{diss},{k},{v},{d.get('wall_s', float('nan'))}")
PY
}

# av: no Riemann solver; ts1/ts2: every channel full or on compression; pm/tkc also with
# only the transverse channels on compression (`transverse`)
dissipations() {
  case $1 in
    av) echo none ;;
    ts1 | ts2) echo full compression leapfrog stiff stiff_full stiff_leapfrog ;;
    pm) echo full compression transverse seed volume stiff stiff_full ;;
    *) echo full compression transverse seed slopes scan leapfrog volume stiff stiff_full stiff_leapfrog ;;
  esac
}
has() { [[ ,$PARTS, == *,$1,* ]]; }

if has breathing; then
  if [[ $QUICK == 1 ]]; then DXS="1e-3"; else DXS="2e-3 1e-3 5e-4"; fi
  for dx in $DXS; do
    for s in $SCHEMES; do
      for d in $(dissipations $s); do
        n=breathing-$dx-$s-$d
        run "$n" cases/ring_breathing.toml "$s" "$d" --set "bodies.0.spacing=$dx"
        row breathing "$dx" "$s" "$d" "$n" mechanical_energy_ratio min_distance_min energy_rel_error
      done
    done
  done
fi
if has breathing_lattice; then
  if [[ $QUICK == 1 ]]; then DXS="1e-3"; else DXS="2e-3 1e-3 5e-4"; fi
  for dx in $DXS; do
    for s in $SCHEMES; do
      for d in $(dissipations $s); do
        n=breathing_lattice-$dx-$s-$d
        run "$n" cases/ring_breathing.toml "$s" "$d" --set "bodies.0.spacing=$dx" \
          --set bodies.0.layout=lattice
        row breathing_lattice "$dx" "$s" "$d" "$n" mechanical_energy_ratio min_distance_min energy_rel_error
      done
    done
  done
fi
if has breathing_polar; then
  if [[ $QUICK == 1 ]]; then DXS="1e-3"; else DXS="2e-3 1e-3 5e-4"; fi
  for dx in $DXS; do
    for s in $SCHEMES; do
      for d in $(dissipations $s); do
        [[ $d == compression ]] && continue
        n=breathing_polar-$dx-$s-$d
        run "$n" cases/ring_breathing.toml "$s" "$d" --set "bodies.0.spacing=$dx" \
          --set bodies.0.lattice=polar --unset bodies.0.lattice_origin --set bodies.0.layout=lattice
        row breathing_polar "$dx" "$s" "$d" "$n" mechanical_energy_ratio min_distance_min energy_rel_error
      done
    done
  done
fi
if has spin; then
  for s in $SCHEMES; do
    for d in $(dissipations $s); do
      n=spin-$s-$d
      run "$n" cases/ring_spin.toml "$s" "$d"
      row spin 1e-3 "$s" "$d" "$n" mechanical_energy_ratio angular_momentum_change min_distance_min energy_rel_error
    done
  done
fi
if has rings && [[ $QUICK == 0 ]]; then
  DXS="1e-3 5e-4"
  for dx in $DXS; do
    for s in $SCHEMES; do
      ds=$(dissipations $s)
      [[ $ds == *volume* ]] && ds="$ds volume_noas"
      for d in $ds; do
        n=rings-$dx-$s-$d
        run "$n" cases/rings.toml "$s" "$d" --set t_end=2.5e-4 \
          --set "bodies.0.spacing=$dx" --set "bodies.1.spacing=$dx" \
          --set monitor.mechanical_energy=true
        row rings "$dx" "$s" "$d" "$n" body0_vx mechanical_energy_ratio min_distance_min energy_rel_error
      done
    done
  done
fi
if has plate; then
  # H/10, H/20, H/40: the lattice spacing of every body (plate and clamp)
  if [[ $QUICK == 1 ]]; then SCALES="1"; else SCALES="1 2 4"; fi
  for scale in $SCALES; do
    for s in ts2 tkc pm; do
      for d in full stiff stiff_full; do
        [[ $s == pm && $d == full ]] && continue
        n=plate-$scale-$s-$d
        run "$n" cases/plate_oscillating.toml "$s" "$d" --set "resolution_scale=$scale"
        python3 scripts/plate_measures.py "$OUT/runs/$n" "H/$((10 * scale))" "$s" "$d" >> "$ROWS" || true
      done
    done
  done
fi
if has taylor && [[ $QUICK == 0 ]]; then
  for scale in 1 2; do
    for s in av ts2 tkc; do
      for d in $(dissipations $s); do
        n=taylor-$scale-$s-$d
        run "$n" cases/taylor_copper.toml "$s" "$d" --set "resolution_scale=$scale"
        row taylor "D0/$((10 * scale))" "$s" "$d" "$n" rod_length rod_impact_diameter
      done
    done
  done
fi

python3 - "$ROWS" > "$OUT/table.md" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| case | dx | scheme | variant | quantity | value | wall s |")
print("| --- | --- | --- | --- | --- | ---: | ---: |")
for r in rows:
    v = float(r["value"])
    print(f"| {r['case']} | {r['dx']} | {r['scheme']} | {r['variant']} | {r['metric']} | {v:.4g} | {float(r['wall_s']):.1f} |")
PY
cat "$OUT/table.md"
