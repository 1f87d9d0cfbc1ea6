#!/usr/bin/env bash
# No uber-shader cost: every technique with virtual_texture: off, counted
# under Valgrind by dmbench and by dmbench_plainshader, whose vt.glsl has
# no virtual-texturing code (tests/instructions/plain_vt.glsl).  The two
# must agree within 0.1 % per configuration: the configuration's shader
# holds only its own path (techniques/render.c, render__defines).  On the
# code where u_vt switched the path at run time, llvmpipe 22.3 ran the
# untaken virtual-texture sampler too and `normal` cost about 2x.
# Usage: uber.sh DMBENCH_PLAINSHADER  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
PLAIN=${1:?usage: uber.sh DMBENCH_PLAINSHADER}
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP="$SRC/tests/instructions/uber.yaml"
t0=$(date +%s)
"$BIN" run "$SWEEP" --out "$OUT/real" --seed 1 --quiet
"$PLAIN" run "$SWEEP" --out "$OUT/plain" --seed 1 --quiet
echo "two runs: $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
python3 - "$OUT/real/latest/results.json" "$OUT/plain/latest/results.json" <<'PY'
import json, sys
real, plain = ({c["key"]: c for c in json.load(open(p))["configs"]} for p in sys.argv[1:])
assert real.keys() == plain.keys(), (real.keys(), plain.keys())
for key, r in sorted(real.items(), key=lambda kv: kv[1]["label"]):
    p = plain[key]
    assert r["status"] == "ok" and p["status"] == "ok", (r["label"], r.get("reason"), p.get("reason"))
    a, b = r["counters"]["Instructions"]["median"], p["counters"]["Instructions"]["median"]
    rel = (a - b) / b
    print(f"{r['label']}: {a:.0f} with vt.glsl, {b:.0f} without VT code ({rel * 100:+.4f} %)")
    assert abs(rel) <= 1e-3, (r["label"], a, b)
print(f"{len(real)} configurations: no technique pays for the virtual-texture path")
PY
