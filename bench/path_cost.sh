#!/usr/bin/env bash
# What timing a camera path costs a run (issue "Speed and memory"; docs/motion.md):
# the wall time of `dmbench run` on a one-configuration sweep of normal
# mapping on the plane at 240×135 with camera.path: dolly over 60 frames,
# against the same configuration still, each in a fresh output root (so
# both render their reference: the whole run, reference included).  Prints
# both times and their ratio; the target is at most 3×.  Asserts the work
# was done: each run measured its one configuration, the dolly with 60
# frames per replay and as many replays as WallTime samples.  The times are
# only as good as the machine was quiet (the load average is printed).
# Usage: bench/path_cost.sh BIN [OUT]
set -euo pipefail
BIN=${1:?usage: bench/path_cost.sh path/to/dmbench [OUT]}
OUT=${2:-$(mktemp -d)}
mkdir -p "$OUT"
common='resolution: [240, 135]\nsweep:\n  mesh: [plane]\n  technique: [normal]\n'
printf "name: path_cost_still\n$common" > "$OUT/still.yaml"
printf "name: path_cost_dolly\n${common}  camera.path: [dolly]\n  camera.path_frames: [60]\n" > "$OUT/dolly.yaml"
# wall seconds of one run of sweep $1 into $OUT/$1
run() {
  local t0 t1
  t0=$(date +%s.%N)
  "$BIN" run "$OUT/$1.yaml" --out "$OUT/$1" --seed 1 --quiet > /dev/null
  t1=$(date +%s.%N)
  python3 -c "print($t1 - $t0)"
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
still=$(run still)
dolly=$(run dolly)
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$OUT" "$still" "$dolly" <<'PY'
import json, sys
out, still, dolly = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
for name in ("still", "dolly"):
    cs = json.load(open(f"{out}/{name}/latest/results.json"))["configs"]
    assert len(cs) == 1 and cs[0]["status"] == "ok", (name, cs)
    p = cs[0].get("path")
    if name == "still":
        assert p is None, p
    else:
        n = len(cs[0]["counters"]["WallTime"]["samples"])
        assert p["frames"] == 60 and p["replays"] == n, (p["frames"], p["replays"], n)
        samples, p99 = n, p["p99_ms"]
print(f"still run {still:.1f} s, dolly run {dolly:.1f} s ({samples} replays of 60 frames, "
      f"p99 {p99:.3f} ms): {dolly / still:.2f}x (target <= 3x)")
PY
