#!/usr/bin/env bash
# Faults (docs/reliability.md): a full disk and a damaged store stop a run
# with a clear message and exit 4 (never endless, never 1); two processes on
# one --out get a refusal through the lock; --resume refuses a missing store
# and another shard; SIGTERM in the middle of a one-scene sweep keeps the
# samples of every finished round and --resume continues from them.
set -uo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
TINY=$SRC/tests/e2e/tiny.yaml
ONE=$SRC/tests/e2e/one_scene.yaml
OUT=$(mktemp -d)
MNT=""
cleanup() { [ -n "$MNT" ] && umount "$MNT" 2>/dev/null; rm -rf "$OUT"; }
trap cleanup EXIT
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }
q() { sqlite3 "$1/dmbench.sqlite" "$2"; }
# check NAME WANT_RC PATTERN RC STDERR
check() {
  if [ "$4" -eq "$2" ] && grep -q -- "$3" <<<"$5"; then ok
  else bad "$1: rc $4 (want $2), stderr: $(head -c 600 <<<"$5") (want /$3/)"; fi
}

# 1. Disk full: a 400 KB tmpfs fills while configurations are saved.
mkdir -p "$OUT/fs"
if mount -t tmpfs -o size=400k tmpfs "$OUT/fs" 2>/dev/null; then
  MNT="$OUT/fs"
  err=$(timeout 300 "$BIN" run "$TINY" --out "$OUT/fs/r" --quiet 2>&1 >/dev/null); rc=$?
  check "disk full" 4 "database or disk is full.*stopped the run" "$rc" "$err"
  n=$(grep -c "disk is full" <<<"$err")
  [ "$n" -le 2 ] && ok || bad "disk full: $n error lines (a bounded number expected)"
  umount "$OUT/fs"; MNT=""
else
  echo "SKIP disk full: mount -t tmpfs was refused (not root or no CAP_SYS_ADMIN)"
fi

# A small finished run to damage, to lock and to compare; its name carries
# raw HTML and an ANSI escape, which must reach neither summary.md nor the
# terminal.
sed 's/^name: e2e-tiny/name: "<img src=x onerror=alert(1)>\\e[31mred"/' "$TINY" > "$OUT/evil.yaml"
err=$("$BIN" run "$OUT/evil.yaml" --out "$OUT/good" 2>&1 >/dev/null) || bad "the tiny run failed"
grep -q $'\e\[31m' <<<"$err" && bad "an ANSI escape from the sweep name reached the terminal" || ok
grep -q "<img" "$OUT/good/latest/summary.md" && bad "raw HTML in summary.md" || ok
grep -q "&lt;img src=x" "$OUT/good/latest/summary.md" && ok || bad "the sweep name is not in summary.md, escaped"

# compare: bad options and bad results.json (exit 2), nothing in common,
# raw HTML in a label kept out of --markdown
J="$OUT/good/latest/results.json"
python3 - "$J" "$OUT" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); o = sys.argv[2]
def w(name, f):
    x = json.loads(json.dumps(d)); f(x); json.dump(x, open(f"{o}/{name}.json", "w"))
w("neg", lambda x: x["configs"][0]["counters"]["WallTime"].__setitem__("median", -5))
w("type", lambda x: x["configs"][0]["counters"]["WallTime"].__setitem__("median", "fast"))
def rekey(x):
    for c in x["configs"]: c["key"] = "f" + c["key"][1:]
w("other", rekey)
def html(x):
    for i, c in enumerate(x["configs"]):   # in a param and in the scene: the short names carry it
        c["params"]["maps"] = f"height=/m/<script>{i}</script>.png"
        c["scene"] = f"plane<script>{i}</script>"
w("html", html)
PY
err=$("$BIN" compare "$J" "$J" --alpha 0 2>&1 >/dev/null); check "--alpha 0" 2 "(0 %, 100 %)" $? "$err"
err=$("$BIN" compare "$J" "$J" --alpha 2 2>&1 >/dev/null); check "--alpha 2" 2 "write 2% or 0.02" $? "$err"
err=$("$BIN" compare "$J" "$J" --tolerance FSInvocatons=0.1 2>&1 >/dev/null); check "--tolerance" 2 "unknown counter 'FSInvocatons'; did you mean 'FSInvocations'" $? "$err"
err=$("$BIN" compare "$J" "$OUT/neg.json" 2>&1 >/dev/null); check "negative time" 2 "WallTime is -5 ns" $? "$err"
err=$("$BIN" compare "$J" "$OUT/type.json" 2>&1 >/dev/null); check "wrong type" 2 "not a number" $? "$err"
err=$("$BIN" compare "$J" "$OUT/other.json" 2>&1 >/dev/null); check "nothing in common" 2 "no configuration in common" $? "$err"
"$BIN" compare "$OUT/html.json" "$OUT/html.json" --markdown "$OUT/c.md" > /dev/null 2>&1
# markdown escapes, not HTML entities: '<' written '\<' renders as text
grep -qE '(^|[^\\])<script' "$OUT/c.md" && bad "raw HTML in compare --markdown" || ok
grep -qF '\<script' "$OUT/c.md" && ok || bad "the label is not in compare --markdown, escaped"

# 2. Damaged store: a page in the middle overwritten.
cp -r "$OUT/good" "$OUT/dmg"
dd if=/dev/urandom of="$OUT/dmg/dmbench.sqlite" bs=4096 seek=10 count=1 conv=notrunc 2>/dev/null
err=$(timeout 120 "$BIN" run "$TINY" --out "$OUT/dmg" --quiet 2>&1 >/dev/null); rc=$?
check "run on a damaged store" 4 "results store is damaged" "$rc" "$err"
err=$(timeout 60 "$BIN" report "$OUT/dmg/latest" 2>&1 >/dev/null); rc=$?
check "report on a damaged store" 4 "results store is damaged" "$rc" "$err"
err=$(timeout 60 "$BIN" fit "$OUT/dmg/latest" 2>&1 >/dev/null); rc=$?
check "fit on a damaged store" 4 "results store is damaged" "$rc" "$err"

# 3. Two processes on one --out: the second is refused while the first runs.
setsid "$BIN" run "$ONE" --out "$OUT/lock" --quiet 2>/dev/null &
pid=$!
for _ in $(seq 1 400); do [ -s "$OUT/lock/dmbench.lock" ] && break; sleep 0.05; done
err=$(timeout 60 "$BIN" run "$ONE" --out "$OUT/lock" --resume --quiet 2>&1 >/dev/null); rc=$?
check "second run on one --out" 4 "is in use by another dmbench run (pid $pid)" "$rc" "$err"
kill -9 -- -"$pid" 2>/dev/null; wait "$pid" 2>/dev/null

# 4. --resume without a store creates nothing; --resume of another shard.
err=$("$BIN" run "$TINY" --out "$OUT/none" --resume --quiet 2>&1 >/dev/null); rc=$?
check "--resume on a missing --out" 2 "no results store there" "$rc" "$err"
[ ! -e "$OUT/none" ] && ok || bad "--resume created $OUT/none"
"$BIN" run "$SRC/tests/e2e/resume.yaml" --out "$OUT/sh" --shard 1/2 --quiet || bad "shard 1/2 failed"
err=$("$BIN" run "$SRC/tests/e2e/resume.yaml" --out "$OUT/sh" --shard 2/2 --resume --quiet 2>&1 >/dev/null); rc=$?
check "--resume of another shard" 2 "measures shard 1/2, not shard 2/2" "$rc" "$err"
err=$("$BIN" run "$SRC/tests/e2e/resume.yaml" --out "$OUT/sh" --resume --quiet 2>&1 >/dev/null); rc=$?
check "--resume without --shard" 2 "measures shard 1/2, not the whole sweep" "$rc" "$err"

# 5. SIGTERM to the runner in the middle of a one-scene sweep whose six
#    configurations are measured in interleaved rounds: the samples of the
#    finished rounds are kept and --resume continues from them.
"$BIN" run "$ONE" --out "$OUT/term" --quiet 2>/dev/null &
pid=$!
n=0
for _ in $(seq 1 600); do
  n=$(q "$OUT/term" "select count(distinct key) from partial_samples" 2>/dev/null || echo 0)
  [ "${n:-0}" -ge 6 ] && break
  sleep 0.05
done
sleep 1
kill -TERM "$pid"; wait "$pid" 2>/dev/null
sleep 0.5
kept=$(q "$OUT/term" "select count(*) from configs")
cp=$(q "$OUT/term" "select count(distinct key) from partial_samples")
smp=$(q "$OUT/term" "select coalesce(sum(length(data)/8),0) from partial_samples where counter='WallTime'")
[ "$((kept + cp))" -ge 6 ] && [ "$smp" -gt 0 ] && ok ||
  bad "SIGTERM: $kept configurations and $cp checkpoints ($smp samples) kept"
"$BIN" run "$ONE" --out "$OUT/term" --resume --quiet || bad "--resume after SIGTERM failed"
test "$(q "$OUT/term" "select count(*) from configs where status='ok'")" -eq 6 && ok || bad "not 6 configurations after --resume"
cont=$(q "$OUT/term" "select count(*) from configs where log like '%continued from%'")
[ "$cont" -ge "$cp" ] && ok || bad "only $cont of $cp checkpointed configurations continued"
test "$(q "$OUT/term" "select count(*) from partial_samples")" -eq 0 && ok || bad "checkpoints left after the run"
test "$(q "$OUT/term" "select min(length(data)/8) from samples where counter='WallTime'")" -eq 24 && ok || bad "a configuration has not 24 samples"
echo "faults: SIGTERM kept $kept configurations + $cp checkpoints ($smp WallTime samples)"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
