#!/usr/bin/env bash
# kill -9 in the middle of a sweep, then --resume: configurations committed
# before the kill are not measured again (their raw samples are unchanged),
# the store is intact, and the final set of keys equals an uninterrupted
# run's.  Also: two shards merged equal the unsharded set of keys.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP=$SRC/tests/e2e/resume.yaml
q() { sqlite3 "$OUT/$1/dmbench.sqlite" "$2"; }

# An uninterrupted run gives the reference set of keys (the suite's, fixture
# resume_full, or one made here: tests/e2e/resume_full.sh).
FULL=$(bash "$SRC/tests/e2e/resume_full.sh" --use "$OUT/full")
sqlite3 "$FULL/dmbench.sqlite" "select key from configs order by key" > "$OUT/full.keys"
test "$(wc -l < "$OUT/full.keys")" -eq 12

# Start a run in its own process group and kill it -9 after two commits.
setsid "$BIN" run "$SWEEP" --out "$OUT/cut" --quiet &
pid=$!
for _ in $(seq 1 600); do
  n=$(q cut "select count(*) from configs" 2>/dev/null || echo 0)
  [ "${n:-0}" -ge 2 ] && break
  sleep 0.05
done
kill -9 -- -"$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
before=$(q cut "select count(*) from configs")
[ "$before" -ge 2 ] && [ "$before" -lt 12 ] || { echo "kill landed at $before configs"; exit 1; }
test "$(q cut "pragma integrity_check")" = ok
q cut "select s.key, hex(s.data) from samples s order by s.key, s.counter" > "$OUT/before.samples"

"$BIN" run "$SWEEP" --out "$OUT/cut" --resume --quiet
q cut "select key from configs order by key" > "$OUT/cut.keys"
diff "$OUT/full.keys" "$OUT/cut.keys"
test "$(q cut "select count(*) from runs")" -eq 1
# every sample row that existed before the kill is still there, unchanged
q cut "select s.key, hex(s.data) from samples s order by s.key, s.counter" > "$OUT/after.samples"
missing=$(comm -23 <(sort "$OUT/before.samples") <(sort "$OUT/after.samples") | wc -l)
[ "$missing" -eq 0 ] || { echo "$missing sample rows changed by --resume"; exit 1; }

# Shards run with GNU parallel (the recipe of docs/scale-out.md), merged,
# equal the full set.
parallel --will-cite -j 2 "$BIN" run "$SWEEP" --out "$OUT/s{}" --shard {}/2 --quiet ::: 1 2
"$BIN" merge "$OUT/m" "$OUT/s1/latest" "$OUT/s2/latest" > /dev/null
q m "select key from configs order by key" > "$OUT/m.keys"
diff "$OUT/full.keys" "$OUT/m.keys"
a=$(q s1 "select count(*) from configs"); b=$(q s2 "select count(*) from configs")
[ $((a + b)) -eq 12 ] && [ "$a" -gt 0 ] && [ "$b" -gt 0 ]
test -s "$OUT/m/latest/report.html"
echo "resume: $before of 12 committed before kill -9; shards $a + $b"
echo "1 passed, 0 failed"
