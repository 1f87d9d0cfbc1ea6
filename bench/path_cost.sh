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
# Also prints each run's peak resident set (the issue's memory target:
# today's run plus the path's frames at the run's resolution).
# Usage: bench/path_cost.sh BIN [OUT]
set -euo pipefail
BIN=${1:?usage: bench/path_cost.sh path/to/dmbench [OUT]}
OUT=${2:-$(mktemp -d)}
mkdir -p "$OUT"
common='resolution: [240, 135]\nsweep:\n  mesh: [plane]\n  technique: [normal]\n'
printf "name: path_cost_still\n$common" > "$OUT/still.yaml"
printf "name: path_cost_dolly\n${common}  camera.path: [dolly]\n  camera.path_frames: [60]\n" > "$OUT/dolly.yaml"
# wall seconds of one run of sweep $1 into $OUT/$1; its peak resident set
# (the largest of the run and the children it waited for, in KB, from
# GNU time) goes to $OUT/$1.rss
run() {
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -f %M -o "$OUT/$1.rss" "$BIN" run "$OUT/$1.yaml" --out "$OUT/$1" --seed 1 --quiet > /dev/null
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
rss = {n: int(open(f"{out}/{n}.rss").read().split()[-1]) for n in ("still", "dolly")}
frame_mb = 240 * 135 * 16 / 2**20   # one RGBA float frame at the run's resolution
print(f"peak resident set: still {rss['still'] / 1024:.1f} MB, dolly {rss['dolly'] / 1024:.1f} MB "
      f"(+{(rss['dolly'] - rss['still']) / 1024:.1f} MB; the path's 60 frames at 240x135 "
      f"would be {60 * frame_mb:.1f} MB)")
PY
