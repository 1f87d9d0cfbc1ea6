#!/usr/bin/env bash
# test_ci_gate: the project's CI gate (ci/gate.sh, run once for the suite by
# test_ci_gate_run into DIR) passes: exit 0, every deterministic counter and
# the Instructions of every configuration of ci/gate.yaml and
# ci/gate-techniques.yaml as in ci/baseline.json and
# ci/baseline-techniques.json (within 0.5 %), no baseline configuration
# missing.  Prints the gate's output and its Markdown reports.
# Usage: ci_gate.sh DIR
set -uo pipefail
DIR=${1:?usage: ci_gate.sh DIR}
[ -f "$DIR/rc" ] || { echo "FAIL: no gate run in $DIR (the fixture test_ci_gate_run did not run)"; exit 1; }
cat "$DIR/gate.log"
for stem in baseline baseline-techniques; do
  [ -f "$DIR/$stem/gate.md" ] && { echo "== $stem"; cat "$DIR/$stem/gate.md"; }
done
rc=$(cat "$DIR/rc")
[ "$rc" = 0 ] || { echo "FAIL: ci/gate.sh exited $rc (1: a count changed or a baseline configuration is missing)"; exit 1; }
echo "ci/gate.sh: exit 0"
