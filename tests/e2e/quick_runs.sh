#!/usr/bin/env bash
# The three runs of the embedded --quick sweep that test_e2e_quick,
# test_e2e_precision and test_reports_quick_browser read, made once for the
# suite by test_e2e_quick_runs (fixture quick_runs, tests/e2e.cmake) where
# those three tests made six of them between them before:
#   DIR/a  --seed 7, with its progress on stderr (DIR/a.log) and its wall
#          time in seconds (DIR/a.seconds)
#   DIR/b  --seed 7 again, --quiet (the same rounds' order; FLIP repeats)
#   DIR/c  --seed 8, --quiet (another order)
# Readers only read them (quick_report.sh copies its run first).
# Usage: quick_runs.sh DIR           make the runs into DIR (emptied first)
#        quick_runs.sh --use DIR     print the runs' root for a reader:
#                                    $QUICK_RUNS (the suite's, set by ctest)
#                                    when set, else the runs made into DIR
#                                    (a reader run by hand)
# (DMBENCH_BINARY set by ctest)
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
if [ "${1:-}" = --use ]; then
  DIR=${2:?usage: quick_runs.sh --use DIR}
  if [ -n "${QUICK_RUNS:-}" ]; then
    for r in a b c; do
      [ -f "$QUICK_RUNS/$r/latest/results.json" ] ||
        { echo "no run in $QUICK_RUNS/$r (fixture test_e2e_quick_runs)" >&2; exit 1; }
    done
    echo "$QUICK_RUNS"
    exit 0
  fi
  bash "$0" "$DIR" >&2
  echo "$DIR"
  exit 0
fi
DIR=${1:?usage: quick_runs.sh DIR | --use DIR}
rm -rf "$DIR"
mkdir -p "$DIR"
start=$(date +%s)
"$BIN" run --quick --seed 7 --out "$DIR/a" 2> "$DIR/a.log" > "$DIR/a.out" || { cat "$DIR/a.log"; exit 1; }
echo $(( $(date +%s) - start )) > "$DIR/a.seconds"
"$BIN" run --quick --seed 7 --out "$DIR/b" --quiet
"$BIN" run --quick --seed 8 --out "$DIR/c" --quiet
echo "three --quick runs in $DIR (the first took $(cat "$DIR/a.seconds") s)"
