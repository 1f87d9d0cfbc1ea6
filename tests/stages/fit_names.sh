#!/usr/bin/env bash
# test_fit_names: `dmbench fit` refuses a typo instead of fitting something
# else (exit 2, with a suggestion): a formula name close to an axis or
# counter, an unknown --group-by axis, an unknown --response of a run.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
printf 'tess_level,WallTime\n1,10\n2,20\n4,40\n' > "$OUT/d.csv"
expect_refused 2 "'tess_levle' would be a fitted parameter; did you mean 'tess_level'?" -- \
  "$BIN" fit --data "$OUT/d.csv" --formula "a + b*tess_levle"
expect_refused 2 "unknown --group-by axis 'techniqe'; did you mean 'technique'?" -- \
  "$BIN" fit "$OUT" --group-by techniqe
expect_refused 2 "unknown --response 'WallTme'; did you mean 'WallTime'?" -- \
  "$BIN" fit "$OUT" --response WallTme
# the same names spelled right go on (the fit of the CSV succeeds)
"$BIN" fit --data "$OUT/d.csv" --formula "a + b*tess_level" >/dev/null && pass=$((pass+1)) ||
  { fail=$((fail+1)); echo "FAIL: a correct formula was refused"; }
tally
