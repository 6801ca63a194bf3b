#!/bin/sh
# Runs libFuzzer on railcontact's fuzz targets, one target after the other (docs/RELIABILITY.md
# "Fuzzing").
#
# Usage: scripts/fuzz.sh [--build DIR] [--seconds S] [--jobs-note] [TARGET...]
#   --build DIR    the fuzz build directory (default build-fuzz; `make fuzz` configures and builds it)
#   --seconds S    libFuzzer's -max_total_time per target (default: $FUZZ_SECONDS, else 60);
#                  the issue's one-hour run per target: scripts/fuzz.sh --seconds 3600
#   TARGET         case_file wheelset_case simpack_profile miniprof_profile text_profile wheel_rail_setup
#                  flexibility_table wheelset_table sweep_file sweep_journal merge wheelset_table_lookup (default: all)
#
# Each target runs on a working corpus DIR/corpus/<target>/ (new inputs go there) seeded with the
# repository's fuzz/corpus/<target>/ (read only) and the dictionary fuzz/dict/<target>.dict when
# there is one, with -rss_limit_mb=2048 -timeout=10; a crash, timeout or out-of-memory input is
# written to fuzz/crashes/<target>/ (commit it with the fix: ctest replays it). The log is
# DIR/logs/<target>.log; the summary prints libFuzzer's last status line per target. Exit status:
# 1 if any target found something.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD="$ROOT/build-fuzz"
SECONDS_PER_TARGET=${FUZZ_SECONDS:-60}
TARGETS=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build) BUILD=$(cd "$2" && pwd) || exit 2; shift 2 ;;
    --seconds) SECONDS_PER_TARGET=$2; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) TARGETS="$TARGETS $1"; shift ;;
  esac
done
[ -n "$TARGETS" ] || TARGETS="case_file wheelset_case simpack_profile miniprof_profile text_profile wheel_rail_setup flexibility_table wheelset_table sweep_file sweep_journal merge wheelset_table_lookup"

mkdir -p "$BUILD/logs"
status=0
summary=""
for target in $TARGETS; do
  fuzzer="$BUILD/fuzz/${target}_fuzz"
  if [ ! -x "$fuzzer" ]; then
    echo "fuzz.sh: $fuzzer is missing: run make fuzz (or cmake --build $BUILD --target fuzzers)" >&2
    exit 2
  fi
  corpus="$BUILD/corpus/$target"
  crashes="$ROOT/fuzz/crashes/$target"
  mkdir -p "$corpus" "$crashes"
  dict=""
  [ -f "$ROOT/fuzz/dict/$target.dict" ] && dict="-dict=$ROOT/fuzz/dict/$target.dict"
  log="$BUILD/logs/$target.log"
  echo "== $target: $SECONDS_PER_TARGET s (log $log)"
  command="$fuzzer -max_total_time=$SECONDS_PER_TARGET -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix=$crashes/ $dict $corpus $ROOT/fuzz/corpus/$target"
  echo "   $command"
  start=$(date +%s)
  # shellcheck disable=SC2086
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 $command >"$log" 2>&1
  rc=$?
  elapsed=$(( $(date +%s) - start ))
  last=$(grep -E '^#[0-9]+' "$log" | tail -n 1)
  execs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
  files=$(find "$corpus" -type f | wc -l)
  if [ $rc -ne 0 ]; then
    status=1
    found=$(grep -E 'Test unit written to' "$log" | sed 's/.*Test unit written to //')
    if [ -n "$found" ]; then
      line="$target: FINDING after $elapsed s (exit $rc): $found"
    else
      line="$target: libFuzzer failed after $elapsed s (exit $rc), no input written: $(head -n 3 "$log" | tr '\n' ' ')"
    fi
  else
    line="$target: $elapsed s, ${execs:-?} executions, $files corpus files; $last"
  fi
  echo "   $line"
  summary="$summary
$line"
done
echo "== summary:$summary"
exit $status
