#!/usr/bin/env bash
# test_viewer.sh MODE — `dmbench view` with the real binary in a virtual X
# server (xvfb-run), as a user would run it.  Modes:
#   batch-equal  every technique: a window screenshot equals `dmbench render`
#                of the same configuration (PSNR >= 50 dB) and is not uniform
#   key-script   a script cycling techniques, levels, filters, meshes, spacing,
#                height, wireframe and overlay runs with no GL error (exit 0)
#   timed        T with --timed-seconds 1 prints a WallTime median in ns/frame
#   no-display   without DISPLAY: exit 2 and a message naming xvfb-run
# Needs DMBENCH_BINARY; VIEWER_IMGCMP is the helper test_viewer_imgcmp.
set -u
BIN=${DMBENCH_BINARY:?DMBENCH_BINARY must point at dmbench}
MODE=${1:?mode}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
view() { xvfb-run -a -s "-screen 0 1024x768x24" "$BIN" view "$@"; }

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
    # techniques 1..7, levels on steep-parallax/pom, filters, meshes, spacing,
    # height, wireframe, overlay, orbit/zoom, reset, help, quit.
    script='1.2.3.4hH.5]]..6]][[.7ff.fm.mp.w.c{drag:30,-10}{wheel:2}.r?..{esc}'
    out=$(view resolution=320x180 --keys "$script" 2>&1)
    rc=$?
    echo "$out"
    [ $rc -eq 0 ] || fail "key script exited $rc"
    echo "$out" | grep -q "GL error" && fail "GL errors reported"
    echo "$out" | grep -q "technique = pom" || fail "the script did not reach technique 7"
    echo "$out" | grep -q "steps = 64" || fail "] did not double the steps"
    echo "$out" | grep -q "filter = aniso2" || fail "F did not change the filter"
    # a bad script is a usage error, before any window opens
    view --keys '{nope}' >/dev/null 2>&1
    [ $? -eq 2 ] || fail "a bad --keys script must exit 2"
    echo "ok: key script ran without GL errors"
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
no-display)
    out=$(env -u DISPLAY -u WAYLAND_DISPLAY "$BIN" view --frames 1 2>&1)
    rc=$?
    echo "$out"
    [ $rc -eq 2 ] || fail "expected exit 2 without a display, got $rc"
    echo "$out" | grep -q "xvfb-run" || fail "the message must suggest xvfb-run"
    echo "ok: no display -> exit 2"
    ;;
*) fail "unknown mode $MODE" ;;
esac
