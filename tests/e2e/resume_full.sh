#!/usr/bin/env bash
# An uninterrupted run of tests/e2e/resume.yaml, made once for the suite by
# test_e2e_resume_full (fixture resume_full, tests/e2e.cmake) and read by
# test_e2e_resume, test_merge_machines and test_slurm_array, which each
# made this same run for themselves before: the set of keys a resumed,
# merged or Slurm-merged run must equal, and the one-machine run a
# two-machine merge is compared with.  They only read it.
# Usage: resume_full.sh DIR         make the run into DIR (emptied first) and
#                                   check it: 12 configurations, every one ok
#        resume_full.sh --use DIR   print the run's output root for a reader:
#                                   $RESUME_FULL (the suite's, set by ctest)
#                                   when set, else the run made into DIR
#                                   (a reader run by hand)
# (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
SRC=${DMBENCH_SOURCE_DIR:?}
BIN=${DMBENCH_BINARY:?}
if [ "${1:-}" = --use ]; then
  DIR=${2:?usage: resume_full.sh --use DIR}
  if [ -n "${RESUME_FULL:-}" ]; then
    [ -f "$RESUME_FULL/latest/results.json" ] ||
      { echo "no run in $RESUME_FULL (fixture test_e2e_resume_full)" >&2; exit 1; }
    echo "$RESUME_FULL"
    exit 0
  fi
  bash "$0" "$DIR" >&2
  echo "$DIR"
  exit 0
fi
DIR=${1:?usage: resume_full.sh DIR | --use DIR}
rm -rf "$DIR"
mkdir -p "$DIR"
"$BIN" run "$SRC/tests/e2e/resume.yaml" --out "$DIR" --quiet
python3 - "$DIR/latest/results.json" <<'PY'
import json, sys
cs = json.load(open(sys.argv[1]))["configs"]
assert len(cs) == 12, f"{len(cs)} configurations, expected 12"
bad = [(c["label"], c.get("reason")) for c in cs if c["status"] != "ok"]
assert not bad, bad
print(f"{sys.argv[1]}: 12 configurations, all ok")
PY
