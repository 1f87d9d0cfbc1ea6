#!/usr/bin/env bash
# The price of software virtual texturing (docs/textures.md): runs
# bench/vt_cost.yaml and prints, per technique, instructions per frame and
# median frame time with virtual_texture off and software, and their ratio.
# Instructions are exact whatever the load; the times are only as good as
# the machine was quiet (the load average is printed).
# Usage: bench/vt_cost.sh BIN [OUT]
set -euo pipefail
BIN=${1:?usage: bench/vt_cost.sh path/to/dmbench [OUT]}
OUT=${2:-$(mktemp -d)}
HERE=$(cd "$(dirname "$0")" && pwd)
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
LP_NUM_THREADS=${LP_NUM_THREADS:-1} "$BIN" run "$HERE/vt_cost.yaml" --out "$OUT" --seed 1 --quiet
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$OUT/latest/results.json" <<'PY'
import json, sys
rows = {}
for c in json.load(open(sys.argv[1]))["configs"]:
    p = c["params"]
    t, vt = p["technique"], p.get("virtual_texture", "off")
    k = c["counters"]
    rows.setdefault(t, {})[vt] = (k["Instructions"].get("median"), k["WallTime"].get("median"))
print(f"{'technique':10} {'instr off':>12} {'instr VT':>12} {'ratio':>6} {'ms off':>8} {'ms VT':>8} {'ratio':>6}")
for t, r in rows.items():
    (io, wo), (iv, wv) = r["off"], r["software"]
    print(f"{t:10} {io:12.0f} {iv:12.0f} {iv / io:6.2f} {wo / 1e6:8.2f} {wv / 1e6:8.2f} {wv / wo:6.2f}")
PY
