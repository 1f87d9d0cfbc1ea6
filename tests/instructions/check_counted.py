"""check_counted.py RESULTS.json...: every configuration of each run is ok
and has Instructions counted (what the readers of a fixture run rely on)."""
import json
import sys

for path in sys.argv[1:]:
    configs = json.load(open(path))["configs"]
    assert configs, (path, "no configuration")
    for c in configs:
        assert c["status"] == "ok", (path, c["label"], c.get("reason"))
        i = c["counters"].get("Instructions")
        assert i is not None and "unavailable" not in i, (path, c["label"], i)
    print(f"{path}: {len(configs)} configurations counted")
