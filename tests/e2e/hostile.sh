#!/usr/bin/env bash
# Hostile input (docs/reliability.md): each is refused with exit 2 and a
# message naming the problem, quickly, and writes nothing; none crashes,
# hangs or runs something else than what was asked.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
R="$OUT/r"
# options
expect_refused 2 "expected K/N with 1 <= K <= N" -- "$BIN" run --shard 1/4294967297 --out "$R"
expect_refused 2 "expected K/N with 1 <= K <= N" -- "$BIN" run --shard 1/2/3 --out "$R"
expect_refused 2 "expected K/N with 1 <= K <= N" -- "$BIN" run --shard " 1/2" --out "$R"
expect_refused 2 "expected a non-negative integer" -- "$BIN" run --seed -5 --out "$R"
expect_refused 2 "expected a non-negative integer" -- "$BIN" run --seed 18446744073709551616 --out "$R"
# a NUL byte ends nothing silently
printf 'name: x\nsweep:\n  mesh: [plane]\n\0  technique: [frobnicate]\n' > "$OUT/nul.yaml"
expect_refused 2 "nul.yaml:4: a NUL byte" -- "$BIN" run "$OUT/nul.yaml" --out "$R"
# FIFOs and devices are not read (they never end)
mkfifo "$OUT/fifo.yaml"
expect_refused 2 "not a regular file" -- "$BIN" run "$OUT/fifo.yaml" --out "$R"
printf 'name: x\nsweep:\n  technique: [pom]\n  maps: ["height=/dev/zero"]\n' > "$OUT/dev.yaml"
expect_refused 2 "height map '/dev/zero' is not a regular file" -- "$BIN" run "$OUT/dev.yaml" --out "$R"
printf 'name: x\nsweep:\n  technique: [pom]\nscene:\n  material: { height: %s }\n' "$OUT/fifo.yaml" > "$OUT/fifomap.yaml"
expect_refused 2 "is not a regular file" -- "$BIN" run "$OUT/fifomap.yaml" --out "$R"
printf 'x,WallTime\n1,3\n' > "$OUT/ok.csv"
expect_refused 2 "not a regular file" -- "$BIN" fit --data /dev/zero --formula "a*x"
# deep nesting: formula, YAML
deep=$(python3 -c "print('a+' + '('*30000 + 'x' + ')'*30000)")
neg=$(python3 -c "print('a+' + '-'*50000 + 'x')")
long=$(python3 -c "print('+'.join(['a']*50000))")
printf 'x,WallTime\n1,3\n2,5\n3,7\n4,9\n' > "$OUT/fit.csv"
expect_refused 2 "nested deeper than 200 levels" -- "$BIN" fit --data "$OUT/fit.csv" --formula "$deep"
expect_refused 2 "nested deeper than 200 levels" -- "$BIN" fit --data "$OUT/fit.csv" --formula "$neg"
expect_refused 2 "more than 2000 operations in a row" -- "$BIN" fit --data "$OUT/fit.csv" --formula "$long"
printf 'name: x\nsweep:\n  technique: [normal]\nmodels:\n  - { name: m, formula: "%s", response: WallTime }\n' "$deep" > "$OUT/deepm.yaml"
expect_refused 2 "deepm.yaml:5: models: m: formula: .*nested deeper than 200" -- "$BIN" run "$OUT/deepm.yaml" --out "$R"
python3 -c "print('name: x\nsweep:\n  technique: [normal]\nscene: ' + '{a: '*40 + '1' + '}'*40)" > "$OUT/deepy.yaml"
expect_refused 2 "deepy.yaml:4:.*nested deeper than 16 levels" -- "$BIN" run "$OUT/deepy.yaml" --out "$R"
# models: are checked before anything is measured
sed 's/a + b\*SamplesPassed; a >= 0; b >= 0/a + b*SamplesPased/' "$SRC/tests/e2e/tiny.yaml" > "$OUT/m1.yaml"
expect_refused 2 "m1.yaml:19: models: resolution-cost: 'SamplesPased' would be a fitted parameter; did you mean 'SamplesPassed'" -- "$BIN" run "$OUT/m1.yaml" --out "$R"
sed 's/a + b\*SamplesPassed; a >= 0; b >= 0/a + (b*SamplesPassed/' "$SRC/tests/e2e/tiny.yaml" > "$OUT/m2.yaml"
expect_refused 2 "m2.yaml:19: models: resolution-cost: formula: column 21: expected ')'" -- "$BIN" run "$OUT/m2.yaml" --out "$R"
# fit on a directory that is not a run creates nothing
mkdir -p "$OUT/notrun/sub"
expect_refused 2 "not a run directory" -- "$BIN" fit "$OUT/notrun/sub"
if [ -e "$OUT/notrun/dmbench.sqlite" ]; then fail=$((fail+1)); echo "FAIL: fit created a store"; else pass=$((pass+1)); fi
# fit: a BOM is not a column, contradictory bounds, overflowing data, glog
printf '\xef\xbb\xbfx,WallTime\n1,3\n2,5\n3,7\n4,9\n' > "$OUT/bom.csv"
out=$("$BIN" fit --data "$OUT/bom.csv" --formula "a + b*x" 2>&1); rc=$?
if [ "$rc" -eq 0 ] && grep -q "b *= *2 " <<<"$out" && ! grep -q "x *=" <<<"$out"; then pass=$((pass+1))
else fail=$((fail+1)); echo "FAIL: BOM csv: rc $rc: $out"; fi
expect_refused 2 "bounds of 'p' contradict each other" -- "$BIN" fit --data "$OUT/fit.csv" --formula "a + p*x; p >= 2; p <= 1"
printf 'x,WallTime\n1,1e308\n2,1.5e308\n3,1.7e308\n4,1.2e308\n' > "$OUT/big.csv"
expect_refused 1 "the fit is not finite" -- "$BIN" fit --data "$OUT/big.csv" --formula "a + b*x"
printf 'x,WallTime\n1,1e-300\n2,2e-300\n3,3e-300\n' > "$OUT/tiny.csv"
err=$("$BIN" fit --data "$OUT/tiny.csv" --formula "a*x" 2>&1 >/dev/null)
if grep -q "InitGoogleLogging\|^[EWI][0-9]\{8\} " <<<"$err"; then fail=$((fail+1)); echo "FAIL: glog output: $err"
else pass=$((pass+1)); fi
# Huber: the standard error of a is on the inliers' noise scale (0.05), not the outliers'
python3 -c "
import math
print('x,WallTime')
for i in range(40):
    print(f'{i},{4 + 2*i + 0.05*math.sin(7*i) + (200 if i % 10 == 0 else 0)}')" > "$OUT/huber.csv"
se=$("$BIN" fit --data "$OUT/huber.csv" --formula "a + b*x" --loss huber | awk '$1 == "a" {print $5}')
if python3 -c "import sys; sys.exit(0 if 0 < float('$se') < 0.5 else 1)" 2>/dev/null; then pass=$((pass+1))
else fail=$((fail+1)); echo "FAIL: Huber standard error of a is '$se' (want < 0.5)"; fi
# nothing may have been written by the failing runs
if [ -e "$R" ]; then fail=$((fail+1)); echo "FAIL: bad input wrote $R"; else pass=$((pass+1)); fi
tally
