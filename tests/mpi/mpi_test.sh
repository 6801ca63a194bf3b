#!/bin/sh
# ctest mpi.three_ranks (docs/SCALING.md): `mpirun -n 3` gives the bytes of the serial run for a
# sweep, a flexibility table, a wheelset table and the studies paper (Fig 5), bound and coefficients
# (Table 1). Arguments: railcontact, mpiexec, source dir.
set -eu
# On a failure the last "step:" line says where (ctest --output-on-failure shows it).
step() { echo "step: $*"; }
cli=$1
mpiexec=$2
source=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/railcontact_mpi_XXXXXX")
trap 'rm -rf "$work"' EXIT
export RAILCONTACT_SCRIPTS=/nonexistent-railcontact-scripts SOURCE_DATE_EPOCH=1700000000
# As root (CI containers) OpenMPI needs both variables; harmless otherwise.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mpi="$mpiexec --oversubscribe -n 3"
# Under AddressSanitizer (make test-sanitize) OpenMPI's own allocations, never freed by design,
# would be reported as leaks: leaks are checked by the other tests.
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0"

# A sweep whose cases differ in cost (one and two patches per wheel, two solvers).
cat > "$work/s.toml" <<'TOML'
[mesh]
element_size_mm = 0.8
[solvers]
run = ["nh-fastsim", "fastsim"]
[grid]
yaw_mrad = [0, 3]
y_mm = { from = -6, to = 6, step = 1.5 }
TOML
step sweep
"$cli" sweep "$work/s.toml" --threads 1 --out "$work/serial" > /dev/null 2>&1
$mpi "$cli" sweep "$work/s.toml" --out "$work/mpi" > "$work/mpi.out" 2> "$work/mpi.err" || { cat "$work/mpi.err"; exit 1; }
cmp "$work/serial/sweep.csv" "$work/mpi/sweep.csv"
cmp "$work/serial/sweep.json" "$work/mpi/sweep.json"
grep -q "and 3 MPI ranks" "$work/mpi.err" || { echo "not run on 3 ranks:"; cat "$work/mpi.err"; exit 1; }
test "$(grep -c '^Wrote' "$work/mpi.out")" = 1  # rank 0 alone reports and writes
rows=$(wc -l < "$work/serial/sweep.csv")
test "$rows" -gt 18

step flextable build
flex="flextable build --y-from-m -0.003 --y-to-m 0.003 --y-step-m 0.0005 --elements 300"
"$cli" $flex --threads 1 --out "$work/f1.json" > /dev/null 2>&1
$mpi "$cli" $flex --out "$work/f3.json" > /dev/null 2> "$work/err" || { cat "$work/err"; exit 1; }
cmp "$work/f1.json" "$work/f3.json"

step wheelset-table build
wheelset="wheelset-table build --y-m=-0.003:0.003:0.0005 --load-N 100000 --element-size-m 0.001 --refine-lateral-force-fraction 0"
"$cli" $wheelset --threads 1 --out "$work/w1.json" > /dev/null 2>&1
$mpi "$cli" $wheelset --out "$work/w3.json" > /dev/null 2> "$work/err" || { cat "$work/err"; exit 1; }
cmp "$work/w1.json" "$work/w3.json"
step study paper
paper="study paper --elements 300 --y-step-m 1.5e-3 --samples 1 --no-figures"
"$cli" $paper --threads 1 --out "$work/p1" > /dev/null 2>&1
$mpi "$cli" $paper --out "$work/p3" > /dev/null 2> "$work/err" || { cat "$work/err"; exit 1; }
cmp "$work/p1/fig5.csv" "$work/p3/fig5.csv"
cmp "$work/p1/fig5_patches.csv" "$work/p3/fig5_patches.csv"
step study bound
bound="study bound --elements 300 --y-step-m 1.5e-3"
"$cli" $bound --threads 1 --out "$work/b1" > /dev/null 2>&1
$mpi "$cli" $bound --out "$work/b3" > /dev/null 2> "$work/err" || { cat "$work/err"; exit 1; }
cmp "$work/b1/bound_sweep.csv" "$work/b3/bound_sweep.csv"
cmp "$work/b1/summary.md" "$work/b3/summary.md"

step study coefficients
coefficients="study coefficients --elements 200 --fine-elements 400 --no-figures"
"$cli" $coefficients --threads 1 --out "$work/c1" > /dev/null 2>&1
$mpi "$cli" $coefficients --out "$work/c3" > /dev/null 2> "$work/err" || { cat "$work/err"; exit 1; }
for f in table1.csv table1_paper.csv table1_fine.csv fig3.csv; do cmp "$work/c1/$f" "$work/c3/$f"; done
echo "mpi: sweep ($rows lines), flexibility table, wheelset table, the paper study's Fig 5, the bound study and"
echo "the coefficient study's Table 1 on 3 ranks: the serial bytes"
