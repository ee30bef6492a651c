#!/usr/bin/env bash
# The C ABI from C, C++ and Fortran (docs/embedding.md): builds libgsph and the gsph
# command (default features), then compiles and runs host/ffi's examples, each checking a
# number against what `gsph run` gives on the same scene:
#   C        host/ffi/c/flyer.c        flyer plate, peak sigma_xx; its snapshot must equal
#                                      gsph run's final.csv byte for byte
#   C        host/ffi/c/coupling.c     external forces each step; the momentum budget closes
#   C++      host/ffi/cpp/ring.cpp     collapsing ring, inner radius after 200 steps
#   Fortran  host/ffi/fortran/flyer.f90 flyer plate, peak sigma_xx
#   C        host/ffi/c/threads.c      (pthreads) destroy racing a stepping thread, a busy
#                                      handle refused, destroy stopping a long run, the
#                                      thread cap of gsph_set_threads
#   C++      host/ffi/cpp/every.cpp    every wrapper of gsph.hpp, checked
#   Fortran  host/ffi/fortran/every.f90 every function of gsph.f90, checked
# and host/ffi/check_bindings.py: every function of gsph.h is wrapped in gsph.hpp, bound
# in gsph.f90 and reached by every.cpp and every.f90 (their undefined symbols, nm -u).
# About 2 minutes after the build.
set -euo pipefail
cd "$(dirname "$0")/.."
for tool in cc c++ gfortran python3 nm; do
  command -v "$tool" >/dev/null || { echo "ffi: $tool is missing (scripts/setup.sh installs it)" >&2; exit 1; }
done
echo "== ffi: cargo build --release -p gsph -p gsph-capi (gsph, libgsph.so, libgsph.a)"
cargo build --release -q -p gsph -p gsph-capi
lib=$PWD/target/release
gsph=$lib/gsph
inc=host/include
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
link=(-L"$lib" -lgsph -Wl,-rpath,"$lib" -lm)

# the value a CSV of gsph's particle table gives: min(sxx - p), or min sqrt(x^2 + y^2)
measure() {
  python3 - "$1" "$2" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
if sys.argv[2] == "peak_sigma_xx":
    v = min(0.0, min(float(r["sxx"]) - float(r["p"]) for r in rows))
else:
    v = min(math.sqrt(float(r["x"]) ** 2 + float(r["y"]) ** 2) for r in rows)
print(repr(v))
PY
}

echo "== ffi: C, flyer plate"
"$gsph" run cases/flyer_plate.toml --out "$out/flyer" --quiet
peak=$(measure "$out/flyer/final.csv" peak_sigma_xx)
cc -std=c11 -O2 -Wall -Wextra -Werror -I"$inc" host/ffi/c/flyer.c "${link[@]}" -o "$out/flyer_c"
"$out/flyer_c" cases/flyer_plate.toml "$peak" "$out/flyer_c.csv"
cmp "$out/flyer_c.csv" "$out/flyer/final.csv"
echo "flyer (C): the snapshot written through the C ABI equals gsph run's final.csv byte for byte"

echo "== ffi: C, coupling (external forces)"
cc -std=c11 -O2 -Wall -Wextra -Werror -I"$inc" host/ffi/c/coupling.c "${link[@]}" -o "$out/coupling_c"
"$out/coupling_c" 100

echo "== ffi: C++, collapsing ring"
ring_set=(--set resolution_scale=0.5 --set output.snapshots=1 --set max_steps=200)
"$gsph" run cases/ring_collapse.toml "${ring_set[@]}" --out "$out/ring" --quiet
inner=$(measure "$out/ring/final.csv" inner_radius)
c++ -std=c++17 -O2 -Wall -Wextra -Werror -I"$inc" host/ffi/cpp/ring.cpp "${link[@]}" -o "$out/ring_cpp"
"$out/ring_cpp" cases/ring_collapse.toml 200 "$inner" resolution_scale=0.5 output.snapshots=1

echo "== ffi: Fortran, flyer plate"
gfortran -std=f2018 -Wall -Werror -J "$out" -c "$inc/gsph.f90" -o "$out/gsph_mod.o"
gfortran -std=f2018 -Wall -Werror -I "$out" host/ffi/fortran/flyer.f90 "$out/gsph_mod.o" "${link[@]}" -o "$out/flyer_f"
"$out/flyer_f" cases/flyer_plate.toml "$peak"

echo "== ffi: C, two threads on one handle (pthreads)"
cc -std=c11 -O2 -Wall -Wextra -Werror -pthread -I"$inc" host/ffi/c/threads.c "${link[@]}" -o "$out/threads_c"
"$out/threads_c" cases/flyer_plate.toml 8

echo "== ffi: the C++ wrapper and the Fortran module cover gsph.h"
c++ -std=c++17 -O2 -Wall -Wextra -Werror -I"$inc" -c host/ffi/cpp/every.cpp -o "$out/every_cpp.o"
gfortran -std=f2018 -Wall -Werror -I "$out" -J "$out" -c host/ffi/fortran/every.f90 -o "$out/every_f.o"
python3 host/ffi/check_bindings.py "$inc/gsph.h" "$inc/gsph.hpp" "$inc/gsph.f90" "$out/every_cpp.o" "$out/every_f.o"
c++ "$out/every_cpp.o" "${link[@]}" -o "$out/every_cpp"
mkdir -p "$out/every_cpp.d" "$out/every_f.d"
"$out/every_cpp" cases/flyer_plate.toml "$out/every_cpp.d"
gfortran "$out/every_f.o" "$out/gsph_mod.o" "${link[@]}" -o "$out/every_f"
"$out/every_f" cases/flyer_plate.toml "$out/every_f.d"
echo "ffi: all examples agree with gsph run"
