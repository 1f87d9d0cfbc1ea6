#!/usr/bin/env bash
# The watchdog kills a hung configuration; the sweep completes with exactly
# that one marked failed and the others measured.  The hang is made by the
# DMBENCH_TEST_HANG hook (the measuring process blocks on reaching `normal`):
# llvmpipe caps shader loops, so no shader can hang this driver.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
start=$(date +%s)
DMBENCH_TEST_HANG=normal "$BIN" run "$SRC/tests/e2e/watchdog.yaml" --out "$OUT" --quiet
took=$(( $(date +%s) - start ))
python3 - "$OUT/latest/results.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
by = {c["params"]["technique"]: c for c in j["configs"]}
assert set(by) == {"texture", "normal", "phong"}, set(by)
assert by["normal"]["status"] == "failed", by["normal"]
assert "watchdog" in by["normal"]["reason"], by["normal"]["reason"]
for t in ("texture", "phong"):
    assert by[t]["status"] == "ok", (t, by[t].get("reason"))
    assert by[t]["counters"]["WallTime"]["median"] > 0
print("watchdog ok:", by["normal"]["reason"])
PY
[ "$took" -lt 120 ] || { echo "the run took ${took}s"; exit 1; }
echo "1 passed, 0 failed"
