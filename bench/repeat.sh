#!/usr/bin/env bash
# Do Instructions repeat for every technique and every axis value that
# changes the work?  Runs tests/instructions/repeat.sh (three runs a sweep:
# two from empty caches, one warm, each in another --seed order; with
# --alone also every configuration alone in a run of its own) on the
# acceptance matrix in bench/repeat/: tessellation levels 1-64, spacing and
# LOD modes, crack-free edges, patch and face culling, light counts,
# shadows, software virtual texturing and vertex filters.  Prints one line
# per configuration (range, spread, and the spread with the C allocator
# kept in) and fails on a spread above 1e-4.  Counts do not depend on the
# machine's load; the time the runs took does.
# Usage: bench/repeat.sh BIN [--alone] [SWEEP...]   (default: bench/repeat/*.yaml)
set -uo pipefail
BIN=$(readlink -f "${1:?usage: bench/repeat.sh path/to/dmbench [--alone] [SWEEP...]}"); shift
HERE=$(cd "$(dirname "$0")" && pwd)
ALONE=""
if [ "${1:-}" = --alone ]; then ALONE=--alone; shift; fi
[ $# -gt 0 ] || set -- "$HERE"/repeat/*.yaml
echo "bench/repeat.sh: $(date -u +%FT%TZ), load $(cut -d' ' -f1-3 /proc/loadavg)"
rc=0
for sweep in "$@"; do
  DMBENCH_BINARY=$BIN DMBENCH_SOURCE_DIR=$HERE/.. bash "$HERE/../tests/instructions/repeat.sh" \
    "$(readlink -f "$sweep")" $ALONE || rc=1
done
exit $rc
