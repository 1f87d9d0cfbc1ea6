#!/usr/bin/env bash
# The embedded default sweep in its --quick form (README, the 1-minute
# version): no file, every technique, results and report written, nothing
# failed.  Prints its wall time; the time bound only catches a run-away.
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
start=$(date +%s)
"$BIN" run --quick --out "$OUT" 2> "$OUT/log"
took=$(( $(date +%s) - start ))
tail -1 "$OUT/log"
python3 - "$OUT/latest/results.json" "$BIN" <<'PY'
import json, subprocess, sys
j = json.load(open(sys.argv[1]))
techs = [l.split()[0] for l in subprocess.run([sys.argv[2], "list", "techniques"], capture_output=True,
         text=True, check=True).stdout.splitlines() if l and not l.startswith(" ")]
ran = {c["params"]["technique"] for c in j["configs"]}
missing = set(techs) - ran - {"reference-mesh"}
assert not missing, missing
bad = [(c["params"]["technique"], c["reason"]) for c in j["configs"] if c["status"] != "ok"]
assert not bad, bad
assert j["run"]["sweep"] == "quick"
print("quick:", len(j["configs"]), "configurations, every technique")
PY
echo "quick sweep: ${took} s"
[ "$took" -lt 300 ]
echo "1 passed, 0 failed"
