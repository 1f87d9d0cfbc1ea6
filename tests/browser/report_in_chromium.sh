#!/bin/sh
# report_in_chromium.sh GEN — opens a generated report.html in headless
# chromium and checks that it renders (screenshot not a single colour), that
# every image loaded, and that the console shows no error.
# GEN is test_reports_browser_gen (writes the synthetic fixture run).
set -eu
gen=$1
work=$(mktemp -d /tmp/dm_reports_browser_XXXXXX)
trap 'rm -rf "$work"' EXIT INT TERM
fail() { echo "FAIL: $*" >&2; exit 1; }

"$gen" "$work/run" || fail "generator failed"
[ -s "$work/run/report.html" ] || fail "no report.html"

# The report needs no script; a copy gets a probe that writes the image
# counts into the DOM once everything has loaded.
probe='<script>window.addEventListener("load",function(){var a=document.images,ok=0;for(var i=0;i<a.length;i++)if(a[i].complete\&\&a[i].naturalWidth>0)ok++;document.body.setAttribute("data-images",ok+"/"+a.length);});</script></body>'
sed "s#</body>#$probe#" "$work/run/report.html" > "$work/run/probe.html"

chrome() {
    timeout 25 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$(mktemp -d "$work/profile_XXXXXX")" --window-size=1280,900 "$@"
}

chrome --screenshot="$work/shot.png" "file://$work/run/report.html" >/dev/null 2>"$work/shot.log" \
    || { cat "$work/shot.log" >&2; fail "chromium --screenshot failed"; }
[ -s "$work/shot.png" ] || fail "no screenshot"
oiiotool --stats "$work/shot.png" | grep -q "Constant: No" || fail "screenshot is a single colour"

chrome --enable-logging=stderr --v=0 --virtual-time-budget=5000 --dump-dom \
    "file://$work/run/probe.html" >"$work/dom.html" 2>"$work/console.log" \
    || { cat "$work/console.log" >&2; fail "chromium --dump-dom failed"; }
images=$(sed -n 's/.*data-images="\([0-9]*\/[0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
[ -n "$images" ] || fail "probe did not run (no data-images in the DOM)"
loaded=${images%/*}
total=${images#*/}
[ "$total" -gt 0 ] || fail "no images in the report"
[ "$loaded" = "$total" ] || fail "only $images images loaded"
if grep -E "Uncaught|ERROR:CONSOLE|CONSOLE\(" "$work/console.log" >&2; then
    fail "console errors"
fi
echo "report rendered; $images images loaded; no console errors"
