#!/usr/bin/env bash
# End to end: a sweep's `published:` block goes with the run (published.json
# with each label's configuration key) and the report sets it beside the
# measured frame times as ratios to the baseline; a label that names no
# planned configuration is refused at plan time with exit 2, file:line and
# a did-you-mean over the planned labels.
set -euo pipefail
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
BIN=${DMBENCH_BINARY:?}

cat > "$OUT/pub.yaml" <<'YAML'
name: pub
resolution: [96, 54]
measure: { warmup_frames: 1, frames_per_sample: 2, samples: { min: 3, max: 3 }, max_seconds: 0.5 }
sweep:
  mesh: [plane]
  technique: [phong, pom]
  steps: [8, 32]
published:
  source: { study: "Test study (2010)", table: "Table 9", gpu: "GPU X" }
  unit: fps
  baseline: phong
  values: { phong: 100, "pom steps=8": 50, "steps=32 pom": 25 }
YAML
sed 's/"steps=32 pom": 25/"pom stesp=32": 25/' "$OUT/pub.yaml" > "$OUT/bad.yaml"
set +e
"$BIN" run "$OUT/bad.yaml" --dry-run --out "$OUT/bad" 2> "$OUT/err.txt"
rc=$?
set -e
cat "$OUT/err.txt"
test "$rc" = 2 || { echo "bad label: exit $rc, expected 2"; exit 1; }
grep -qF "bad.yaml:12: published label 'pom stesp=32' names no planned configuration; did you mean 'pom steps=32'? valid planned labels: phong, pom steps=8, pom steps=32" "$OUT/err.txt"

# a bad block is refused when the file is read (exit 2, file:line:col)
sed 's/unit: fps/unit: hz/' "$OUT/pub.yaml" > "$OUT/unit.yaml"
set +e
"$BIN" run "$OUT/unit.yaml" --dry-run 2> "$OUT/err2.txt"
rc=$?
set -e
test "$rc" = 2 || { echo "bad unit: exit $rc, expected 2"; exit 1; }
grep -qF "unit.yaml:10:9: published.unit: unknown unit 'hz'; did you mean 'ms'? valid units: fps, seconds, ms" "$OUT/err2.txt" ||
  { cat "$OUT/err2.txt"; exit 1; }

"$BIN" run "$OUT/pub.yaml" --out "$OUT/s" --quiet
python3 - "$OUT/s/latest" <<'PY'
import json, re, sys
d = sys.argv[1]
pub = json.load(open(d + "/published.json"))
res = json.load(open(d + "/results.json"))
keys = {}
for c in res["configs"]:
    p = c["params"]
    keys[(p["technique"], str(p["steps"]) if "steps" in p else None)] = (c["key"], c)
want = {"phong": ("phong", None), "pom steps=8": ("pom", "8"), "steps=32 pom": ("pom", "32")}
assert [v["label"] for v in pub["values"]] == list(want), pub
for v in pub["values"]:
    assert v["key"] == keys[want[v["label"]]][0], (v, keys)
md = open(d + "/summary.md").read()
html = open(d + "/report.html").read()
assert "## Published figures beside ours" in md, md
assert 'id="published"' in html
def wall(c):
    return c["counters"]["WallTime"]["median"]
base = wall(keys[("phong", None)][1])
for label, pr in (("pom steps=8", 2.0), ("steps=32 pom", 4.0)):
    mr = wall(keys[want[label]][1]) / base
    row = re.search(r"^\| %s \| [^|]+ \| %.3f \| [^|]+ \| %.3f \| ([^|]+) \|$" % (re.escape(label), pr, mr), md, re.M)
    assert row, (label, pr, mr, md)
    f = max(pr / mr, mr / pr)
    same = lambda r: (r > 1.05) - (r < 0.95)
    agrees = same(pr) == same(mr) and f <= 2
    assert row.group(1).startswith("agrees") == agrees, (row.group(1), pr, mr)
print("ok")
PY

# sharded runs merged: the merged run keeps the published figures (the
# labels' keys are the same configurations) and its report has the section
"$BIN" run "$OUT/pub.yaml" --out "$OUT/k1" --shard 1/2 --quiet
"$BIN" run "$OUT/pub.yaml" --out "$OUT/k2" --shard 2/2 --quiet
"$BIN" merge "$OUT/m" "$OUT/k1/latest" "$OUT/k2/latest" > /dev/null
cmp -s "$OUT/s/latest/published.json" "$OUT/m/latest/published.json" ||
  { echo "merged run: published.json missing or different"; exit 1; }
grep -qF "## Published figures beside ours" "$OUT/m/latest/summary.md" ||
  { echo "merged run: no published section in summary.md"; exit 1; }
echo "merge ok"

