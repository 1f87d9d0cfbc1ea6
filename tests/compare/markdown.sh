#!/usr/bin/env bash
# `dmbench compare --markdown` as a CI step uses it, on synthetic runs (no
# GL): the file is always written — also when nothing compared (no
# configuration in common, environments differ, a side missing), saying
# why — and --only-changed leaves the PASS rows out.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
S="$SRC/tests/compare/synth.py"
python3 "$S" "$OUT/a.json" --seed 1 --configs 6
python3 "$S" "$OUT/b.json" --seed 1 --configs 6 --id synth-b
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
j = json.load(open(out + "/a.json"))
for c in j["configs"]:   # other keys and other parameters: nothing to pair
    c["key"] = "f" + c["key"][1:]
    c["params"]["steps"] = str(int(c["params"].get("steps", "0")) + 1)
json.dump(j, open(out + "/other.json", "w"))
j = json.load(open(out + "/a.json"))
j["run"]["environment"]["cpu"] = "Another CPU"
json.dump(j, open(out + "/env.json", "w"))
j = json.load(open(out + "/b.json"))
j["configs"][2]["counters"]["SamplesPassed"]["value"] += 1
json.dump(j, open(out + "/changed.json", "w"))
PY

# md_case WANT_RC PATTERN ARGS...: compare exits WANT_RC and the Markdown file
# exists and holds PATTERN.
md_case() {
  local want=$1 pat=$2 rc=0; shift 2
  rm -f "$OUT/pr.md"
  "$BIN" compare "$@" --markdown "$OUT/pr.md" --quiet >/dev/null 2>&1 || rc=$?
  if [ "$rc" -eq "$want" ] && [ -s "$OUT/pr.md" ] && grep -q -- "$pat" "$OUT/pr.md"; then pass=$((pass+1))
  else fail=$((fail+1)); echo "FAIL: compare $* -> rc $rc (want $want); pr.md: $(head -c 300 "$OUT/pr.md" 2>/dev/null || echo missing) (want /$pat/)"; fi
}
md_case 0 "^## dmbench compare: PASS — 0 regressed, 0 inconclusive, 0 improved, 6 passed of 6 configurations" "$OUT/a.json" "$OUT/b.json"
md_case 0 "<details><summary>6 PASS</summary>" "$OUT/a.json" "$OUT/b.json"
md_case 1 "| REGRESSION | SamplesPassed changed 2115 → 2116 |" "$OUT/a.json" "$OUT/changed.json"
md_case 1 "<details><summary>5 PASS" "$OUT/a.json" "$OUT/changed.json"
md_case 2 "^## dmbench compare: nothing compared" "$OUT/a.json" "$OUT/other.json"
md_case 2 "no configuration in common" "$OUT/a.json" "$OUT/other.json"
md_case 2 "^- cpu: 'Synthetic CPU' (BASE) vs 'Another CPU' (NEW)" "$OUT/a.json" "$OUT/env.json"
md_case 2 "missing.json: no such file" "$OUT/a.json" "$OUT/missing.json"
# --only-changed: the changed row, no PASS block
"$BIN" compare "$OUT/a.json" "$OUT/changed.json" --markdown "$OUT/pr.md" --only-changed --quiet >/dev/null 2>&1
if grep -q "| REGRESSION |" "$OUT/pr.md" && ! grep -q "<details>" "$OUT/pr.md"; then pass=$((pass+1))
else fail=$((fail+1)); echo "FAIL: --only-changed"; cat "$OUT/pr.md"; fi
tally
