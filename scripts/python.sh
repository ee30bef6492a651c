#!/usr/bin/env bash
# The Python package (docs/python.md): creates the virtual environment .venv when missing
# (numpy, pytest, matplotlib, maturin, vtk, h5py), builds and installs host/python into it with
# `pip install ./host/python` (maturin: release build of the extension in target/), runs
# the pytest suite against the gsph command (GSPH_BIN, default target/release/gsph, built
# when missing; test_vtk_xdmf.py opens its snapshots with VTK's XDMF reader, as ParaView
# does, and with h5py) and the documentation's example (writes out/python/flyer_profile.png).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${GSPH_VENV:-$PWD/.venv}
if [ ! -x "$venv/bin/python" ]; then
  echo "python: creating $venv" >&2
  python3 -m venv "$venv"
fi
py="$venv/bin/python"
# the build backend runs the `maturin` executable of the venv
export PATH="$venv/bin:$PATH"
if ! "$py" -c 'import numpy, pytest, matplotlib, maturin, vtkmodules.vtkIOXdmf2, h5py' 2>/dev/null; then
  echo "python: installing numpy, pytest, matplotlib, maturin, vtk, h5py into $venv (pip)" >&2
  "$py" -m pip install -q --upgrade pip
  "$py" -m pip install -q numpy pytest matplotlib "maturin>=1.9,<2" vtk h5py
fi
export GSPH_BIN=${GSPH_BIN:-$PWD/target/release/gsph}
if [ ! -x "$GSPH_BIN" ]; then
  cargo build --release -q -p gsph
fi
echo "== python: pip install ./host/python"
# the build backend (maturin) is in the venv already: no isolated build environment
"$py" -m pip install -q --no-build-isolation --force-reinstall --no-deps ./host/python
echo "== python: pytest host/python/tests"
(cd /tmp && "$py" -m pytest -q -p no:cacheprovider "$OLDPWD/host/python/tests")
echo "== python: docs/examples/flyer_profile.py"
MPLBACKEND=Agg "$py" docs/examples/flyer_profile.py out/python/flyer_profile.png
