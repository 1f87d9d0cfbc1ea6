#!/usr/bin/env bash
# Camera paths (camera.path, docs/motion.md) as `dmbench render --frame N`
# draws them, checked against still renders of the same camera:
# - a dolly's first frame is the still camera at camera.distance, its last
#   the still camera at camera.dolly_to with the lights where the dolly keeps
#   them (light.distance is relative to camera.distance: 1.2 × 3 = 4.5 ×
#   0.8), PSNR over 60 dB: the same image up to float rounding;
# - an orbit's frame F/2 is the still camera turned by 180° (identical),
#   and frame F wraps to frame 0 (identical);
# - a flyover's frames differ from one another;
# - a still path's key and image are those of a configuration without the
#   key (still scenes keep their keys);
# - a run times path configurations beside the still ones (their keys and
#   labels as without camera.path): every figure of results.json's "path"
#   recomputed from the stored per-frame series; a bad value exits 2 with
#   the valid choices;
# - the frames quality along the path compares are written as images for
#   the report's filmstrip (docs/motion.md, "In the report"): the first and
#   last with the default K, every frame with K = 1 on 4 frames, 16 of 17
#   spread by the rule (computed here) with K = 1 on 20; results.json lists
#   them, the files exist, a written frame is `render --frame N`'s image,
#   the report shows a filmstrip per dolly configuration (and `report
#   --out` copies its images), and the same run
#   stored before frames were written (schema 7) reports without them,
#   saying why.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
R="mesh=plane technique=normal resolution=120x68"
render() { local out=$1; shift; "$BIN" render $R "$@" --png "$OUT/$out.png" > /dev/null; }
psnr() { "$BIN" diff "$OUT/$1.png" "$OUT/$2.png" --json -o "$OUT/map.png" |
           python3 -c 'import json,sys; d=json.load(sys.stdin); print(1e9 if d["PSNR_infinite"] else d["PSNR"])'; }
same() { cmp -s "$OUT/$1.png" "$OUT/$2.png" || { echo "FAIL: $1 and $2 differ"; fail=$((fail+1)); return; }; pass=$((pass+1)); }
differ() { cmp -s "$OUT/$1.png" "$OUT/$2.png" && { echo "FAIL: $1 and $2 are the same image"; fail=$((fail+1)); return; }; pass=$((pass+1)); }
over() { python3 -c "import sys; sys.exit(0 if float('$1') > $2 else 1)" && pass=$((pass+1)) ||
           { echo "FAIL: $3: $1 not over $2"; fail=$((fail+1)); }; }

D="camera.path=dolly camera.path_frames=60 camera.distance=3 camera.dolly_to=0.8"
render d0 $D --frame 0
render d59 $D --frame 59
render s3 camera.distance=3
render s08 camera.distance=0.8 light.distance=4.5
same d0 s3
over "$(psnr s08 d59)" 60 "dolly's last frame against the still camera at 0.8"
differ d0 d59

O="mesh=sphere camera.path=orbit camera.path_frames=60 camera.azimuth=30"
render o0 $O --frame 0
render o30 $O --frame 30
render o60 $O --frame 60
render s210 mesh=sphere camera.azimuth=210
same o30 s210
same o60 o0
differ o0 o30

F="camera.path=flyover camera.path_frames=60"
render f0 $F --frame 0
render f30 $F --frame 30
differ f0 f30

render still camera.path=still
same still s3

# A run times the path configurations beside the still ones.  Every figure
# of a path's "path" object is recomputed here from its per-frame series
# (the store's and results.json's, which must agree), not copied.
printf 'name: paths\nresolution: [64, 36]\nmeasure: { samples: { min: 3, max: 3 } }\nsweep:\n  mesh: [plane]\n  technique: [texture, normal]\n  camera.path: [still, dolly]\n  camera.path_frames: [12]\n' > "$OUT/p.yaml"
printf 'name: still\nresolution: [64, 36]\nsweep:\n  mesh: [plane]\n  technique: [texture, normal]\n' > "$OUT/s.yaml"
"$BIN" run "$OUT/s.yaml" --dry-run > "$OUT/still.txt" 2>&1
"$BIN" run "$OUT/p.yaml" --out "$OUT/r" > "$OUT/run.txt" 2>&1
python3 - "$OUT/r/latest/results.json" "$OUT/r/dmbench.sqlite" "$OUT/still.txt" "$OUT/r/latest/results.csv" \
  "$OUT/r/latest/summary.md" "$OUT/run.txt" <<'PY'
import csv, json, math, os, re, sqlite3, struct, sys
d = json.load(open(sys.argv[1]))
cs = d["configs"]
assert len(cs) == 4 and not d.get("left_out"), (len(cs), d.get("left_out"))
assert all(c["status"] == "ok" for c in cs), [c["reason"] for c in cs]
db = sqlite3.connect(sys.argv[2])
# the still configurations: the keys and labels of a sweep without camera.path, no path object
still = dict(re.findall(r"^  ([0-9a-f]{16})  (plane 64×36 · \w+)  ", open(sys.argv[3]).read(), re.M))
assert len(still) == 2, still
for c in cs:
    if c["params"].get("camera.path", "still") == "still":
        assert c["key"] in still and c["label"] == still[c["key"]], (c["key"], c["label"], still)
        assert "path" not in c and "camera.path" not in c["params"], c.get("path")
        assert db.execute("SELECT count(*) FROM path_frames WHERE key=?", (c["key"],)).fetchone()[0] == 0

def q7(xs, p):  # type-7 quantile
    xs = sorted(xs); h = (len(xs) - 1) * p; lo = math.floor(h)
    return xs[lo] + (h - lo) * (xs[min(lo + 1, len(xs) - 1)] - xs[lo])

def close(a, b, what, rel=1e-9):
    assert abs(a - b) <= rel * max(abs(a), abs(b)), (what, a, b)

paths = [c for c in cs if c["params"].get("camera.path") == "dolly"]
assert len(paths) == 2, [c["params"].get("camera.path") for c in cs]
csv_rows = {r["key"]: r for r in csv.DictReader(open(sys.argv[4], newline=""))}
md, term = open(sys.argv[5]).read(), open(sys.argv[6]).read()
for c in paths:
    p, F = c["path"], 12
    wall = c["counters"]["WallTime"]["samples"]
    S = len(wall)
    assert p["frames"] == F and p["replays"] == S == 3, (p["frames"], p["replays"], S)
    assert c["label"].endswith("camera.path=dolly"), c["label"]
    frames, replays, blob = db.execute("SELECT frames, replays, data FROM path_frames WHERE key=?",
                                       (c["key"],)).fetchone()
    stored = struct.unpack("<%dd" % (len(blob) // 8), blob)
    assert (frames, replays, len(stored)) == (F, S, S * F), (frames, replays, len(stored))
    assert all(math.isfinite(t) and t > 0 for t in stored), stored
    rows = [stored[s * F:(s + 1) * F] for s in range(S)]
    assert rows == [tuple(r) for r in p["frame_ns"]], "results.json's series is not the store's"
    for s in range(S):   # each WallTime sample is its replay's mean frame time
        close(wall[s], sum(rows[s]) / F, "WallTime sample %d" % s)
    med = [sorted(rows[s][f] for s in range(S))[S // 2] for f in range(F)]
    p50, p95, p99 = (q7(med, x) for x in (0.5, 0.95, 0.99))
    close(p["p50_ms"], p50 / 1e6, "p50"); close(p["p95_ms"], p95 / 1e6, "p95"); close(p["p99_ms"], p99 / 1e6, "p99")
    assert p["p50_ms"] <= p["p95_ms"] <= p["p99_ms"], p
    close(p["one_percent_low_ms"], max(med) / 1e6, "1 % low (ceil(12/100) = 1 frame: the slowest)")
    close(p["one_percent_low_fps"], 1000 / p["one_percent_low_ms"], "1 % low fps")
    want = [f for f in range(F) if med[f] > 2 * p50]
    assert p["stutter_frames"] == want and p["stutters"] == len(want), (p["stutter_frames"], want)
    spread = sorted((max(r[f] for r in rows) - min(r[f] for r in rows)) / med[f] for f in range(F))
    close(p["replay_spread"], q7(spread, 0.5), "replay spread")
    assert p["noisy"] is (p["replay_spread"] > 0.10), (p["noisy"], p["replay_spread"])
    r = csv_rows[c["key"]]
    close(float(r["path_p99_ms"]), p["p99_ms"], "csv p99", 1e-8)   # 9 significant digits
    assert int(r["path_stutters"]) == len(want), r
    assert c["label"] in md, "summary.md lacks the path row of " + c["label"]
    line = [l for l in term.splitlines() if c["label"].split(" · ")[1].split()[0] in l and "path p99" in l]
    got = [re.search(r"path p99 ([0-9.]+) ms, (\d+) stutter", l).groups() for l in line]
    assert any(abs(float(ms) - p99 / 1e6) <= 0.0011 and int(n) == len(want) for ms, n in got), (got, p99, want)
assert "## Along the path" in md
for c in cs:
    if "path" not in c:
        assert csv_rows[c["key"]]["path_p99_ms"] == "", csv_rows[c["key"]]
# quality along the path: none for a still configuration; on the dolly the
# default K, a reference at the first and last frame (K = F - 1 = 11)
for c in cs:
    q = c["path_quality"]
    if c["params"].get("camera.path", "still") == "still":
        assert q is None and "camera.path_ref_every" not in c["params"], (c["label"], q)
        continue
    assert q and q["computed"] and q["frames"] == 12 and q["every"] == 11, (c["label"], q)
    assert q["reference_frames"] == [0, 11] and len(q["FLIP"]) == 2 and len(q["SSIM"]) == 2, q
    assert q["temporal_error_mean"] >= 0 and q["images"]["temporal"].endswith("-temporal.png"), q
    # the filmstrip's frames: both reference frames, each with its reference and FLIP map
    run = os.path.dirname(sys.argv[1])
    shots = q["frames_shown"]
    assert [s["frame"] for s in shots] == [0, 11], shots
    for s in shots:
        assert s["test"] == "img/%s-path-f%03d.png" % (c["key"], s["frame"]), s
        assert s["flip"] == "img/%s-path-f%03d-flip.png" % (c["key"], s["frame"]), s
        assert re.fullmatch(r"img/ref-[0-9a-f]{8}-f%03d\.png" % s["frame"], s["reference"]), s
        for k in ("test", "reference", "flip"):
            assert os.path.getsize(os.path.join(run, s[k])) > 0, s[k]
    n = db.execute("SELECT count(*) FROM path_shots WHERE key=?", (c["key"],)).fetchone()[0]
    assert n == 2, n
# texture and normal mapping on the dolly have their own reference ("same")
refs = {s["reference"] for c in paths for s in c["path_quality"]["frames_shown"]}
assert len(refs) == 4, refs
PY
pass=$((pass+1))
# A run stored before the frames were written (schema 7: no path_shots)
# still reports, its filmstrip saying why it is absent.
cp -r "$OUT/r" "$OUT/old"
python3 -c 'import sqlite3,sys; db=sqlite3.connect(sys.argv[1]); db.executescript("DROP TABLE path_shots; PRAGMA user_version=7;"); db.close()' "$OUT/old/dmbench.sqlite"
"$BIN" report "$OUT/old/latest" > /dev/null
n=$(grep -c 'class="missing film-none">No filmstrip for' "$OUT/old/latest/report.html" || true)
f=$(grep -c 'class="film" tabindex' "$OUT/old/latest/report.html" || true)
if [ "$n" = 2 ] && [ "$f" = 0 ]; then pass=$((pass+1)); else echo "FAIL: old run's report: $n filmstrips absent with the reason, $f shown (want 2, 0)"; fail=$((fail+1)); fi
f=$(grep -o 'class="film" tabindex' "$OUT/r/latest/report.html" | wc -l)
if [ "$f" = 2 ]; then pass=$((pass+1)); else echo "FAIL: the run's report shows $f filmstrips, not 2"; fail=$((fail+1)); fi

# `report --out` copies the filmstrip's images and the temporal maps with the rest.
"$BIN" report "$OUT/r/latest" --out "$OUT/moved" > /dev/null
python3 - "$OUT/r/latest/results.json" "$OUT/moved" <<'PY'
import json, os, sys
want = set()
for c in json.load(open(sys.argv[1]))["configs"]:
    q = c["path_quality"] or {}
    want |= {s[k] for s in q.get("frames_shown", []) for k in ("test", "reference", "flip")}
    if q.get("images", {}).get("temporal"):
        want.add(q["images"]["temporal"])
assert len(want) == 2 * (2 * 3 + 1), sorted(want)   # per configuration: 2 frames x (frame, reference, map), a temporal map
missing = [w for w in want if not os.path.isfile(os.path.join(sys.argv[2], w))]
assert not missing, missing
PY
pass=$((pass+1))

# A written frame is the frame `render --frame` draws.
nk=$(python3 -c 'import json,sys; print([c["key"] for c in json.load(open(sys.argv[1]))["configs"] if c["params"].get("camera.path")=="dolly" and c["params"]["technique"]=="normal"][0])' "$OUT/r/latest/results.json")
"$BIN" render mesh=plane technique=normal resolution=64x36 camera.path=dolly camera.path_frames=12 --frame 11 \
  --png "$OUT/n11.png" > /dev/null
cp "$OUT/r/latest/img/$nk-path-f011.png" "$OUT/w11.png"
same n11 w11

# K = 1: every frame of 4 written; of 17, 16 by the rule (round half up of
# j (n - 1) / 15, computed here: all but frame 8), the first and last always.
printf 'name: film\nresolution: [32, 18]\nmeasure: { warmup_frames: 1, samples: { min: 2, max: 2 }, max_seconds: 1, counters: [WallTime] }\nscene:\n  mesh: plane\n  technique: normal\n  camera.path: dolly\n  camera.path_ref_every: 1\nsweep:\n  camera.path_frames: [4, 17]\n' > "$OUT/k1.yaml"
"$BIN" run "$OUT/k1.yaml" --out "$OUT/k1" --quiet > "$OUT/k1.txt" 2>&1 || { cat "$OUT/k1.txt"; exit 1; }
python3 - "$OUT/k1/latest/results.json" <<'PY'
import json, os, sys
from fractions import Fraction
d = json.load(open(sys.argv[1]))
run = os.path.dirname(sys.argv[1])
got = {}
for c in d["configs"]:
    q = c["path_quality"]
    F = q["frames"]
    assert q["computed"] and q["every"] == 1 and len(q["FLIP"]) == F, q
    shots = q["frames_shown"]
    got[F] = [s["frame"] for s in shots]
    for s in shots:
        for k in ("test", "reference", "flip"):
            assert os.path.getsize(os.path.join(run, s[k])) > 0, s[k]
spread = [int(Fraction(j * 16, 15) + Fraction(1, 2)) for j in range(16)]
assert got[4] == [0, 1, 2, 3], got[4]
assert got[17] == spread and len(set(spread)) == 16 and spread[0] == 0 and spread[-1] == 16, (got[17], spread)
assert 8 not in got[17]
imgs = os.listdir(os.path.join(run, "img"))
assert sum(n.count("-path-f") and not n.endswith("-flip.png") for n in imgs) == 4 + 16, sorted(imgs)
PY
pass=$((pass+1))
expect_refused 2 "expected one of: still, orbit, dolly, flyover (did you mean 'dolly'?)" -- \
  "$BIN" render $R camera.path=doly --png "$OUT/x.png"
expect_refused 2 "camera.path_frames" -- "$BIN" render $R camera.path=orbit camera.path_frames=1 --png "$OUT/x.png"
tally
