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
PY
[ -s "$OUT/map.png" ] && pass=$((pass+1)) || { echo "FAIL: no map written"; fail=$((fail+1)); }
# identical: zero everywhere, PSNR infinite
out=$("$BIN" diff "$OUT/a.pfm" "$OUT/a.pfm")
grep -q "FLIP        0.000000 mean, 0.000000 max" <<<"$out" && grep -q "PSNR        inf dB" <<<"$out" \
  && pass=$((pass+1)) || { echo "FAIL: identical: $out"; fail=$((fail+1)); }
# another viewing condition changes nothing on flat images, and is echoed
"$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" --ppd 30 | grep -q "0.285017 mean.*at 30 pixels per degree" \
  && pass=$((pass+1)) || { echo "FAIL: --ppd 30"; fail=$((fail+1)); }
# NaN: said on stderr, counted, not spread into the metrics
"$BIN" diff "$OUT/a.pfm" "$OUT/nan.pfm" --json >"$OUT/j" 2>"$OUT/e"
grep -q "non-finite (NaN/Inf) pixels: 0 in .*, 1 in .*nan.pfm" "$OUT/e" && pass=$((pass+1)) \
  || { echo "FAIL: NaN not said: $(cat "$OUT/e")"; fail=$((fail+1)); }
python3 -c "import json,sys,math; d=json.load(open(sys.argv[1])); assert d['NonFinitePixels']==1 and all(isinstance(d[k],float) and math.isfinite(d[k]) for k in ('RMSE','SSIM','FLIP','FLIPMax'))" "$OUT/j" \
  && pass=$((pass+1)) || { echo "FAIL: NaN propagated: $(cat "$OUT/j")"; fail=$((fail+1)); }
# bad input: exit 2 with a reason
expect_refused 2 "differ in size: .*a.pfm' is 24x16, .*small.pfm' is 12x16" -- "$BIN" diff "$OUT/a.pfm" "$OUT/small.pfm"
expect_refused 2 "cannot read .*text.png" -- "$BIN" diff "$OUT/a.pfm" "$OUT/text.png"
expect_refused 2 "cannot read .*missing.png" -- "$BIN" diff "$OUT/missing.png" "$OUT/a.pfm"
expect_refused 2 "expected two images" -- "$BIN" diff "$OUT/a.pfm"
expect_refused 2 "ppd" -- "$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" --ppd 0
expect_refused 2 "cannot write" -- "$BIN" diff "$OUT/a.pfm" "$OUT/b.pfm" -o "$OUT/no/such/dir/map.png"
tally
