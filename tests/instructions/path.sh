#!/usr/bin/env bash
# Instructions of a configuration on a camera path count a replay of the
# path, each frame finished on its own, per frame (run/callgrind.c:
# callgrind_path_frames; docs/counters.md, "On a camera path"), not its
# frame 0:
# - a two-frame path whose two frames are the still camera at 0.8 exactly
#   (an orbit of 2 frames, 180° a frame, turned back by
#   camera.orbit_deg_per_frame -180; a dolly that does not move is refused
#   as bad input, and one that moves 10 micrometres already counts 1.4 %
#   more, as the dolly below) counts what the still camera at 0.8 counts,
#   within 1e-3 (the
#   per-frame division and the per-frame glFinish; without the latter two
#   frames counted 12 % less each);
# - a two-frame dolly from 3 to 0.8 draws the still camera at 3 (frame 0)
#   and at 0.8 (frame 1; tests/e2e/paths.sh checks both images): its count
#   differs from frame 0's by over 10 % and lies within 5 % of the mean of
#   the two still counts (measured 1.8 % above it: its view changes every
#   frame, a still configuration's does not).
# Two runs, so two Valgrind children: the still camera at 0.8 with the
# orbit turned back there (one sweep, camera.path [still, orbit]; a still
# configuration ignores the path's frames, run/path_timing.c), and the
# dolly with its frame 0.  Sharing a child moves the 160 k-instruction
# frames by what the child counted before (docs/counters.md, 10-180 a
# frame): on 2026-11-29 the two counted 160 590 and 160 588 in one child,
# 160 542 and 160 636 in a child each; 10^-3 is 160.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
head='resolution: [32, 18]
measure:
  warmup_frames: 1
  frames_per_sample: 1
  samples: { min: 2, max: 2, target_ci: 0.5 }
  max_seconds: 1
  counters: [Instructions]
scene:
  texture_size: 64'
printf '%s\nname: path-near\nsweep:\n  mesh: [plane]\n  technique: [texture]\n  camera.distance: [0.8]\n  light.distance: [4.5]\n  camera.path: [still, orbit]\n  camera.path_frames: [2]\n  camera.orbit_deg_per_frame: [-180]\n' \
  "$head" > "$OUT/near.yaml"
printf '%s\nname: path-dolly\nsweep:\n  mesh: [plane]\n  technique: [texture]\n  camera.distance: [3]\n  camera.path: [still, dolly]\n  camera.path_frames: [2]\n  camera.dolly_to: [0.8]\n' \
  "$head" > "$OUT/dolly.yaml"
"$BIN" run "$OUT/near.yaml" --out "$OUT/near" --quiet
"$BIN" run "$OUT/dolly.yaml" --out "$OUT/dolly" --quiet
python3 - "$OUT/near/latest/results.json" "$OUT/dolly/latest/results.json" <<'PY'
import json, sys
def counts(path):
    out = {}
    for c in json.load(open(path))["configs"]:
        assert c["status"] == "ok", (path, c["label"], c.get("reason"))
        i = c["counters"]["Instructions"]
        assert "unavailable" not in i, (path, c["label"], i)
        out[c["params"].get("camera.path", "still")] = i["median"]
    return out
near, d = counts(sys.argv[1]), counts(sys.argv[2])
assert sorted(near) == ["orbit", "still"] and sorted(d) == ["dolly", "still"], (sorted(near), sorted(d))
f0, f1, dolly, still = d["still"], near["still"], d["dolly"], near["orbit"]
mean = (f0 + f1) / 2
print(f"frame 0 (still at 3): {f0:.0f}, frame 1 (still at 0.8): {f1:.0f}, mean {mean:.0f}; "
      f"dolly 3 to 0.8: {dolly:.0f} ({(dolly - mean) / mean:+.2%} from the mean); orbit turned back at 0.8: {still:.0f}")
assert abs(still - f1) / f1 < 1e-3, ("two identical frames should count as one still frame", still, f1)
assert abs(f1 - f0) / f0 > 0.2, ("the two views should cost differently", f0, f1)
assert abs(dolly - f0) / f0 > 0.1, ("the dolly counted only its frame 0", dolly, f0)
assert abs(dolly - mean) / mean < 0.05, ("the dolly's count is not near the mean of its two frames", dolly, mean)
print("PASS")
PY
