#!/usr/bin/env bash
# Accuracy-against-time studies: every scheme (av, pm, ts1, ts2, tkc) on every case, at a
# ladder of resolutions, one thread per run so the wall times compare. Writes
# out/studies/<case>/ (study.csv, study.md, error_vs_time.png/svg,
# error_vs_particles.png/svg) and copies the plots and tables to docs/studies/ for the
# docs/validation.md §2 (the studies) and docs/performance.md.
#
# 16 minutes on one thread of a shared 2-core machine (967 s, measured with a cargo build
# running alongside). GSPH=path/to/gsph uses that binary and skips the build.
#
# All five schemes run every case (`gsph check` and a coarse run of each pass), so none is
# left out. ring_collapse sets `riemann = "two_shock"`, which av does not read: `gsph study`
# leaves it out of the av runs and says so.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z "${GSPH:-}" ]]; then
  cargo build --release -p gsph
  GSPH=target/release/gsph
fi
g="$GSPH"
o=out/studies
d=docs/studies
schemes=av,pm,ts1,ts2,tkc
mkdir -p "$o" "$d"

# study CASE RESOLUTIONS [METRIC]
study() {
  local case=$1 res=$2 metric=${3:-}
  local args=(study "cases/$case.toml" --schemes "$schemes" --resolutions "$res"
    --threads 1 --out "$o/$case")
  [[ -n "$metric" ]] && args+=(--metric "$metric")
  echo "== $case: resolutions $res${metric:+, metric $metric}"
  local t0=$SECONDS
  "$g" "${args[@]}"
  echo "== $case done in $((SECONDS - t0)) s"
}

# 1D (100-200 particles at scale 1; cost ~ scale^2). Error: L1 of sigma_xx (flyer plate,
# Riemann problem) or of v_x (sound wave), relative to the final stress / sigma_1 /
# the pulse amplitude.
study flyer_plate 0.5,1,2,4,8,16,32 l1_error_relative
study riemann_al 0.5,1,2,4,8,16,32 l1_error_relative
study sound_cu 0.5,1,2,4,8,16,32 l1_error_relative
# 2D strips, periodic across (1,000 / 2,000 particles at scale 1; cost ~ scale^3).
study riemann_al_2d 0.5,1,2,4 l1_error_relative
study sound_cu_2d 0.5,1,2,3 l1_error_relative
# 2D shells (8,172 / 11,309 particles at scale 1). Error: radius_error, the larger of the
# relative errors of the inner and outer stopping radii.
study ring_collapse 0.35,0.5,0.7,1 radius_error
study verney_al 0.35,0.5,0.7,1 radius_error

for c in flyer_plate riemann_al sound_cu riemann_al_2d sound_cu_2d ring_collapse verney_al; do
  cp "$o/$c/error_vs_time.png" "$d/$c.png"
  cp "$o/$c/error_vs_particles.png" "$d/${c}_particles.png"
  cp "$o/$c/study.md" "$d/$c.md"
  cp "$o/$c/study.csv" "$d/$c.csv"
done
echo "studies in $o, plots and tables in $d"
