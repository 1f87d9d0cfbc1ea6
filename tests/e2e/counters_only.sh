#!/usr/bin/env bash
# A run shows what it measured (issue 46): a sweep whose counters have no
# WallTime prints no "nan ms", no budget and no pick; the terminal,
# summary.md and report.html say why and show the counters it measured,
# labelled as everywhere else, in grouped digits, the terminal within 100
# columns.  Deterministic counters only: no Valgrind, a few seconds.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
cat > "$OUT/co.yaml" <<'YAML'
name: counters-only
resolution: [96, 64]
measure:
  warmup_frames: 1
  frames_per_sample: 1
  samples: { min: 2, max: 2, target_ci: 50% }
  counters: [VerticesSubmitted, VSInvocations, ClippingOutputPrimitives, FSInvocations, SamplesPassed]
sweep:
  mesh: [plane]
  technique: [texture, normal]
YAML
"$BIN" run "$OUT/co.yaml" --out "$OUT/r" >"$OUT/stdout" 2>"$OUT/stderr"
"$BIN" report "$OUT/r/latest" >/dev/null 2>&1   # the rebuilt files say the same
python3 - "$OUT" <<'PY'
import json, os, re, sys
out = sys.argv[1]
run = os.path.join(out, "r", "latest")
stdout, stderr = open(os.path.join(out, "stdout")).read(), open(os.path.join(out, "stderr")).read()
md = open(os.path.join(run, "summary.md")).read()
html = open(os.path.join(run, "report.html")).read()
j = json.load(open(os.path.join(run, "results.json")))
fails = []
def check(ok, what):
    if not ok:
        fails.append(what)

def grouped(v):   # plain digits, groups of three joined by U+202F from 1 000 up
    s = "%d" % round(v)
    if len(s) < 4:
        return s
    parts = []
    while s:
        parts.insert(0, s[-3:]); s = s[:-3]
    return "\u202f".join(parts)

why = "no timing counter measured: no budget or pick"
for name, text in (("stdout", stdout), ("stderr", stderr), ("summary.md", md), ("report.html", html)):
    check(re.search(r"\bnan\b", text, re.I) is None, name + " prints nan")
    check("Under 0 ms" not in text and "nothing fits" not in text, name + " names a budget of 0 ms")
check(why in stdout, "the terminal does not say why there is no pick")
check(why.capitalize() in md and why.capitalize() in html, "summary.md/report.html do not say why")
check(re.search(r"^- *$", md, re.M) is None, "summary.md has an empty bullet")
check("budget: none: no timing counter measured" in md, "summary.md's budget line")
check(stderr.count("counted (no timing counter)") == 2, "progress lines: " + stderr)
for line in stdout.splitlines():
    check(len(line) <= 100, "terminal line over 100 columns: %r" % line)
check(len(j["configs"]) == 2, "two configurations")
big = 0
for c in j["configs"]:
    label = c["label"].split(" · ", 1)[1]          # the scene is the heading
    fs = c["counters"]["FSInvocations"]["value"]
    sp = c["counters"]["SamplesPassed"]["value"]
    big += fs >= 1000 or sp >= 1000
    # a row per block of columns (the table wraps at 100 columns)
    row = " ".join(l for l in stdout.splitlines() if l.startswith("  " + label + " "))
    check(re.search(r"\s%s(\s|$)" % grouped(fs), row) and re.search(r"\s%s(\s|$)" % grouped(sp), row),
          "terminal row of %s: %r (want %s, %s)" % (label, row, grouped(fs), grouped(sp)))
    mdrow = [l for l in md.splitlines() if l.startswith("| " + label + " |")]
    check(mdrow and "| %s |" % grouped(fs) in mdrow[0] and "| %s |" % grouped(sp) in mdrow[0],
          "summary.md row of %s: %r" % (label, mdrow))
    check('<td class="n">%s</td>' % grouped(fs) in html, "report.html cell %s" % grouped(fs))
check(big > 0, "no counter reached 1 000: the grouping is not exercised")
check("Answer: what was measured" in html and 'class="answer counters"' in html, "report.html answer")
if fails:
    print("\n".join("FAIL: " + f for f in fails)); print(stdout); print(md); sys.exit(1)
print("counters-only ok")
PY
