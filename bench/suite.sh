#!/usr/bin/env bash
# The test suite's cost, test by test (docs/testing.md): clones the
# checkout's HEAD into a scratch directory, builds it from nothing (timed),
# runs ctest there (timed), and prints each test's wall time, its share of
# the test phase, its labels (valgrind, sanitize, fuzz, browser, slurm,
# gate, e2e, unit, quick) and its result, slowest first, with the load
# average before and after each phase.  With --count, also what each test
# spent it on: how many times it started the dmbench binary and how many
# Valgrind children it started.
#
# Usage: bench/suite.sh [--quick] [--count] [CTEST_ARGS...]
#   --quick   time the quick tier only (ctest -L quick, `make check`)
#   --count   count each test's dmbench starts and Valgrind children: the
#             clone's build/dmbench and `valgrind` on PATH become small
#             wrappers that log the test that started them (a few ms a
#             start; leave it off for the timing figures of the docs)
#   CTEST_ARGS are passed to ctest, e.g. -L gate or -R test_store
#   JOBS (default nproc) is the build's -j, TEST_JOBS (default nproc + 1,
#   as `make test`) ctest's; KEEP=1 keeps the scratch directory (its path
#   is printed).
# Stop other work on the machine first: every figure is only as good as the
# machine was quiet, which is why the load averages are printed.
set -uo pipefail
SRC=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel) || exit 1
JOBS=${JOBS:-$(nproc)}
TEST_JOBS=${TEST_JOBS:-$(( $(nproc) + 1 ))}
quick=0; count=0; args=()
for a in "$@"; do
  case $a in
    --quick) quick=1 ;;
    --count) count=1 ;;
    *) args+=("$a") ;;
  esac
done
[ "$quick" = 1 ] && args=(-L quick "${args[@]}")
W=$(mktemp -d "${TMPDIR:-/tmp}/dmbench-suite-XXXXXX")
[ "${KEEP:-0}" = 1 ] && echo "scratch directory: $W" || trap 'rm -rf "$W"' EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }

git clone -q "$SRC" "$W/src" || exit 1
echo "commit $(git -C "$W/src" rev-parse --short HEAD), $(nproc) cores, JOBS=$JOBS, TEST_JOBS=$TEST_JOBS, $(date -u +%FT%TZ)"
[ "$quick" = 1 ] && echo "the quick tier (ctest -L quick)"
echo "load before the build: $(load)"
t0=$(date +%s.%N)
make -C "$W/src" build JOBS="$JOBS" > "$W/build.log" 2>&1 || { tail -20 "$W/build.log"; exit 1; }
t1=$(date +%s.%N)
echo "build from a clean clone: $(awk "BEGIN{printf \"%.0f\", $t1 - $t0}") s; load after it: $(load)"
cd "$W/src/build" || exit 1
ctest -N "${args[@]}" --show-only=json-v1 > "$W/tests.json" 2>/dev/null

# --count: wrappers that log "WHAT<TAB>command line of the ctest test that
# started it" (the ancestor whose parent is ctest) in one write, then exec
# the real one.
if [ "$count" = 1 ]; then
  mkdir -p "$W/shim"
  who='p=$$; while pp=$(cut -d" " -f4 /proc/$p/stat 2>/dev/null) && [ "${pp:-0}" -gt 1 ]; do
    if [ "$(cat /proc/$pp/comm 2>/dev/null)" = ctest ]; then tr "\0" " " < /proc/$p/cmdline; break; fi; p=$pp; done'
  real_vg=$(command -v valgrind || true)
  if [ -n "$real_vg" ]; then
    printf '#!/bin/bash\nt=$(%s)\nprintf "valgrind\\t%%s\\n" "$t" >> %q\nexec %q "$@"\n' \
      "$who" "$W/count.log" "$real_vg" > "$W/shim/valgrind"
    chmod +x "$W/shim/valgrind"; export PATH="$W/shim:$PATH"
  fi
  mv dmbench dmbench.real
  printf '#!/bin/bash\nt=$(%s)\nprintf "dmbench\\t%%s\\n" "$t" >> %q\nexec -a "$0" %q "$@"\n' \
    "$who" "$W/count.log" "$PWD/dmbench.real" > dmbench
  chmod +x dmbench
  : > "$W/count.log"
fi

echo "load before the tests: $(load)"
t2=$(date +%s.%N)
ctest -j "$TEST_JOBS" --output-junit "$W/junit.xml" "${args[@]}" > "$W/ctest.log" 2>&1
rc=$?
t3=$(date +%s.%N)
echo "test phase: $(awk "BEGIN{printf \"%.0f\", $t3 - $t2}") s (ctest exit $rc); load after it: $(load)"
[ "$count" = 1 ] && mv dmbench.real dmbench
python3 - "$W/junit.xml" "$W/tests.json" "$W/count.log" "$count" <<'PY'
import json, sys, collections, xml.etree.ElementTree as ET
labels, by_cmd = {}, {}
for t in json.load(open(sys.argv[2])).get("tests", []):
    by_cmd[" ".join(t.get("command", [])).strip()] = t["name"]
    for p in t.get("properties", []):
        if p.get("name") == "LABELS":
            labels[t["name"]] = ",".join(p.get("value", []))
counted = sys.argv[4] == "1"
starts = collections.defaultdict(collections.Counter)
if counted:
    for line in open(sys.argv[3], errors="replace"):
        what, _, cmd = line.rstrip("\n").partition("\t")
        starts[by_cmd.get(cmd.strip(), "(not a test of this ctest)")][what] += 1
rows = []
for tc in ET.parse(sys.argv[1]).getroot().iter("testcase"):
    res = "failed" if tc.find("failure") is not None else "skipped" if tc.find("skipped") is not None else "passed"
    rows.append((float(tc.get("time", 0)), tc.get("name"), res))
total = sum(r[0] for r in rows) or 1
print(f"{len(rows)} tests, {total:.0f} s summed over the tests (ctest runs them in parallel)")
extra = " dmbench starts | Valgrind children |" if counted else ""
print(f"| test | s | share | labels | result |{extra}\n|---|---|---|---|---|" + ("---|---|" if counted else ""))
for t, name, res in sorted(rows, reverse=True):
    c = starts.get(name, {})
    more = f" {c.get('dmbench', 0)} | {c.get('valgrind', 0)} |" if counted else ""
    print(f"| {name} | {t:.1f} | {100 * t / total:.1f} % | {labels.get(name, '')} | {res} |{more}")
if counted and "(not a test of this ctest)" in starts:
    c = starts["(not a test of this ctest)"]
    print(f"started outside the tests above: {c.get('dmbench', 0)} dmbench, {c.get('valgrind', 0)} Valgrind")
PY
exit $rc
