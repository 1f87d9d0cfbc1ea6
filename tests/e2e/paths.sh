#!/usr/bin/env bash
# Camera paths (camera.path, docs/motion.md) as `dmbench render --frame N`
# draws them, checked against still renders of the same camera:
# - a dolly's first frame is the still camera at camera.distance, its last
#   the still camera at camera.dolly_to with the lights where the dolly keeps
#   them (light.distance is relative to camera.distance: 1.2 × 3 = 4.5 ×
#   0.8), PSNR over 60 dB: the same image up to float rounding;
# - an orbit's frame F/2 is the still camera turned by 180° (identical),
#   and frame F wraps to frame 0 (identical);
# - a flyover's frames differ from one another;
# - a still path's key and image are those of a configuration without the
#   key (still scenes keep their keys);
# - a run leaves path configurations out, with the reason, and measures the
#   still ones; a bad value exits 2 with the valid choices.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
R="mesh=plane technique=normal resolution=120x68"
render() { local out=$1; shift; "$BIN" render $R "$@" --png "$OUT/$out.png" > /dev/null; }
psnr() { "$BIN" diff "$OUT/$1.png" "$OUT/$2.png" --json -o "$OUT/map.png" |
           python3 -c 'import json,sys; d=json.load(sys.stdin); print(1e9 if d["PSNR_infinite"] else d["PSNR"])'; }
same() { cmp -s "$OUT/$1.png" "$OUT/$2.png" || { echo "FAIL: $1 and $2 differ"; fail=$((fail+1)); return; }; pass=$((pass+1)); }
differ() { cmp -s "$OUT/$1.png" "$OUT/$2.png" && { echo "FAIL: $1 and $2 are the same image"; fail=$((fail+1)); return; }; pass=$((pass+1)); }
over() { python3 -c "import sys; sys.exit(0 if float('$1') > $2 else 1)" && pass=$((pass+1)) ||
           { echo "FAIL: $3: $1 not over $2"; fail=$((fail+1)); }; }

D="camera.path=dolly camera.path_frames=60 camera.distance=3 camera.dolly_to=0.8"
render d0 $D --frame 0
render d59 $D --frame 59
render s3 camera.distance=3
render s08 camera.distance=0.8 light.distance=4.5
same d0 s3
over "$(psnr s08 d59)" 60 "dolly's last frame against the still camera at 0.8"
differ d0 d59

O="mesh=sphere camera.path=orbit camera.path_frames=60 camera.azimuth=30"
render o0 $O --frame 0
render o30 $O --frame 30
render o60 $O --frame 60
render s210 mesh=sphere camera.azimuth=210
same o30 s210
same o60 o0
differ o0 o30

F="camera.path=flyover camera.path_frames=60"
render f0 $F --frame 0
render f30 $F --frame 30
differ f0 f30

render still camera.path=still
same still s3

printf 'name: paths\nresolution: [80, 45]\nmeasure: { samples: { min: 3, max: 3 } }\nsweep:\n  mesh: [plane]\n  technique: [normal]\n  camera.path: [still, dolly, orbit]\n' > "$OUT/p.yaml"
"$BIN" run "$OUT/p.yaml" --out "$OUT/r" --quiet > /dev/null
# Paths run: the still configuration keeps its key and params (no path
# key, no path quality); dolly and orbit get quality along the path with
# the default K: a reference at the first and last frame (K = F - 1 = 59).
python3 - "$OUT/r/latest/results.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
cs = {c["params"].get("camera.path", "still"): c for c in d["configs"]}
assert sorted(cs) == ["dolly", "orbit", "still"], [c["params"] for c in d["configs"]]
assert "camera.path_ref_every" not in cs["still"]["params"] and cs["still"]["path_quality"] is None, cs["still"]
for p in ("dolly", "orbit"):
    q = cs[p]["path_quality"]
    assert q and q["frames"] == 60 and q["every"] == 59 and q["reference_frames"] == [0, 59], (p, q)
    assert len(q["FLIP"]) == 2 and len(q["SSIM"]) == 2 and q["temporal_error_mean"] >= 0, (p, q)
    assert q["images"]["temporal"].endswith("-temporal.png"), q
PY
pass=$((pass+1))
expect_refused 2 "expected one of: still, orbit, dolly, flyover (did you mean 'dolly'?)" -- \
  "$BIN" render $R camera.path=doly --png "$OUT/x.png"
expect_refused 2 "camera.path_frames" -- "$BIN" render $R camera.path=orbit camera.path_frames=1 --png "$OUT/x.png"
tally
