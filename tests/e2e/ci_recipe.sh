#!/usr/bin/env bash
# docs/ci-gating.md's recipe runs as written: every `ci/perf-gate.sh` and
# `dmbench` command line of the page's ```sh and ```yaml blocks is run
# with the built binary as both BASE and NEW (ROUNDS=2) in a scratch
# checkout layout (repo/{ci,sweeps,build/dmbench}, base/build/dmbench,
# dmbench on PATH) and must exit 0, or 3 (inconclusive timing, which the
# recipe lets pass); and every ci/ or sweeps/ file the page names exists.
# git/cmake/install lines are the CI system's set-up and are skipped.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
DOC="$SRC/docs/ci-gating.md"

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
while IFS= read -r cmd; do
  rc=0
  (cd "$W/repo" && PATH="$W/bin:$PATH" ROUNDS=2 timeout 900 bash -c "$cmd") >"$OUT/cmd.log" 2>&1 </dev/null || rc=$?
  if [ "$rc" = 0 ] || [ "$rc" = 3 ]; then pass=$((pass+1)); echo "ok (exit $rc): $cmd"
  else fail=$((fail+1)); echo "FAIL (exit $rc): $cmd"; tail -5 "$OUT/cmd.log"; fi
done < "$OUT/commands"
# What the recipe promises to leave behind.
for f in perf/perf.md perf/instructions.xml perf/timing.xml perf/timing.json baseline.md; do
  [ -s "$W/repo/$f" ] && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: the recipe left no $f"; }
done
grep -q '^## dmbench compare: ' "$W/repo/perf/perf.md" && pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: perf.md has no headline"; }
tally
