#!/usr/bin/env bash
# Every sweep shipped in sweeps/ plans on this driver (`dmbench run SWEEP
# --dry-run` exits 0), and every study-table sweep (s<N>-table*.yaml,
# s2-section*.yaml) carries a `published:` block whose labels each name one
# planned configuration (the dry run refuses any other with exit 2), with
# every published figure's label present in the printed plan.  A sweep
# with `drivers:` (s3-table7-1-sparse.yaml: zink) plans under its drivers.
set -euo pipefail
SRC=${DMBENCH_SOURCE_DIR:?}
BIN=${DMBENCH_BINARY:?}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
n_tables=0
for f in "$SRC"/sweeps/*.yaml; do
  name=$(basename "$f")
  if ! "$BIN" run "$f" --dry-run --out "$TMP/none" > "$TMP/plan.txt" 2> "$TMP/err.txt"; then
    echo "$name: the dry run failed:"; cat "$TMP/err.txt"; exit 1
  fi
  case "$name" in
    s[1-4]-table*.yaml|s2-section*.yaml) ;;
    *) continue ;;
  esac
  # a sweep with `drivers:` plans under each of them (`== driver X` heads
  # each plan); one whose driver is not installed here cannot be checked
  if grep -q '^== driver .*: left out' "$TMP/plan.txt"; then
    echo "$name: $(grep -m1 '^== driver' "$TMP/plan.txt"); its labels are not checked here"
    n_tables=$((n_tables + 1))
    continue
  fi
  n_tables=$((n_tables + 1))
  python3 - "$f" "$TMP/plan.txt" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
plan = open(sys.argv[2]).read()
m = re.search(r"^published:\n((?:[ #].*\n?)*)", text, re.M)
assert m, "%s: no published: block" % sys.argv[1]
block = m.group(1)
vals = re.search(r"^  values:\n((?:    .*\n?)*)", block, re.M)
assert vals, "%s: published: has no values" % sys.argv[1]
labels = [l.split(":")[0].strip().strip('"') for l in vals.group(1).splitlines()
          if l.strip() and not l.strip().startswith("#")]
assert labels, sys.argv[1]
base = re.search(r"^  baseline: (.*)$", block, re.M).group(1).strip().strip('"')
assert base in labels, (base, labels)
# each label's words hold for one planned configuration line
# (a planned line is "  KEY  SCENE · TECHNIQUE AXIS=VALUE...  estimate: ...",
# the one label form: the mesh leads the scene part, and only the axes that
# vary within the scene are shown)
rows = [re.sub(r"  estimate: .*$|  \(\d+ combinations folded\).*$", "", r[20:])
        for r in plan.splitlines() if re.match(r"^  [0-9a-f]{16}  ", r)]
def holds(word, row, implicit):
    scene, _, tech = row.partition(" · ")
    if word.startswith("mesh="):
        return scene.split(" ")[0] == word[5:]
    if "=" in word:   # an axis its scene does not vary is not in the label (implicit: it holds)
        key = word.split("=")[0] + "="
        return (" %s " % word) in " " + tech + " " or (implicit and (" " + key) not in " " + tech)
    return tech.split(" ")[0] == word
for l in labels:
    hits = [r for r in rows if all(holds(w, r, False) for w in l.split())]
    if not hits:
        hits = [r for r in rows if all(holds(w, r, True) for w in l.split())]
    assert len(hits) == 1, (sys.argv[1], l, hits)
print("%s: %d published labels, each one planned configuration" % (sys.argv[1], len(labels)))
PY
done
test "$n_tables" -ge 8 || { echo "expected the 8 study-table sweeps, found $n_tables"; exit 1; }

# S4's two tables compare pairs that differ the way S4's did.  Each table
# sweep runs with its own scene and a counters-only measure section:
#  - 8.3/8.4: one level per tile from helper points against the CPU's
#    bounding-sphere distance give different evaluation counts;
#    (the window is smaller: these counts do not depend on it);
#  - 8.1/8.2: the reduced body's vertex plus evaluation invocations match the
#    original's vertex invocations within 1 % (S4's matched complexity).
# The sweep's own quality line stays: both compare each configuration with
# itself (`technique: same`), where the default reference, reference-mesh
# 4x supersampled, made each run a third longer for images no check reads.
counts_of() {   # SWEEP OUT: run SWEEP with counters only into OUT
  python3 - "$1" "$TMP/$2.yaml" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
s = re.sub(r"^measure:\n(?:  .*\n)+", "measure:\n  warmup_frames: 1\n  frames_per_sample: 1\n"
           "  samples: { min: 2, max: 2 }\n  counters: [VSInvocations, TESInvocations]\n", s, flags=re.M)
s = re.sub(r"^resolution:.*$", "resolution: [256, 192]", s, flags=re.M)   # counts do not depend on it
open(sys.argv[2], "w").write(s)
PY
  "$BIN" run "$TMP/$2.yaml" --out "$TMP/$2" --quiet
}
counts_of "$SRC/sweeps/s4-table8-3-4.yaml" t834
counts_of "$SRC/sweeps/s4-table8-1-2.yaml" t812
python3 - "$TMP/t834/latest/results.csv" "$TMP/t812/latest/results.csv" <<'PY'
import csv, sys
rows = {r["lod"]: r for r in csv.DictReader(open(sys.argv[1]))}
pts, cpu = int(rows["object-points"]["TESInvocations"]), int(rows["object-cpu"]["TESInvocations"])
print("S4 8.3/8.4: TESInvocations object-points %d, object-cpu %d" % (pts, cpu))
assert pts > 0 and cpu > 0 and pts != cpu, (pts, cpu)
rows = {r["technique"]: r for r in csv.DictReader(open(sys.argv[2]))}
orig = int(rows["phong"]["VSInvocations"])
red = int(rows["tess-displacement"]["VSInvocations"]) + int(rows["tess-displacement"]["TESInvocations"])
print("S4 8.1/8.2: original VSInvocations %d, reduced VS + TES %d (%+.2f %%)"
      % (orig, red, 100.0 * (red - orig) / orig))
assert orig > 0 and abs(red - orig) <= 0.01 * orig, (orig, red)
PY
