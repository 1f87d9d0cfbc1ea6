#!/usr/bin/env bash
# The project's CI gate run once for the suite (fixture ci_gate_run,
# tests/instructions.cmake): `ci/gate.sh dmbench DIR` counts ci/gate.yaml
# and ci/gate-techniques.yaml into DIR/baseline and DIR/baseline-techniques
# and compares them with the committed baselines; its output goes to
# DIR/gate.log and its exit code to DIR/rc.  test_ci_gate asserts that
# code; test_instructions_gate and test_instructions_uber read the runs.
# This test passes when both runs exist with every configuration counted,
# whatever the gate's verdict, so a changed count fails test_ci_gate alone.
# Usage: gate_run.sh DIR  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
DIR=${1:?usage: gate_run.sh DIR}
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
rm -rf "$DIR"
mkdir -p "$DIR"
t0=$(date +%s)
rc=0
bash "$SRC/ci/gate.sh" "$BIN" "$DIR" > "$DIR/gate.log" 2>&1 || rc=$?
echo "$rc" > "$DIR/rc"
cat "$DIR/gate.log"
echo "ci/gate.sh: exit $rc in $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
[ "$rc" = 0 ] || [ "$rc" = 1 ] || exit 1      # 2: the gate could not compare (see above)
python3 "$SRC/tests/instructions/check_counted.py" "$DIR/baseline/latest/results.json" \
  "$DIR/baseline-techniques/latest/results.json"
