#!/usr/bin/env bash
# docs/ci-gating.md's recipe runs as written: every `ci/perf-gate.sh` and
# `dmbench` command line of the page's ```sh and ```yaml blocks is run
# with the built binary as both BASE and NEW (ROUNDS=5, the fewest the paired test can decide with at --alpha 0.01) in a scratch
# checkout layout (repo/{ci,sweeps,build/dmbench}, base/build/dmbench,
# dmbench on PATH) and must exit 0, or 3 (inconclusive timing, which the
# recipe lets pass); and every ci/ or sweeps/ file the page names exists.
# git/cmake/install lines are the CI system's set-up and are skipped.
# Usage: ci_recipe.sh [PART]: PART `perf-gate` runs the ci/perf-gate.sh
# lines (the job), `baseline` the dmbench lines (the baseline recipe), each
# with what it must leave behind; the suite runs the two side by side as
# test_ci_recipe and test_ci_recipe_baseline.  Without PART, both.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
DOC="$SRC/docs/ci-gating.md"
PART=${1:-all}
case $PART in all|perf-gate|baseline) ;; *) echo "usage: ci_recipe.sh [perf-gate|baseline]"; exit 2;; esac

[ "$PART" = baseline ] ||   # the files the page names: checked once
for f in $(grep -o '\(ci\|sweeps\)/[A-Za-z0-9_.-]*\.\(sh\|yaml\|json\)' "$DOC" | sort -u); do
  if [ -e "$SRC/$f" ]; then pass=$((pass+1)); else fail=$((fail+1)); echo "FAIL: $DOC names $f, which does not exist"; fi
done

W="$OUT/w"
mkdir -p "$W/repo/build" "$W/base/build" "$W/bin"
ln -s "$SRC/ci" "$W/repo/ci"; ln -s "$SRC/sweeps" "$W/repo/sweeps"
ln -s "$BIN" "$W/repo/build/dmbench"; ln -s "$BIN" "$W/base/build/dmbench"; ln -s "$BIN" "$W/bin/dmbench"

# The command lines, in page order, once each; "|| [ $? -eq 3 ]" (the
# recipe's way to let 3 pass) is checked by the exit rule below.
python3 - "$DOC" > "$OUT/commands" <<'PY'
import re, sys
lines, seen, block = [], set(), None
for raw in open(sys.argv[1]):
    if raw.startswith("```"):
        block = None if block else raw[3:].strip()
        continue
    if block not in ("sh", "yaml"):
        continue
    line = re.sub(r"^\s*(- )?(run: )?", "", raw.rstrip())
    line = re.sub(r"\s*\|\| \[ \$\? -eq 3 \]$", "", line)
    if re.match(r"(ci/perf-gate\.sh|dmbench) ", line) and line not in seen:
        seen.add(line)
        lines.append(line)
print("\n".join(lines))
PY
n=$(wc -l < "$OUT/commands")
[ "$n" -ge 5 ] && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: only $n recipe commands found in $DOC"; }
# this part's lines: the job's (ci/perf-gate.sh) or the baseline recipe's (dmbench)
case $PART in
  perf-gate) grep '^ci/perf-gate\.sh ' "$OUT/commands" > "$OUT/part" || true ;;
  baseline) grep '^dmbench ' "$OUT/commands" > "$OUT/part" || true ;;
  all) cp "$OUT/commands" "$OUT/part" ;;
esac
[ -s "$OUT/part" ] && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: no $PART command in $DOC"; }
while IFS= read -r cmd; do
  rc=0
  (cd "$W/repo" && PATH="$W/bin:$PATH" ROUNDS=5 timeout 900 bash -c "$cmd") >"$OUT/cmd.log" 2>&1 </dev/null || rc=$?
  if [ "$rc" = 0 ] || [ "$rc" = 3 ]; then pass=$((pass+1)); echo "ok (exit $rc): $cmd"
  else fail=$((fail+1)); echo "FAIL (exit $rc): $cmd"; tail -5 "$OUT/cmd.log"; fi
done < "$OUT/part"
# What the recipe promises to leave behind.
case $PART in
  perf-gate) left="perf/perf.md perf/instructions.xml perf/timing.xml perf/timing.json" ;;
  baseline) left="baseline.md" ;;
  all) left="perf/perf.md perf/instructions.xml perf/timing.xml perf/timing.json baseline.md" ;;
esac
for f in $left; do
  [ -s "$W/repo/$f" ] && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: the recipe left no $f"; }
done
[ "$PART" = baseline ] ||
{ grep -q '^## dmbench compare: ' "$W/repo/perf/perf.md" && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: perf.md has no headline"; }; }
tally
