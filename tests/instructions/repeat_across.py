"""repeat_across.py GATE_RUN STAGE_RUN: Instructions repeat between two
processes on every fragment technique.  GATE_RUN is the CI gate's run of
ci/gate-techniques.yaml (fixture ci_gate_run), STAGE_RUN the stage
counters' run of tests/stages/techniques.yaml (fixture stage_run_cube):
two sweeps, two Valgrind children, other company and other orders, with
the same scene, so eight configurations are the same key in both (every
technique with virtual texturing off but vertex-displacement, whose gate
configurations name a vertex filter).  Asserts: exactly those eight
techniques are shared; each is ok in both runs with two samples, the two
samples of a run within 1e-4 (one child: test_instructions_repeat's
threshold); the two runs' medians within 1e-4 or ACROSS = 200 instructions
a frame, whichever is larger: test_instructions_gate's rule for two runs,
since what a child counted before moves a frame by tens of instructions,
more than 1e-4 of the smallest frames here (texture: 906 k; measured 0-48
apart, 2026-11-29).  Both runs must come from the same build (ctest makes
the fixtures anew): two runs made five hours apart in another tree, with
rebuilds between, were 200-260 apart on every technique.  Prints each
configuration's two counts."""
import json
import sys

ACROSS = 200
SHARED = {"texture", "phong", "normal", "bump", "parallax", "steep-parallax", "pom", "tess-displacement"}

runs = [{c["key"]: c for c in json.load(open(p + "/latest/results.json"))["configs"]} for p in sys.argv[1:3]]
keys = runs[0].keys() & runs[1].keys()
techniques = {runs[1][k]["label"].split(" · ", 1)[1].split()[0] for k in keys}
assert techniques == SHARED and len(keys) == len(SHARED), \
    ("the two runs no longer share one configuration of each technique", sorted(techniques), len(keys))
worst = 0.0
for key in sorted(keys, key=lambda k: runs[1][k]["label"]):
    medians = []
    for r, name in zip(runs, sys.argv[1:3]):
        c = r[key]
        assert c["status"] == "ok", (name, key, c.get("reason"))
        i = c["counters"]["Instructions"]
        assert "unavailable" not in i and len(i["samples"]) == 2, (name, key, i)
        s = i["samples"]
        assert abs(s[1] - s[0]) <= 1e-4 * min(s), (name, key, s)
        medians.append(i["median"])
    diff = abs(medians[1] - medians[0])
    worst = max(worst, diff / min(medians))
    print(f"{runs[1][key]['label']}: {medians[0]:.0f} (gate) vs {medians[1]:.0f} (stages) instructions/frame, "
          f"{medians[1] - medians[0]:+.0f} ({diff / min(medians):.1e})")
    assert diff <= max(1e-4 * min(medians), ACROSS), (key, runs[1][key]["label"], medians)
print(f"worst {worst:.1e}: {len(keys)} configurations repeat between the gate's run and the stage run")
