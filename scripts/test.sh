#!/usr/bin/env bash
# The test suite (what `make test` and CI run): formatting, lints, every unit, integration
# and validation test, and the no_std proof (the core alone and the firmware runner built
# for a Cortex-M4F without std or an allocator).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "== cargo test (release: the validation tests run simulations)"
cargo test --workspace --release
echo "== no_std: gsph-core for thumbv7em-none-eabihf"
cargo build -p gsph-core --release --target thumbv7em-none-eabihf
cargo build -p gsph-core --release --target thumbv7em-none-eabihf --no-default-features --features f32,dim1,scheme-ts,effects-strength
cargo rustc -p gsph-core --release --example firmware_flyer --target thumbv7em-none-eabihf -- -C link-arg=--entry=gsph_flyer_main
echo "== firmware runner on the host (fails if stepping allocates)"
cargo run -q -p gsph-core --release --example firmware_flyer
echo "== docs"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps -q
echo "all checks passed"
