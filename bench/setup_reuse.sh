#!/usr/bin/env bash
# SPEC §12 "setup reuse": a second run of the default sweep spends < 10 % of
# its wall time outside measured frames (program and texture caches).
# Runs the default sweep twice into one output root and prints the runner's
# own accounting of each run.  Usage: bench/setup_reuse.sh BIN [OUT]
set -euo pipefail
BIN=${1:?usage: setup_reuse.sh path/to/dmbench [OUT]}
OUT=${2:-$(mktemp -d)}
mkdir -p "$OUT"
for i in 1 2; do
  "$BIN" run --out "$OUT" 2> "$OUT/run$i.log" > /dev/null
  echo "run $i: $(grep 'in measured frames' "$OUT/run$i.log")"
done
