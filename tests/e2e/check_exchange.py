"""check_exchange.py SCHEMA COMPARE_TXT HISTORY_TXT RUN_DIR... — the checks of
exchange.sh on the files it made (Debian's python3 with python3-jsonschema)."""
import copy, json, re, sys
import jsonschema

schema_path, compare_txt, history_txt, runs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
schema = json.load(open(schema_path))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
docs = [json.load(open(r + "/results.json")) for r in runs]

# Every run validates; a copy without a label, with a string median or an
# unknown status does not (the schema can fail).
for r, d in zip(runs, docs):
    errors = list(validator.iter_errors(d))
    assert not errors, (r, [e.message for e in errors[:3]])
    assert d["schema_version"] == 1
for breakage in ("label", "median", "status"):
    bad = copy.deepcopy(docs[0])
    c = bad["configs"][0]
    if breakage == "label":
        del c["label"]
    elif breakage == "median":
        c["counters"]["WallTime"]["median"] = "fast"
    else:
        c["status"] = "great"
    assert list(validator.iter_errors(bad)), "schema accepted a config with a broken " + breakage

def timed(d):
    """label -> config for the ok configurations with a WallTime."""
    return {c["label"]: c for c in d["configs"]
            if c["status"] == "ok" and "median" in c["counters"].get("WallTime", {})}

for r, d in zip(runs, docs):
    want = timed(d)
    assert want and len(set(want)) == len(want)
    # one label everywhere: "mesh W×H · technique axis=value": summary.md and
    # report.html say it as a scene heading plus the row's own part
    summary = open(r + "/summary.md").read()
    html = open(r + "/report.html").read()
    for c in d["configs"]:
        lab = c["label"]
        scene, sep, own = lab.partition(" · ")
        assert sep and scene.startswith(c["params"]["mesh"] + " ") and own.startswith(c["params"]["technique"]), lab
        assert "\n## " + scene + "\n" in summary, (lab, "summary.md heading")
        assert "| " + own.split(" [")[0] + " | " in summary, (lab, "summary.md row")
        assert ">Scene " + scene + "</h2>" in html.replace("&times;", "×"), (lab, "report.html heading")
    assert any(c["pareto"] for c in d["configs"])
    # Google Benchmark JSON
    g = json.load(open(r + "/export-gbench.json"))
    assert set(g["context"]) >= {"date", "num_cpus", "mhz_per_cpu", "cpu_scaling_enabled", "library_build_type"}
    names = [b["name"] for b in g["benchmarks"]]
    assert sorted(names) == sorted(want), (names, list(want))
    for b in g["benchmarks"]:
        w = want[b["name"]]["counters"]["WallTime"]
        assert b["run_type"] == "iteration" and b["time_unit"] == "ns"
        assert b["real_time"] == w["median"] and b["iterations"] == len(w["samples"])
        assert isinstance(b["cpu_time"], (int, float)) and b["cpu_time"] > 0
    # Bencher Metric Format
    m = json.load(open(r + "/export-bmf.json"))
    assert sorted(m) == sorted(want)
    for name, measures in m.items():
        w = want[name]["counters"]["WallTime"]
        lat = measures["latency"]
        assert lat["value"] == w["median"] and lat["lower_value"] == w["ci95"][0] and lat["upper_value"] == w["ci95"][1]
        assert lat["lower_value"] <= lat["value"] <= lat["upper_value"]
        for k, v in measures.items():
            assert re.fullmatch(r"[a-z0-9-]+", k) and set(v) <= {"value", "lower_value", "upper_value"}, (k, v)
        assert measures["samples-passed"]["value"] == want[name]["counters"]["SamplesPassed"]["value"]
        assert measures["ssim"]["value"] == want[name]["quality"]["SSIM"]
    # github-action-benchmark: [{name, unit, value, range?, extra?}]
    for form in ("smaller", "bigger"):
        entries = json.load(open(r + "/export-gab-%s.json" % form))
        assert isinstance(entries, list) and entries
        for e in entries:
            assert set(e) <= {"name", "unit", "value", "range", "extra"} and {"name", "unit", "value"} <= set(e)
            assert isinstance(e["value"], (int, float)) and isinstance(e["name"], str)
        by = {e["name"]: e for e in entries}
        for name, c in want.items():
            if form == "smaller":
                assert by[name]["unit"] == "ms" and abs(by[name]["value"] - c["counters"]["WallTime"]["median"] / 1e6) < 1e-12
                assert by[name + " (RMSE)"]["value"] == c["quality"]["RMSE"]
            else:
                assert by[name + " (SSIM)"]["value"] == c["quality"]["SSIM"]

# compare.py: one row per configuration (plus OVERALL_GEOMEAN)
strip = re.compile(r"\x1b\[[0-9;]*m")
rows = [strip.sub("", l) for l in open(compare_txt).read().splitlines()]
want = timed(docs[0])
found = {}
for l in rows:
    for name in want:
        if l.startswith(name + " ") and re.match(r"\s+[-+]\d", l[len(name):]):
            found[name] = found.get(name, 0) + 1
assert found == {n: 1 for n in want}, (found, rows)
assert any(l.startswith("OVERALL_GEOMEAN") for l in rows)

# history: three values per configuration, the medians of the three runs
text = open(history_txt).read()
blocks = re.split(r"\n(?=\S.*  \[[0-9a-f]{16}\])", text)[1:]
assert len(blocks) == len(timed(docs[-1])), text
for b in blocks:
    head = b.splitlines()[0]
    key = re.search(r"\[([0-9a-f]{16})\]", head).group(1)
    assert " 3 runs" in head, head
    got = [float(l.split()[2]) for l in b.splitlines()[2:] if l.strip()]
    exp = [next(c for c in d["configs"] if c["key"] == key)["counters"]["WallTime"]["median"] / 1e6 for d in docs]
    assert len(got) == 3 and all(abs(g - e) <= 5e-5 * max(1, e) for g, e in zip(got, exp)), (got, exp)
# report.html trend lines: none in the first run; in the last, one per
# configuration with the three runs' medians (oldest first) in its title
assert 'class="spark"' not in open(runs[0] + "/report.html").read()
html = open(runs[-1] + "/report.html").read()
titles = re.findall(r'<svg class="spark"[^>]*><title>median ms, oldest first:([^<]*)</title>', html)
assert len(titles) == len(timed(docs[-1])), (len(titles), len(timed(docs[-1])))
medians = sorted(tuple(round(d_c["counters"]["WallTime"]["median"] / 1e6, 3) for d_c in
                       [next(c for c in d["configs"] if c["key"] == k) for d in docs])
                 for k in [c["key"] for c in timed(docs[-1]).values()])
assert sorted(tuple(float(v) for v in t.split()) for t in titles) == medians, (titles, medians)

print("schema: %d runs valid, 3 breakages caught; exports: 4 formats x %d runs; compare.py: %d rows; "
      "history: %d configurations x 3 runs; %d trend lines" % (len(runs), len(runs), len(found), len(blocks),
                                                            len(titles)))
