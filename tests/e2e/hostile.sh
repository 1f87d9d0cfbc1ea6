#!/usr/bin/env bash
# Hostile input (docs/reliability.md): each is refused with exit 2 and a
# message naming the problem, quickly, and writes nothing; none crashes,
# hangs or runs something else than what was asked.
set -uo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
pass=0; fail=0
expect() {  # expect CODE PATTERN -- command...
  local code=$1 pat=$2; shift 3
  local err; err=$(timeout 60 "$@" 2>&1 >/dev/null); local rc=$?
  if [ "$rc" -eq "$code" ] && grep -q -- "$pat" <<<"$err"; then pass=$((pass+1))
  else fail=$((fail+1)); echo "FAIL: ${*:0:4} -> rc $rc (want $code), stderr: $(head -c 400 <<<"$err") (want /$pat/)"; fi
}
R="$OUT/r"
# options
expect 2 "expected K/N with 1 <= K <= N" -- "$BIN" run --shard 1/4294967297 --out "$R"
expect 2 "expected K/N with 1 <= K <= N" -- "$BIN" run --shard 1/2/3 --out "$R"
expect 2 "expected K/N with 1 <= K <= N" -- "$BIN" run --shard " 1/2" --out "$R"
expect 2 "expected a non-negative integer" -- "$BIN" run --seed -5 --out "$R"
expect 2 "expected a non-negative integer" -- "$BIN" run --seed 18446744073709551616 --out "$R"
# a NUL byte ends nothing silently
printf 'name: x\nsweep:\n  mesh: [plane]\n\0  technique: [frobnicate]\n' > "$OUT/nul.yaml"
expect 2 "nul.yaml:4: a NUL byte" -- "$BIN" run "$OUT/nul.yaml" --out "$R"
# FIFOs and devices are not read (they never end)
mkfifo "$OUT/fifo.yaml"
expect 2 "not a regular file" -- "$BIN" run "$OUT/fifo.yaml" --out "$R"
printf 'name: x\nsweep:\n  technique: [pom]\n  maps: ["height=/dev/zero"]\n' > "$OUT/dev.yaml"
expect 2 "height map '/dev/zero' is not a regular file" -- "$BIN" run "$OUT/dev.yaml" --out "$R"
printf 'name: x\nsweep:\n  technique: [pom]\nscene:\n  material: { height: %s }\n' "$OUT/fifo.yaml" > "$OUT/fifomap.yaml"
expect 2 "is not a regular file" -- "$BIN" run "$OUT/fifomap.yaml" --out "$R"
printf 'x,WallTime\n1,3\n' > "$OUT/ok.csv"
expect 2 "not a regular file" -- "$BIN" fit --data /dev/zero --formula "a*x"
# deep nesting: formula, YAML
deep=$(python3 -c "print('a+' + '('*30000 + 'x' + ')'*30000)")
neg=$(python3 -c "print('a+' + '-'*50000 + 'x')")
long=$(python3 -c "print('+'.join(['a']*50000))")
printf 'x,WallTime\n1,3\n2,5\n3,7\n4,9\n' > "$OUT/fit.csv"
expect 2 "nested deeper than 200 levels" -- "$BIN" fit --data "$OUT/fit.csv" --formula "$deep"
expect 2 "nested deeper than 200 levels" -- "$BIN" fit --data "$OUT/fit.csv" --formula "$neg"
expect 2 "more than 2000 operations in a row" -- "$BIN" fit --data "$OUT/fit.csv" --formula "$long"
printf 'name: x\nsweep:\n  technique: [normal]\nmodels:\n  - { name: m, formula: "%s", response: WallTime }\n' "$deep" > "$OUT/deepm.yaml"
expect 2 "deepm.yaml:5: models: m: formula: .*nested deeper than 200" -- "$BIN" run "$OUT/deepm.yaml" --out "$R"
python3 -c "print('name: x\nsweep:\n  technique: [normal]\nscene: ' + '{a: '*40 + '1' + '}'*40)" > "$OUT/deepy.yaml"
expect 2 "deepy.yaml:4:.*nested deeper than 16 levels" -- "$BIN" run "$OUT/deepy.yaml" --out "$R"
# models: are checked before anything is measured
sed 's/a + b\*SamplesPassed; a >= 0; b >= 0/a + b*SamplesPased/' "$SRC/tests/e2e/tiny.yaml" > "$OUT/m1.yaml"
expect 2 "m1.yaml:19: models: resolution-cost: 'SamplesPased' would be a fitted parameter; did you mean 'SamplesPassed'" -- "$BIN" run "$OUT/m1.yaml" --out "$R"
sed 's/a + b\*SamplesPassed; a >= 0; b >= 0/a + (b*SamplesPassed/' "$SRC/tests/e2e/tiny.yaml" > "$OUT/m2.yaml"
expect 2 "m2.yaml:19: models: resolution-cost: formula: column 21: expected ')'" -- "$BIN" run "$OUT/m2.yaml" --out "$R"
# fit on a directory that is not a run creates nothing
mkdir -p "$OUT/notrun/sub"
expect 2 "not a run directory" -- "$BIN" fit "$OUT/notrun/sub"
if [ -e "$OUT/notrun/dmbench.sqlite" ]; then fail=$((fail+1)); echo "FAIL: fit created a store"; else pass=$((pass+1)); fi
# nothing may have been written by the failing runs
if [ -e "$R" ]; then fail=$((fail+1)); echo "FAIL: bad input wrote $R"; else pass=$((pass+1)); fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
