#!/usr/bin/env bash
# test_loop_trips: LoopTrips counted by hand (docs/counters.md, "Loop
# trips").  On tests/stages/loop_trips.yaml every fragment runs steps/2
# iterations of the search loop, so each SIMD group runs steps/2 trips.
# llvmpipe runs a fragment shader on 4x4 blocks, once per triangle that
# touches the block (FSInvocations counts 16 a block), in groups of
# (vector bits / 32) fragments, the width its renderer string names
# ("LLVM 15.0.6, 256 bits": 8); on the square full-screen quad every group
# of every touched block holds a covered fragment of that triangle.  So
# LoopTrips = steps/2 * FSInvocations / group width, exactly; 0 for normal
# mapping.  No Valgrind; ~10 s.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
bits=$("$BIN" info | sed -n 's/.*renderer.*llvmpipe.* \([0-9]*\) bits).*/\1/p')
[ -n "$bits" ] || { echo "SKIP: not llvmpipe (the group width is llvmpipe's)"; exit 77; }
"$BIN" run "$SRC/tests/stages/loop_trips.yaml" --out "$OUT/r" --seed 1 --quiet
python3 - "$OUT/r/latest/results.json" "$bits" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
width = int(sys.argv[2]) // 32
bad, n = [], 0
for c in j["configs"]:
    p, k = c["params"], c["counters"]
    t = k.get("LoopTrips", {})
    if "unavailable" in t or "value" not in t and "median" not in t:
        bad.append(f"{p['technique']} {p['resolution']}: LoopTrips missing or unavailable: {t}")
        continue
    trips = t.get("value", t.get("median"))
    fs = k["FSInvocations"].get("value", k["FSInvocations"].get("median"))
    steps = p.get("steps", "-")   # normal mapping does not read steps: one configuration a resolution
    want = 0 if p["technique"] == "normal" else int(steps) // 2 * fs / width
    print(f"{p['technique']} {p['resolution']} steps {steps}: LoopTrips {trips:.0f}, "
          f"by hand {want:.0f} (FSInvocations {fs:.0f}, {width} fragments a group)")
    n += 1
    if trips != want:
        bad.append(f"{p['technique']} {p['resolution']} steps {steps}: {trips} != {want}")
if n != 10:
    bad.append(f"{n} configurations checked, expected 10")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
