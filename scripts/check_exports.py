#!/usr/bin/env python3
"""The shared library's export list (cmake/railcontact.map): only the documented API leaves
librailcontact.so.

The documented API is the C API (rc_*) and the names the public C++ headers
(include/railcontact/*.hpp) declare in namespace railcontact, outside its `detail` namespace.
Internal names of the library (railcontact::detail::, railcontact::geometry::, InfluenceOperator, ...)
are compiled into the same objects but are not declared there, and stay local.

  check_exports.py SOURCE_DIR STATIC_LIB SHARED_LIB          the check (ctest architecture.exports)
  check_exports.py SOURCE_DIR STATIC_LIB SHARED_LIB --write  rewrites cmake/railcontact.map

The check fails when
  (a) cmake/railcontact.map is not the list the public headers and the static library give
      (a public function added or removed: run with --write and rebuild),
  (b) the shared library defines a dynamic symbol that is neither rc_* nor a public name,
  (c) a public name's symbol of the static library is missing from the shared library.
"""
import os
import re
import subprocess
import sys

INTERNAL_NAMESPACES = {"detail", "geometry", "fastsim_detail", "wheel_rail"}
SPECIAL = re.compile(r"^(typeinfo name for|typeinfo for|vtable for|VTT for|non-virtual thunk to|guard variable for) ")
TOP = re.compile(r"railcontact::(operator\S+?(?=\()|[A-Za-z_][A-Za-z_0-9]*)")
HEADER = """/* Symbols exported by librailcontact.so: the C API (rc_*) and the C++ API, the names the public
   headers include/railcontact/*.hpp declare in namespace railcontact (outside railcontact::detail).
   Everything else (the library's internal classes and functions, Eigen, fmt, standard-library
   instantiations) stays local. Written by scripts/check_exports.py --write, checked by the ctest
   architecture.exports: a public function added to a header is added here by that command. */
"""


def public_tokens(source):
    tokens = set()
    directory = os.path.join(source, "include", "railcontact")
    for name in sorted(os.listdir(directory)):
        if not name.endswith(".hpp"):
            continue
        with open(os.path.join(directory, name), encoding="utf-8") as f:
            text = f.read()
        text = re.sub(r"//.*", "", text)
        text = re.sub(r"#include.*", "", text)
        # The detail namespaces of the public headers hold opaque implementation types only.
        text = re.sub(r"namespace detail \{.*?\}\s*// namespace detail", "", text, flags=re.S)
        tokens |= set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", text))
    return tokens


def symbols(path, dynamic, kinds="TWVDBRuiv"):
    """Defined symbols of `kinds` (nm's letters; the default: every global one), demangled."""
    args = ["nm", "-C", "--defined-only"] + (["-D"] if dynamic else []) + [path]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    found = []
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if len(parts) == 3 and parts[1] in kinds:
            found.append(parts[2])
    return found


def top_name(symbol):
    """The first name after railcontact:: of a C++ symbol (None for other symbols)."""
    bare = SPECIAL.sub("", symbol)
    if not bare.startswith("railcontact::"):
        return None
    m = TOP.match(bare)
    return m.group(1) if m else None


def public_symbols(source, static_lib):
    """The static library's strong symbols of public names (demangled, sorted), and those names.
    Weak ones (inline functions, type information of classes without a key function) are
    instantiated by every program that uses them and need not leave the library."""
    tokens = public_tokens(source)
    names, found = set(), set()
    strong = set(symbols(static_lib, False, "TDBR"))
    # ... but a public class's type information and vtable (the exception's, Error, which a program
    # catches from the library) leave it too.
    type_data = {s for s in symbols(static_lib, False, "V") if re.match(r"(typeinfo|typeinfo name|vtable) for ", s)}
    for s in sorted(strong | type_data):
        top = top_name(s)
        if top and top not in INTERNAL_NAMESPACES and (top in tokens or top.startswith("operator")):
            names.add(top)
            found.add(s)
    return sorted(found), sorted(names)


def version_script(exported):
    # Exact demangled names (quoted: no wildcards), so that an internal name sharing a public one's
    # prefix (validate_rolling_input, validate) stays local.
    lines = [HEADER, "{", "  global:", "    rc_*;", '    extern "C++" {']
    lines += [f'      "{s}";' for s in exported]
    lines += ["    };", "  local: *;", "};", ""]
    return "\n".join(lines)


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    source, static_lib, shared_lib = sys.argv[1:4]
    wanted, names = public_symbols(source, static_lib)
    map_path = os.path.join(source, "cmake", "railcontact.map")
    expected = version_script(wanted)
    if "--write" in sys.argv[4:]:
        with open(map_path, "w", encoding="utf-8") as f:
            f.write(expected)
        print(f"check_exports: wrote {map_path} ({len(wanted)} symbols of {len(names)} public names)")
        return 0
    problems = []
    with open(map_path, encoding="utf-8") as f:
        if f.read() != expected:
            problems.append(f"{map_path} is not the export list of the public headers: run "
                            f"`/usr/bin/python3 scripts/check_exports.py . build/librailcontact.a "
                            f"build/librailcontact.so --write` and rebuild")
    public = set(names)
    exported = set()
    for s in symbols(shared_lib, True):
        if s.startswith("rc_") or s.startswith("_"):  # the C API; linker-defined (_init, _fini, ...)
            continue
        top = top_name(s)
        if top is None or top not in public:
            problems.append(f"exported but not public API: {s}")
        exported.add(s)
    for s in wanted:
        if s not in exported:
            problems.append(f"public but not exported: {s}")
    if problems:
        print("\n".join(problems[:40]))
        if len(problems) > 40:
            print(f"... and {len(problems) - 40} more")
        return 1
    print(f"check_exports: {len(exported)} C++ symbols of {len(names)} public names exported, "
          f"nothing else but rc_*: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
