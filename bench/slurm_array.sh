#!/usr/bin/env bash
# The default sweep as a 4-shard Slurm job array on a local single-node
# cluster (tests/slurm/cluster.sh) against one `dmbench run` process.
# Prints wall times with the load average before and after each; the
# reference cache is shared (DMBENCH_CACHE_DIR under OUT), so the first of
# the three timings pays for the references: one process (cold), the array,
# one process again (warm).  The node offers every CPU of this machine to
# Slurm, one per task, so at most nproc shards run at once.
# Usage: bench/slurm_array.sh path/to/dmbench [SHARDS]   (needs root, slurm-wlm, munge)
set -euo pipefail
BIN=$(readlink -f "${1:?usage: slurm_array.sh path/to/dmbench [SHARDS]}")
N=${2:-4}
SRC=$(cd "$(dirname "$0")/.." && pwd)
source "$SRC/tests/slurm/cluster.sh"
OUT=$(mktemp -d /tmp/dmbench-slurm-bench.XXXXXX)
trap 'cluster_stop; rm -rf "$OUT"' EXIT
export DMBENCH_CACHE_DIR=$OUT/cache LP_NUM_THREADS=1
cluster_start "$OUT/cluster"
load() { cut -d' ' -f1-3 /proc/loadavg; }
one() {
  local t0 t1
  echo "load before: $(load)"
  t0=$(date +%s.%N)
  "$BIN" run --out "$OUT/one$1" --quiet
  t1=$(date +%s.%N)
  echo "one process ($2): $(echo "$t1 - $t0" | bc) s, $(sqlite3 "$OUT/one$1/dmbench.sqlite" 'select count(*) from configs') configurations; load after: $(load)"
}
one 1 cold
echo "load before: $(load)"
t0=$(date +%s.%N)
"$BIN" slurm --shards "$N" --out "$OUT/array" > "$OUT/submit.out"
job=$(sed -n 's/^merge job: //p' "$OUT/submit.out")
while squeue -h -j "$job" 2>/dev/null | grep -q .; do sleep 0.5; done
t1=$(date +%s.%N)
state=$(scontrol show job -o "$job" | grep -o 'JobState=[A-Z]*')
echo "$N-shard array + merge job ($state): $(echo "$t1 - $t0" | bc) s, $(sqlite3 "$OUT/array/merged/dmbench.sqlite" 'select count(*) from configs') configurations merged; load after: $(load)"
for k in $(seq 1 "$N"); do
  echo "  shard $k: $(sqlite3 "$OUT/array/shards/s$k/dmbench.sqlite" "select (select count(*) from configs) || ' configurations, ' || round((julianday(finished) - julianday(started)) * 86400) || ' s' from runs")"
done
one 2 warm
