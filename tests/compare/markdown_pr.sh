#!/usr/bin/env bash
# `dmbench compare --markdown` fit to paste into a code review (issue 46),
# on synthetic runs (no GL): no HTML entities, notes whole, one precision
# per column, a signed change that agrees with the ratio, the machine's
# load and precision lines of stdout, advice capped at 100 more samples;
# and --rounds that can never reach a verdict refused with the minimum.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
S="$SRC/tests/compare/synth.py"
python3 "$S" "$OUT/a.json" --seed 1 --configs 6
python3 "$S" "$OUT/b.json" --seed 2 --configs 6 --id synth-b --scale 1.08 --cv 0.05
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
for name, scale in (("a", 1.0), ("b", 1.012)):   # exact counts: +1.2 % is an instruction regression
    j = json.load(open(f"{out}/{name}.json"))
    j["configs"][2]["counters"]["SamplesPassed"]["value"] += (name == "b")
    json.dump(j, open(f"{out}/{name}.json", "w"))
    for i, c in enumerate(j["configs"]):
        c["counters"]["Instructions"] = {"unit": "items", "deterministic": True, "partial": False,
                                         "value": round(12345678 * (i + 1) * (scale if i == 4 else 1))}
    json.dump(j, open(f"{out}/{name}i.json", "w"))
PY
"$BIN" compare "$OUT/a.json" "$OUT/b.json" --markdown "$OUT/pr.md" --json "$OUT/cmp.json" >"$OUT/stdout" 2>"$OUT/stderr"
rc=$?
[ "$rc" -eq 1 ] && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: compare exited $rc, want 1"; cat "$OUT/stderr"; }
"$BIN" compare "$OUT/ai.json" "$OUT/bi.json" --markdown "$OUT/pri.md" --quiet 2>/dev/null
cat "$OUT/pr.md" "$OUT/pri.md"
python3 - "$OUT" <<'PY' && pass=$((pass+1)) || fail=$((fail+1))
import json, re, sys
out = sys.argv[1]
md = open(f"{out}/pr.md").read()
stdout = open(f"{out}/stdout").read()
items = json.load(open(f"{out}/cmp.json"))["configs"]
mdi = open(f"{out}/pri.md").read()
fails = []
def check(ok, what):
    if not ok:
        fails.append(what)
check(re.search(r"&(gt|lt|amp|quot|#\d+);", md + mdi) is None, "an HTML entity in the markdown")
# the machine's load and precision, as stdout prints them
for line in stdout.splitlines():
    if line.startswith(("machine: ", "precision ")):
        check("- " + line.replace("->", "→").replace(">=", "≥") in md, "stdout line missing: " + line)
check("load 0.50" in md and "- precision BASE:" in md and "- precision NEW:" in md, "load/precision lines")
# the table: one precision per column, the change signed and equal to the ratio's
rows = [l for l in md.splitlines() if l.startswith("| plane")]
check(len(rows) == 6, "%d rows, want 6" % len(rows))
rowsi = [l for l in mdi.splitlines() if l.startswith("| plane")]
check(len(rowsi) == 6 and any("| REGRESSION |" in l and "+1.20 %" in l for l in rowsi),
      "the instruction table: %s" % rowsi)
rows += rowsi
instr_rows = 0
for l in rows:
    cells = [c.strip() for c in l.strip("|").split(" | ")]
    name, base, new, ratio, change, ci = cells[:6]
    for v in (base, new):
        ok = re.fullmatch(r"\d+\.\d{3} ms", v) or re.fullmatch(r"\d{1,3}(\u202f\d{3})* instr", v)
        check(ok, "Base/New %r of %s" % (v, name))
    instr_rows += base.endswith("instr")
    if ratio != "–":
        check(re.fullmatch(r"\d+\.\d{4}", ratio), "ratio %r" % ratio)
        m = re.fullmatch(r"([+−])(\d+\.\d{2}) %", change)
        check(m, "change %r" % change)
        if m:
            signed = float(m.group(2)) * (1 if m.group(1) == "+" else -1)
            check(abs(signed - (float(ratio) - 1) * 100) <= 0.006, "change %s vs ratio %s" % (change, ratio))
    check(ci == "–" or re.fullmatch(r"\d\.\d{3}–\d\.\d{3}", ci), "CI %r" % ci)
check(instr_rows >= 1, "no instruction row (grouped digits)")
# notes whole: every changed item's note, as it reads in markdown
for it in items:
    note = it.get("note")
    if it["verdict"] == "PASS" or not note or it.get("machine_held"):
        continue
    want = note.replace("->", "→").replace(">=", "≥").replace("<=", "≤")
    check(want in md, "note cut or changed: %r" % want)
    n = re.search(r"about (\d+) more", note)
    check(not n or int(n.group(1)) <= 100, "advice past 100: %r" % note)
check("more than 100 samples per side: the difference is below what this machine can resolve" in md,
      "no capped advice in the markdown (the synthetic runs have CIs too wide to decide)")
if fails:
    print("\n".join("FAIL: " + f for f in fails)); sys.exit(1)
print("markdown ok")
PY
# --rounds: 0 is not a count; fewer than the paired test's minimum (5 at
# --alpha 0.01, 4 at 0.05: 2/C(2n,n) < alpha) can never reach a verdict;
# rounds without --paired are refused.  All before any run starts.
expect_refused 2 "rounds" -- "$BIN" compare --paired "$BIN" "$BIN" "$SRC/tests/e2e/tiny.yaml" --rounds 0
expect_refused 2 "--rounds 3: too few to reach a verdict.*fewer than 5 rounds" -- \
  "$BIN" compare --paired "$BIN" "$BIN" "$SRC/tests/e2e/tiny.yaml" --rounds 3
expect_refused 2 "--rounds 3: too few.*--alpha 0.05.*fewer than 4 rounds" -- \
  "$BIN" compare --paired "$BIN" "$BIN" "$SRC/tests/e2e/tiny.yaml" --rounds 3 --alpha 0.05
expect_refused 2 "--rounds 6: rounds are for --paired only" -- "$BIN" compare "$OUT/a.json" "$OUT/b.json" --rounds 6
tally
