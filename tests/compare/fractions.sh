#!/usr/bin/env bash
# One percentage grammar (sweep/fraction.h) in every fraction flag of
# `dmbench compare`: "P%" and its fraction give the same setting (read back
# from --json), and a bare number above 1 is refused (exit 2) naming both
# ways to say it.  The sweep-file key (samples.target_ci) is tested in
# test_sweep_parse.  Synthetic runs: no GL.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
python3 "$SRC/tests/compare/synth.py" "$OUT/a.json" --seed 1

# setting FLAG VALUE FIELD: the settings.FIELD that `compare --json` records.
setting() {
  "$BIN" compare "$OUT/a.json" "$OUT/a.json" --quiet "$1" "$2" --json "$OUT/s.json" >/dev/null 2>&1
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["settings"]; v=s
for k in sys.argv[2].split("."): v=v[k]
print(repr(float(v)))' "$OUT/s.json" "$3" 2>/dev/null
}

#        flag            percent fraction  bare   field
rows=(  "--time-threshold 5%    0.05     5      time_threshold"
        "--time-threshold 3.3%  0.033    3.3    time_threshold"
        "--threshold      0.5%  0.005    5      threshold"
        "--alpha          1%    0.01     2      alpha"
        "--ssim-drop      2%    0.02     2      ssim_drop"
        "--tolerance      FSInvocations=3% FSInvocations=0.03 FSInvocations=3 tolerances.FSInvocations" )
for row in "${rows[@]}"; do
  read -r flag pct frac bare field <<<"$row"
  a=$(setting "$flag" "$pct" "$field"); b=$(setting "$flag" "$frac" "$field")
  if [ -n "$a" ] && [ "$a" = "$b" ]; then pass=$((pass+1))
  else fail=$((fail+1)); echo "FAIL: $flag $pct gives '$a', $flag $frac gives '$b'"; fi
  n=${bare#*=}                     # the number of a COUNTER=N value
  expect_refused 2 "write ${n}% or" -- "$BIN" compare "$OUT/a.json" "$OUT/a.json" "$flag" "$bare"
  expect_refused 2 "$flag" -- "$BIN" compare "$OUT/a.json" "$OUT/a.json" "$flag" "${bare}x"
done
# Beyond its range a percentage is refused too, naming the range.
expect_refused 2 "(0 %, 100 %)" -- "$BIN" compare "$OUT/a.json" "$OUT/a.json" --alpha 100%
expect_refused 2 "(0 %, 100 %)" -- "$BIN" compare "$OUT/a.json" "$OUT/a.json" --threshold 0
# A time threshold above 100 % is said as a percentage.
[ "$(setting --time-threshold 150% time_threshold)" = "1.5" ] && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: 150%"; }
tally
