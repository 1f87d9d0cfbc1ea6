#!/usr/bin/env bash
# Files with a contract and what other tools read (issue 18): three runs of
# the tiny sweep in one store; every results.json validates against
# docs/results.schema.json (and a broken copy does not); each export has its
# format's documented shape with the run's own numbers; compare.py from
# libbenchmark-tools compares two gbench exports with one row per
# configuration; `history` shows three values per configuration; `fit
# --data` reads results.csv; `report --out` writes elsewhere.
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
PY=/usr/bin/python3          # Debian's python3: python3-scipy, python3-jsonschema
COMPARE=/usr/share/benchmark/compare.py
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for i in 1 2 3; do
  "$BIN" run "$SRC/tests/e2e/tiny.yaml" --out "$OUT/res" --quiet
  sleep 1                    # run ids are per second
done
mapfile -t RUNS < <(ls -d "$OUT"/res/2*/ | sed 's#/$##' | sort)
[ ${#RUNS[@]} -eq 3 ] || fail "expected 3 runs, got ${#RUNS[@]}"

for r in "${RUNS[@]}"; do
  for f in gbench bmf gab-smaller gab-bigger; do
    "$BIN" export "$r" --format "$f" -o "$r/export-$f.json" 2>/dev/null
  done
done
set +e
"$BIN" export "${RUNS[0]}" --format nope 2> "$OUT/bad.txt"; rc=$?
set -e
[ $rc -eq 2 ] || fail "export --format nope: exit $rc, want 2"
grep -q "valid choices: gbench, bmf, gab-smaller, gab-bigger" "$OUT/bad.txt" || fail "$(cat "$OUT/bad.txt")"
set +e
"$BIN" history --store "$OUT/res/dmbench.sqlite" --technique nope 2> "$OUT/bad.txt"; rc1=$?
"$BIN" history --store "$OUT/nothere.sqlite" 2>> "$OUT/bad.txt"; rc2=$?
"$BIN" history --stor x 2>> "$OUT/bad.txt"; rc3=$?
set -e
[ "$rc1$rc2$rc3" = 222 ] || fail "history bad input: exits $rc1 $rc2 $rc3, want 2 2 2: $(cat "$OUT/bad.txt")"
grep -q "history: --technique 'nope' is not in run .*; valid techniques of the run: normal" "$OUT/bad.txt" || fail "$(cat "$OUT/bad.txt")"
grep -q "nothere.sqlite: no such store" "$OUT/bad.txt" || fail "$(cat "$OUT/bad.txt")"
grep -q -- "--store" "$OUT/bad.txt" || fail "$(cat "$OUT/bad.txt")"

$PY "$COMPARE" --no-color benchmarks "${RUNS[0]}/export-gbench.json" "${RUNS[1]}/export-gbench.json" \
  > "$OUT/compare.txt" || fail "compare.py exited $?"
"$BIN" history --store "$OUT/res/dmbench.sqlite" > "$OUT/history.txt"
"$BIN" fit --data "${RUNS[0]}/results.csv" --formula "a + b*SamplesPassed" \
  --response WallTime_median_ms > "$OUT/fit.txt" || fail "fit --data results.csv"
before=$(md5sum < "${RUNS[2]}/report.html")
"$BIN" report "${RUNS[2]}" --out "$OUT/elsewhere" > /dev/null
[ "$(md5sum < "${RUNS[2]}/report.html")" = "$before" ] || fail "report --out overwrote the run's report"
for f in report.html results.json results.csv summary.md; do
  [ -s "$OUT/elsewhere/$f" ] || fail "report --out: no $f"
done

$PY "$SRC/tests/e2e/check_exchange.py" "$SRC/docs/results.schema.json" "$OUT/compare.txt" \
  "$OUT/history.txt" "${RUNS[@]}"
echo "1 passed, 0 failed"
