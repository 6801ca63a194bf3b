#!/bin/sh
# Prints the instruction set (a -march value) that `make test-portable` builds the suite with: one
# that runs on this CPU and makes the compiler generate other floating-point code than
# -march=native does, so that a test comparing two code paths to the last bit fails here as it
# would on another CPU (docs/RELIABILITY.md "Reproducibility across CPUs"). The first of
#   icelake-server  AVX-512 with Intel's tuning (256-bit vectors preferred): on AMD CPUs with
#                   AVX-512, whose tuning prefers 128-bit vectors, the code of an Intel Xeon;
#   x86-64-v3       AVX2 and FMA without AVX-512 (on an AVX-512 Xeon: 4 SIMD lanes instead of 8);
#   x86-64-v2       SSE4.2 without FMA (every a*b+c rounded twice)
# whose vector instructions this CPU has and whose code differs from native's (other vector
# instruction sets, FMA or tuning); x86-64 when none does.
# Usage: portable_arch.sh [C++ compiler]   (default: $CXX, else c++, the compiler CMake picks)
set -eu
cxx=${1:-${CXX:-c++}}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The instruction-set extensions GCC may use for C++ code on its own (not system instructions
# such as sgx or rdseed, which only intrinsics emit and a virtual machine may hide).
features() {
  "$cxx" -march="$1" -Q --help=target 2>/dev/null |
    awk '$2 == "[enabled]" && $1 ~ /^-m(sse|ssse3|avx|fma|f16c|bmi|lzcnt|popcnt|movbe|adx)/ { print $1 }' | sort
}
# What decides the floating-point code: vector width, FMA, and the tuning's cost model.
signature() {
  "$cxx" -march="$1" -Q --help=target 2>/dev/null |
    awk '$1 ~ /^-m(avx|avx2|fma|avx512f)$/ || $1 == "-mtune=" { print $1 $2 }'
}

features native > "$work/native"
test -s "$work/native" || { echo "portable_arch.sh: $cxx does not list its target options (-Q --help=target)" >&2; exit 1; }
signature native > "$work/native.signature"
for arch in icelake-server x86-64-v3 x86-64-v2; do
  features "$arch" | comm -23 - "$work/native" > "$work/missing"
  signature "$arch" > "$work/signature"
  if [ ! -s "$work/missing" ] && ! cmp -s "$work/signature" "$work/native.signature"; then
    echo "$arch"
    exit 0
  fi
done
echo x86-64
