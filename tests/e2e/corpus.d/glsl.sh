# corpus.d/glsl.sh — user GLSL techniques (header, parameters, sources
# changed during a run), sourced by corpus.sh.

# uglsl NAME HEADER...: a user technique file in $OUT/glsl with the header
# lines given and built-in normal's entry point; prints its path.
uglsl() {
  local f="$OUT/glsl/$1.glsl"; shift; mkdir -p "$OUT/glsl"
  { printf '%s\n' "$@"; echo 'vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, SURFACE_H0); }'; } > "$f"
  echo "$f"
}
# usweep NAME GLSL [COUNTERS]: a 16x16 sweep of built-in normal and the file.
usweep() {
  sweep "$1" "resolution: [16, 16]" "measure:" "  warmup_frames: 1" "  frames_per_sample: 1" \
    "  samples: { min: 2, max: 2 }" "  max_seconds: 1" "  counters: [${3:-WallTime}]" \
    "sweep:" "  mesh: [plane]" "  technique: [normal, $2]"
}
# configs STORE: "N M", the configurations stored and how many are ok.
configs() {
  python3 -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); print(*c.execute(\"select count(*), count(case when status='ok' then 1 end) from configs\").fetchone())" "$1" 2>/dev/null
}
# check WHAT GOT WANT: one pass or fail, for a case that was judged here
# (WHAT starts with its id; not under CORPUS_PROBE or when CORPUS_ONLY left it out).
check() {
  [ -z "${CORPUS_PROBE:-}" ] && [ -n "${RAN[${1%%:*}]+x}" ] || return 0
  if [ "$2" = "$3" ]; then pass=$((pass+1)); else echo "FAIL: $1: got '$2', want '$3'"; fail=$((fail+1)); fi
}

if wanted glsl/; then
# ---- @param values the shader would not receive as recorded ----
f=$(uglsl bigint "//@technique bigint" "//@param bign int 0 4294967296 1")
hcase glsl/int-range 2 "bigint.glsl:2: parameter 'bign': MAX 4294967296 does not fit the GLSL type int" \
  -- "$BIN" run "$(usweep bigint "$f")" --out "$NEVER"
f=$(uglsl bigfloat "//@technique bigfloat" "//@param bigf float 0 1e300 1")
hcase glsl/float-range 2 "bigfloat.glsl:2: parameter 'bigf': MAX 1e300 does not fit the GLSL type float" \
  -- "$BIN" run "$(usweep bigfloat "$f")" --out "$NEVER"
# ---- names that would be a second results.csv column or a second uniform ----
for n in key status scene label path_p99_ms; do
  f=$(uglsl "col-$n" "//@technique col-$n" "//@param $n int 0 4 1")
  hcase "glsl/param-$n" 2 "col-$n.glsl:2: parameter '$n' would be a second '$n' column of results.csv" \
    -- "$BIN" run "$(usweep "col-$n" "$f")" --out "$NEVER"
done
for n in shininess f0; do
  f=$(uglsl "uni-$n" "//@technique uni-$n" "//@param $n float 0 1 0.5")
  hcase "glsl/param-uniform-$n" 2 "uni-$n.glsl:2: parameter '$n' would declare the uniform u_$n" \
    -- "$BIN" run "$(usweep "uni-$n" "$f")" --out "$NEVER"
done
# (a shader the GLSL compiler crashes on: children.sh, children/compiler-crash-*)
# ---- #include: refused in code at its line, prose in a comment ----
f=$(uglsl include "//@technique include" '#include "lighting.glsl"')
hcase glsl/include 2 "include.glsl:2: #include is not supported in a user technique" \
  -- "$BIN" run "$(usweep include "$f")" --out "$NEVER"
f=$(uglsl include-comment "//@technique include-comment" "/* was:" '#include "nowhere.glsl"' "*/")
hcase glsl/include-comment 0 "" -- "$BIN" render "technique=$f" resolution=16x16 --png "$OUT/glsl/ic.png"
# ---- header text: control bytes shown as '?', text that is not UTF-8 refused ----
f=$(uglsl latin1 "//@technique latin1" $'//@summary caf\xe9')
hcase glsl/latin1-summary 2 "latin1.glsl:2: byte 0xe9 at column 15 is not UTF-8" \
  -- "$BIN" list techniques "$f" --json
f=$(uglsl ansi "//@technique ansi" $'//@summary \e]0;pwned\a\e[2J')
hcase glsl/ansi-summary 0 "" -- "$BIN" list techniques "$f"
check "glsl/ansi-summary: control bytes on the terminal" "$("$BIN" list techniques "$f" | grep -c $'\e')" 0

# ---- a source edited while a run is going: one run, one version of each ----
# The "valgrind" of these cases (DMBENCH_VALGRIND) copies $EDIT over the
# user's file once, as an editor would while the counting child starts, then
# runs the child without Valgrind (its counts are then unavailable, quickly).
D="$OUT/glsl/edit"; mkdir -p "$D"
cat > "$D/vg.sh" <<'EOF'
#!/bin/sh
[ -n "$EDIT" ] && [ ! -e "$EDIT.done" ] && cp "$EDIT" "$TARGET" && : > "$EDIT.done"
while [ "${1#--}" != "$1" ]; do shift; done
exec "$@"
EOF
chmod +x "$D/vg.sh"
u=$(uglsl edit-u "//@technique edit-u"); cp "$u" "$D/orig.glsl"
uglsl edit-valid "//@technique edit-u" "// edited" > /dev/null
printf '//@technique edit-u\nvec3 user_surface(vec2 uv, vec3 v) { return vec3(uv) }\n' > "$OUT/glsl/edit-broken.glsl"
s=$(usweep edit "$u" "WallTime, Instructions")
for e in valid broken; do
  cp "$D/orig.glsl" "$u"; rm -rf "$D/$e" "$OUT/glsl/edit-$e.glsl.done"
  hcase "glsl/edited-during-run-$e" 2 "edit-u.glsl: the user technique's file changed since the run started" \
    -- env DMBENCH_VALGRIND="$D/vg.sh" EDIT="$OUT/glsl/edit-$e.glsl" TARGET="$u" DMBENCH_COUNT_JOBS=1 \
       "$BIN" run "$s" --out "$D/$e" --quiet
  check "glsl/edited-during-run-$e: configurations recorded" "$(configs "$D/$e/dmbench.sqlite")" "0 0"
done
# the file restored: --resume measures both, normal included
cp "$D/orig.glsl" "$u"
hcase glsl/restored-resume 0 "" -- env DMBENCH_VALGRIND="$D/vg.sh" DMBENCH_COUNT_JOBS=1 \
  "$BIN" run "$s" --out "$D/broken" --quiet --resume
check "glsl/restored-resume: configurations" "$(configs "$D/broken/dmbench.sqlite")" "2 2"
# edited after the run: --resume refuses to add the other version
cp "$OUT/glsl/edit-valid.glsl" "$u"
hcase glsl/edited-resume 2 "--resume: $u: the user technique's file changed since run" \
  -- env DMBENCH_VALGRIND="$D/vg.sh" DMBENCH_COUNT_JOBS=1 "$BIN" run "$s" --out "$D/broken" --quiet --resume
check "glsl/edited-resume: configurations" "$(configs "$D/broken/dmbench.sqlite")" "2 2"
cp "$D/orig.glsl" "$u"
fi
