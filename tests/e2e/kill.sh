#!/usr/bin/env bash
# No process outlives its run (docs/reliability.md, "Interruptions"): the
# parent is killed with SIGTERM and with SIGKILL at each stage that has a
# child — a probe child (a user shader whose compile takes seconds; zink
# hung at start-up where Mesa 25 is installed), the timed measuring child
# (hung by DMBENCH_TEST_HANG), the Valgrind counting child (Instructions
# pass) and the `dmbench run` that `drivers` starts per driver — and 5 s
# later no process of that run may be left.  The processes of a run are
# found by a variable set for it alone (DMBENCH_KILL_TEST=<unique>,
# inherited by every child, Valgrind's too), so no other process on the
# machine is matched.  Also: after SIGTERM or SIGKILL of `drivers`,
# `drivers` again on the same --out is not refused as "in use", and no
# product source forks but core/dm_proc.c.
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
MARK="kill-$$-$RANDOM$RANDOM"
LEFT=""   # processes found left behind: killed at the end, after the checks that need them
trap 'kill -KILL $LEFT 2>/dev/null; rm -rf "$OUT"' EXIT

# pids of the processes of run $1 (their environment holds its marker)
procs() {
  grep -lzxF "DMBENCH_KILL_TEST=$MARK-$1" /proc/[0-9]*/environ 2>/dev/null | cut -d/ -f3
}
# wait_for SECONDS CMD...: true once CMD succeeds, false after SECONDS
wait_for() {
  local t=$1; shift
  for _ in $(seq $((t * 10))); do "$@" && return 0; sleep 0.1; done
  return 1
}
# a process of run $1 other than pid $2 whose command line has $3
has_child() {
  local p
  for p in $(procs "$1"); do
    [ "$p" != "$2" ] && tr '\0' ' ' 2>/dev/null < "/proc/$p/cmdline" | grep -qF -- "$3" && return 0
  done
  return 1
}
# stage NAME SIGNAL WHAT READY... -- COMMAND...: starts COMMAND as run
# NAME-SIGNAL, waits until READY succeeds (a stage is reached), sends
# SIGNAL to COMMAND's process and checks that within 5 s no process of the
# run is left (the ones left are killed and listed).
stage() {
  local name=$1 sig=$2; shift 2
  local ready=()
  while [ "$1" != "--" ]; do ready+=("$1"); shift; done; shift
  local id="$name-$sig"
  env DMBENCH_KILL_TEST="$MARK-$id" "$@" > "$OUT/$id.log" 2>&1 &
  local pid=$!
  RUN_ID=$id RUN_PID=$pid
  if ! wait_for 60 "${ready[@]}"; then
    echo "FAIL: $id: the stage was not reached in 60 s: $(tail -c 300 "$OUT/$id.log")"
    fail=$((fail+1)); kill -KILL $(procs "$id") 2>/dev/null; wait "$pid" 2>/dev/null; return
  fi
  kill -s "$sig" "$pid"
  wait "$pid" 2>/dev/null
  if wait_for 5 none_left; then
    pass=$((pass+1))
  else
    local left; left=$(procs "$id")
    echo "FAIL: $id: processes left 5 s after SIG$sig of the parent:"
    for p in $left; do echo "  $p (PPID $(awk '{print $4}' "/proc/$p/stat" 2>/dev/null)): $(tr '\0' ' ' 2>/dev/null < "/proc/$p/cmdline" | head -c 200)"; done
    LEFT="$LEFT $left"
    fail=$((fail+1))
  fi
}
child_of_run() { has_child "$RUN_ID" "$RUN_PID" "$1"; }
none_left() { [ -z "$(procs "$RUN_ID")" ]; }
# a child of the run exists and the run's directory does (past the probe)
measuring() { [ -e "$1/dmbench.lock" ] && child_of_run ""; }
counting() { child_of_run "__instructions"; }
# `drivers` started its run and that run its measuring child
driver_run() { [ -e "$1/llvmpipe/dmbench.lock" ] && [ "$(procs "$RUN_ID" | wc -l)" -ge 3 ]; }

base() {   # base NAME TECHNIQUE COUNTERS: a 16x16 sweep of one configuration
  cat > "$OUT/$1.yaml" <<EOF
name: kill
resolution: [16, 16]
measure:
  warmup_frames: 1
  frames_per_sample: 1
  samples: { min: 3, max: 3 }
  counters: [$3]
  timeout_s: 120
sweep:
  mesh: [plane]
  technique: [$2]
EOF
}
# a valid shader the compiler takes seconds over (40000 dependent
# statements), its text unique so no shader cache has it
python3 - "$OUT/slow.glsl" "$MARK" <<'EOF'
import sys
body = "".join("    s = s * x + %d.0;\n" % i for i in range(40000))
open(sys.argv[1], "w").write("//@technique slow\n// %s\nvec3 user_surface(vec2 uv, vec3 v)\n{\n"
                             "    float x = uv.x;\n    float s = 0.0;\n%s    return vec3(uv, fract(s) * 0.0 + 0.5);\n}\n"
                             % (sys.argv[2], body))
EOF
base probe slow.glsl WallTime
# the driver probe itself hung: zink whose Vulkan ICD names no library (a
# broken Mesa 25 install hangs at start-up); only where Mesa 25 is installed
M25=${DMBENCH_MESA25_PREFIX:-/opt/dmbench/mesa-25}
if [ -e "$M25/lvp_icd.json" ]; then
  mkdir -p "$OUT/brokenicd"; ln -sfn "$M25/usr" "$OUT/brokenicd/usr"
  printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "/nonexistent/libvulkan_lvp.so", "api_version": "1.4.0"}}\n' \
    > "$OUT/brokenicd/lvp_icd.json"
fi
base timed normal WallTime
base counting normal Instructions
base quick normal WallTime

for sig in TERM KILL; do
  stage probe $sig child_of_run "" -- env MESA_SHADER_CACHE_DISABLE=true "$BIN" run "$OUT/probe.yaml" --out "$OUT/probe-$sig" --quiet
  [ -e "$OUT/brokenicd/lvp_icd.json" ] && stage driver-probe $sig child_of_run "" -- \
    env DMBENCH_DRIVER=zink DMBENCH_MESA25_PREFIX="$OUT/brokenicd" "$BIN" run "$OUT/quick.yaml" --out "$OUT/dp-$sig" --quiet
  stage timed $sig measuring "$OUT/timed-$sig" -- \
    env DMBENCH_TEST_HANG=normal "$BIN" run "$OUT/timed.yaml" --out "$OUT/timed-$sig" --quiet
  stage counting $sig counting -- \
    env DMBENCH_TEST_HANG=normal "$BIN" run "$OUT/counting.yaml" --out "$OUT/counting-$sig" --quiet --count-jobs 1
  stage drivers $sig driver_run "$OUT/drivers-$sig" -- \
    env DMBENCH_TEST_HANG=normal "$BIN" drivers "$OUT/timed.yaml" --drivers llvmpipe --out "$OUT/drivers-$sig" --quiet
  # the killed `drivers` left no run holding its output's lock: the next one runs
  rc=0; err=$(timeout 120 "$BIN" drivers "$OUT/quick.yaml" --drivers llvmpipe --out "$OUT/drivers-$sig" --quiet 2>&1 >/dev/null) || rc=$?
  if [ "$rc" -eq 0 ]; then pass=$((pass+1))
  else echo "FAIL: drivers again after SIG$sig: exit $rc: $(grep -m1 'error' <<<"$err" | head -c 300)"; fail=$((fail+1)); fi
done

# one rule in one place: no product source calls fork() but core/dm_proc.c
forks=$(cd "$SRC" && grep -rlE '\bv?fork[[:space:]]*\(' --include='*.c' --include='*.cc' \
          bench cli core counters gate models reports run store sweep techniques viewer | grep -vx core/dm_proc.c)
if [ -z "$forks" ]; then pass=$((pass+1)); else echo "FAIL: fork() outside core/dm_proc.c: $forks"; fail=$((fail+1)); fi
tally
