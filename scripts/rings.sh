#!/usr/bin/env bash
# Do the colliding rings bounce apart intact? (issue 14 item 2; docs/rings.md)
# Runs cases/rings.toml in every gsph scheme with and without artificial stress, at
# dx = 1e-3 m (4,416 particles; --resolution 5e-4 for 17,592) to t_end = 2.5e-4 s (the rings
# meet at about 1.6e-5 s and, if they stay whole, separate again before 1.5e-4 s), and
# writes for each run:
#   out/rings/dx_DX/SCHEME_{as,noas}/            the run (summary.json, series.csv, snapshots)
#   out/rings/dx_DX/SCHEME_{as,noas}_5e-5.png    the particles at 5e-5 s coloured by sigma_xx
#   out/rings/dx_DX/SCHEME_{as,noas}_end.png     the particles at t_end
# and one table out/rings/dx_DX/rings.md: (KE+SE)/KE0 and the close-pair fraction (nearest
# neighbour < 0.75 dx) at 5e-5 s, their worst over the run, the smallest pair distance over
# dx, and the left ring's centre-of-mass vx/u0 at t_end (negative: it rebounded).
#
#   scripts/rings.sh [--resolution 1e-3|5e-4] [--threads N] [--schemes "av ts2"] [--no-plain]
#                    [--tag NAME --set KEY=VALUE ...]
#
# --set passes scene overrides to every run (e.g. --set kernel=wendland_c2); --tag names
# the variant: its runs go to out/rings/dx_DX/NAME/ instead.
#
# Time on 2 cores (dx = 1e-3, 2 threads, 25,000 steps per run): about 1 min (av) to 4 min
# (tkc) per run. GSPH overrides the binary (default target/release/gsph, built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
DX=1e-3
THREADS=2
SCHEMES="av pm ts1 ts2 tkc"
VARIANTS="as noas"
T_END=2.5e-4
TAG=""
EXTRA=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --resolution) DX=${2:?--resolution needs 1e-3 or 5e-4}; shift ;;
    --threads) THREADS=${2:?--threads needs a count}; shift ;;
    --schemes) SCHEMES=${2:?--schemes needs a list}; shift ;;
    --no-plain) VARIANTS="as" ;;
    --tag) TAG=${2:?--tag needs a name}; shift ;;
    --set) EXTRA+=(--set "${2:?--set needs KEY=VALUE}"); shift ;;
    -h|--help) sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
    *) echo "rings: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
case $DX in 1e-3|5e-4) ;; *) echo "rings: --resolution 1e-3|5e-4" >&2; exit 2 ;; esac
GSPH=${GSPH:-$ROOT/target/release/gsph}
if [[ ! -x $GSPH ]]; then
  echo "rings: building gsph (cargo build --release -p gsph)" >&2
  cargo build --release -q -p gsph
fi
OUT=$ROOT/out/rings/dx_$DX${TAG:+/$TAG}
mkdir -p "$OUT"
scale=$(awk -v d="$DX" 'BEGIN { printf "%.6g", 5e-4 / d }')
# series and snapshots: every 5e-6 s (50 intervals) so that 5e-5 s is a snapshot
rows=()
for s in $SCHEMES; do
  for v in $VARIANTS; do
    name=${s}_$v
    set=(--set "scheme=$s" --set "resolution_scale=$scale" --set "t_end=$T_END"
      --set output.snapshots=50 --threads "$THREADS" --quiet "${EXTRA[@]}")
    [[ $v == noas ]] && set+=(--unset options.artificial_stress)
    echo "rings: $name (dx $DX, to $T_END s)" >&2
    rm -rf "${OUT:?}/$name"
    if ! "$GSPH" run cases/rings.toml "${set[@]}" --out "$OUT/$name" >"$OUT/$name.log" 2>&1; then
      echo "rings: $name failed: $(tail -1 "$OUT/$name.log")" >&2
      rows+=("| $s | $v | failed: $(tail -1 "$OUT/$name.log") | | | | | |")
      continue
    fi
    "$GSPH" plot particles "$OUT/$name" --field sigma_xx --time 5e-5 --range=-4e5,4e5 \
      --out "$OUT/${name}_5e-5.png" >/dev/null
    "$GSPH" plot particles "$OUT/$name" --field sigma_xx --range=-4e5,4e5 \
      --out "$OUT/${name}_end.png" >/dev/null
    rows+=("$(python3 - "$OUT/$name" "$s" "$v" <<'EOF'
import csv, json, sys
d, scheme, variant = sys.argv[1:4]
summ = json.load(open(d + "/summary.json"))
rows = list(csv.DictReader(open(d + "/series.csv")))
t = [float(r["t"]) for r in rows]
k = min(range(len(t)), key=lambda i: abs(t[i] - 5e-5))
ke0 = float(rows[0]["kinetic"])
u0 = 0.059 * 4032.3891927275595
def e(r):
    return (float(r["kinetic"]) + float(r["strain_energy"])) / ke0
worst_e = min(e(r) for r in rows)
close = [float(r["close_fraction"]) for r in rows]
dmin = min(float(r["min_distance"]) for r in rows)
vx = [float(r["body0_vx"]) / u0 for r in rows]
flip = next((t[i] for i in range(len(vx)) if vx[i] < 0), None)
print("| %s | %s | %.4f | %.4f | %.2f %% | %.2f %% | %.3f | %+.4f | %s |" % (
    scheme, variant, e(rows[k]), worst_e, 100 * close[k], 100 * max(close), dmin, vx[-1],
    "%.3g" % flip if flip is not None else "never"))
EOF
)")
  done
done
{
  echo "# Colliding rings to $T_END s, dx = $DX m${TAG:+, $TAG (${EXTRA[*]})} ($(date -u +%F), gsph $(git rev-parse --short HEAD))"
  echo
  echo "| scheme | AS | (KE+SE)/KE0 at 5e-5 s | worst | close at 5e-5 s | worst | min distance / dx | vx_L/u0 at t_end | vx_L < 0 from (s) |"
  echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  printf '%s\n' "${rows[@]}"
} >"$OUT/rings.md"
cat "$OUT/rings.md"
