#!/usr/bin/env bash
# End to end: `dmbench compare` and `dmbench baseline` with the real binary.
# Two runs of a small sweep never compare as a regression (exit 0 or 3) and
# compare exactly on counters (--counters-only exit 0); an injected 3x
# slowdown is a regression (exit 1); a changed deterministic counter is a
# regression naming it; a fingerprint mismatch is exit 2 unless allowed;
# JUnit, Markdown and JSON outputs parse and carry the verdicts; stores,
# tags and accepted baselines resolve; paired mode on one binary twice
# never reports a regression.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP="$SRC/tests/compare/e2e.yaml"

"$BIN" run "$SWEEP" --out "$OUT/a" --tag main --seed 1 --quiet
"$BIN" run "$SWEEP" --out "$OUT/b" --tag pr --seed 2 --quiet
A="$OUT/a/latest"; B="$OUT/b/latest"
python3 - "$A/results.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
bad = [(c["key"], c.get("reason")) for c in j["configs"] if c["status"] != "ok"]
assert not bad, ("the e2e sweep must run cleanly", bad)
PY

# Self: a run against itself (timing only, no Instructions) passes: the
# same samples on both sides are a ratio of exactly 1, never INCONCLUSIVE.
# Two separate runs: exactly equal on counters; their times may truly differ
# (drift of a shared machine between runs: a 1.6x slower second run was
# measured here), so only the outputs are checked — the paired mode below
# is the no-false-alarm check.
expect_compare 0 "$A" "$A" --json "$OUT/aa.json"
grep -q "^REGRESSION" "$OUT/stdout" && { echo "self-compare reported a regression"; exit 1; }
expect_compare "0 1 3" "$A" "$B" --junit "$OUT/ab.xml" --markdown "$OUT/ab.md" --json "$OUT/ab.json"
# the text output fits 100 columns (its lines were up to 374); a wrapped line
# goes on four columns in, and every configuration still has its row
python3 - "$OUT/stdout" "$OUT/ab.json" <<'PY'
import json, sys
lines = open(sys.argv[1], encoding="utf-8").read().splitlines()
wide = [l for l in lines if len(l) > 100]
assert not wide, "lines over 100 columns:\n" + "\n".join(wide)
keys = [c["key"] for c in json.load(open(sys.argv[2]))["configs"]]
rows = [l for l in lines if l.split(" ")[0] in ("REGRESSION", "INCONCLUSIVE", "IMPROVEMENT", "PASS", "SKIPPED")]
assert len(rows) == len(keys), (len(rows), len(keys))
for k in keys:
    assert any(k in r for r in rows), k
PY
expect_compare 0 "$A" "$B" --counters-only
expect_compare 0 "$A/results.json" "$OUT/b" --counters-only       # a file and an output root

# Injected slowdown, changed counter, other CPU: copies of A's results.json.
python3 - "$A/results.json" "$OUT" <<'PY'
import json, sys, copy
src, out = sys.argv[1], sys.argv[2]
j = json.load(open(src))
slow = copy.deepcopy(j)
for c in slow["configs"]:
    w = c["counters"]["WallTime"]
    w["samples"] = [s * 3.0 for s in w["samples"]]
    w["median"] *= 3.0
json.dump(slow, open(out + "/slow.json", "w"))
cnt = copy.deepcopy(j)
cnt["configs"][0]["counters"]["SamplesPassed"]["value"] += 1
json.dump(cnt, open(out + "/counter.json", "w"))
env = copy.deepcopy(j)
env["run"]["environment"]["cpu"] = "Some Other CPU"
json.dump(env, open(out + "/env.json", "w"))
PY
expect_compare 1 "$A" "$OUT/slow.json" --junit "$OUT/slow.xml" --markdown "$OUT/slow.md"
grep -q "^REGRESSION" "$OUT/stdout"
expect_compare 1 "$A" "$OUT/counter.json" --counters-only
sed -e ':a;N;$!ba;s/\n    / /g' "$OUT/stdout" | grep -q "SamplesPassed changed"   # wrapped lines joined
expect_compare 2 "$A" "$OUT/env.json"
grep -q "cpu: " "$OUT/stderr"
expect_compare "0 3" "$A" "$OUT/env.json" --allow-env-mismatch
grep -q "warning: environment fingerprints differ" "$OUT/stderr"
expect_compare 0 "$A" "$OUT/env.json" --counters-only              # CPU is not part of the driver

python3 - "$OUT" "$A/results.json" <<'PY'
import json, sys, xml.etree.ElementTree as ET
out, src = sys.argv[1], sys.argv[2]
n = len(json.load(open(src))["configs"])
labels = {c["key"]: c["label"] for c in json.load(open(src))["configs"]}   # the report's one label
for name, want in (("slow", "REGRESSION"), ("ab", "any")):
    root = ET.parse(f"{out}/{name}.xml").getroot()
    cases = root.findall(".//testcase")
    assert len(cases) == n, (name, len(cases))
    verdicts = []
    for c in cases:
        key = c.get("name")[-17:-1]
        assert c.get("name") == labels[key] + " [" + key + "]", (c.get("name"), labels[key])
        text = c.find("system-out").text
        assert text.startswith("verdict="), text
        verdicts.append(text.split()[0][8:])
        assert (c.find("failure") is not None) == (verdicts[-1] == "REGRESSION"), text
    if want == "REGRESSION":   # 1.5x slower: a regression, or (noisy) undecided, never a pass
        assert "REGRESSION" in verdicts and set(verdicts) <= {"REGRESSION", "INCONCLUSIVE"}, verdicts
md = open(f"{out}/slow.md").read()
assert "| Configuration | Base | New | Ratio | Change | 95% CI of ratio | Verdict | Note |" in md and md.count(" REGRESSION |") >= 1, md
j = json.load(open(f"{out}/aa.json"))
assert j["summary"]["REGRESSION"] == 0 and len(j["configs"]) == n, j["summary"]
assert j["summary"]["exit_code"] == 0 and j["summary"]["PASS"] == n, j["summary"]
assert len(json.load(open(f"{out}/ab.json"))["configs"]) == n
PY

# Stores and tags, accepted baselines.
expect_compare 0 --base-store "$OUT/a/dmbench.sqlite" --base-tag main --new-store "$OUT/b/dmbench.sqlite" --new-tag pr --counters-only
"$BIN" baseline accept "$A" --reason "e2e baseline" >/dev/null
expect_compare 0 --baseline --store "$OUT/a/dmbench.sqlite" "$B" --counters-only
grep -q "e2e baseline" "$OUT/stderr"
expect_compare 2 "$A" "$B" --time-treshold 5%
grep -q "did you mean '--time-threshold'" "$OUT/stderr"
expect_compare 2 "$A" "$OUT/missing.json"
for t in 0 100% 1.5 -1 abc; do                 # --threshold outside (0, 100 %)
  expect_compare 2 "$A" "$B" --threshold "$t"
  grep -q -- "--threshold" "$OUT/stderr"
done
expect_compare 0 "$A" "$A" --threshold 0.1%

# Paired mode, the same binary on both sides: never a regression.
# several separate runs a side: pooled one minimum per run; both sides must have several
expect_compare 2 "$A,$B" "$B"
grep -q "BASE has 2 runs and NEW 1: give both sides several runs" "$OUT/stderr" || { cat "$OUT/stderr"; exit 1; }
expect_compare "0 3" "$A,$B" "$B,$A"
sed -e ':a;N;$!ba;s/\n    / /g' "$OUT/stdout" | grep -q "several separate runs per side, each one sample" || { cat "$OUT/stdout"; exit 1; }
expect_compare 0 --paired "$BIN" "$BIN" "$SRC/tests/compare/paired.yaml" --rounds 2 --counters-only --quiet
echo "compare cli: all passed"
