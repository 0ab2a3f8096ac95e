#!/usr/bin/env bash
# The long property run of tests/numeric/random_scenes_test.cpp, split into
# seed ranges and resumable: each finished range leaves its closing lines in
# LOG_DIR/TYPE-FIRST.log; a range whose log says it passed is not run again.
#
#   scripts/property-run.sh TYPE [SCENES [CHUNK]]
#     TYPE    double | long_double (the RandomScenes type names)
#     SCENES  seeds 1 .. SCENES (default 1000000)
#     CHUNK   seeds per range (default 100000)
#   LOG_DIR   where the range logs go (default property-run/ in the build dir)
#   FIRST     the first seed (default 1): resume on another machine from a
#             range boundary, FIRST = 1 + a multiple of CHUNK
#
# Prints one line per range (its [ info ] line), then the total.  Exits
# non-zero at the first range that fails (its log holds the failure).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
type="${1:?usage: scripts/property-run.sh double|long_double [SCENES [CHUNK]]}"
scenes="${2:-1000000}"
chunk="${3:-100000}"
start_seed="${FIRST:-1}"
LOG_DIR="${LOG_DIR:-$BUILD_DIR/property-run}"
binary="$BUILD_DIR/tests/numeric/superball_numeric_tests"
[ -x "$binary" ] || { echo "property-run.sh: $binary is missing: build with -DSUPERBALL_BUILD_TESTS=ON" >&2; exit 2; }
mkdir -p "$LOG_DIR"
for ((first = start_seed; first <= scenes; first += chunk)); do
  count=$(( first + chunk - 1 <= scenes ? chunk : scenes - first + 1 ))
  log="$LOG_DIR/$type-$first-$count.log"
  if ! grep -q "^\[  PASSED  \] 1 test" "$log" 2>/dev/null; then
    start=$(date +%s)
    SUPERBALL_PROPERTY_SCENES=$count SUPERBALL_PROPERTY_FIRST_SEED=$first \
      "$binary" --gtest_filter="RandomScenes/$type.Physics*" > "$log.part" 2>&1 || { cat "$log.part" | tail -n 40; exit 1; }
    echo "[ time ] $(( $(date +%s) - start )) s" >> "$log.part"
    mv "$log.part" "$log"
  fi
  grep -h "^\[ info \]\|^\[ time \]" "$log" | tr '\n' ' '; echo
done
echo "$type: seeds $start_seed .. $scenes passed in ranges of $chunk (logs in $LOG_DIR)"
