#!/usr/bin/env bash
# The Instructions gate end to end, under Valgrind: ci/gate.yaml run twice
# with dmbench and once with dmbench_slowshader (a fragment shader with a
# few more steps per fragment).  The first dmbench run is the CI gate's own
# (RUNS/baseline, made once for the suite by test_ci_gate_run with
# --seed 1); this test counts the second (--seed 2, another order) and the
# slower shader's.  Asserts: every configuration has
# Instructions; the two samples of a run agree within 0.01 % and the two
# runs within 0.05 %; `compare` of the two runs exits 0 (PASS everywhere, also without
# --counters-only); the slower shader is a REGRESSION on every
# configuration (exit 1) by more than the 0.5 % threshold; the original
# binary against it passes again (IMPROVEMENT, exit 0).
# Usage: gate.sh DMBENCH_SLOWSHADER RUNS  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
SLOW=${1:?usage: gate.sh DMBENCH_SLOWSHADER RUNS}
RUNS=${2:?usage: gate.sh DMBENCH_SLOWSHADER RUNS}
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP="$SRC/ci/gate.yaml"

# expect CODE ARGS...: expect_compare, with the verdicts in the test log.
expect() {
  expect_compare "$@"
  cat "$OUT/stdout"
}

[ -f "$RUNS/baseline/latest/results.json" ] || { echo "no gate run in $RUNS (fixture test_ci_gate_run)"; exit 1; }
ln -s "$(readlink -f "$RUNS/baseline")" "$OUT/a"
t0=$(date +%s)
"$BIN" run "$SWEEP" --out "$OUT/b" --seed 2 --quiet
t1=$(date +%s)
"$SLOW" run "$SWEEP" --out "$OUT/s" --seed 1 --quiet
t2=$(date +%s)
echo "one gate run: $((t1 - t0)) s; two: $((t2 - t0)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"

python3 - "$OUT/a/latest/results.json" "$OUT/b/latest/results.json" <<'PY'
import json, sys
runs = [{c["key"]: c for c in json.load(open(p))["configs"]} for p in sys.argv[1:]]
assert runs[0].keys() == runs[1].keys() and len(runs[0]) == 3, (runs[0].keys(), runs[1].keys())
for key, a in runs[0].items():
    b = runs[1][key]
    assert a["status"] == "ok" and b["status"] == "ok", (key, a.get("reason"), b.get("reason"))
    ia, ib = a["counters"]["Instructions"], b["counters"]["Instructions"]
    assert "unavailable" not in ia and "unavailable" not in ib, (key, ia, ib)
    for s in (ia["samples"], ib["samples"]):          # repeated samples of one run: within 0.01 %
        assert len(s) == 2 and abs(s[1] - s[0]) <= 1e-4 * s[0], (key, s)
    rel = abs(ib["median"] - ia["median"]) / ia["median"]
    # two runs in other orders and cache states: within 0.01 %, fifty times
    # below the gate's threshold (docs/counters.md, "Repeatability of
    # Instructions": a few instructions apart)
    assert rel <= 1e-4, (key, ia["median"], ib["median"], rel)
    ipp = a["counters"]["InstructionsPerPixel"]["value"]
    sp = a["counters"]["SamplesPassed"]["value"]
    assert abs(ipp - ia["median"] / sp) <= 1e-9 * ipp, (key, ipp, ia["median"], sp)
    print(f"{key}: {ia['median']:.0f} vs {ib['median']:.0f} instructions/frame (spread {rel:.2e})")
PY

expect 0 "$OUT/a/latest" "$OUT/b/latest"
expect 0 "$OUT/a/latest" "$OUT/b/latest" --counters-only
expect 1 "$OUT/a/latest" "$OUT/s/latest" --counters-only --json "$OUT/slow.json"
python3 - "$OUT/slow.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert len(j["configs"]) == 3   # the three meshes of ci/gate.yaml
for c in j["configs"]:
    assert c["verdict"] == "REGRESSION", c
    assert c["instructions_ratio"] > 1.005, c
    print(f"slower shader detected on {c['configuration']}: +{(c['instructions_ratio'] - 1) * 100:.2f} % instructions")
PY
expect 0 "$OUT/s/latest" "$OUT/b/latest" --counters-only   # restored: faster again, passes
grep -q "IMPROVEMENT" "$OUT/stdout"
echo "instructions gate: all passed"
