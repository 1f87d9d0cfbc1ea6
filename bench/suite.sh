#!/usr/bin/env bash
# The test suite's cost, test by test (docs/testing.md): clones the
# checkout's HEAD into a scratch directory, builds it from nothing (timed),
# runs ctest there (timed), and prints each test's wall time, its share of
# the test phase, its labels (what it spends the time on: valgrind,
# sanitize, fuzz, browser, slurm, gate, e2e, unit) and its result, slowest
# first, with the load average before and after each phase.
#
# Usage: bench/suite.sh [CTEST_ARGS...]      e.g. bench/suite.sh -L quick
#   JOBS (default nproc) is ctest's -j and the build's; KEEP=1 keeps the
#   scratch directory (its path is printed).
# Stop other work on the machine first: every figure is only as good as the
# machine was quiet, which is why the load averages are printed.
set -uo pipefail
SRC=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel) || exit 1
JOBS=${JOBS:-$(nproc)}
W=$(mktemp -d "${TMPDIR:-/tmp}/dmbench-suite-XXXXXX")
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$W"' EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }

git clone -q "$SRC" "$W/src" || exit 1
echo "commit $(git -C "$W/src" rev-parse --short HEAD), $(nproc) cores, JOBS=$JOBS, $(date -u +%FT%TZ)"
echo "load before the build: $(load)"
t0=$(date +%s.%N)
make -C "$W/src" build JOBS="$JOBS" > "$W/build.log" 2>&1 || { tail -20 "$W/build.log"; exit 1; }
t1=$(date +%s.%N)
echo "build from a clean clone: $(awk "BEGIN{printf \"%.0f\", $t1 - $t0}") s; load after it: $(load)"
cd "$W/src/build" || exit 1
ctest -N "$@" --show-only=json-v1 > "$W/tests.json" 2>/dev/null
echo "load before the tests: $(load)"
t2=$(date +%s.%N)
ctest -j "$JOBS" --output-junit "$W/junit.xml" "$@" > "$W/ctest.log" 2>&1
rc=$?
t3=$(date +%s.%N)
echo "test phase: $(awk "BEGIN{printf \"%.0f\", $t3 - $t2}") s (ctest exit $rc); load after it: $(load)"
python3 - "$W/junit.xml" "$W/tests.json" <<'PY'
import json, sys, xml.etree.ElementTree as ET
labels = {}
for t in json.load(open(sys.argv[2])).get("tests", []):
    for p in t.get("properties", []):
        if p.get("name") == "LABELS":
            labels[t["name"]] = ",".join(p.get("value", []))
rows = []
for tc in ET.parse(sys.argv[1]).getroot().iter("testcase"):
    res = "failed" if tc.find("failure") is not None else "skipped" if tc.find("skipped") is not None else "passed"
    rows.append((float(tc.get("time", 0)), tc.get("name"), res))
total = sum(r[0] for r in rows) or 1
print(f"{len(rows)} tests, {total:.0f} s summed over the tests (ctest runs them in parallel)")
print(f"| test | s | share | labels | result |\n|---|---|---|---|---|")
for t, name, res in sorted(rows, reverse=True):
    print(f"| {name} | {t:.1f} | {100 * t / total:.1f} % | {labels.get(name, '')} | {res} |")
PY
exit $rc
