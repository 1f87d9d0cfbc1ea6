#!/usr/bin/env bash
# End to end: `dmbench run SWEEP --dry-run` prints the plan — counts, folded
# combinations, left-out configurations with their reasons — measures
# nothing and creates nothing; after a real run of the same sweep, a stored
# model gives each configuration an estimated measuring time.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"

# texture does not read tess_level (2 combinations fold into each
# configuration); virtual_texture=sparse is left out at plan time.
cat > "$OUT/dry.yaml" <<'YAML'
name: dry
resolution: [96, 54]
sweep:
  technique: [texture]
  virtual_texture: [off, software, sparse]
  tess_level: [1, 16]
YAML
"$BIN" run "$OUT/dry.yaml" --dry-run --out "$OUT/store" > "$OUT/plan.txt"
test ! -e "$OUT/store" || { echo "a dry run created $OUT/store"; exit 1; }
python3 - "$OUT/plan.txt" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
print(t)
assert "6 combinations -> 3 configurations (0 excluded by the sweep, 3 folded" in t, t
assert "2 planned, 1 left out; nothing is measured" in t, t
# the one label form of every file: scene · technique and the axes that vary
planned = re.findall(r"^  ([0-9a-f]{16})  plane 96×54 · texture virtual_texture=(\w+)  "
                     r"\(2 combinations folded\)  estimate: none", t, re.M)
assert sorted(v for _, v in planned) == ["off", "software"], planned
assert "tess_level" not in t.split("\nleft out (")[0].split("planned configurations")[1], t
left = re.findall(r"^  technique=texture virtual_texture=sparse: (.*)$", t, re.M)
assert len(left) == 1 and "the driver lacks GL_ARB_sparse_texture" in left[0], left
assert "estimated time: unknown" in t, t
PY

# After a real run, its fitted model (resolution-cost: a + b*SamplesPassed)
# predicts every configuration of the same sweep; the dry run adds nothing
# to the store.
"$BIN" run "$SRC/tests/e2e/tiny.yaml" --out "$OUT/s" --quiet
runs_before=$(ls "$OUT/s" | wc -l)
"$BIN" run "$SRC/tests/e2e/tiny.yaml" --dry-run --out "$OUT/s" > "$OUT/plan2.txt"
test "$(ls "$OUT/s" | wc -l)" = "$runs_before" || { echo "the dry run wrote into $OUT/s"; exit 1; }
python3 - "$OUT/plan2.txt" "$OUT/s/latest/results.json" <<'PY'
import json, re, sys
t = open(sys.argv[1]).read()
print(t)
j = json.load(open(sys.argv[2]))
fit = [f for f in j["fits"] if f["model"] == "resolution-cost"]
assert fit, j["fits"]
assert "8 combinations -> 4 configurations (0 excluded by the sweep, 4 folded" in t, t
est = re.findall(r"^  ([0-9a-f]{16})  .*  estimate: ([0-9.e+-]+) ms/frame, ([0-9.e+-]+) s "
                 r"\(model resolution-cost\)$", t, re.M)
assert sorted(k for k, _, _ in est) == sorted(c["key"] for c in j["configs"]), (est, t)
assert all(float(ms) > 0 and float(s) > 0 for _, ms, s in est), est
total = float(re.search(r"^estimated time: ([0-9.e+-]+) s for the 4 of 4 configurations", t, re.M).group(1))
assert abs(total - sum(float(s) for _, _, s in est)) <= 0.06 * total, (total, est)
PY
echo "1 passed, 0 failed"
