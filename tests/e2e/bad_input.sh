#!/usr/bin/env bash
# Bad input (docs/reliability.md): exit 2, a message naming file:line and the valid
# choices, and nothing written.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
BAD="$SRC/tests/data/bad-sweeps"
expect_refused 2 "03-unknown-axis.yaml:4:.*did you mean 'tess_level'" -- "$BIN" run "$BAD/03-unknown-axis.yaml" --out "$OUT/r"
expect_refused 2 "04-unknown-technique.yaml:4:.*expected one of" -- "$BIN" run "$BAD/04-unknown-technique.yaml" --out "$OUT/r"
expect_refused 2 "YAML syntax error" -- "$BIN" run "$BAD/01-yaml-syntax.yaml" --out "$OUT/r"
expect_refused 2 "cannot read the sweep file" -- "$BIN" run "$OUT/missing.yaml" --out "$OUT/r"
expect_refused 2 "unknown option '--shrad'; did you mean '--shard'" -- "$BIN" run --shrad 1/2
expect_refused 2 "expected K/N" -- "$BIN" run --shard 3/2
expect_refused 2 "unknown command 'rnu'; did you mean 'run'" -- "$BIN" rnu
expect_refused 2 "invalid value 'cubee' for mesh" -- "$BIN" render mesh=cubee --png "$OUT/x.png"
expect_refused 2 "no such run directory" -- "$BIN" report "$OUT/nope"
expect_refused 2 "run: --budget '0': expected seconds per configuration" -- "$BIN" run --budget 0
expect_refused 2 "run: --extra-time 'inf': expected seconds for the whole run, 0 (none) or more and finite" -- "$BIN" run --extra-time inf
expect_refused 2 "run: --extra-time '-1': expected seconds for the whole run, 0 (none) or more and finite" -- "$BIN" run --extra-time -1
expect_refused 2 "mesh file '/nonexistent/x.obj' cannot be used" -- "$BIN" render mesh=file:/nonexistent/x.obj --png "$OUT/x.png"
expect_refused 2 "fit: --loss 'l2': expected one of: huber, cauchy, none" -- "$BIN" fit "$OUT" --loss l2
expect_refused 2 "unknown counter 'VSInvocatons'; did you mean 'VSInvocations'" -- "$BIN" list counters --passes WallTime,VSInvocatons
expect_refused 2 "merge: .*no such run directory" -- "$BIN" merge "$OUT/m" "$OUT/nope"
expect_refused 2 "report: --metric: unknown metric 'rsme'; did you mean 'rmse'" -- "$BIN" report "$OUT" --metric rsme
expect_refused 2 "render: --debug 'normls': expected one of: none, normals (did you mean 'normals'?)" -- "$BIN" render technique=normal --debug normls --png "$OUT/x.png"
expect_refused 2 "invalid value 'phongg' for tess_smooth; expected one of: off, phong (did you mean 'phong'?)" -- "$BIN" render technique=tess-displacement tess_smooth=phongg --png "$OUT/x.png"
printf 'x,WallTime\n1,3\n2,5\n3,7\n4,9\n' > "$OUT/fit.csv"
expect_refused 2 "formula: bound 1 ' a => 0'" -- "$BIN" fit --data "$OUT/fit.csv" --formula "a + b*x; a => 0"
printf 'name: x\nsweep:\n  technique: [phong, pom]\nexclude:\n  - { technique: normal }\n' > "$OUT/ex.yaml"
expect_refused 2 "ex.yaml:5: exclude value 'normal' of technique is not one of the sweep's values (phong, pom)" -- "$BIN" run "$OUT/ex.yaml" --out "$OUT/r"
# nothing may have been written by the failing runs
if [ -e "$OUT/r" ]; then fail=$((fail+1)); echo "FAIL: a bad sweep wrote $OUT/r"; else pass=$((pass+1)); fi
# an unwritable output directory is a clean exit 2
touch "$OUT/file"
expect_refused 2 "cannot create or write the output directory" -- "$BIN" run "$SRC/tests/e2e/tiny.yaml" --out "$OUT/file/sub"
tally
