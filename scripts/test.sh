#!/usr/bin/env bash
# The test suite (what `make test` and CI run): formatting, lints, every unit, integration
# and validation test, the no_std proof (the core alone and the firmware runner built for a
# Cortex-M4F without std or an allocator, and run under QEMU), the C/C++/Fortran examples
# of the C ABI and the Python package.
set -euo pipefail
cd "$(dirname "$0")/.."
# each section's start, in seconds since the suite began (where the time goes: issue 44)
section() { echo "== [$SECONDS s] $*"; }
scripts/setup.sh
section "cargo fmt --check"
cargo fmt --all -- --check
section "cargo clippy"
# with the MPI domain decomposition (feature `mpi`; the narrow build below checks the
# code without it)
cargo clippy --workspace --all-targets --features gsph/mpi -- -D warnings
cargo clippy -p gsph --all-targets --no-default-features --features dim1,scheme-ts,effects-strength -- -D warnings
section "cargo test (release: the validation tests run simulations; with MPI, host/tests/mpi.rs)"
# host/python is tested through pip and pytest below (scripts/python.sh)
cargo test --workspace --exclude gsph-python --release --features gsph/mpi
section "no_std: gsph-core for thumbv7em-none-eabihf"
cargo build -p gsph-core --release --target thumbv7em-none-eabihf
cargo build -p gsph-core --release --target thumbv7em-none-eabihf --no-default-features --features f32,dim1,scheme-ts,effects-strength
# the scene-reading types (feature serde: no_std with serde's alloc)
cargo build -p gsph-core --release --target thumbv7em-none-eabihf --no-default-features --features serde,dim1,scheme-ts
# the firmware with every specialisation links into the board's memory map
cargo rustc -p gsph-core --release --example firmware_flyer --target thumbv7em-none-eabihf -- -C link-arg=-Tcore/firmware/mps2_an386.ld
section "firmware runner on the host (fails if stepping allocates)"
# the example as the test build above compiled it (the workspace's features: no second
# build of gsph-core, as `cargo run -p gsph-core` would make)
cargo build -q --release --workspace --exclude gsph-python --example firmware_flyer
target/release/examples/firmware_flyer
section "firmware runner on an emulated Cortex-M4F (QEMU), f64 and f32, against the host and gsph run"
scripts/firmware.sh
section "the C ABI from C, C++ and Fortran, against gsph run"
scripts/ffi.sh
section "the Python package (pip install ./host/python, pytest, the plotting example)"
scripts/python.sh
section "one-specialisation build: runs what it contains, refuses the rest in one line"
# docs/performance.md "Compile-time-selected builds". Dev profile, own target dir (about 2 minutes).
cargo build -q -p gsph --no-default-features --features cli,dim1,scheme-ts,effects-strength --target-dir target/one-spec
one=target/one-spec/debug/gsph
ok=$("$one" check cases/flyer_plate.toml --set scheme=ts1)
grep -qx 'kernel    step_1d_ts_strength (compiled; this build contains 2 of 48 specialisations)' <<<"$ok"
if refused=$("$one" check cases/riemann_al_2d.toml 2>&1); then
    echo "the one-specialisation build accepted cases/riemann_al_2d.toml"; exit 1
fi
echo "$refused"
grep -qx 'error: cases/riemann_al_2d.toml: this gsph was built without the specialisation 2D tkc (strength+correction+muscl) `step_2d_pm_strength_correction_muscl` (it contains 2 of 48); rebuild with `--features dim2,scheme-pm,effects-strength,effects-correction,effects-muscl` or the default features' <<<"$refused"
section "target/release/gsph: the default build (no MPI), as the README says; several copies under mpirun refuse"
# ffi.sh and python.sh built it with the default features; this is a no-op then
cargo build --release -q -p gsph
target/release/gsph --version | grep -qx 'features: cli, hdf5, plot'
if copies=$(OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  mpirun --oversubscribe -np 2 target/release/gsph check cases/flyer_plate.toml 2>&1); then
  echo "a gsph built without MPI ran as two copies under mpirun"; exit 1
fi
grep -q 'error: this gsph was built without MPI, and an MPI launcher started it as rank 0 of 2' <<<"$copies"
echo "$copies" | head -1
section "docs"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps -q
RUSTDOCFLAGS="-D warnings" cargo doc -p gsph --features mpi --no-deps -q
echo "all checks passed in $SECONDS s"
