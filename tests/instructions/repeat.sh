#!/usr/bin/env bash
# Instructions repeat across processes, caches and orders: SWEEP (default
# repeat.yaml: one configuration of each program family, tessellation at
# two levels) counted by three separate runs: two from empty caches (shader, map, reference and
# program caches in fresh directories) and one from the first run's warm
# caches, each with another --seed, so its Valgrind children count the
# configurations in another order.  The cold runs deal the configurations
# to two children (--count-jobs 2); the warm run counts them all in one
# child (--count-jobs 1), so each shares its child with other company.
# With --alone, also every configuration alone in a child of its own
# (--shard K/N, warm caches).
# Prints one line per configuration: the counts' range and spread, and the
# spread the same counts would have with the C allocator's instructions
# kept in (what Instructions counted before it left them out; each
# configuration's log names that part).
# Asserts: every configuration counted in each run; all its counts (two
# samples a run) within 1e-4 (0.01 %); no run warns about Instructions.
# Usage: repeat.sh [SWEEP] [--alone]  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set
# by ctest or bench/repeat.sh): the three runs, then the check.
# The suite runs the same in steps, each a ctest test, so the two cold runs
# go side by side (tests/instructions.cmake; the runs stay in DIR):
#   repeat.sh --run cold1|cold2|warm DIR   one run (warm: after cold1)
#   repeat.sh --check DIR                  the check of the three
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
STEP="" DIR=""
case "${1:-}" in
  --run) STEP=${2:?usage: repeat.sh --run cold1|cold2|warm DIR}; DIR=${3:?usage: repeat.sh --run STEP DIR}; set -- ;;
  --check) STEP=check; DIR=${2:?usage: repeat.sh --check DIR}; set -- ;;
esac
if [ -n "$DIR" ]; then   # the runs stay in DIR for the next step: not lib.sh's scratch OUT
  rm -rf "$OUT"; trap - EXIT
  OUT=$DIR; mkdir -p "$OUT"
fi
SWEEP=${1:-$SRC/tests/instructions/repeat.yaml}
ALONE=${2:-}

# run NAME CACHE SEED [ARGS...]: one run with its caches under $OUT/CACHE.
run() {
  local name=$1 cache=$2 seed=$3; shift 3
  mkdir -p "$OUT/$cache"
  XDG_CACHE_HOME="$OUT/$cache" DMBENCH_CACHE_DIR="$OUT/$cache/dmbench" MESA_SHADER_CACHE_DIR="$OUT/$cache/mesa" \
    "$BIN" run "$SWEEP" --out "$OUT/$name.root" --seed "$seed" --quiet "$@"
  ln -s "$(readlink -f "$OUT/$name.root/latest")" "$OUT/$name"
}

# The runs: cold1 and cold2 from empty caches, two children each; warm from
# cold1's caches and program binaries, now filled, in one child.
t0=$(date +%s)
case $STEP in
  cold1|cold2)
    n=${STEP#cold}
    rm -rf "${OUT:?}/$STEP" "$OUT/$STEP.root" "$OUT/c$n"
    run "$STEP" "c$n" "$n" --count-jobs 2
    echo "$STEP: $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
    exit 0 ;;
  warm)
    [ -d "$OUT/c1" ] && [ -e "$OUT/cold1" ] || { echo "no cold1 run in $OUT (test_instructions_repeat_cold1)"; exit 1; }
    rm -rf "$OUT/warm" "$OUT/warm.root"
    run warm c1 3 --count-jobs 1
    echo "warm: $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
    exit 0 ;;
  check) ;;
  *)
    run cold1 c1 1 --count-jobs 2
    run cold2 c2 2 --count-jobs 2 &  # two runs at a time at most: CI has 2 cores
    run warm c1 3 --count-jobs 1
    wait $! ;;
esac
runs=("$OUT/cold1" "$OUT/cold2" "$OUT/warm")
for r in "${runs[@]}"; do
  [ -f "$r/results.json" ] || { echo "no run $r (tests test_instructions_repeat_cold1, _cold2, _warm)"; exit 1; }
done
if [ "$ALONE" = --alone ]; then
  n=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["configs"]))' "$OUT/cold1/results.json")
  for k in $(seq 1 "$n"); do
    run "alone$k" c1 4 --shard "$k/$n"
    runs+=("$OUT/alone$k")
  done
fi
t1=$(date +%s)
echo "$(basename "$SWEEP"): ${#runs[@]} runs in $((t1 - t0)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"

python3 - "${runs[@]}" <<'PY'
import json, re, sys
runs = [json.load(open(d + "/results.json")) for d in sys.argv[1:]]
for r, name in zip(runs, sys.argv[1:]):   # e.g. samples that disagree; GPUTime's coverage is not ours
    assert not [w for w in r["warnings"] if "Instructions" in w], (name, r["warnings"])
cfg = [{c["key"]: c for c in r["configs"]} for r in runs]
whole = cfg[:3]                  # the three full runs; --alone runs hold one configuration each
assert all(c.keys() == whole[0].keys() for c in whole), [sorted(c) for c in whole]
alloc_re = re.compile(r"the C allocator's (\d+) instructions per frame")
worst = worst_kept = 0.0
for key, c0 in sorted(whole[0].items(), key=lambda kv: kv[1]["label"]):
    counts, kept = [], []
    for c in (x[key] for x in cfg if key in x):
        assert c["status"] == "ok", (key, c.get("reason"))
        i = c["counters"]["Instructions"]
        assert "unavailable" not in i, (key, i)
        assert len(i["samples"]) == 2, (key, i)
        counts += i["samples"]
        m = alloc_re.search(c.get("log") or "")
        kept += [s + (int(m.group(1)) if m else 0) for s in i["samples"]]
    spread = (max(counts) - min(counts)) / min(counts)
    spread_kept = (max(kept) - min(kept)) / min(kept)
    worst, worst_kept = max(worst, spread), max(worst_kept, spread_kept)
    print(f"{c0['label']}: {min(counts):.0f} .. {max(counts):.0f} instructions/frame in {len(counts)} "
          f"samples, spread {spread:.1e} (allocator kept in: {spread_kept:.1e})")
    assert spread <= 1e-4, (key, c0["label"], counts, spread)
print(f"worst spread {worst:.1e} (allocator kept in: {worst_kept:.1e}); instructions repeat: all passed")
PY
