#!/usr/bin/env bash
# Runs every cargo-fuzz target of host/fuzz for SECONDS each (default 300), one after the
# other, on the stable toolchain (RUSTC_BOOTSTRAP=1 lets stable rustc take the -Z flags
# cargo-fuzz passes) without a sanitizer (the code under test is safe Rust). Installs
# cargo-fuzz if it is missing. Not part of `make test` or CI: see docs/fuzzing.md.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-300}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scene riemann eos strength)
fi
command -v c++ >/dev/null 2>&1 || { echo "fuzz: libfuzzer-sys needs a C++ compiler (apt-get install g++)" >&2; exit 1; }
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "fuzz: installing cargo-fuzz" >&2
  cargo install cargo-fuzz --locked
fi
export RUSTC_BOOTSTRAP=1
cd host/fuzz
# The scene target starts from the shipped scenes.
mkdir -p corpus/scene
cp ../../cases/*.toml corpus/scene/
for t in "${targets[@]}"; do
  echo "== fuzz $t for ${secs}s" >&2
  mkdir -p "corpus/$t"
  # -timeout: a scene may legitimately build up to 1e8 particles; a single input running
  # longer than this is reported (as a hang) all the same. -rss_limit_mb likewise.
  cargo fuzz run --sanitizer none --release "$t" "corpus/$t" -- \
    -max_total_time="$secs" -timeout=30 -rss_limit_mb=4096 -print_final_stats=1
done
