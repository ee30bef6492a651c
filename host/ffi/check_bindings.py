#!/usr/bin/env python3
"""The C++ wrapper and the Fortran module cover the whole C ABI (run by scripts/ffi.sh).

    check_bindings.py gsph.h gsph.hpp gsph.f90 EVERY_CPP.o EVERY_F.o

Every function declared in gsph.h must be
- called in gsph.hpp (a wrapper calls it),
- bound in gsph.f90 (an interface `function NAME(...) bind(c)` or `subroutine`, made public),
- reached by the programs host/ffi/cpp/every.cpp and host/ffi/fortran/every.f90: an
  undefined symbol of their object files (`nm -u`), directly or (Fortran) through a
  helper of the module that calls it (`version()` calls gsph_version), so that compiling
  and running them calls every wrapper.
And gsph.f90 binds nothing gsph.h does not declare. Exits 1 naming what is missing.
"""

import re
import subprocess
import sys


def strip_c_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def undefined_symbols(obj):
    out = subprocess.run(["nm", "-u", obj], check=True, capture_output=True, text=True).stdout
    return {line.split()[-1] for line in out.splitlines() if line.strip()}


def main(header, hpp, f90, cpp_obj, f_obj):
    h = strip_c_comments(open(header).read())
    names = re.findall(r"^[A-Za-z_][\w \*]*?\b(gsph_\w+)\(", h, re.M)
    if len(names) < 10:
        sys.exit(f"check_bindings: only {len(names)} functions found in {header}")
    wrapper = strip_c_comments(open(hpp).read())
    fortran = re.sub(r"![^\n]*", "", open(f90).read())
    bound = {
        m.lower()
        for m in re.findall(r"(?:function|subroutine)[ \t]+(\w+)[ \t]*\([^)]*\)[^\n]*bind\(c", fortran, re.I)
    }
    public = {
        n.strip().lower()
        for line in re.findall(r"^\s*public\s*::(.*)$", fortran, re.M | re.I)
        for n in line.split(",")
    }
    # the module's helpers (after `contains`) and the C functions each calls
    helpers = {
        name.lower(): {c.lower() for c in re.findall(r"\b(gsph_\w+)\s*\(", body)}
        for name, body in re.findall(
            r"^\s*function[ \t]+(\w+)\s*\((.*?)^\s*end function",
            fortran.split("contains", 1)[-1],
            re.M | re.S | re.I,
        )
    }
    f_syms = undefined_symbols(f_obj)
    for helper, called in helpers.items():
        if f"__gsph_MOD_{helper}" in f_syms:
            f_syms |= called
    reached = {"every.cpp": undefined_symbols(cpp_obj), "every.f90": f_syms}
    missing = []
    for n in names:
        if not re.search(rf"\b{n}\s*\(", wrapper):
            missing.append(f"{n}: not called in {hpp}")
        if n not in bound:
            missing.append(f"{n}: no bind(c) interface in {f90}")
        elif n not in public:
            missing.append(f"{n}: bound in {f90} but not public")
        for prog, syms in reached.items():
            if n not in syms:
                missing.append(f"{n}: not called by host/ffi/.../{prog}")
    stale = sorted(bound - set(names) - {"c_strlen"})
    missing += [f"{n}: bound in {f90} but not in {header}" for n in stale]
    if missing:
        for m in missing:
            print(f"check_bindings: {m}", file=sys.stderr)
        sys.exit(1)
    print(
        f"bindings: all {len(names)} functions of gsph.h are wrapped in gsph.hpp, bound in "
        "gsph.f90, and called by every.cpp and every.f90"
    )


if __name__ == "__main__":
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    main(*sys.argv[1:])
