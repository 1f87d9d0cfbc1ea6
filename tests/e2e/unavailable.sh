#!/usr/bin/env bash
# A counter the driver cannot provide is reported as unavailable with the
# reason — never as 0 — through results.json, results.csv and the report.
# The missing extension is simulated with DMBENCH_HIDE_EXTENSIONS.
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
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
echo "1 passed, 0 failed"
