#!/usr/bin/env bash
# `dmbench diff REF TEST`: the metrics of two image files, the FLIP map and
# the exit codes.  Images are written here as PFM (float, read by
# OpenImageIO) so the values are exact; the flat grey pair 0.5 | 0.6 has
# FLIP 0.285017 everywhere, the compressed HyAB computed by hand in
# test_reports_flip (no edges, no points, the filtered flat colour stays
# itself).
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"

# pfm FILE W H R G B [NAN_AT]: a flat colour image; pixel NAN_AT (index) NaN.
pfm() {
  python3 - "$@" <<'PY'
import struct, sys
path, w, h, r, g, b = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), *map(float, sys.argv[4:7])
nan_at = int(sys.argv[7]) if len(sys.argv) > 7 else -1
with open(path, "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
    for i in range(w * h):
        px = (float("nan"), g, b) if i == nan_at else (r, g, b)
        f.write(struct.pack("<3f", *px))
PY
}
pfm "$OUT/a.pfm" 24 16 0.5 0.5 0.5
pfm "$OUT/b.pfm" 24 16 0.6 0.6 0.6
pfm "$OUT/small.pfm" 12 16 0.5 0.5 0.5
pfm "$OUT/nan.pfm" 24 16 0.5 0.5 0.5 37
echo "not an image" >"$OUT/text.png"

# the flat pair: FLIP mean and max 0.285017 (hand value), map written
"$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" --json -o "$OUT/map.png" >"$OUT/j" 2>"$OUT/e"; rc=$?
[ $rc -eq 0 ] && pass=$((pass+1)) || { echo "FAIL: diff exited $rc: $(cat "$OUT/e")"; fail=$((fail+1)); }
python3 - "$OUT/j" <<'PY' && pass=$((pass+1)) || { echo "FAIL: JSON $(cat "$OUT/j")"; fail=$((fail+1)); }
import json, sys
d = json.load(open(sys.argv[1]))
assert abs(d["FLIP"] - 0.285017) < 1e-5 and abs(d["FLIPMax"] - 0.285017) < 1e-5, d
assert abs(d["FLIPPixelsPerDegree"] - 67.0206) < 1e-9 and d["width"] == 24 and d["height"] == 16
assert abs(d["RMSE"] - 0.1) < 1e-6 and d["SSIM"] < 1 and d["NonFinitePixels"] == 0
# every one of the 24 x 16 pixels has FLIP 0.285: all in the bin 0.2-0.3
assert d["FLIPHistogram"] == [0, 0, 384, 0, 0, 0, 0, 0, 0, 0], d["FLIPHistogram"]
# PFM has no alpha: no silhouette figure, and the reason instead
assert "SilhouetteError" not in d and "opaque" in d["SilhouetteErrorLeftOut"], d
assert d["FLIPMap"].endswith("/map.png"), d
PY
[ -s "$OUT/map.png" ] && pass=$((pass+1)) || { echo "FAIL: no map written"; fail=$((fail+1)); }
# identical: zero everywhere, PSNR infinite
out=$("$BIN" diff "$OUT/a.pfm" "$OUT/a.pfm")
grep -q "FLIP        mean 0.000000, max 0.000000" <<<"$out" && grep -q "PSNR        inf dB" <<<"$out" \
  && pass=$((pass+1)) || { echo "FAIL: identical: $out"; fail=$((fail+1)); }
# another viewing condition changes nothing on flat images, and is echoed
"$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" --ppd 30 | grep -q "mean 0.285017, .*at 30 pixels per degree" \
  && pass=$((pass+1)) || { echo "FAIL: --ppd 30"; fail=$((fail+1)); }
# NaN: said on stderr, counted, not spread into the metrics
"$BIN" diff "$OUT/a.pfm" "$OUT/nan.pfm" --json >"$OUT/j" 2>"$OUT/e"
grep -q "non-finite (NaN/Inf) pixels: 0 in .*, 1 in .*nan.pfm" "$OUT/e" && pass=$((pass+1)) \
  || { echo "FAIL: NaN not said: $(cat "$OUT/e")"; fail=$((fail+1)); }
python3 -c "import json,sys,math; d=json.load(open(sys.argv[1])); assert d['NonFinitePixels']==1 and all(isinstance(d[k],float) and math.isfinite(d[k]) for k in ('RMSE','SSIM','FLIP','FLIPMax'))" "$OUT/j" \
  && pass=$((pass+1)) || { echo "FAIL: NaN propagated: $(cat "$OUT/j")"; fail=$((fail+1)); }
# the text: labelled quartiles, the histogram, silhouette left out with its
# reason, and the map written without -o beside TEST (b.pfm -> b.flip.png)
rm -f "$OUT/b.flip.png"
out=$(cd "$OUT" && "$BIN" diff a.pfm b.pfm)
grep -q "weighted quartiles (by error, as FLIP pools them): Q1 0.2850, median 0.2850, Q3 0.2850" <<<"$out" \
  && grep -qE "^    \[0\.2, 0\.3\)       384 100\.00 %  #{40}$" <<<"$out" \
  && grep -qE "^    \[0\.9, 1\.0\]         0   0\.00 %  $" <<<"$out" \
  && grep -q "silhouette  left out: both images are opaque everywhere" <<<"$out" \
  && grep -q "map         b.flip.png (FLIP per pixel" <<<"$out" && [ -s "$OUT/b.flip.png" ] \
  && pass=$((pass+1)) || { echo "FAIL: text or default map: $out"; fail=$((fail+1)); }
# an image with alpha (TGA, 32 bits: half the pixels transparent): the
# silhouette is computed, 1 - IoU = 1 - 192/384 = 0.5 against the opaque REF
python3 - "$OUT/half.tga" <<'PY'
import struct, sys
w, h = 24, 16
with open(sys.argv[1], "wb") as f:
    f.write(struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, w, h, 32, 8 | 0x20))
    for y in range(h):
        for x in range(w):
            f.write(bytes((128, 128, 128, 255 if y < h // 2 else 0)))   # BGRA
PY
"$BIN" diff "$OUT/a.pfm" "$OUT/half.tga" --json -o "$OUT/half_map.png" >"$OUT/j" 2>"$OUT/e"
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert abs(d['SilhouetteError']-0.5)<1e-9 and 'SilhouetteErrorLeftOut' not in d, d" "$OUT/j" \
  && pass=$((pass+1)) || { echo "FAIL: alpha silhouette: $(cat "$OUT/j" "$OUT/e")"; fail=$((fail+1)); }
# a default place that cannot be written: a warning, the figures still printed
mkdir -p "$OUT/ro" && cp "$OUT/b.pfm" "$OUT/ro/" && chmod a-w "$OUT/ro"
if [ "$(id -u)" != 0 ]; then   # root writes anyway
  out=$("$BIN" diff "$OUT/a.pfm" "$OUT/ro/b.pfm" 2>"$OUT/e"); rc=$?
  [ $rc -eq 0 ] && grep -q "the FLIP map was not written" "$OUT/e" && grep -q "SSIM" <<<"$out" \
    && pass=$((pass+1)) || { echo "FAIL: read-only default place: rc $rc $(cat "$OUT/e")"; fail=$((fail+1)); }
fi
chmod u+w "$OUT/ro"
# bad input: exit 2 with a reason
expect_refused 2 "differ in size: .*a.pfm' is 24x16, .*small.pfm' is 12x16" -- "$BIN" diff "$OUT/a.pfm" "$OUT/small.pfm"
expect_refused 2 "cannot read .*text.png" -- "$BIN" diff "$OUT/a.pfm" "$OUT/text.png"
expect_refused 2 "cannot read .*missing.png" -- "$BIN" diff "$OUT/missing.png" "$OUT/a.pfm"
expect_refused 2 "expected two images" -- "$BIN" diff "$OUT/a.pfm"
expect_refused 2 "ppd" -- "$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" --ppd 0
expect_refused 2 "cannot write" -- "$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" -o "$OUT/no/such/dir/map.png"
tally
