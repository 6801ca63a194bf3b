#!/bin/sh
# ctest c_api.valgrind (label valgrind): the C examples under valgrind's memcheck, against the
# build's librailcontact.so (the library that is installed) and headers:
#   - tests/install/example.c, the installed-package example (a solver, a wheelset by load);
#   - tests/install/handles.c, every handle created, used and destroyed in every order.
# Clean means no invalid read or write, no use of uninitialised values and no definitely or
# indirectly lost block (--errors-for-leak-kinds=definite,indirect): valgrind exits 1 otherwise.
# Exit 77 (ctest: skipped) when valgrind is missing, or cannot run the library: valgrind 3.19
# does not decode AVX-512, which a build with -march=native (RAILCONTACT_ARCH=native, the default) on
# such a CPU contains. `make test-valgrind` builds the library without it and runs this test.
# Usage: valgrind_test.sh C_COMPILER BUILD_DIR SOURCE_DIR GENERATED_INCLUDE_DIR
set -eu
cc=$1
build=$(cd "$2" && pwd)
source=$(cd "$3" && pwd)
generated=$4
work=$build/valgrind-test
rm -rf "$work"
mkdir -p "$work"

if ! command -v valgrind > /dev/null 2>&1; then
  echo "valgrind is not installed (make deps installs it): skipped"
  exit 77
fi
library=$(find "$build" -maxdepth 1 -name 'librailcontact.so' | head -n 1)
test -n "$library" || { echo "no librailcontact.so in $build (cmake --build $build --target railcontact_shared)"; exit 1; }

status=0
for program in example handles; do
  "$cc" -std=c11 -Wall -Wextra -pedantic -Werror -g -O1 "$source/tests/install/$program.c" \
    -I"$source/include" -I"$generated" -L"$build" -lrailcontact -Wl,-rpath,"$build" -lm -o "$work/$program"
  echo "== valgrind $program"
  set +e
  valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect \
    --log-file="$work/$program.valgrind" "$work/$program"
  code=$?
  set -e
  if grep -q "unhandled instruction bytes" "$work/$program.valgrind"; then
    echo "valgrind cannot decode an instruction of the library (AVX-512 of -march=native?): skipped;"
    echo "run make test-valgrind (a build with RAILCONTACT_ARCH=OFF)"
    exit 77
  fi
  grep -E "ERROR SUMMARY|definitely lost|indirectly lost|All heap blocks were freed" "$work/$program.valgrind" || true
  if [ "$code" -ne 0 ]; then
    cat "$work/$program.valgrind"
    status=1
  fi
done
[ "$status" -eq 0 ] && rm -rf "$work" && echo "c_api.valgrind: clean"
exit "$status"
