#!/usr/bin/env bash
# Quality of virtual-texture configurations is deterministic: the scene's
# reference is rendered with plain textures whichever configuration the
# measuring process meets first.  Three seeds (three orders of the four
# configurations, a virtual-texture one first in at least one) must give
# every configuration the same metrics.  Before the fix a run whose first
# configuration was virtual-textured had no reference ("virtual_texture=
# software covers the fragment-stage techniques only, not 'reference-mesh'")
# and left the whole scene without quality.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
for s in 1 2 3; do
  "$BIN" run "$SRC/tests/e2e/vt_quality.yaml" --out "$OUT/r$s" --seed "$s" --quiet
done
python3 - "$OUT"/r1/latest/results.json "$OUT"/r2/latest/results.json "$OUT"/r3/latest/results.json <<'PY'
import json, sys
runs = [json.load(open(p))["configs"] for p in sys.argv[1:]]
firsts = set()
for cs in runs:
    assert len(cs) == 4, [c["label"] for c in cs]
    firsts.add(cs[0]["params"]["virtual_texture"])
assert "software" in firsts, "no seed put a virtual-texture configuration first; pick other seeds"
base = {c["label"]: c["quality"] for c in runs[0]}
for cs in runs:
    for c in cs:
        q = c["quality"]
        assert q and "SSIM" in q, (c["label"], q, c.get("reason"))
        assert q["SSIM"] == base[c["label"]]["SSIM"] and q["PSNR"] == base[c["label"]]["PSNR"], (c["label"], q, base[c["label"]])
for l, q in sorted(base.items()):
    print(f"{l}: SSIM {q['SSIM']:.5f}, PSNR {q['PSNR']:.2f} dB in every order")
PY

# The heatmap is the FLIP map (images.heatmap and images.flip name one
# file), on FLIP's fixed scale 0..1: the brightest red of a map (the
# ramp's red rises with the error up to 7/8 of the scale) orders the maps
# as their largest FLIP error does, so maps compare side by side.
python3 - "$OUT/r1/latest" <<'PY'
import json, subprocess, sys
d = sys.argv[1]
rows = []
for c in json.load(open(d + "/results.json"))["configs"]:
    assert c["images"]["heatmap"] == c["images"]["flip"], c["images"]
    out = subprocess.run(["oiiotool", "--stats", d + "/" + c["images"]["heatmap"]],
                         capture_output=True, text=True).stdout
    red = int([l for l in out.splitlines() if "Stats Max" in l][0].split()[2])
    rows.append((c["quality"]["FLIPMax"], red, c["label"]))
rows.sort()
for (e0, r0, l0), (e1, r1, l1) in zip(rows, rows[1:]):
    assert e1 == e0 or e1 > 0.875 or r1 >= r0, (l0, e0, r0, l1, e1, r1)
assert rows[0][1] < rows[-1][1] or rows[0][0] == rows[-1][0], rows
for e, r, l in rows:
    print(f"{l}: FLIP max {e:.3f}, brightest heatmap red {r}/255")
PY
