#!/usr/bin/env bash
# A counted run made once and read by several tests (ctest fixtures,
# tests/instructions.cmake): SWEEP run by dmbench (or BIN) into DIR, which
# is emptied first and kept in the build tree after the test.  Asserts what
# every reader relies on: every configuration ok, with Instructions counted.
# Usage: fixture_run.sh DIR SWEEP [BIN]  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
DIR=${1:?usage: fixture_run.sh DIR SWEEP [BIN]}
SWEEP=${2:?usage: fixture_run.sh DIR SWEEP [BIN]}
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
RUNBIN=${3:-$BIN}
rm -rf "$DIR"
mkdir -p "$DIR"
t0=$(date +%s)
"$RUNBIN" run "$SWEEP" --out "$DIR" --seed 1 --quiet
echo "$(basename "$SWEEP"): $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
python3 "$SRC/tests/instructions/check_counted.py" "$DIR/latest/results.json"
