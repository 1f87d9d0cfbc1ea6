# corpus.d/children.sh — child processes (probe, counting, driver runs) and
# the environment they meet; sourced by corpus.sh.  (Killing the parent at
# each stage with a child is tests/e2e/kill.sh.)

if wanted children; then
# A user GLSL that crashes the GLSL compiler: a valid shader, one sum of
# 300 000 terms (~600 KB), overflows the compiler's stack.  run, render and
# predict compile user techniques in a child first: exit 2 naming the file,
# never a SIGSEGV of dmbench, never "the driver probe produced no result".
python3 - "$OUT/crash.glsl" <<'EOF'
import sys
open(sys.argv[1], "w").write("//@technique crash\nvec3 user_surface(vec2 uv, vec3 v)\n{\n    float x = uv.x;\n"
                             "    float s = " + "+".join(["x"] * 300000) + ";\n    return vec3(uv, fract(s) * 0.0 + 0.5);\n}\n")
EOF
f=$(sweep crash "resolution: [16, 16]" "sweep:" "  mesh: [plane]" "  technique: [crash.glsl]")
hcase children/compiler-crash-run 2 "crash.glsl: the GLSL compiler crashed on user technique 'crash'" -- \
  "$BIN" run "$f" --out "$NEVER"
hcase children/compiler-crash-render 2 "crash.glsl: the GLSL compiler crashed" -- \
  "$BIN" render "technique=$OUT/crash.glsl" resolution=16x16 --png "$OUT/crash.png"
hcase children/compiler-crash-predict 2 "crash.glsl: the GLSL compiler crashed" -- \
  "$BIN" predict "$f" --from "$OUT/ok/latest"
# A valid shader whose compile outlasts the probe's limit (100 000
# dependent statements: 10-30 s; the limit set to 3 s, which the driver
# probe itself meets; a text no shader cache holds): exit 2 naming the
# file and the limit, not exit 4 "crashed or hung".
python3 - "$OUT/slowc.glsl" "$$-$RANDOM" <<'EOF'
import sys
body = "".join("    s = s * x + %d.0;\n" % i for i in range(100000))
open(sys.argv[1], "w").write("//@technique slowc\n// %s\nvec3 user_surface(vec2 uv, vec3 v)\n{\n    float x = uv.x;\n"
                             "    float s = 0.0;\n%s    return vec3(uv, fract(s) * 0.0 + 0.5);\n}\n" % (sys.argv[2], body))
EOF
f=$(sweep slowc "resolution: [16, 16]" "sweep:" "  mesh: [plane]" "  technique: [slowc.glsl]")
hcase children/compile-timeout-run 2 "slowc.glsl: compiling user technique 'slowc' took more than 3 s" -- \
  env DMBENCH_PROBE_TIMEOUT=3 MESA_SHADER_CACHE_DISABLE=true "$BIN" run "$f" --out "$NEVER"
hcase children/probe-timeout-text 2 "DMBENCH_PROBE_TIMEOUT=abc: not a number of seconds in (0, 86400]" -- \
  env DMBENCH_PROBE_TIMEOUT=abc "$BIN" info
hcase children/probe-timeout-zero 2 "DMBENCH_PROBE_TIMEOUT=0: not a number of seconds" -- \
  env DMBENCH_PROBE_TIMEOUT=0 "$BIN" run "$OUT/ok.yaml" --out "$NEVER"

# A driver that hangs at start-up: `info` asks it in a child with the
# probe's deadline and exits 4 naming the limit.  With Mesa 25: zink whose
# Vulkan ICD names no library (a broken install); without it, a deadline
# no driver can meet.
M25=${DMBENCH_MESA25_PREFIX:-/opt/dmbench/mesa-25}
if [ -e "$M25/lvp_icd.json" ]; then
  mkdir -p "$OUT/brokenicd"; ln -sfn "$M25/usr" "$OUT/brokenicd/usr"
  printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "/nonexistent/libvulkan_lvp.so", "api_version": "1.4.0"}}\n' \
    > "$OUT/brokenicd/lvp_icd.json"
  hang=(env DMBENCH_DRIVER=zink DMBENCH_MESA25_PREFIX="$OUT/brokenicd" DMBENCH_PROBE_TIMEOUT=3)
else
  hang=(env DMBENCH_PROBE_TIMEOUT=0.01)
fi
hcase children/info-driver-hangs 4 "the driver did not answer within" -- "${hang[@]}" "$BIN" info
hcase children/run-driver-hangs 4 "the driver probe did not answer within" -- \
  "${hang[@]}" "$BIN" run "$OUT/ok.yaml" --out "$OUT/hangrun" --quiet
# The user's Vulkan loader variables under DMBENCH_DRIVER=zink: the loader
# prefers VK_DRIVER_FILES to the VK_ICD_FILENAMES dmbench sets, and the
# filters remove drivers; dmbench sets or clears them all, so zink runs
# (without Mesa 25 there is nothing to test: exit 0).
zink='[ -e "$0/lvp_icd.json" ] || exit 0; exec env DMBENCH_DRIVER=zink "${@:2}" "$1" info'
hcase children/zink-vk-driver-files 0 "" -- bash -c "$zink" "$M25" "$BIN" VK_DRIVER_FILES=/nonexistent.json
hcase children/zink-loader-disable 0 "" -- bash -c "$zink" "$M25" "$BIN" VK_LOADER_DRIVERS_DISABLE='*' \
  VK_ADD_DRIVER_FILES=/nonexistent.json
# dmbench's own marker for its children (DMBENCH_DRIVER_APPLIED) inherited
# from a user's shell: ignored; `info` and `run` record the driver used.
hcase children/inherited-marker-info 0 "" -- \
  bash -c 'DMBENCH_DRIVER_APPLIED=zink "$0" info --json > "$1"' "$BIN" "$OUT/marker-info.json"
hcase children/inherited-marker-run 0 "" -- \
  env DMBENCH_DRIVER_APPLIED=zink:1 "$BIN" run "$OUT/ok.yaml" --out "$OUT/marker" --quiet
if [ "${case_ok:-0}" = 1 ] && [ -z "${CORPUS_PROBE:-}" ]; then
  got=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['environment']['driver'], \
json.load(open(sys.argv[2]))['run']['environment']['driver'])" "$OUT/marker-info.json" "$OUT/marker/latest/results.json" 2>&1)
  if [ "$got" = "default default" ]; then pass=$((pass+1))
  else echo "FAIL: an inherited DMBENCH_DRIVER_APPLIED: info and run record '$got', want 'default default'"; fail=$((fail+1)); fi
fi
# the marker with DMBENCH_DRIVER naming the same driver: applied all the
# same (before, zink was recorded while llvmpipe rendered)
if [ -e "$M25/lvp_icd.json" ]; then
  r=$(DMBENCH_DRIVER=zink DMBENCH_DRIVER_APPLIED=zink "$BIN" info --json 2>/dev/null |
      python3 -c "import json,sys; print(json.load(sys.stdin)['environment']['renderer'])" 2>&1)
  case "$r" in zink*) pass=$((pass+1)) ;;
    *) echo "FAIL: DMBENCH_DRIVER=zink with an inherited marker renders on '$r'"; fail=$((fail+1)) ;; esac
fi
if [ -e "$NEVER" ]; then echo "FAIL: a refused run wrote $NEVER"; fail=$((fail+1)); else pass=$((pass+1)); fi
fi
