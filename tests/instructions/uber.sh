#!/usr/bin/env bash
# No uber-shader cost: every technique with virtual_texture: off, counted
# under Valgrind by dmbench and by dmbench_plainshader, whose vt.glsl has
# no virtual-texturing code (tests/instructions/plain_vt.glsl).  dmbench's
# counts are the CI gate's run of ci/gate-techniques.yaml (RUNS, made once
# for the suite by test_ci_gate_run), whose configurations include those of
# uber.yaml key for key; this test counts dmbench_plainshader's.  The two
# must agree within 0.1 % per configuration: the configuration's shader
# holds only its own path (techniques/render.c, render__defines).  On the
# code where u_vt switched the path at run time, llvmpipe 22.3 ran the
# untaken virtual-texture sampler too and `normal` cost about 2x.
# Usage: uber.sh DMBENCH_PLAINSHADER RUNS  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
PLAIN=${1:?usage: uber.sh DMBENCH_PLAINSHADER RUNS}
RUNS=${2:?usage: uber.sh DMBENCH_PLAINSHADER RUNS}
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP="$SRC/tests/instructions/uber.yaml"
REAL="$RUNS/baseline-techniques/latest/results.json"
[ -f "$REAL" ] || { echo "no gate run in $RUNS (fixture test_ci_gate_run)"; exit 1; }
t0=$(date +%s)
"$PLAIN" run "$SWEEP" --out "$OUT/plain" --seed 1 --quiet
echo "one run: $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
python3 - "$REAL" "$OUT/plain/latest/results.json" <<'PY'
import json, sys
real, plain = ({c["key"]: c for c in json.load(open(p))["configs"]} for p in sys.argv[1:])
# every technique that samples the maps, pom also with soft shadows
assert len(plain) == 10, sorted(c["label"] for c in plain.values())
assert plain.keys() <= real.keys(), ("not in the gate's run:", sorted(plain.keys() - real.keys()))
for key, p in sorted(plain.items(), key=lambda kv: kv[1]["label"]):
    r = real[key]
    assert r["status"] == "ok" and p["status"] == "ok", (r["label"], r.get("reason"), p.get("reason"))
    a, b = r["counters"]["Instructions"]["median"], p["counters"]["Instructions"]["median"]
    rel = (a - b) / b
    print(f"{r['label']}: {a:.0f} with vt.glsl, {b:.0f} without VT code ({rel * 100:+.4f} %)")
    assert abs(rel) <= 1e-3, (r["label"], a, b)
print(f"{len(plain)} configurations: no technique pays for the virtual-texture path")
PY
