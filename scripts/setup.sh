#!/usr/bin/env bash
# One-time set-up of a fresh Debian/Ubuntu machine for gsph: the HDF5 C library (for the
# hdf5-metno crate), pkg-config, Open MPI and libclang (for the `mpi` feature: the mpi-sys
# crate generates its bindings with bindgen), C/C++/Fortran compilers and python3-venv
# (the C ABI's examples and the Python package), QEMU (the firmware runner on an emulated
# Cortex-M4F), and the bare-metal Rust target used to prove the core is no_std.
# Idempotent: does nothing when everything is present.
set -euo pipefail

need_apt=()
if ! pkg-config --exists hdf5 2>/dev/null; then
  need_apt+=(libhdf5-dev)
fi
command -v pkg-config >/dev/null 2>&1 || need_apt+=(pkg-config)
command -v mpirun >/dev/null 2>&1 || need_apt+=(openmpi-bin)
command -v mpicc >/dev/null 2>&1 || need_apt+=(libopenmpi-dev)
# bindgen loads libclang.so or libclang-N.so (libclang-cpp, which LLVM's other packages
# bring, is not it)
if ! ls /usr/lib/llvm-*/lib/libclang.so* /usr/lib/llvm-*/lib/libclang-[0-9]*.so* >/dev/null 2>&1 &&
  ! ldconfig -p 2>/dev/null | grep -Eq 'libclang(-[0-9.]+)?\.so'; then
  need_apt+=(libclang-dev)
fi
# QEMU's Cortex-M boards (mps2-an386) run the firmware runner (scripts/firmware.sh).
command -v qemu-system-arm >/dev/null 2>&1 || need_apt+=(qemu-system-arm)
# The C ABI's examples (scripts/ffi.sh): C, C++ and Fortran compilers.
command -v cc >/dev/null 2>&1 || need_apt+=(gcc)
command -v c++ >/dev/null 2>&1 || need_apt+=(g++)
command -v gfortran >/dev/null 2>&1 || need_apt+=(gfortran)
# The Python package (scripts/python.sh): python3 with venv and pip.
if ! command -v python3 >/dev/null 2>&1; then
  need_apt+=(python3 python3-venv python3-pip)
elif ! python3 -c 'import venv, ensurepip' >/dev/null 2>&1; then
  need_apt+=(python3-venv python3-pip)
fi
if [ ${#need_apt[@]} -gt 0 ]; then
  echo "setup: installing ${need_apt[*]} (apt)" >&2
  sudo_cmd=""
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq "${need_apt[@]}" >/dev/null
fi

if command -v rustup >/dev/null 2>&1; then
  if ! rustup target list --installed 2>/dev/null | grep -q '^thumbv7em-none-eabihf$'; then
    echo "setup: adding the thumbv7em-none-eabihf target (rustup)" >&2
    rustup target add thumbv7em-none-eabihf >/dev/null
  fi
fi
