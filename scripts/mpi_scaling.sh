#!/usr/bin/env bash
# MPI scaling of gsph (docs/mpi.md). Builds gsph with `--features mpi`, then
#
#   strong (default): the 2D steel->SiC impact (cases/steel_sic_impact.toml, 51,200
#     particles) for STEPS steps: one process with 1 and 2 threads, and mpirun -np 1, 2
#     (1 thread per rank), alternated ROUNDS times; prints wall time, µs per
#     particle-step, the halo bytes per step and the share of the loop spent in halo
#     exchanges (summary.json's `mpi` object);
#   weak: RANKS (default 1 2 4 8 16) ranks x PER_RANK particles each (the 2D impact with
#     resolution_scale chosen so that the run has PER_RANK x ranks particles), 1 thread
#     per rank; efficiency = t(1) / t(n). Meant for the 16-core device machine.
#
# Usage: scripts/mpi_scaling.sh [strong|weak]   env: STEPS ROUNDS RANKS PER_RANK OUT
# Output: a table on stdout and $OUT/*.csv (default out/mpi_scaling).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-strong}
STEPS=${STEPS:-60}
ROUNDS=${ROUNDS:-2}
OUT=${OUT:-out/mpi_scaling}
mkdir -p "$OUT"
scripts/setup.sh
# the build `make test` makes (same features, so no rebuild after it)
cargo test -q --release --workspace --features gsph/mpi --no-run 2>/dev/null
bin=target/release/gsph
# containers: allow root, no cross-memory attach; laptops: allow more ranks than cores
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1

# run NAME RANKS THREADS [--set ...]: one run, prints a row
run() {
  local name=$1 ranks=$2 threads=$3
  shift 3
  local dir="$OUT/$name"
  local cmd=("$bin" run cases/steel_sic_impact.toml --out "$dir" --quiet --threads "$threads"
    --set "max_steps=$STEPS" --set output.snapshots=1 --set output.series=2 "$@")
  if [ "$ranks" -gt 0 ]; then cmd=(mpirun -np "$ranks" "${cmd[@]}"); fi
  "${cmd[@]}" >/dev/null
  python3 - "$dir/summary.json" "$name" "$ranks" "$threads" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
name, ranks, threads = sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
n, steps, wall = s["particles"], s["steps"], s["wall_s"]
m = s.get("mpi", {})
halo = m.get("halo_bytes_per_step", 0.0)
comm = m.get("halo_seconds", 0.0) + m.get("rebuild_seconds", 0.0)
ghosts = m.get("ghosts", 0)
print(f"{name},{max(ranks,1)},{threads},{n},{steps},{wall:.3f},{1e6*wall/(n*steps):.3f},"
      f"{ghosts},{halo:.0f},{comm/wall if wall else 0:.3f}")
EOF
}

header="run,ranks,threads,particles,steps,wall_s,us_per_particle_step,ghosts,halo_bytes_per_step,comm_fraction"
case "$mode" in
  strong)
    echo "$header" | tee "$OUT/strong.csv"
    for r in $(seq "$ROUNDS"); do
      run "serial_t1_r$r" 0 1 | tee -a "$OUT/strong.csv"
      run "np1_t1_r$r" 1 1 | tee -a "$OUT/strong.csv"
      run "np2_t1_r$r" 2 1 | tee -a "$OUT/strong.csv"
      run "serial_t2_r$r" 0 2 | tee -a "$OUT/strong.csv"
    done
    ;;
  weak)
    PER_RANK=${PER_RANK:-51200}
    echo "$header" | tee "$OUT/weak.csv"
    for n in ${RANKS:-1 2 4 8 16}; do
      # the bundled case has 51,200 particles at resolution_scale 1 (N ~ scale^2)
      scale=$(python3 -c "print(($PER_RANK*$n/51200)**0.5)")
      run "weak_np$n" "$n" 1 --set "resolution_scale=$scale" | tee -a "$OUT/weak.csv"
    done
    ;;
  *) echo "usage: $0 [strong|weak]" >&2; exit 2 ;;
esac
