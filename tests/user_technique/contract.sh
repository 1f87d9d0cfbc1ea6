#!/usr/bin/env bash
# User techniques without Valgrind (docs/user-techniques.md): the examples'
# parameters are axes (listed, folded by the planner), a technique's keys
# change with its file's text and no other's, `normal` rewritten as a user
# technique renders the built-in's image bit for bit, every bad file stops
# the run with exit 2 and its exact message, a hanging user shader fails
# alone through the watchdog and a NaN-writing one is counted by the
# quality metrics.
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# -- parameters are axes ------------------------------------------------------
"$BIN" list axes "$SRC/examples/relief.glsl" > "$OUT/axes.txt"
grep -Eq '^relief_linear +default 16 +int 1\.\.256' "$OUT/axes.txt" || fail "relief_linear not listed"
grep -Eq '^relief_binary +default 6 +int 0\.\.16' "$OUT/axes.txt" || fail "relief_binary not listed"
"$BIN" list techniques "$SRC/examples/pom-texel.glsl" > "$OUT/tech.txt"
grep -q '^pom-texel ' "$OUT/tech.txt" || fail "pom-texel not listed"
grep -q 'texel_rate, texel_min_steps, texel_max_steps$' "$OUT/tech.txt" || fail "pom-texel's axes"

# -- planning: folded as built-in axes are; keys follow the file ---------------
mkdir "$OUT/ex"
cp "$SRC/examples/relief.glsl" "$SRC/examples/pom-texel.glsl" "$SRC/examples/relief-vs-pom.yaml" "$OUT/ex/"
plan() { "$BIN" run "$OUT/ex/relief-vs-pom.yaml" --out "$OUT/dry" --dry-run 2>/dev/null; }
plan > "$OUT/plan1.txt"
# 3 techniques x steps 2 x relief_linear 2 x texel_rate 2 = 24 combinations;
# each technique reads one of the three axes: 2 configurations each
grep -q '24 combinations -> 6 configurations' "$OUT/plan1.txt" || fail "folding: $(head -1 "$OUT/plan1.txt")"
[ "$(grep -c ' · relief relief_linear=' "$OUT/plan1.txt")" = 2 ] || fail "relief configurations"
grep -q 'plane 320×180 · pom-texel texel_rate=4 ' "$OUT/plan1.txt" || fail "pom-texel label"
keys() { grep -E " · $1 " "$2" | awk '{print $1}' | sort; }
printf '\n// an edit\n' >> "$OUT/ex/relief.glsl"
plan > "$OUT/plan2.txt"
[ "$(keys pom "$OUT/plan1.txt")" = "$(keys pom "$OUT/plan2.txt")" ] || fail "pom's keys moved"
[ "$(keys pom-texel "$OUT/plan1.txt")" = "$(keys pom-texel "$OUT/plan2.txt")" ] || fail "pom-texel's keys moved"
for k in $(keys relief "$OUT/plan2.txt"); do
  ! grep -q "$k" "$OUT/plan1.txt" || fail "relief's key $k did not change with its source"
done
test ! -e "$OUT/dry" || fail "a dry run created its output"

# -- the examples end to end: measured, against the reference, in the report ---
"$BIN" run "$SRC/tests/user_technique/examples.yaml" --out "$OUT/ex-run" --quiet 2> /dev/null
python3 - "$OUT/ex-run/latest/results.json" <<'PY'
import json, sys
cs = json.load(open(sys.argv[1]))["configs"]
by = {(c["params"]["technique"], c["params"].get("relief_linear")): c for c in cs}
assert set(by) == {("pom", None), ("relief", 4), ("relief", 32), ("pom-texel", None)}, list(by)
for k, c in by.items():
    assert c["status"] == "ok", (k, c.get("reason"), c.get("log"))
    q = c["quality"]
    assert q["NonFinitePixels"] == 0 and 0 < q["SSIM"] <= 1 and q["PSNR"] > 10, (k, q)
    assert c["counters"]["SamplesPassed"]["value"] == by[("pom", None)]["counters"]["SamplesPassed"]["value"]
PY
grep -q 'relief relief_linear=32' "$OUT/ex-run/latest/report.html" || fail "relief not in the report"
grep -q 'pom-texel' "$OUT/ex-run/latest/report.html" || fail "pom-texel not in the report"

# -- bit for bit: normal as a user technique -----------------------------------
# (normal-color also writes the shading out in its own user_color())
"$BIN" render technique=normal resolution=96x54 light_count=2 --exr "$OUT/normal.exr" > /dev/null
for u in normal-user normal-color; do
  "$BIN" render technique="$SRC/tests/user_technique/$u.glsl" resolution=96x54 light_count=2 \
    --exr "$OUT/user.exr" > /dev/null
  "$BIN" diff "$OUT/normal.exr" "$OUT/user.exr" > "$OUT/diff.txt"
  grep -Eq 'RMSE +0$' "$OUT/diff.txt" && grep -Eq 'MaxError +0 ' "$OUT/diff.txt" \
    || fail "$u differs from normal: $(cat "$OUT/diff.txt")"
done

# the same for a level function: tess-uniform is lod: uniform
"$BIN" render technique=tess-displacement tess_level=12 resolution=96x54 --exr "$OUT/tess.exr" > /dev/null
"$BIN" render technique="$SRC/tests/user_technique/tess-uniform.glsl" tess_level=12 resolution=96x54 \
  --exr "$OUT/tess-user.exr" > /dev/null
"$BIN" diff "$OUT/tess.exr" "$OUT/tess-user.exr" > "$OUT/diff.txt"
grep -Eq 'RMSE +0$' "$OUT/diff.txt" && grep -Eq 'MaxError +0 ' "$OUT/diff.txt" \
  || fail "tess-uniform differs from tess-displacement: $(cat "$OUT/diff.txt")"
"$BIN" run "$SRC/tests/user_technique/tess.yaml" --out "$OUT/tess" --quiet 2> /dev/null
python3 - "$OUT/tess/latest/results.json" <<'PY'
import json, sys
cs = json.load(open(sys.argv[1]))["configs"]
by = {(c["params"]["technique"], c["params"].get("tess_view_step")): c for c in cs}
assert len(by) == 4, list(by)   # tess_view_step folds for the two that do not read it
val = lambda c, k: c["counters"][k]["value"]
ref, user = by[("tess-displacement", None)], by[("tess-uniform", None)]
for k in ("VSInvocations", "TCSPatches", "TESInvocations", "FSInvocations", "SamplesPassed"):
    assert val(ref, k) == val(user, k), (k, val(ref, k), val(user, k))
fine, coarse = by[("tess-view", 0.02)], by[("tess-view", 0.1)]
# on the 2-triangle plane at distance 3 an edge spans over 0.5 rad: 0.02 rad
# per segment asks more than 64 (clamped: as uniform 64), 0.1 far fewer
assert val(fine, "TESInvocations") == val(ref, "TESInvocations"), (val(fine, "TESInvocations"), val(ref, "TESInvocations"))
assert val(coarse, "TESInvocations") < val(ref, "TESInvocations") / 4, val(coarse, "TESInvocations")
print("tess: %d evaluations at level 64, tess-view 0.1 rad: %d" % (val(ref, "TESInvocations"), val(coarse, "TESInvocations")))
PY

# -- bad input: exit 2, the exact message, nothing run --------------------------
cd "$OUT"
bad() {   # bad NAME GLSL_TEXT EXPECTED_MESSAGE
  printf '%b' "$2" > "$1.glsl"
  printf 'name: bad\nresolution: [32, 18]\nsweep:\n  technique: [normal, %s.glsl]\n' "$1" > "$1.yaml"
  set +e; "$BIN" run "$1.yaml" --out bad --quiet 2> err.txt; rc=$?; set -e
  [ "$rc" = 2 ] || fail "$1: exit $rc, expected 2: $(cat err.txt)"
  python3 -c 'import sys; sys.exit(sys.argv[1] not in open("err.txt").read())' "$3" \
    || fail "$1: expected '$3', got: $(cat err.txt)"
  test ! -e bad || fail "$1: something was run"
}
OK='vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, SURFACE_H0); }\n'
bad compile '//@technique c1\nvec3 user_surface(vec2 uv, vec3 v)\n{\n    vec2 wrong = uv.xyx;\n    return vec3(uv, 0.5);\n}\n' \
  "dmbench: error: compile.glsl: user technique 'c1' does not compile; the driver says:
compile.glsl:4:2: error: initializer of type vec3 cannot be assigned to variable of type vec2"
bad noentry '//@technique c2\nvec3 surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }\n' \
  'dmbench: error: noentry.yaml:4:23: noentry.glsl: no entry point: define `vec3 user_surface(vec2 uv, vec3 v)` returning the visible point'"'"'s UV (xy) and height (z)'
bad signature '//@technique c3\n\nvec2 user_surface(vec2 uv)\n{ return uv; }\n' \
  'dmbench: error: signature.yaml:4:23: signature.glsl:3: entry point has the wrong signature `vec2 user_surface(vec2)`; expected `vec3 user_surface(vec2 uv, vec3 v)`'
bad collide "//@technique c4\n//@param steps int 1 64 8\n$OK" \
  "dmbench: error: collide.yaml:4:23: collide.glsl:2: parameter 'steps' collides with the built-in axis 'steps'; choose another name (\`dmbench list axes\` lists the names in use)"
bad badtype "//@technique c5\n//@param sharp bool 0 1 0\n$OK" \
  "dmbench: error: badtype.yaml:4:23: badtype.glsl:2: parameter 'sharp' has type 'bool'; valid types: int, float"
bad emptyrange "//@technique c6\n\n//@param sharp int 8 4 6\n$OK" \
  "dmbench: error: emptyrange.yaml:4:23: emptyrange.glsl:3: parameter 'sharp' has an empty range [8, 4] (MIN is above MAX)"
bad noname "$OK" \
  "dmbench: error: noname.yaml:4:23: noname.glsl: no \`//@technique NAME\` line: a user technique declares its name"
bad taken "//@technique pom\n$OK" \
  "dmbench: error: taken.yaml:4:23: taken.glsl:1: technique name 'pom' is taken (by a built-in technique); choose another in \`//@technique\`"
bad tesssig "//@technique c7\n//@base tess-level\nfloat user_tess_level(vec3 a)\n{ return 1.0; }\n" \
  "dmbench: error: tesssig.yaml:4:23: tesssig.glsl:3: entry point has the wrong signature \`float user_tess_level(vec3)\`; expected \`float user_tess_level(vec3 a, vec3 b)\`"
bad colorsig "//@technique c9\n$OK\nvec3 user_color(vec2 uv, vec3 v, vec3 at) { return vec3(1.0); }\n" \
  "dmbench: error: colorsig.yaml:4:23: colorsig.glsl:4: entry point has the wrong signature \`vec3 user_color(vec2, vec3, vec3)\`; expected \`vec4 user_color(vec2 uv, vec3 v, vec3 at)\`"
bad base "//@technique c8\n//@base vertex\n$OK" \
  "dmbench: error: base.yaml:4:23: base.glsl:2: unknown base 'vertex'; valid bases: fragment, tess-level"
printf 'name: bad\nsweep:\n  technique: [missing.glsl]\n' > missing.yaml
set +e; "$BIN" run missing.yaml --out bad --quiet 2> err.txt; rc=$?; set -e
[ "$rc" = 2 ] && grep -qF 'dmbench: error: missing.yaml:3:15: missing.glsl: technique file not found' err.txt \
  || fail "missing: exit $rc: $(cat err.txt)"
mkfifo fifo.glsl
printf 'name: bad\nsweep:\n  technique: [fifo.glsl]\n' > fifo.yaml
set +e; timeout 20 "$BIN" run fifo.yaml --out bad --quiet 2> err.txt; rc=$?; set -e
[ "$rc" = 2 ] && grep -qF 'dmbench: error: fifo.yaml:3:15: fifo.glsl: technique file is not a regular file (a directory, FIFO or device)' err.txt \
  || fail "fifo: exit $rc: $(cat err.txt)"
test ! -e bad || fail "something was run"

# -- run time: a hang fails alone, NaN is counted -------------------------------
"$BIN" run "$SRC/tests/user_technique/hang.yaml" --out "$OUT/hang" --quiet 2> /dev/null
python3 - "$OUT/hang/latest/results.json" <<'PY'
import json, sys
by = {c["params"]["technique"]: c for c in json.load(open(sys.argv[1]))["configs"]}
assert set(by) == {"normal", "hang", "nan"}, list(by)
assert by["hang"]["status"] == "failed", by["hang"]["status"]
assert "watchdog" in by["hang"]["reason"], by["hang"]["reason"]
assert by["normal"]["status"] == "ok" and by["nan"]["status"] == "ok"
assert by["normal"]["quality"]["NonFinitePixels"] == 0
# the right half of the plane (u > 0.5) is NaN: some pixels, not all
n = by["nan"]["quality"]["NonFinitePixels"]
assert 0 < n < 32 * 18, n
print("hang failed alone; nan: %d non-finite pixels" % n)
PY
echo "user techniques: contract ok"
