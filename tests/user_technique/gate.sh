#!/usr/bin/env bash
# The instruction gate on user techniques, under Valgrind
# (docs/user-techniques.md): tests/user_technique/gate.yaml run once;
# normal written as a user technique has the built-in's pipeline statistics
# exactly and its Instructions within 0.1 %; then relief.glsl made more
# expensive (twice the binary refinement steps, same parameters) and run
# again: its key changes with its source, `compare` pairs the two by their
# parameters, says the source changed, and fails the gate (exit 1,
# REGRESSION on Instructions); `export` writes the user technique's figures.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
cp "$SRC/tests/user_technique/gate.yaml" "$SRC/tests/user_technique/normal-user.glsl" \
   "$SRC/examples/relief.glsl" "$OUT/"

t0=$(date +%s)
"$BIN" run "$OUT/gate.yaml" --out "$OUT/a" --quiet
echo "one run: $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
python3 - "$OUT/a/latest/results.json" <<'PY'
import json, sys
by = {c["params"]["technique"]: c for c in json.load(open(sys.argv[1]))["configs"]}
assert set(by) == {"normal", "normal-user", "relief"}, list(by)
for t, c in by.items():
    assert c["status"] == "ok", (t, c.get("reason"), c.get("log"))
stats = ["VerticesSubmitted", "PrimitivesSubmitted", "VSInvocations", "ClippingInputPrimitives",
         "ClippingOutputPrimitives", "PrimitivesGenerated", "FSInvocations", "SamplesPassed"]
n, u = by["normal"]["counters"], by["normal-user"]["counters"]
for s in stats:
    assert n[s]["value"] == u[s]["value"], (s, n[s]["value"], u[s]["value"])
ni, ui = n["Instructions"]["median"], u["Instructions"]["median"]
rel = (ui - ni) / ni
assert abs(rel) <= 1e-3, (ni, ui, rel)
print(f"normal {ni:.0f}, normal-user {ui:.0f} instructions/frame ({rel * 100:+.3f} %)")
PY

# the user's shader made more expensive; only it is measured again
sed -i 's/i < u_relief_binary; i++/i < 2 * u_relief_binary; i++/' "$OUT/relief.glsl"
grep -q '2 \* u_relief_binary' "$OUT/relief.glsl"
sed -i 's/technique: \[normal, normal-user.glsl, relief.glsl\]/technique: [relief.glsl]/' "$OUT/gate.yaml"
"$BIN" run "$OUT/gate.yaml" --out "$OUT/b" --quiet
expect_compare 1 "$OUT/a/latest" "$OUT/b/latest" --counters-only --json "$OUT/cmp.json"
cat "$OUT/stdout"
sed -e ':a;N;$!ba;s/\n    / /g' "$OUT/stdout" | grep -q "technique source changed: key"   # wrapped lines joined
python3 - "$OUT/cmp.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert len(j["configs"]) == 1, j["configs"]
c = j["configs"][0]
assert c["verdict"] == "REGRESSION" and c["instructions_ratio"] > 1.005, c
print(f"relief with twice the refinement: +{(c['instructions_ratio'] - 1) * 100:.2f} % instructions, REGRESSION")
PY

"$BIN" export "$OUT/a/latest" --format gbench -o "$OUT/gbench.json"
python3 - "$OUT/gbench.json" <<'PY'
import json, sys
names = [b["name"] for b in json.load(open(sys.argv[1]))["benchmarks"]]
assert any("relief" in n for n in names) and any("normal-user" in n for n in names), names
PY
echo "user techniques: instruction gate ok"
