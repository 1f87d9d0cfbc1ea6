#!/bin/sh
# quick_report.sh DMBENCH ARTIFACTS [RUNS] — the default quick run's report.html in
# headless chromium, as a new user sees it: at 1280x800 and 1920x1080 the
# first scene's recommendation (p.pick) lies entirely in the first screen
# (DOM position), every front row whose CI half-width is over ±5 % (the mean
# of −x %/+y %; 0.1 of slack for the printed rounding) carries its noisy mark, the page does not overflow horizontally, no SVG chart text is
# clipped (every text box inside its SVG's box), no id is used twice, and the
# file is under 2 MB.
# The screenshots stay in ARTIFACTS (CI keeps them).  Then `report --out`
# into a folder that is moved elsewhere: every full-size link is relative and
# resolves inside it, and chromium loads every image of the moved copy.
# The run is a copy of the suite's third --quick run (RUNS/c, made once by
# tests/e2e/quick_runs.sh; without RUNS the script makes its own).
set -eu
bin=$1
art=$2
runs=${3:-}
work=$(mktemp -d /tmp/dm_quick_report_XXXXXX)
trap 'rm -rf "$work"' EXIT INT TERM
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir -p "$art"

if [ -n "$runs" ]; then
    [ -f "$runs/c/latest/report.html" ] || fail "no run in $runs/c (fixture test_e2e_quick_runs)"
    cp -a "$runs/c" "$work/res"
else
    "$bin" run --quick --out "$work/res" --quiet 2>"$work/run.log" || { cat "$work/run.log" >&2; fail "run --quick"; }
fi
html="$work/res/latest/report.html"
size=$(wc -c < "$html")
[ "$size" -lt 2000000 ] || fail "report.html is $size bytes, the limit is 2 MB"

# A copy with a probe that writes what it measured into the DOM.
probe='<script>window.addEventListener("load",function(){'
probe="$probe"'var f=(document.getElementById("answer-0")||document).querySelector("p.pick"),r=f?f.getBoundingClientRect():null,bad=[],n=0,um=0;'
probe="$probe"'document.querySelectorAll("table.front tbody tr").forEach(function(tr){var c=tr.cells[tr.cells.length-3];'
probe="$probe"'if(!c)return;var w=(c.textContent.match(/[0-9.]+(?=%)/g)||[]).map(parseFloat);'
probe="$probe"'var h=w.length>1?(w[0]+w[1])/2:(w[0]||0);if(h>5.1\&\&!c.querySelector(".noisy"))um++;});'
probe="$probe"'document.body.setAttribute("data-unmarked",um);'
probe="$probe"'document.body.setAttribute("data-overflow",document.documentElement.scrollWidth-innerWidth);'
probe="$probe"'document.querySelectorAll("svg").forEach(function(s){var b=s.getBoundingClientRect();'
probe="$probe"'s.querySelectorAll("text").forEach(function(t){var q=t.getBoundingClientRect();n++;'
probe="$probe"'if(q.width>0\&\&(q.left<b.left-1||q.right>b.right+1||q.top<b.top-1||q.bottom>b.bottom+1))'
probe="$probe"'bad.push(t.textContent.slice(0,40));});});'
probe="$probe"'document.body.setAttribute("data-front",r?Math.round(r.top)+" "+Math.round(r.bottom)+" "+innerHeight:"none");'
probe="$probe"'document.body.setAttribute("data-texts",n);'
probe="$probe"'var ids={},dup=0;document.querySelectorAll("[id]").forEach(function(e){dup+=ids[e.id]?1:0;ids[e.id]=1;});'
probe="$probe"'document.body.setAttribute("data-dupids",dup);'
probe="$probe"'document.body.setAttribute("data-clipped",bad.length+(bad.length?": "+bad.slice(0,5).join(" | "):""));'
probe="$probe"'});</script></body>'
sed "s#</body>#$probe#" "$html" > "$work/res/latest/probe.html"

chrome() {
    timeout 40 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync --hide-scrollbars \
        --user-data-dir="$(mktemp -d "$work/profile_XXXXXX")" "$@"
}

for win in 1280,800 1920,1080; do
    name=$(echo "$win" | tr , x)
    chrome --window-size=$win --screenshot="$art/report-$name.png" "file://$html" >/dev/null 2>&1 \
        || fail "screenshot at $name"
    [ -s "$art/report-$name.png" ] || fail "no screenshot at $name"
    chrome --window-size=$win --virtual-time-budget=5000 --dump-dom "file://$work/res/latest/probe.html" \
        > "$work/dom.html" 2>/dev/null || fail "dump-dom at $name"
    front=$(sed -n 's/.*data-front="\([^"]*\)".*/\1/p' "$work/dom.html" | head -n 1)
    clipped=$(sed -n 's/.*data-clipped="\([^"]*\)".*/\1/p' "$work/dom.html" | head -n 1)
    texts=$(sed -n 's/.*data-texts="\([0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
    unmarked=$(sed -n 's/.*data-unmarked="\([0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
    overflow=$(sed -n 's/.*data-overflow="\(-*[0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
    [ -n "$front" ] && [ "$front" != none ] || fail "$name: no recommendation (#answer-0 p.pick) in the DOM"
    set -- $front
    [ "$1" -ge 0 ] && [ "$2" -le "$3" ] || fail "$name: recommendation at y $1..$2, the first screen ends at $3"
    [ "${unmarked:-x}" = 0 ] || fail "$name: $unmarked front rows wider than ±5 % without a noisy mark"
    [ "${overflow:-1}" -le 0 ] || fail "$name: the page is $overflow px wider than the window"
    grep -Eq 'class="pick">(<b>Provisional: [^<]*</b>; )?<b>Under [0-9.]* ms</b>' "$html" || fail "no 'Under N ms' recommendation in the page"
    [ "${texts:-0}" -gt 0 ] || fail "$name: no SVG text measured"
    [ "$clipped" = 0 ] || fail "$name: clipped chart text: $clipped"
    dup=$(sed -n 's/.*data-dupids="\([0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
    [ "${dup:-x}" = 0 ] || fail "$name: ${dup:-?} ids used twice (the charts' clip paths?)"
    echo "$name: recommendation at y $1..$2 of $3; noisy rows marked; no overflow; $texts chart texts, none clipped"
done
"$bin" report "$work/res/latest" --out "$work/pub" >/dev/null || fail "report --out"
mv "$work/pub" "$work/moved"
links=$(grep -o 'class="full" href="[^"]*"' "$work/moved/report.html" | sed 's/.*href="//; s/"$//')
[ -n "$links" ] || fail "no full-size links in the gallery"
nlinks=0
for l in $links; do
    case $l in /*|*..*) fail "full-size link $l leaves the folder" ;; esac
    [ -f "$work/moved/$l" ] || fail "full-size link $l does not resolve in the moved folder"
    nlinks=$((nlinks + 1))
done
probe='<script>window.addEventListener("load",function(){var a=document.images,ok=0;'
probe="$probe"'for(var i=0;i<a.length;i++)if(a[i].complete\&\&a[i].naturalWidth>0)ok++;'
probe="$probe"'document.body.setAttribute("data-images",ok+"/"+a.length);});</script></body>'
sed "s#</body>#$probe#; s#loading=\"lazy\" ##g" "$work/moved/report.html" > "$work/moved/probe.html"
chrome --window-size=1280,800 --virtual-time-budget=8000 --dump-dom "file://$work/moved/probe.html" \
    > "$work/dom.html" 2>/dev/null || fail "dump-dom of the moved copy"
images=$(sed -n 's/.*data-images="\([0-9]*\/[0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
[ -n "$images" ] && [ "${images%/*}" = "${images#*/}" ] && [ "${images#*/}" -gt 0 ] \
    || fail "moved report --out copy: only ${images:-no} images loaded"
echo "moved report --out copy: $nlinks full-size links resolve, $images images load"
echo "report.html: $size bytes; screenshots in $art"
