#!/usr/bin/env bash
# Time per pass of each scheme on the colliding rings (docs/notes/performance_history.md "Profiles"):
# builds a 2D-only gsph with full debug info (target/prof, about 2.5 minutes), records 300
# steps of cases/rings.toml per scheme on one thread with `perf record` (Linux perf; apt
# package linux-perf), and prints the share of each pass (scripts/profile_passes.py).
#
#   scripts/profile.sh [SCHEME ...]      (default: av ts2 tkc)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v perf >/dev/null || { echo "profile: needs perf (apt-get install linux-perf)" >&2; exit 1; }
schemes=("$@")
[[ ${#schemes[@]} -gt 0 ]] || schemes=(av ts2 tkc)
cargo build --profile profiling -q -p gsph --no-default-features \
  --features dim2,scheme-av,scheme-pm,scheme-ts,effects-strength,effects-muscl,effects-correction,cli,hdf5 \
  --target-dir target/prof
bin=target/prof/profiling/gsph
mkdir -p out/profile
for s in "${schemes[@]}"; do
  perf record -q -F 1999 -o "out/profile/$s.data" -- "$bin" run cases/rings.toml --set "scheme=$s" \
    --set max_steps=300 --unset monitor --set output.snapshots=1 --threads 1 --quiet \
    --out "out/profile/run_$s" >/dev/null 2>&1
  echo "== $s"
  python3 scripts/profile_passes.py "out/profile/$s.data" "$bin"
done
