#!/usr/bin/env bash
# Setup reuse (docs/measurement.md): a second run of the default sweep spends < 10 % of
# its wall time outside measured frames (program, texture and reference
# caches).  Runs the default sweep twice into one output root and prints the
# runner's own accounting of each run, then where the time outside the
# measured frames went (from the measuring processes' --verbose lines:
# per-configuration setup, warm-up, statistics pass, images + quality).
# Usage: bench/setup_reuse.sh BIN [OUT] [RUNS]   (RUNS default 2; with an
# OUT of an earlier call, RUNS=1 measures one more warm run)
set -euo pipefail
BIN=${1:?usage: setup_reuse.sh path/to/dmbench [OUT] [RUNS]}
OUT=${2:-$(mktemp -d)}
RUNS=${3:-2}
mkdir -p "$OUT"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq 1 "$RUNS"); do
  log="$OUT/run$i-$(date +%H%M%S).log"
  "$BIN" run --verbose --out "$OUT" 2> "$log" > /dev/null
  echo "run $i: $(grep 'in measured frames' "$log")"
  awk '/debug: measure [0-9a-f]+: setup/ {
         n++; s += $6; w += $9; st += $12; sa += $15; q += $18
         if ($0 ~ /reference cache/) hit++
       }
       END { printf "  per-configuration sums (%d configs): setup %.1f s, warm-up %.1f s, statistics %.1f s, " \
                    "sampling %.1f s, images+quality %.1f s; references from cache: %d\n",
                    n, s / 1e3, w / 1e3, st / 1e3, sa / 1e3, q / 1e3, hit }' "$log"
  echo "  load after: $(cut -d' ' -f1-3 /proc/loadavg)"
done
