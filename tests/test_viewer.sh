#!/usr/bin/env bash
# test_viewer.sh MODE — `dmbench view` with the real binary in a virtual X
# server (xvfb-run), as a user would run it.  Modes:
#   batch-equal  every technique: a window screenshot equals `dmbench render`
#                of the same configuration (PSNR >= 50 dB) and is not uniform
#   key-script   a script cycling techniques, levels, filters, meshes, spacing,
#                height, wireframe and overlay runs with no GL error (exit 0)
#   timed        T with --timed-seconds 1 prints a WallTime median in ns/frame
#   config       --config KEY --results DIR renders that configuration
#   no-display   without DISPLAY: exit 2 and a message naming xvfb-run
#   light-normals  L, N and right-drag pan run with no GL error; an N
#                screenshot equals `dmbench render --debug normals`, and L for
#                5 frames equals a batch render at light.azimuth 45 + 5*2, and
#                A (play camera.path) for 6 frames equals `render --frame 6`
# Needs DMBENCH_BINARY; VIEWER_IMGCMP is the helper test_viewer_imgcmp.
set -u
BIN=${DMBENCH_BINARY:?DMBENCH_BINARY must point at dmbench}
MODE=${1:?mode}
XVFB=(xvfb-run -a -s "-screen 0 1024x768x24")
# batch-equal: one X server for the whole loop (each start costs ~0.5 s)
if [ "$MODE" = batch-equal ] && [ -z "${VIEWER_IN_XVFB:-}" ]; then
    exec "${XVFB[@]}" env VIEWER_IN_XVFB=1 bash "$0" "$MODE"
fi
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
view() {
    if [ -n "${VIEWER_IN_XVFB:-}" ]; then "$BIN" view "$@"; else "${XVFB[@]}" "$BIN" view "$@"; fi
}

case "$MODE" in
batch-equal)
    techs=$("$BIN" list techniques | awk '/^[a-z]/ {print $1}')
    [ -n "$techs" ] || fail "no techniques listed"
    n=0
    for t in $techs; do
        view technique="$t" resolution=256x144 --frames 3 --screenshot "a-$t.png" >/dev/null ||
            fail "view technique=$t exited $?"
        "$BIN" render technique="$t" resolution=256x144 --png "b-$t.png" >/dev/null ||
            fail "render technique=$t exited $?"
        "${VIEWER_IMGCMP:?}" "a-$t.png" "b-$t.png" 50 || fail "technique $t: window != batch"
        n=$((n + 1))
    done
    echo "ok: $n techniques match the batch render"
    ;;
key-script)
    # every technique (digits 1..9, 0) with levels ] [ , spacing P and filter F
    # on each, then meshes, height, wireframe, overlay, orbit/zoom, reset,
    # help and Esc.
    count=$("$BIN" list techniques | grep -c '^[a-z]')
    [ "$count" -gt 10 ] && count=10
    script=''
    for i in $(seq 1 "$count"); do script+="$((i % 10))]].[pf."; done
    script+='m.mhH.w.c{drag:30,-10}{wheel:2}.r?..{esc}'
    out=$(view resolution=320x180 --keys "$script" 2>&1)
    rc=$?
    echo "$out"
    [ $rc -eq 0 ] || fail "key script exited $rc"
    echo "$out" | grep -q "GL error" && fail "GL errors reported"
    last=$("$BIN" list techniques | awk '/^[a-z]/ {print $1}' | sed -n "${count}p")
    echo "$out" | grep -q "technique = $last" || fail "the script did not reach technique $count ($last)"
    echo "$out" | grep -q "steps = 64" || fail "] did not double the parallax steps"
    echo "$out" | grep -q "filter = aniso2" || fail "F did not change the filter"
    echo "$out" | grep -q "counters overlay on" || fail "C did not turn the overlay on"
    # a bad script is a usage error, before any window opens
    view --keys '{nope}' >/dev/null 2>&1
    [ $? -eq 2 ] || fail "a bad --keys script must exit 2"
    echo "ok: key script over $count techniques ran without GL errors"
    ;;
timed)
    out=$(view technique=normal resolution=256x144 --keys 'T.' --timed-seconds 1 2>&1)
    rc=$?
    echo "$out"
    [ $rc -eq 0 ] || fail "timed run exited $rc"
    line=$(echo "$out" | grep '^timed: WallTime median')
    [ -n "$line" ] || fail "no timed result line"
    ns=$(echo "$line" | sed -E 's/.*median ([0-9]+) ns\/frame.*/\1/')
    [[ "$ns" =~ ^[0-9]+$ ]] && [ "$ns" -gt 0 ] || fail "median is not a positive ns/frame: $line"
    echo "$out" | grep -q '^timed: per frame: WallTime .* VSInvocations [0-9]' || fail "no counters line"
    echo "ok: timed median $ns ns/frame"
    ;;
config)
    # --config KEY --results DIR takes the params of that configuration;
    # KEY=VALUE arguments override them.  A unique key prefix is enough.
    mkdir run
    cat > run/results.json <<'JSON'
{"run": {"id": "viewer-test"}, "configs": [
 {"key": "00aa11bb22cc33dd", "status": "ok", "params": {"technique": "bump", "mesh": "sphere",
  "resolution": "128x72", "camera.azimuth": 75, "height_scale": 0.1}},
 {"key": "00aa99bb22cc33dd", "status": "ok", "params": {"technique": "texture"}}]}
JSON
    view --config 00aa11 --results run camera.elevation=40 --frames 2 --screenshot a.png >/dev/null ||
        fail "view --config exited $?"
    "$BIN" render technique=bump mesh=sphere resolution=128x72 camera.azimuth=75 height_scale=0.1 \
        camera.elevation=40 --png b.png >/dev/null || fail "render exited $?"
    "${VIEWER_IMGCMP:?}" a.png b.png 50 || fail "--config did not reproduce the configuration"
    "$BIN" view --config 00aa --results run >/dev/null 2>&1
    [ $? -eq 2 ] || fail "an ambiguous --config must exit 2"
    "$BIN" view --config 00aa11 >/dev/null 2>&1
    [ $? -eq 2 ] || fail "--config without --results must exit 2"
    echo "ok: --config reproduces a measured configuration"
    ;;
no-display)
    out=$(env -u DISPLAY -u WAYLAND_DISPLAY "$BIN" view --frames 1 2>&1)
    rc=$?
    echo "$out"
    [ $rc -eq 2 ] || fail "expected exit 2 without a display, got $rc"
    echo "$out" | grep -q "xvfb-run" || fail "the message must suggest xvfb-run"
    echo "ok: no display -> exit 2"
    ;;
light-normals)
    out=$(view technique=pom resolution=256x144 --keys 'L..N..{pan:20,-10}.l.n.r..{esc}' 2>&1)
    rc=$?
    echo "$out"
    [ $rc -eq 0 ] || fail "L/N/pan script exited $rc"
    echo "$out" | grep -q "GL error" && fail "GL errors reported"
    echo "$out" | grep -q "light orbit on" || fail "L did not turn the light orbit on"
    echo "$out" | grep -q "normals view on" || fail "N did not turn the normals view on"
    view technique=pom resolution=256x144 --keys 'N' --frames 3 --screenshot n-a.png >/dev/null ||
        fail "view with N exited $?"
    "$BIN" render technique=pom resolution=256x144 --debug normals --png n-b.png >/dev/null ||
        fail "render --debug normals exited $?"
    "${VIEWER_IMGCMP:?}" n-a.png n-b.png 50 || fail "N screenshot != render --debug normals"
    # the orbit advances once per frame from the frame L is typed: 5 frames -> 45 + 10
    view technique=normal resolution=256x144 --keys 'L' --frames 5 --screenshot l-a.png >/dev/null ||
        fail "view with L exited $?"
    "$BIN" render technique=normal resolution=256x144 light.azimuth=55 --png l-b.png >/dev/null ||
        fail "render light.azimuth=55 exited $?"
    "${VIEWER_IMGCMP:?}" l-a.png l-b.png 50 || fail "L for 5 frames != light.azimuth=55"
    "$BIN" render technique=normal resolution=256x144 --png l-c.png >/dev/null
    "${VIEWER_IMGCMP:?}" l-a.png l-c.png 50 >/dev/null 2>&1 && fail "L did not move the light"
    # A plays camera.path from the frame it is typed: 6 frames -> frame index 6
    P="technique=normal resolution=256x144 camera.path=dolly camera.path_frames=12 camera.dolly_to=1.2"
    out=$(view $P --keys 'A' --frames 6 --screenshot p-a.png 2>&1) || fail "view with A exited $?"
    echo "$out" | grep -q "dolly playing, frame 0 (1 of 12 along the path)" || fail "A did not play: $out"
    "$BIN" render $P --frame 6 --png p-b.png >/dev/null || fail "render --frame 6 exited $?"
    "${VIEWER_IMGCMP:?}" p-a.png p-b.png 50 || fail "A for 6 frames != render --frame 6"
    "$BIN" render $P --frame 0 --png p-c.png >/dev/null
    "${VIEWER_IMGCMP:?}" p-a.png p-c.png 50 >/dev/null 2>&1 && fail "A did not move the camera"
    echo "ok: L, N and pan; N equals the batch normals view; L and A are deterministic"
    ;;
*) fail "unknown mode $MODE" ;;
esac
