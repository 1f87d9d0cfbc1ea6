#!/bin/sh
# report_in_chromium.sh GEN — opens a generated report.html in headless
# chromium and checks that it renders (screenshot not a single colour), that
# every image loaded, that the gallery's cards are one width with their
# captions below the images, that a click on a render flips to the
# reference's full-size file, that no id is used twice, that the heatmap's
# legend stands before the cards with its colour scale drawn and states the
# scale in the words of `dmbench diff --heatmap`'s help (scale.txt), that
# a camera path's section has its frame-time plot with the stutter marked
# and its quality plot, that its filmstrip's buttons and keys step and flip
# the large view to the expected files (frame 20's frame, reference and
# FLIP map, then frame 40) with a caption naming the frame,
# and nothing past the right edge of a 1280×800 window (outside a
# horizontal scroller) nor a page wider than it, and that the console
# shows no error.
# GEN is test_reports_browser_gen (writes the synthetic fixture run).
set -eu
gen=$1
work=$(mktemp -d /tmp/dm_reports_browser_XXXXXX)
trap 'rm -rf "$work"' EXIT INT TERM
fail() { echo "FAIL: $*" >&2; exit 1; }

"$gen" "$work/run" || fail "generator failed"
[ -s "$work/run/report.html" ] || fail "no report.html"

# The report needs no script; a copy gets a probe that writes into the DOM
# once everything has loaded: the image counts; the gallery's layout (every
# card of a grid one width, every caption below its card's images); what a
# click on a render shows (the reference's file, full size, not its
# thumbnail); and ids used twice.
probe='<script>window.addEventListener("load",function(){var a=document.images,ok=0;for(var i=0;i<a.length;i++)if(a[i].complete\&\&a[i].naturalWidth>0)ok++;document.body.setAttribute("data-images",ok+"/"+a.length);'
probe="$probe"'var w={},beside=0,cards=0;document.querySelectorAll(".grid>.pair").forEach(function(p){cards++;w[p.offsetWidth]=1;'
probe="$probe"'var c=p.querySelector(".cap");if(!c)return;p.querySelectorAll("img").forEach(function(im){'
probe="$probe"'if(c.getBoundingClientRect().top<im.getBoundingClientRect().bottom-1)beside++;});});'
probe="$probe"'document.body.setAttribute("data-cards",cards+" "+Object.keys(w).length+" "+beside);'
probe="$probe"'var f=document.querySelector("img.flip");if(f){f.click();document.body.setAttribute("data-flip",f.getAttribute("src"));}'
probe="$probe"'var ids={},dup=0;document.querySelectorAll("[id]").forEach(function(e){dup+=ids[e.id]?1:0;ids[e.id]=1;});'
probe="$probe"'var lg=null;document.querySelectorAll("p.const").forEach(function(p){if(!lg\&\&p.textContent.indexOf("Heatmap: ")==0)lg=p;});'
probe="$probe"'var card=document.querySelector(".grid>.pair"),sc=lg?lg.querySelector(".scale"):null;'
probe="$probe"'document.body.setAttribute("data-legend",lg\&\&card\&\&sc\&\&lg.getBoundingClientRect().bottom<=card.getBoundingClientRect().top\&\&sc.offsetWidth>0\&\&getComputedStyle(sc).backgroundImage.indexOf("gradient")>=0?"before":"missing");'
probe="$probe"'if(lg)document.body.setAttribute("data-legend-text",lg.textContent.replace(/"/g,"\x27"));'
probe="$probe"'var ps=document.querySelector("section.path-scene"),pl=ps?ps.querySelectorAll(".chart path.path-median").length+" "+ps.querySelectorAll(".chart path.path-flip").length:0,over=0;'
probe="$probe"'if(ps)ps.querySelectorAll("*").forEach(function(e){if(e.getBoundingClientRect().right>window.innerWidth+0.5\&\&!e.closest(".scroll"))over++;});'
probe="$probe"'document.body.setAttribute("data-path",(ps?1:0)+" "+pl+" "+ps.querySelectorAll("circle.path-stutter").length+" "+over+" "+(document.documentElement.scrollWidth>window.innerWidth?1:0));'
probe="$probe"'var fm=document.querySelector(".film"),fr="none";if(fm){var b=fm.querySelector(".film-big"),r=[b.getAttribute("src")],kd=function(k){fm.dispatchEvent(new KeyboardEvent("keydown",{key:k,bubbles:true}));r.push(b.getAttribute("src"));};'
probe="$probe"'fm.querySelector(".film-next").click();r.push(b.getAttribute("src"));fm.querySelector(".film-flip").click();r.push(b.getAttribute("src"));fm.querySelector(".film-flip").click();r.push(b.getAttribute("src"));'
probe="$probe"'kd("f");kd("ArrowRight");r.push(fm.querySelector(".film-cap").textContent.indexOf("frame 40 of 60")>=0\&\&fm.querySelector(".film-cap").textContent.indexOf("FLIP 0.07, SSIM 0.9")>0?"caption":"no-caption");fr=r.join(" ");}'
probe="$probe"'document.body.setAttribute("data-film",fr);'
probe="$probe"'document.body.setAttribute("data-dupids",dup);});</script></body>'
sed "s#</body>#$probe#" "$work/run/report.html" > "$work/run/probe.html"

chrome() {
    timeout 25 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$(mktemp -d "$work/profile_XXXXXX")" --window-size=1280,800 "$@"
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
cards=$(sed -n 's/.*data-cards="\([0-9 ]*\)".*/\1/p' "$work/dom.html" | head -n 1)
set -- $cards
[ "${1:-0}" -ge 2 ] || fail "gallery: ${1:-no} cards"
[ "$2" = 1 ] || fail "gallery: cards of $2 different widths"
[ "$3" = 0 ] || fail "gallery: $3 captions beside their images"
flip=$(sed -n 's/.*data-flip="\([^"]*\)".*/\1/p' "$work/dom.html" | head -n 1)
[ "$flip" = "img/c0_ref.png" ] || fail "a click on a render shows '${flip:-nothing}', not the reference's file"
dup=$(sed -n 's/.*data-dupids="\([0-9]*\)".*/\1/p' "$work/dom.html" | head -n 1)
[ "${dup:-x}" = 0 ] || fail "${dup:-?} ids used twice"
legend=$(sed -n 's/.*data-legend="\([a-z]*\)".*/\1/p' "$work/dom.html" | head -n 1)
[ "$legend" = before ] || fail "heatmap legend: ${legend:-no probe}, not before the cards with its scale drawn"
scale=$(cat "$work/run/scale.txt")
grep -F "data-legend-text=\"Heatmap: $scale" "$work/dom.html" >/dev/null \
    || fail "the heatmap legend does not state the scale as diff --heatmap does: $scale"
path=$(sed -n 's/.*data-path="\([0-9 ]*\)".*/\1/p' "$work/dom.html" | head -n 1)
[ "$path" = "1 1 1 1 0 0" ] || fail "along the path (section, frame-time plots, quality plots, stutters, elements past the right edge outside a scroller, page wider than the window): '${path:-no probe}', not '1 1 1 1 0 0'"
k=0123456789abcdef
film=$(sed -n 's/.*data-film="\([^"]*\)".*/\1/p' "$work/dom.html" | head -n 1)
want="img/$k-path-f000.png img/$k-path-f020.png img/ref-0badf00d-f020.png img/$k-path-f020-flip.png img/$k-path-f020.png img/$k-path-f040.png caption"
[ "$film" = "$want" ] || fail "filmstrip (start, next, flip, flip, key F, key →, caption): '${film:-no probe}', not '$want'"
if grep -E "Uncaught|ERROR:CONSOLE|CONSOLE\(" "$work/console.log" >&2; then
    fail "console errors"
fi
echo "report rendered; along the path: plot and stutter, the filmstrip steps and flips, no horizontal overflow at 1280x800; $images images loaded; $1 gallery cards of one width, captions below; a click flips to $flip; ids unique; the heatmap legend before the cards, in diff --heatmap's words; no console errors"
