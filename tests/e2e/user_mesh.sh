#!/usr/bin/env bash
# End to end: `mesh: file:PATH` on the mesh axis.  The committed cube OBJ
# (6 quads) goes through Assimp to 24 vertices and 12 triangles, which the
# pipeline statistics must count exactly, the same as the built-in cube; the
# path is relative to the sweep file, not to the working directory.  Bad
# files (unreadable, no UVs, no normals, no triangles) stop the plan with
# exit 2 naming the sweep file's line, the mesh file and what is wrong.
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

cd "$OUT"   # not the sweep file's directory: the path must still resolve
"$BIN" run "$SRC/tests/e2e/user_mesh.yaml" --out "$OUT/runs" --quiet
python3 - "$OUT/runs/latest/results.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
by = {c["params"]["mesh"].split("/")[-1]: c for c in j["configs"]}
assert set(by) == {"cube.obj", "cube"}, list(by)
for name, c in by.items():
    assert c["status"] == "ok", (name, c.get("reason"), c.get("log"))
    v = {k: c["counters"][k]["value"] for k in
         ("VerticesSubmitted", "PrimitivesSubmitted", "VSInvocations", "ClippingInputPrimitives")}
    # 12 triangles drawn indexed: 36 indices fetched, 24 distinct vertices shaded
    assert v == {"VerticesSubmitted": 36, "PrimitivesSubmitted": 12, "VSInvocations": 24,
                 "ClippingInputPrimitives": 12}, (name, v)
    # 24 vertices x 48 bytes + 36 indices x 4 bytes
    assert c["counters"]["MeshBytes"]["value"] == 24 * 48 + 36 * 4, c["counters"]["MeshBytes"]
print("user mesh counts ok")
PY

# Bad files: exit 2 at plan time, naming the file and the problem.
bad() {   # bad NAME OBJ_TEXT EXPECTED_PHRASE
  printf '%b' "$2" > "$OUT/$1.obj"
  printf 'name: bad\nsweep:\n  mesh: [file:%s.obj]\n  technique: [normal]\n' "$1" > "$OUT/$1.yaml"
  set +e
  "$BIN" run "$OUT/$1.yaml" --out "$OUT/bad" --quiet 2> "$OUT/err.txt"
  rc=$?
  set -e
  [ "$rc" = 2 ] || { echo "$1: exit $rc, expected 2"; cat "$OUT/err.txt"; exit 1; }
  grep -q "$1.yaml:3:" "$OUT/err.txt" || { echo "$1: no sweep line"; cat "$OUT/err.txt"; exit 1; }
  grep -q "$OUT/$1.obj" "$OUT/err.txt" || { echo "$1: no file name"; cat "$OUT/err.txt"; exit 1; }
  grep -q "$3" "$OUT/err.txt" || { echo "$1: no '$3'"; cat "$OUT/err.txt"; exit 1; }
  test ! -e "$OUT/bad" || { echo "$1: something was run"; exit 1; }
}
bad no-uv 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n' "no texture coordinates"
bad no-normal 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n' "no normals"
bad bad-index 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 9/1/1\n' "Assimp cannot read it"
bad lines-only 'v 0 0 0\nv 1 0 0\nl 1 2\n' "no triangles"
rm -f "$OUT/missing.obj"
printf 'name: bad\nsweep:\n  mesh: [file:missing.obj]\n' > "$OUT/missing.yaml"
set +e; "$BIN" run "$OUT/missing.yaml" --out "$OUT/bad" --quiet 2> "$OUT/err.txt"; rc=$?; set -e
[ "$rc" = 2 ] && grep -q "$OUT/missing.obj" "$OUT/err.txt" || { echo "missing: exit $rc"; cat "$OUT/err.txt"; exit 1; }
echo "bad mesh files refused"
