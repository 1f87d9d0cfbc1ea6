#!/usr/bin/env bash
# merge and shards, without a scheduler:
#  - shards measured in two environments (LP_NUM_THREADS 1 and 2: two
#    fingerprints, as two machines would give) merge into one run that keeps
#    them apart: every configuration carries its machine, scenes are per
#    machine, the report says so; compare against a one-machine run compares
#    the configurations of that machine and not the others;
#  - merge refuses a shard given twice and reports a missing one, creating
#    nothing; merge/fit of a directory that is not a run create nothing;
#  - --resume of a shard's store with another --shard is refused with both.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP=$SRC/tests/e2e/resume.yaml
q() { sqlite3 "$1" "$2"; }
fail() { echo "FAIL: $*"; exit 1; }
expect2() {   # expect2 NAME REGEX CMD...: exit 2 and stderr matching REGEX
  local name=$1 re=$2 rc=0; shift 2
  "$@" > "$OUT/o" 2> "$OUT/e" || rc=$?
  [ "$rc" -eq 2 ] || fail "$name: exit $rc, expected 2 ($(cat "$OUT/e"))"
  grep -Eq "$re" "$OUT/e" || fail "$name: message '$(cat "$OUT/e")' lacks /$re/"
}

# the one-machine run (LP_NUM_THREADS=1, as ctest sets it) that the merge is
# compared with: the suite's (fixture resume_full) or one made here
FULL=$(LP_NUM_THREADS=1 bash "$SRC/tests/e2e/resume_full.sh" --use "$OUT/full")
LP_NUM_THREADS=1 "$BIN" run "$SWEEP" --out "$OUT/s1" --shard 1/2 --quiet
LP_NUM_THREADS=2 "$BIN" run "$SWEEP" --out "$OUT/s2" --shard 2/2 --quiet
fp1=$(q "$OUT/s1/dmbench.sqlite" "select value from run_env where key='fingerprint'")
fp2=$(q "$OUT/s2/dmbench.sqlite" "select value from run_env where key='fingerprint'")
[ "$fp1" != "$fp2" ] || fail "LP_NUM_THREADS did not change the fingerprint"

# Refusals first: nothing may be created.
expect2 "shard twice" "shard 1/2 given twice" "$BIN" merge "$OUT/m" "$OUT/s1/latest" "$OUT/s1/latest"
expect2 "missing shard" "shard 2/2: not given" "$BIN" merge "$OUT/m" "$OUT/s1/latest"
[ ! -e "$OUT/m" ] || fail "a refused merge created $OUT/m"
mkdir -p "$OUT/plain/sub"
expect2 "merge non-run" "not a run directory" "$BIN" merge "$OUT/m" "$OUT/plain/sub"
expect2 "fit non-run" "not a run directory" "$BIN" fit "$OUT/plain/sub"
[ -z "$(find "$OUT/plain" -type f)" ] && [ ! -e "$OUT/m" ] || fail "merge/fit of a non-run created files"
expect2 "resume other shard" "measures shard 1/2, not shard 2/2" \
  "$BIN" run "$SWEEP" --out "$OUT/s1" --shard 2/2 --resume --quiet
expect2 "resume unsharded" "measures shard 1/2, not the whole sweep" \
  "$BIN" run "$SWEEP" --out "$OUT/s1" --resume --quiet

# Two machines, merged.
"$BIN" merge "$OUT/m" "$OUT/s1/latest" "$OUT/s2/latest" > "$OUT/merge.out" 2> "$OUT/merge.err"
grep -q "2 machines" "$OUT/merge.err" || fail "merge did not say it saw 2 machines"
db=$OUT/m/dmbench.sqlite
[ "$(q "$db" "select count(*) from configs")" -eq 12 ] || fail "merged run does not have 12 configurations"
n1=$(q "$OUT/s1/dmbench.sqlite" "select count(*) from configs")
[ "$(q "$db" "select count(*) from config_params where name='machine' and value='$fp1'")" -eq "$n1" ] \
  || fail "shard 1's configurations are not all on machine $fp1"
[ "$(q "$db" "select count(*) from config_params where name='machine' and value='$fp2'")" -eq $((12 - n1)) ] \
  || fail "shard 2's configurations are not all on machine $fp2"
[ "$(q "$db" "select count(*) from configs where scene not like '% @ $fp1' and scene not like '% @ $fp2'")" -eq 0 ] \
  || fail "a scene without its machine"
[ "$(q "$db" "select count(*) from run_env where key in ('machine $fp1', 'machine $fp2')")" -eq 2 ] \
  || fail "the machines are not described in the environment"
grep -q "merged from 2 machines" "$OUT/m/latest/report.html" || fail "report.html does not say 2 machines"
grep -q "merged from 2 machines" "$OUT/m/latest/summary.md" || fail "summary.md does not say 2 machines"
# chart text is written as character references: decode them first
perl -CS -pe 's/&#x([0-9a-f]+);/chr(hex($1))/ge' "$OUT/m/latest/report.html" > "$OUT/report.txt"
# every chart is per scene and a scene carries its machine, so no chart pools
# machines: each machine's scenes have their own time chart
for fp in "$fp1" "$fp2"; do
  grep -q "Time per configuration: [^<]* @ $fp" "$OUT/report.txt" \
    || fail "no time chart of machine $fp's scenes in report.html"
done
grep "Time per configuration: " "$OUT/report.txt" | grep -v " @ $fp1\| @ $fp2" | grep -q . \
  && fail "a time chart of a scene without its machine"

# compare: the one-machine run against the merge compares machine 1's
# configurations and marks machine 2's as not compared.
# (timings get a wide threshold: the runs are minutes apart on a shared
# machine, and this test is about which configurations are compared)
rc=0
"$BIN" compare "$FULL/latest" "$OUT/m/latest" --time-threshold 400% --json "$OUT/cmp.json" > "$OUT/cmp.out" 2>&1 || rc=$?
[ "$rc" -eq 3 ] || fail "compare exit $rc, expected 3 (inconclusive): $(cat "$OUT/cmp.out")"
# compare's lines wrap at 100 columns, continuations four columns in: join them
sed -i ':a;N;$!ba;s/\n    */ /g' "$OUT/cmp.out"
other=$(grep -o "measured on machine $fp1 in BASE and $fp2 in NEW: not compared" "$OUT/cmp.out" | wc -l)
[ "$other" -eq $((12 - n1)) ] || fail "$other configurations marked as other-machine, expected $((12 - n1))"
items=$(grep -Ec "^[A-Z]+ +.* [0-9a-f]{16}  " "$OUT/cmp.out" || true)
[ "$((items - other))" -eq "$n1" ] || fail "$((items - other)) configurations of machine 1 compared, expected $n1"
echo "machines: $n1 + $((12 - n1)) configurations on $fp1 and $fp2 kept apart"
echo "1 passed, 0 failed"
