#!/usr/bin/env bash
# test_loop_trips: LoopTrips and FragmentGroups counted by hand
# (docs/counters.md, "Loop trips" and "Fragment groups").  llvmpipe runs a
# fragment shader on 4x4 blocks, once per triangle that touches the block
# (FSInvocations counts 16 a block), in groups of (vector bits / 32)
# fragments, the width its renderer string names ("LLVM 15.0.6, 256 bits":
# 8, the block's rows two at a time: 4x2 fragments), and runs only the
# groups that hold a fragment the triangle covers.  The full-screen quad
# (tests/stages/loop_trips.yaml) is two triangles split along the diagonal
# from the lower left to the upper right corner; a pixel belongs to the
# lower one when its centre lies below it.  So, by hand:
#   FragmentGroups = over both triangles, the 4x2 groups holding one of its pixels;
#   LoopTrips = steps/2 * FragmentGroups (every fragment stops at steps/2), 0 for normal.
# On the square quads every group of a touched block holds one
# (FragmentGroups = FSInvocations / 8); at 64x48 and 100x36 some do not.
# No Valgrind; ~15 s.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
bits=$("$BIN" info | sed -n 's/.*renderer.*llvmpipe.* \([0-9]*\) bits).*/\1/p')
[ -n "$bits" ] || { echo "SKIP: not llvmpipe (the group width is llvmpipe's)"; exit 77; }
[ "$bits" = 256 ] || { echo "SKIP: llvmpipe at $bits bits (the groups' shape, 4x2, is measured at 256 bits only)"; exit 77; }
"$BIN" run "$SRC/tests/stages/loop_trips.yaml" --out "$OUT/r" --seed 1 --quiet
python3 - "$OUT/r/latest/results.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
gw, gh = 4, 2   # a group's fragments at 256 bits: two rows of four

def groups_by_hand(w, h):
    """The groups over both triangles of the quad that hold one of its pixels."""
    n = 0
    for lower in (True, False):
        n += len({(x // gw, y // gh) for y in range(h) for x in range(w)
                  if ((y + 0.5) * w < (x + 0.5) * h) == lower})
    return n

def val(k, name):
    t = k.get(name, {})
    return t.get("value", t.get("median")) if "unavailable" not in t else None

bad, n, partial = [], 0, 0
for c in j["configs"]:
    p, k = c["params"], c["counters"]
    trips, groups, fs = val(k, "LoopTrips"), val(k, "FragmentGroups"), val(k, "FSInvocations")
    if trips is None or groups is None:
        bad.append(f"{p['technique']} {p['resolution']}: missing or unavailable: {k.get('LoopTrips')} {k.get('FragmentGroups')}")
        continue
    w, h = map(int, p["resolution"].split("x"))
    steps = p.get("steps", "-")   # normal mapping does not read steps: one configuration a resolution
    want_g = groups_by_hand(w, h)
    want_t = 0 if p["technique"] == "normal" else int(steps) // 2 * want_g
    print(f"{p['technique']} {p['resolution']} steps {steps}: FragmentGroups {groups:.0f}, by hand {want_g} "
          f"(FSInvocations / {gw * gh} = {fs / (gw * gh):.0f}); LoopTrips {trips:.0f}, by hand {want_t}")
    n += 1
    partial += want_g < fs / (gw * gh)
    if groups != want_g:
        bad.append(f"{p['technique']} {p['resolution']}: FragmentGroups {groups} != {want_g}")
    if trips != want_t:
        bad.append(f"{p['technique']} {p['resolution']} steps {steps}: LoopTrips {trips} != {want_t}")
if n != 20:
    bad.append(f"{n} configurations checked, expected 20")
if partial < 10:   # the two oblong resolutions: 5 configurations each
    bad.append(f"only {partial} configurations with groups the quad leaves empty, expected 10")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
