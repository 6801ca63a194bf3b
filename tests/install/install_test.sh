#!/bin/sh
# ctest install.package: installs the build into a scratch prefix under the build directory and
# builds and runs, against the *installed* package only,
#   - C programs through pkg-config (railcontact.pc, nothing else on the search path) and gcc,
#     run without LD_LIBRARY_PATH (the rpath of the .pc's Libs),
#   - a C++ program through find_package(railcontact) in a tiny CMake project,
#   - a Fortran program through iso_c_binding (when gfortran is installed),
#   - `import railcontact` from the installed Python package (when it was built).
# Usage: install_test.sh CMAKE BUILD_DIR SOURCE_DIR
set -eu
cmake=$1
build=$(cd "$2" && pwd)
source=$(cd "$3" && pwd)
prefix=$build/install-test/prefix
work=$build/install-test/work
rm -rf "$build/install-test"
mkdir -p "$work"

echo "== cmake --install $build --prefix $prefix"
"$cmake" --install "$build" --prefix "$prefix" > "$work/install.log"
library=$(find "$prefix" -name 'librailcontact.so' | head -n 1)
test -n "$library" || { echo "librailcontact.so was not installed"; exit 1; }
libdir=$(dirname "$library")
test -f "$prefix/include/railcontact/railcontact.h"
test -f "$prefix/include/railcontact/version.h"
test -f "$prefix/include/railcontact/railcontact.hpp"
test -f "$libdir/cmake/railcontact/railcontactConfig.cmake"
soname=$(objdump -p "$library" | awk '/SONAME/ {print $2}')
echo "SONAME $soname"
case "$soname" in librailcontact.so.[0-9]*) ;; *) echo "unexpected SONAME $soname"; exit 1 ;; esac

echo "== C through pkg-config"
# Only railcontact.pc on the search path: the C API requires no other package (no eigen3.pc).
export PKG_CONFIG_LIBDIR="$libdir/pkgconfig"
unset PKG_CONFIG_PATH
pkg-config --modversion railcontact
test -z "$(pkg-config --print-requires railcontact)" || { echo "railcontact.pc requires other packages"; exit 1; }
gcc -std=c11 -Wall -Wextra -pedantic -Werror "$source/tests/install/example.c" \
  $(pkg-config --cflags --libs railcontact) -lm -o "$work/example_c"
gcc -std=c11 -Wall -Wextra -pedantic -Werror "$source/tests/install/destroy_null.c" \
  $(pkg-config --cflags --libs railcontact) -o "$work/destroy_null"
# The programs run as built, without LD_LIBRARY_PATH: railcontact.pc's Libs carry the rpath.
env -u LD_LIBRARY_PATH "$work/example_c"
env -u LD_LIBRARY_PATH "$work/destroy_null"
unset PKG_CONFIG_LIBDIR

echo "== C++ through find_package(railcontact)"
"$cmake" -S "$source/tests/install/cxx" -B "$work/cxx" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  > "$work/cxx_configure.log"
"$cmake" --build "$work/cxx" > "$work/cxx_build.log"
LD_LIBRARY_PATH="$libdir" "$work/cxx/example_cxx"

if command -v gfortran > /dev/null 2>&1; then
  echo "== Fortran through iso_c_binding"
  gfortran -Wall -o "$work/example_f" "$source/tests/install/example.f90" -L"$libdir" -lrailcontact
  LD_LIBRARY_PATH="$libdir" "$work/example_f"
else
  echo "== Fortran: gfortran not installed, skipped"
fi

package=$(find "$prefix" -type f -path '*-packages/railcontact/__init__.py' | head -n 1)
if [ -n "$package" ]; then
  echo "== Python from the installed package"
  site=$(dirname "$(dirname "$package")")
  (cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -c "
import railcontact, sys
assert railcontact.__file__.startswith('$prefix'), railcontact.__file__
r = railcontact.creep_forces(6e-3, 4e-3, 80e3, xi=0.05, elements=1000)
print('Python', railcontact.__version__, 'F1 =', round(r.F1_N, 1), 'N from', railcontact.__file__)
assert abs(r.F1_N / (-0.3 * 80e3) - 1) < 1e-2
")
fi
rm -rf "$build/install-test"
echo "install.package: OK"
