#!/usr/bin/env bash
# dmbench slurm on a real single-node Slurm cluster (tests/slurm/cluster.sh):
#  1. a job the cluster rejects (unknown partition): Slurm's message, exit
#     non-zero, no job scripts left behind;
#  2. a 4-shard job array of a small sweep: the merge job completes and the
#     merged run holds every key of the plan once (the plan's keys come from
#     an unsharded run of the same sweep) and a report;
#  3. a task that fails (its shard directory holds another shard's store):
#     the merge job names the shard with Slurm's state and reason, merges
#     the other shards and fails;
#  4. --resume submits only the missing shard; the merge is complete again;
#  5. --resume with every shard complete submits only the merge job.
# Exit 77 (skipped) only when Slurm or MUNGE is not installed or we are not
# root (slurmd needs root).
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
SWEEP=$SRC/tests/e2e/resume.yaml
source "$SRC/tests/slurm/cluster.sh"
t0=$(date +%s)
if [ "$(id -u)" -ne 0 ]; then echo "SKIP: slurmd needs root to start jobs"; exit 77; fi
T=$(mktemp -d /tmp/dmbench-slurm.XXXXXX)
trap 'cluster_stop; rm -rf "$T"' EXIT
rc=0; cluster_start "$T/cluster" || rc=$?
[ "$rc" -eq 0 ] || exit "$rc"
OUT=$T/out
q() { sqlite3 "$1" "$2"; }
fail() { echo "FAIL: $*"; for f in "$OUT"/slurm/logs/*; do echo "== $f"; cat "$f"; done; exit 1; }

# Waits (at most $2 s) until job $1 has left the queue; prints its state.
wait_job() {
  local i
  for i in $(seq 1 $(( $2 * 2 ))); do
    squeue -h -j "$1" 2>/dev/null | grep -q . || break
    sleep 0.5
  done
  squeue -h -j "$1" 2>/dev/null | grep -q . && { scancel "$1"; fail "job $1 still queued after $2 s"; }
  scontrol show job -o "$1" | grep -o 'JobState=[A-Z_]*' | cut -d= -f2
}
merge_job() { sed -n 's/^merge job: //p' "$1"; }

# 1. rejected by the cluster
if "$BIN" slurm "$SWEEP" --shards 4 --out "$OUT" --partition nosuch > "$T/rej.out" 2> "$T/rej.err"; then
  fail "a job for an unknown partition was accepted"
fi
grep -qi "invalid partition" "$T/rej.err" || fail "Slurm's message missing: $(cat "$T/rej.err")"
[ ! -e "$OUT/slurm" ] || fail "a rejected submission left $OUT/slurm behind"

# The plan's keys, independently: the same sweep unsharded (the suite's run,
# fixture resume_full, or one made here: tests/e2e/resume_full.sh).
FULL=$(bash "$SRC/tests/e2e/resume_full.sh" --use "$T/full")
q "$FULL/dmbench.sqlite" "select key from configs order by key" > "$T/plan.keys"
n_plan=$(wc -l < "$T/plan.keys")
[ "$n_plan" -eq 12 ] || fail "the plan has $n_plan keys, expected 12"

check_merged() {
  local db=$OUT/merged/dmbench.sqlite run
  run=$(basename "$(readlink -f "$OUT/merged/latest")")
  q "$db" "select key from configs where run='$run' order by key" > "$T/merged.keys"
  diff "$T/plan.keys" "$T/merged.keys" || fail "merged keys differ from the plan"
  [ "$(q "$db" "select count(*) - count(distinct key) from configs where run='$run'")" -eq 0 ] || fail "a key twice"
  test -s "$OUT/merged/latest/report.html" || fail "no report"
}

# 2. a 4-shard job array
"$BIN" slurm "$SWEEP" --shards 4 --out "$OUT" > "$T/sub1.out"
cat "$T/sub1.out"
grep -q "^array job: [0-9]* (shards 1-4 of 4)" "$T/sub1.out" || fail "no array job"
state=$(wait_job "$(merge_job "$T/sub1.out")" 150)
[ "$state" = COMPLETED ] || fail "merge job $state"
check_merged
for k in 1 2 3 4; do
  [ "$(q "$OUT/shards/s$k/dmbench.sqlite" "select value from run_env where key='shard'")" = "$k/4" ] \
    || fail "shard $k did not record shard $k/4"
done
t_array=$(( $(date +%s) - t0 ))

# 3. a failing task: shard 3's directory holds shard 2's store
rm -rf "$OUT/shards/s3"
cp -r "$OUT/shards/s2" "$OUT/shards/s3"
"$BIN" slurm "$SWEEP" --shards 4 --out "$OUT" --resume > "$T/sub2.out"
grep -q "^array job: [0-9]* (shards 3 of 4)" "$T/sub2.out" || fail "resume did not submit shard 3 only: $(cat "$T/sub2.out")"
state=$(wait_job "$(merge_job "$T/sub2.out")" 90)
[ "$state" = FAILED ] || fail "the merge job of a failed shard ended $state"
log=$OUT/slurm/logs/merge.out
grep -q "shard 3/4 failed: .*measures shard 2/4, not 3/4; Slurm: JobState=FAILED Reason=NonZeroExitCode ExitCode=2:0" "$log" \
  || fail "the merge job did not report shard 3 with Slurm's reason: $(cat "$log")"
grep -q "merged 3 runs" "$log" || fail "the other shards were not merged: $(cat "$log")"

# 4. --resume after removing the bad results: only shard 3 runs again
rm -rf "$OUT/shards/s3"
"$BIN" slurm "$SWEEP" --shards 4 --out "$OUT" --resume > "$T/sub3.out"
grep -q "^array job: [0-9]* (shards 3 of 4)" "$T/sub3.out" || fail "resume did not submit shard 3 only"
state=$(wait_job "$(merge_job "$T/sub3.out")" 90)
[ "$state" = COMPLETED ] || fail "merge job after --resume $state"
check_merged

# 5. --resume with every shard complete: only the merge job runs
"$BIN" slurm "$SWEEP" --shards 4 --out "$OUT" --resume > "$T/sub4.out"
grep -q "^every shard is complete: only the merge job was submitted" "$T/sub4.out" || fail "$(cat "$T/sub4.out")"
state=$(wait_job "$(merge_job "$T/sub4.out")" 60)
[ "$state" = COMPLETED ] || fail "merge-only job $state"
check_merged

echo "slurm: 4-shard array + merge in ${t_array} s (cluster start included); whole test $(( $(date +%s) - t0 )) s"
echo "1 passed, 0 failed"
