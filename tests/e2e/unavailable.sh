#!/usr/bin/env bash
# A counter the driver cannot provide is reported as unavailable with the
# reason — never as 0 — through results.json, results.csv and the report.
# The missing extension is simulated with DMBENCH_HIDE_EXTENSIONS; missing
# Valgrind (Instructions) with DMBENCH_VALGRIND naming no executable, and
# Valgrind crashing or hanging with DMBENCH_VALGRIND naming a script that does.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
DMBENCH_HIDE_EXTENSIONS=GL_ARB_pipeline_statistics_query \
  "$BIN" run "$SRC/tests/e2e/tiny.yaml" --out "$OUT" --quiet
python3 - "$OUT/latest" <<'PY'
import json, os, sys
run = sys.argv[1]
j = json.load(open(os.path.join(run, "results.json")))
for c in j["configs"]:
    assert c["status"] == "ok", c.get("reason")
    cs = c["counters"]
    for name in ("VSInvocations", "FSInvocations", "ClippingOutputPrimitives"):
        v = cs[name]
        assert "unavailable" in v and "GL_ARB_pipeline_statistics_query" in v["unavailable"], v
        assert "value" not in v or v["value"] is None, v
    # occlusion queries are core GL: still measured
    assert cs["SamplesPassed"]["value"] > 0
    assert cs["WallTime"]["median"] > 0
    # a derived counter over an unavailable input is unavailable, not 0 or inf
    assert "unavailable" in cs["ShadingEfficiency"], cs["ShadingEfficiency"]
html = open(os.path.join(run, "report.html")).read()
assert "unavailable" in html
print("unavailable ok")
PY
# Instructions asked for where Valgrind is missing: unavailable with the
# reason in every configuration (and InstructionsPerPixel with it), the run
# goes on and measures everything else.
sed 's/counters: \[/counters: [Instructions, InstructionsPerPixel, /' "$SRC/tests/e2e/tiny.yaml" > "$OUT/instr.yaml"
grep -q "counters: \[Instructions, InstructionsPerPixel, " "$OUT/instr.yaml"
DMBENCH_VALGRIND=/nonexistent/valgrind "$BIN" run "$OUT/instr.yaml" --out "$OUT/instr" --quiet
python3 - "$OUT/instr/latest" <<'PY'
import json, os, sys
j = json.load(open(os.path.join(sys.argv[1], "results.json")))
assert j["configs"]
for c in j["configs"]:
    assert c["status"] == "ok", c.get("reason")
    cs = c["counters"]
    assert "valgrind not found" in cs["Instructions"]["unavailable"], cs["Instructions"]
    assert "unavailable" in cs["InstructionsPerPixel"], cs["InstructionsPerPixel"]
    assert cs["WallTime"]["median"] > 0 and cs["SamplesPassed"]["value"] > 0
assert j["passes"]["Instructions"] == "instructions" and j["passes"]["WallTime"] == "timing"
print("Instructions unavailable ok")
PY
# Valgrind crashing or hanging in the Instructions children (two side by
# side, --count-jobs 2): every configuration they were counting fails with
# Valgrind's own message (the hang through each child's watchdog, 10 x
# timeout_s), Valgrind is started once per child (no endless retry),
# nothing is left running, and the run finishes.
cat > "$OUT/crash-valgrind" <<'SH'
#!/bin/sh
echo started >> "$FAKE_VG_LOG"
echo "==1== valgrind: the 'impossible' happened (simulated)" >&2
exit 1
SH
# the hang sleeps for a duration no other process on the machine has, so
# that the check below finds only this test's child
nap=600.$$$RANDOM
cat > "$OUT/hang-valgrind" <<SH
#!/bin/sh
echo started >> "\$FAKE_VG_LOG"
echo "==1== valgrind: simulated hang" >&2
exec sleep $nap
SH
chmod +x "$OUT/crash-valgrind" "$OUT/hang-valgrind"
if grep -q '^  timeout_s:' "$OUT/instr.yaml"; then
  sed -i 's/^  timeout_s: .*/  timeout_s: 1/' "$OUT/instr.yaml"
else
  sed -i 's/^measure:/measure:\n  timeout_s: 1/' "$OUT/instr.yaml"
fi
for kind in crash hang; do
  FAKE_VG_LOG=$OUT/$kind.log DMBENCH_VALGRIND=$OUT/$kind-valgrind \
    timeout 120 "$BIN" run "$OUT/instr.yaml" --out "$OUT/$kind" --quiet --count-jobs 2
  [ "$(wc -l < "$OUT/$kind.log")" -eq 2 ] || { echo "FAIL: $kind: Valgrind started $(wc -l < "$OUT/$kind.log") times, not once per child"; exit 1; }
  python3 - "$OUT/$kind/latest" "$kind" <<'PY'
import json, os, sys
j = json.load(open(os.path.join(sys.argv[1], "results.json")))
want = {"crash": "exited with status 1", "hang": "made no progress for 10 s (killed)"}[sys.argv[2]]
msg = {"crash": "the 'impossible' happened", "hang": "simulated hang"}[sys.argv[2]]
assert j["configs"]
for c in j["configs"]:
    assert c["status"] == "failed", c
    assert want in c["reason"] and msg in c["reason"], c["reason"]
print(sys.argv[2], "ok: every configuration failed with Valgrind's message")
PY
done
pgrep -f "sleep $nap" >/dev/null && { echo "FAIL: the hung Valgrind child was left running"; exit 1; }
# A counting child killed while it prepares the second configuration of
# its batch (run/count_child.c prepares a whole batch, then counts it):
# that configuration alone fails, with the signal; the first, prepared but
# not counted yet, and the rest are counted by one new child, under the
# real Valgrind; the killed one leaves no file in TMPDIR (Valgrind's
# gdbserver FIFOs: the counting children run without it).
cat > "$OUT/kill-valgrind" <<'PY'
#!/usr/bin/env python3
import os, signal, subprocess, sys
log = os.environ["FAKE_VG_LOG"]
with open(log, "a") as f:
    f.write("started\n")
first = sum(1 for _ in open(log)) == 1
child = subprocess.Popen([os.environ["REAL_VG"]] + sys.argv[1:], stdout=subprocess.PIPE)
preparing = 0
for line in child.stdout:
    sys.stdout.buffer.write(line)
    sys.stdout.flush()
    preparing += line.startswith(b"W ")
    if first and preparing == 2:
        child.kill()
        child.wait()
        os.kill(os.getpid(), signal.SIGKILL)
sys.exit(child.wait())
PY
chmod +x "$OUT/kill-valgrind"
sed 's/^  timeout_s: .*/  timeout_s: 120/' "$OUT/instr.yaml" > "$OUT/instr-kill.yaml"
mkdir -p "$OUT/tmp-kill"   # the children's TMPDIR: the killed Valgrind leaves no gdbserver FIFO there
FAKE_VG_LOG=$OUT/kill.log REAL_VG=$(command -v valgrind) DMBENCH_VALGRIND=$OUT/kill-valgrind TMPDIR=$OUT/tmp-kill \
  timeout 600 "$BIN" run "$OUT/instr-kill.yaml" --out "$OUT/kill" --quiet --count-jobs 1 --seed 1
[ "$(wc -l < "$OUT/kill.log")" -eq 2 ] || { echo "FAIL: kill: Valgrind started $(wc -l < "$OUT/kill.log") times, not twice"; exit 1; }
fifos=$(ls "$OUT/tmp-kill" | grep -c '^vgdb-pipe') || true
[ "$fifos" -eq 0 ] || { echo "FAIL: kill: the killed Valgrind child left $fifos vgdb FIFOs in TMPDIR"; exit 1; }
python3 - "$OUT/kill/latest" <<'PY'
import json, os, sys
j = json.load(open(os.path.join(sys.argv[1], "results.json")))
failed = [c for c in j["configs"] if c["status"] != "ok"]
counted = [c for c in j["configs"] if c["status"] == "ok"]
assert len(failed) == 1 and "died of signal 9" in failed[0]["reason"], [c.get("reason") for c in failed]
assert len(counted) >= 2, len(counted)
for c in counted:
    assert c["counters"]["Instructions"]["median"] > 0, c["counters"]["Instructions"]
print(f"kill ok: the configuration being prepared failed; {len(counted)} others counted by the new child")
PY
echo "4 passed, 0 failed"
