#!/usr/bin/env bash
# Instructions repeat across processes, caches and orders: repeat.yaml
# (every technique, tessellation at two levels) counted by three separate
# runs: two from empty caches (shader, map, reference and program caches
# in fresh directories) and one from the first run's warm caches, each
# with another --seed, so its Valgrind child counts the configurations in
# another order.  Asserts: every configuration counted in each run; the two
# samples of a run and the three runs agree within 0.01 %; no run warns.
# Usage: repeat.sh  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP="$SRC/tests/instructions/repeat.yaml"

# run NAME CACHE SEED: one run with its caches under $OUT/CACHE.
run() {
  mkdir -p "$OUT/$2"
  XDG_CACHE_HOME="$OUT/$2" DMBENCH_CACHE_DIR="$OUT/$2/dmbench" MESA_SHADER_CACHE_DIR="$OUT/$2/mesa" \
    "$BIN" run "$SWEEP" --out "$OUT/$2/out" --seed "$3" --quiet
  ln -s "$(readlink -f "$OUT/$2/out/latest")" "$OUT/$1"   # latest moves on with the next run
}

t0=$(date +%s)
run cold1 c1 1
run cold2 c2 2 &  # two at a time at most: CI has 2 cores
run warm c1 3     # c1's caches and program binaries, now filled
wait $!
t1=$(date +%s)
echo "three runs: $((t1 - t0)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"

python3 - "$OUT/cold1" "$OUT/cold2" "$OUT/warm" <<'PY'
import json, sys
runs = [json.load(open(d + "/results.json")) for d in sys.argv[1:]]
cfg = [{c["key"]: c for c in r["configs"]} for r in runs]
techs = {c["params"]["technique"] for c in cfg[0].values()}
assert len(techs) == 10 and len(cfg[0]) == 11, (techs, len(cfg[0]))
assert all(c.keys() == cfg[0].keys() for c in cfg), [sorted(c) for c in cfg]
for r, name in zip(runs, sys.argv[1:]):
    assert not r["warnings"], (name, r["warnings"])
worst = 0.0
for key, c0 in sorted(cfg[0].items(), key=lambda kv: kv[1]["label"]):
    counts = []
    for c in (x[key] for x in cfg):
        assert c["status"] == "ok", (key, c.get("reason"))
        i = c["counters"]["Instructions"]
        assert "unavailable" not in i, (key, i)
        assert len(i["samples"]) == 2, (key, i)
        counts += i["samples"]
    spread = (max(counts) - min(counts)) / min(counts)
    worst = max(worst, spread)
    print(f"{c0['label']}: {min(counts):.0f} .. {max(counts):.0f} instructions/frame (spread {spread:.1e})")
    assert spread <= 1e-4, (key, c0["label"], counts, spread)
print(f"worst spread {worst:.1e}; instructions repeat: all passed")
PY
