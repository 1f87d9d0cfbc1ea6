#!/usr/bin/env bash
# Drivers (run/drivers.h, docs/drivers.md): tests/e2e/drivers.yaml on the
# default driver (the system's Mesa 22.3 llvmpipe), on llvmpipe of Mesa 25
# and on zink over lavapipe (Mesa 25, scripts/install-mesa25).  Asserts:
# - every configuration renders on every driver;
# - the drivers' deterministic counts agree, except FSInvocations (22.3
#   counts 4x4 blocks, 25 and zink covered pixels: then it equals
#   SamplesPassed) and what is derived from it;
# - Mesa 25's llvmpipe renders byte-identical images to 22.3's, and zink
#   within 40 dB PSNR of them, its PSNR against the reference within
#   0.1 dB of llvmpipe's;
# - the fingerprints differ (compare keeps drivers apart);
# - an unknown driver and a missing Mesa 25 exit 2 with the reason;
# - `dmbench drivers` runs the three and sets them side by side
#   (drivers.md/json: every configuration on each driver, Kendall's tau of
#   the times and qualities per pair, each scene's front per driver),
#   the drivers taking turns on three shards, each driver's merged after;
# - virtual_texture: sparse on zink against software (below).
# Skipped (77) when Mesa 25 is not installed.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
expect_refused 2 "unknown driver; the drivers are: default llvmpipe llvmpipe-25 zink" -- \
  env DMBENCH_DRIVER=voodoo "$BIN" info
expect_refused 2 "needs Mesa 25 in /nonexistent" -- \
  env DMBENCH_DRIVER=zink DMBENCH_MESA25_PREFIX=/nonexistent "$BIN" info
expect_refused 2 "none of the drivers asked for is installed here" -- \
  env DMBENCH_MESA25_PREFIX=/nonexistent "$BIN" drivers --drivers zink --out "$OUT/none"
expect_refused 2 "unknown driver 'zin' (did you mean 'zink'?)" -- "$BIN" drivers --drivers zin
expect_refused 2 "DMBENCH_DRIVER=zink is set: unset it" -- \
  env DMBENCH_DRIVER=zink "$BIN" drivers --drivers llvmpipe
# a sweep naming its drivers: `run` makes one run per driver; a driver not
# installed (Mesa 25 moved away) is left out with the reason; a misspelt
# name is the file's line with a suggestion
printf 'name: bad\ndrivers: [llvmpipe, zinc]\n' > "$OUT/bad.yaml"
expect_refused 2 "bad.yaml:2: drivers: unknown driver 'zinc' (did you mean 'zink'?)" -- \
  "$BIN" run "$OUT/bad.yaml" --out "$OUT/bad"
expect_refused 2 "bad.yaml:2: drivers: unknown driver 'zinc' (did you mean 'zink'?)" -- \
  "$BIN" run "$OUT/bad.yaml" --dry-run   # the dry run plans under each driver: the same check
printf 'name: twice\ndrivers: [zink, llvmpipe, zink]\n' > "$OUT/twice.yaml"
expect_refused 2 "twice.yaml:2:27: drivers: 'zink' is listed twice (line 2)" -- "$BIN" run "$OUT/twice.yaml"
printf 'name: empty\ndrivers: []\n' > "$OUT/empty.yaml"
expect_refused 2 "empty.yaml:2:10: drivers: expected a non-empty list of driver names" -- "$BIN" run "$OUT/empty.yaml"
DMBENCH_MESA25_PREFIX=/nonexistent "$BIN" run "$SRC/tests/e2e/drivers_key.yaml" --out "$OUT/key" \
  --quiet > "$OUT/key.txt" 2> "$OUT/key.err"
grep -q "^1 driver ran, 1 left out, 0 failed" "$OUT/key.txt" || { cat "$OUT/key.txt" "$OUT/key.err"; exit 1; }
grep -q "| llvmpipe-25 | — | left out: driver 'llvmpipe-25' needs Mesa 25 in /nonexistent" "$OUT/key/drivers.md" ||
  { cat "$OUT/key/drivers.md"; exit 1; }
test -s "$OUT/key/llvmpipe/latest/results.json"
tally
if ! DMBENCH_DRIVER=zink "$BIN" info >/dev/null 2>&1; then
  echo "Mesa 25 is not installed (scripts/install-mesa25): skipped"
  exit 77
fi
timeout 1800 "$BIN" drivers "$SRC/tests/e2e/drivers.yaml" --drivers default,llvmpipe-25,zink \
  --out "$OUT" --seed 1 --quiet > "$OUT/drivers.txt" 2> "$OUT/drivers.err" || { cat "$OUT/drivers.err"; exit 1; }
grep -q "^3 drivers ran, 0 left out, 0 failed; side by side: $OUT/drivers.md" "$OUT/drivers.txt"
# the drivers take turns on three shards (docs/drivers.md): every driver runs
# shard K before any runs K + 1, and each driver's shards are merged
turns=$(sed -n 's/^dmbench: drivers: \([a-z0-9-]*\), turn \([0-9]\) of 3: .*--shard \([0-9]\)\/3 .*/\1 \2 \3/p' "$OUT/drivers.err" | tr '\n' ,)
[ "$turns" = "default 1 1,llvmpipe-25 1 1,zink 1 1,default 2 2,llvmpipe-25 2 2,zink 2 2,default 3 3,llvmpipe-25 3 3,zink 3 3," ] ||
  { echo "turns: $turns"; cat "$OUT/drivers.err"; exit 1; }
for d in default llvmpipe-25 zink; do
  for k in 1 2 3; do test -s "$OUT/$d/shard-$k-of-3/latest/results.json"; done
  grep -q "^merged 3 runs, 5 configurations: $OUT/$d/" "$OUT/drivers.txt"
done
python3 - "$OUT" <<'PY'
import json, sys
j = json.load(open(sys.argv[1] + "/drivers.json"))
assert [d["driver"] for d in j["drivers"]] == ["default", "llvmpipe-25", "zink"], j["drivers"]
assert all(d["configs_ok"] == 5 for d in j["drivers"]), j["drivers"]
assert len(j["configs"]) == 5 and all(len(c["drivers"]) == 3 for c in j["configs"])
assert len(j["agreement"]) == 3, j["agreement"]
for a in j["agreement"]:
    assert a["configs"] == 5 and -1 <= a["tau_walltime"] <= 1, a
    # tau's bootstrap interval holds tau (5 configurations: 3 or more, so there is one)
    assert a["tau_walltime_lo"] <= a["tau_walltime"] <= a["tau_walltime_hi"], a
    if {a["a"], a["b"]} == {"default", "llvmpipe-25"}:
        assert a["tau_ssim"] == 1, a        # byte-identical images: the same quality order
        assert a["tau_ssim_lo"] == 1 and a["tau_ssim_hi"] == 1, a
for c in j["configs"]:                      # each median with its CI around it
    for d, v in c["drivers"].items():
        assert v["WallTime_ci_lo_ms"] <= v["WallTime_ms"] <= v["WallTime_ci_hi_ms"], (c["key"], d, v)
front = next(iter(j["fronts"].values()))
assert set(front) - {"differences"} == {"default", "llvmpipe-25", "zink", "agree", "scene"}, front
# fronts that differ say what differs: each member off a front, with the
# configuration that beats it there and whether the time CIs say so clearly
assert front["agree"] == ("differences" not in front), front
for d in front.get("differences", []):
    assert d["on"] != d["off"] and d["key"] in front[d["on"]] and d["key"] not in front[d["off"]], d
    assert "why" in d or ("dominated_by" in d and isinstance(d["clear"], bool)), d
# the drift check between the drivers' runs: each run times the CPU
# calibration kernel at its start and end, so it has figures, and says
# whether the runs' means moved more than within a run
dr = j["drift"]
assert set(dr) == {"moved", "noise", "drifted"} and dr["noise"] >= 0.05, dr
assert dr["drifted"] == (dr["moved"] > dr["noise"]), dr
md = open(sys.argv[1] + "/drivers.md").read()
assert "## Did the machine's speed move between the drivers' runs?" in md, md
assert "The fronts differ." not in md, md
assert front["agree"] == ("What differs:" not in md), md
for a in j["agreement"]:
    print(f"{a['a']} · {a['b']}: tau of WallTime {a['tau_walltime']:.3f} "
          f"[{a['tau_walltime_lo']:.3f}, {a['tau_walltime_hi']:.3f}], of SSIM {a['tau_ssim']:.3f}")
print("fronts agree:", front["agree"], front.get("differences", []))
print("drift:", dr)
PY
python3 - "$OUT" <<'PY'
import json, subprocess, sys
out = sys.argv[1]
docs = {d: json.load(open(f"{out}/{d}/latest/results.json")) for d in ("default", "llvmpipe-25", "zink")}
fp = {d: j["run"]["environment"]["fingerprint"] for d, j in docs.items()}
assert len(set(fp.values())) == 3, fp
runs = {d: {c["key"]: c for c in j["configs"]} for d, j in docs.items()}
skip = {"WallTime", "TimePerPixel", "ShadingEfficiency", "FSInvocations"}
def val(c, n):
    v = c["counters"].get(n) or {}
    return v.get("value", v.get("median"))
for key, base in sorted(runs["default"].items(), key=lambda kv: kv[1]["label"]):
    assert base["status"] == "ok", (base["label"], base.get("reason"))
    for d in ("llvmpipe-25", "zink"):
        c = runs[d][key]
        assert c["status"] == "ok", (d, c["label"], c.get("reason"))
        for n in base["counters"]:
            if n not in skip:
                assert val(c, n) == val(base, n), (d, c["label"], n, val(base, n), val(c, n))
        assert val(c, "FSInvocations") == val(c, "SamplesPassed"), (d, c["label"])
        assert val(base, "FSInvocations") % 16 == 0, base["label"]
        a, b = f"{out}/default/latest/img/{key}.png", f"{out}/{d}/latest/img/{key}.png"
        r = subprocess.run(["idiff", "-a", a, b], capture_output=True, text=True).stdout
        psnr = [float(l.split("=")[1]) for l in r.splitlines() if "Peak SNR" in l] or [float("inf")]
        dq = c["quality"]["PSNR"] - base["quality"]["PSNR"]
        if d == "llvmpipe-25":
            assert open(a, "rb").read() == open(b, "rb").read(), (d, c["label"], r)
            what = "byte-identical image"
        else:
            assert psnr[0] >= 40, (d, c["label"], r)
            assert abs(dq) <= 0.1, (d, c["label"], dq)
            what = f"{psnr[0]:.1f} dB against llvmpipe's image"
        print(f"{c['label']} on {d}: counts equal, {what}, PSNR vs reference {dq:+.3f} dB")
PY

# virtual_texture: sparse (GL_ARB_sparse_texture, zink only): pages
# committed from the same feedback and LRU as the software path.  Against
# software on the same driver: the same images (every texel the shader
# reads was committed and uploaded, else it would read zero), the same
# resident pages, committed bytes = resident pages x 128² x 12 bytes; the
# same metrics in two orders.  On the default driver: left out with the
# missing extension named.
"$BIN" run "$SRC/tests/e2e/sparse.yaml" --dry-run > "$OUT/dry.txt"
grep -q "virtual_texture=sparse: the driver lacks GL_ARB_sparse_texture" "$OUT/dry.txt" ||
  { echo "sparse not left out on the default driver:"; cat "$OUT/dry.txt"; exit 1; }
for s in 1 2; do
  DMBENCH_DRIVER=zink timeout 600 "$BIN" run "$SRC/tests/e2e/sparse.yaml" --out "$OUT/sp$s" --seed "$s" --quiet
done
python3 - "$OUT" <<'PY'
import json, subprocess, sys
out = sys.argv[1]
runs = [{c["label"]: c for c in json.load(open(f"{out}/sp{s}/latest/results.json"))["configs"]} for s in (1, 2)]
def val(c, n):
    v = c["counters"][n]
    return v.get("value", v.get("median"))
for label, sp in sorted(runs[0].items()):
    if not label.endswith("virtual_texture=sparse"):
        continue
    sw = runs[0][label.replace("=sparse", "=software")]
    assert sp["status"] == "ok", (label, sp.get("reason"), sp.get("log"))
    r = subprocess.run(["idiff", "-a", f"{out}/sp1/latest/{sw['images']['render']}",
                        f"{out}/sp1/latest/{sp['images']['render']}"], capture_output=True, text=True).stdout
    psnr = [float(l.split("=")[1]) for l in r.splitlines() if "Peak SNR" in l] or [float("inf")]
    assert psnr[0] >= 50, (label, r)
    res = val(sp, "VTPagesResident")
    assert res == val(sw, "VTPagesResident") and res > 1, (label, res, val(sw, "VTPagesResident"))
    assert val(sp, "VTCommittedBytes") == res * 128 * 128 * 12, (label, val(sp, "VTCommittedBytes"), res)
    assert runs[1][label]["quality"]["PSNR"] == sp["quality"]["PSNR"], (label, runs[1][label]["quality"], sp["quality"])
    print(f"{label}: {res:.0f} pages committed ({val(sp, 'VTCommittedBytes'):.0f} bytes), "
          f"{psnr[0]:.1f} dB against software VT, PSNR vs reference {sp['quality']['PSNR']:.2f} dB in both orders")
PY

# tess-displacement through the page table (its evaluation stage reads the
# height at the finest resident level, vt_table.glsl), sparse against
# software on zink: the same feedback commits the same pages (bytes =
# pages x 128² x 12); the displaced surfaces differ a little (measured: the
# two images 30.4 dB apart, docs/textures.md), and both are as close to the
# reference (within 0.1 dB).
DMBENCH_DRIVER=zink timeout 600 "$BIN" run "$SRC/tests/e2e/sparse_tess.yaml" --out "$OUT/spt" --seed 1 --quiet
python3 - "$OUT/spt/latest" <<'PY'
import json, subprocess, sys
d = sys.argv[1]
run = {c["params"]["virtual_texture"]: c for c in json.load(open(d + "/results.json"))["configs"]}
sp, sw = run["sparse"], run["software"]
assert sp["status"] == "ok" and sw["status"] == "ok", (sp.get("reason"), sw.get("reason"))
val = lambda c, n: c["counters"][n].get("value", c["counters"][n].get("median"))
res = val(sp, "VTPagesResident")
assert res == val(sw, "VTPagesResident") and res > 1, (res, val(sw, "VTPagesResident"))
assert val(sp, "VTCommittedBytes") == res * 128 * 128 * 12, (val(sp, "VTCommittedBytes"), res)
r = subprocess.run(["idiff", "-a", d + "/" + sw["images"]["render"], d + "/" + sp["images"]["render"]],
                   capture_output=True, text=True).stdout
psnr = [float(l.split("=")[1]) for l in r.splitlines() if "Peak SNR" in l] or [float("inf")]
dq = sp["quality"]["PSNR"] - sw["quality"]["PSNR"]
assert psnr[0] >= 25 and abs(dq) <= 0.1, (psnr, sp["quality"]["PSNR"], sw["quality"]["PSNR"])
print(f"tess-displacement sparse: {res:.0f} pages committed as in software VT, images {psnr[0]:.1f} dB apart, "
      f"PSNR vs reference {sp['quality']['PSNR']:.2f} dB ({dq:+.3f} dB against software)")
PY
