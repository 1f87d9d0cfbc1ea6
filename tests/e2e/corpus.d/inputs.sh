# corpus.d/inputs.sh — the user's map and mesh files edited during a run or
# before --resume (run/inputs.h: one run measures one version of each
# file); sourced by corpus.sh after glsl.sh (configs, check).

if wanted map/ || wanted mesh/; then
D="$OUT/inputs"; mkdir -p "$D"
# png FILE GREY: a 16x16 grey PNG height map.
png() {
  python3 - "$1" "$2" <<'PY'
import struct, sys, zlib
path, v = sys.argv[1], int(sys.argv[2])
raw = b"".join(b"\0" + bytes([v] * 48) for _ in range(16))
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 16, 16, 8, 2, 0, 0, 0))
                       + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
PY
}
png "$D/h.png" 128; png "$D/h-edited.png" 200; cp "$D/h.png" "$D/h-orig.png"
cp "$SRC/tests/data/meshes/cube.obj" "$D/m.obj"; cp "$D/m.obj" "$D/m-orig.obj"
# isweep NAME COUNTERS: the built-in cube, then the user's mesh, both with the
# user's height map: four configurations in two scenes, cube first.
isweep() {
  sweep "$1" "resolution: [16, 16]" "measure:" "  warmup_frames: 1" "  frames_per_sample: 1" \
    "  samples: { min: 2, max: 2 }" "  max_seconds: 1" "  counters: [$2]" \
    "scene:" "  material: { height: $D/h.png }" \
    "sweep:" "  mesh: [cube, file:$D/m.obj]" "  technique: [normal, pom]"
}
# The counting "valgrind" (DMBENCH_VALGRIND) copies $EDIT over $TARGET once,
# as an editor would while the child starts, then runs the child without
# Valgrind (its counts are unavailable, quickly).
cat > "$D/vg.sh" <<'SH'
#!/bin/sh
[ -n "$EDIT" ] && [ ! -e "$TARGET.done" ] && cp "$EDIT" "$TARGET" && : > "$TARGET.done"
while [ "${1#--}" != "$1" ]; do shift; done
exec "$@"
SH
# watch.sh FILE CMD...: runs CMD; once its progress shows the second of four
# configurations done (the cube scene measured, the user mesh's scene next),
# appends a comment line to FILE; stderr passed on, CMD's exit code kept.
cat > "$D/watch.sh" <<'SH'
#!/bin/bash
f=$1; shift
exec 3>&1
"$@" 2>&1 1>&3 | while IFS= read -r l; do
  printf '%s\n' "$l" >&2
  case $l in "[2/4]"*) echo "# edited" >> "$f" ;; esac
done
exit "${PIPESTATUS[0]}"
SH
chmod +x "$D/vg.sh" "$D/watch.sh"

s=$(isweep inputs-time WallTime)
# the mesh edited while the measuring children time the run: the child that
# would commit the user mesh's scene finds it changed; the cube's scene stays
hcase mesh/edited-while-timed 2 "m.obj: the mesh file changed since the run started" \
  -- "$D/watch.sh" "$D/m.obj" "$BIN" run "$s" --out "$D/timed"
check "mesh/edited-while-timed: configurations recorded" "$(configs "$D/timed/dmbench.sqlite")" "2 2"
# the file restored: --resume measures the rest
cp "$D/m-orig.obj" "$D/m.obj"
hcase mesh/restored-resume 0 "" -- "$BIN" run "$s" --out "$D/timed" --quiet --resume
check "mesh/restored-resume: configurations" "$(configs "$D/timed/dmbench.sqlite")" "4 4"
# edited after the run: --resume refuses to add another version
echo "# edited" >> "$D/m.obj"
hcase mesh/edited-resume 2 "--resume: $D/m.obj: the file changed since run" \
  -- "$BIN" run "$s" --out "$D/timed" --quiet --resume
cp "$D/m-orig.obj" "$D/m.obj"
touch "$D/m.obj"   # the same bytes, a new time: not a change
hcase mesh/touched-resume 0 "" -- "$BIN" run "$s" --out "$D/timed" --quiet --resume

s=$(isweep inputs-count "WallTime, Instructions")
# the height map replaced while the Instructions pass counts: nothing recorded
hcase map/edited-during-count 2 "h.png: the map file changed since the run started" \
  -- env DMBENCH_VALGRIND="$D/vg.sh" EDIT="$D/h-edited.png" TARGET="$D/h.png" DMBENCH_COUNT_JOBS=1 \
     "$BIN" run "$s" --out "$D/count" --quiet
check "map/edited-during-count: configurations recorded" "$(configs "$D/count/dmbench.sqlite")" "0 0"
cp "$D/h-orig.png" "$D/h.png"
fi
