#!/usr/bin/env python3
"""Writes a synthetic results.json for the compare tests (no GL needed).

synth.py OUT [--configs N] [--scenes S] [--samples K] [--scale F] [--cv C]
             [--seed N] [--cpu-scale F] [--load L] [--rounds-shift F,F,...]

Each scene has N configurations (technique=t<i>, steps=<8*(i+1)>), WallTime
and CPUTime samples (CPUTime = WallTime / cpu-scale), SamplesPassed and
FSInvocations counts and their ratio ShadingEfficiency.  --rounds-shift
multiplies round r of every configuration by the r-th factor (a machine
that slowed down for that round).
"""
import argparse, json, random

p = argparse.ArgumentParser()
p.add_argument("out")
p.add_argument("--configs", type=int, default=4)
p.add_argument("--scenes", type=int, default=1)
p.add_argument("--samples", type=int, default=12)
p.add_argument("--scale", type=float, default=1.0)
p.add_argument("--cv", type=float, default=0.02)
p.add_argument("--seed", type=int, default=1)
p.add_argument("--cpu-scale", type=float, default=1.0)
p.add_argument("--load", type=float, default=0.5)
p.add_argument("--rounds-shift", default="")
p.add_argument("--id", default=None)
a = p.parse_args()
rng = random.Random(a.seed)
shift = [float(x) for x in a.rounds_shift.split(",") if x]
configs = []
for s in range(a.scenes):
    for i in range(a.configs):
        base = 1e6 * (i + 1) * (s + 1)
        wall = []
        for r in range(a.samples):
            f = shift[r] if r < len(shift) else 1.0
            wall.append(base * a.scale * f * (1 + a.cv * rng.gauss(0, 1)))
        cpu = [w / a.cpu_scale for w in wall]
        def timed(x):
            xs = sorted(x)
            n = len(xs)
            med = xs[n // 2] if n % 2 else (xs[n // 2 - 1] + xs[n // 2]) / 2
            return {"unit": "ns", "deterministic": False, "partial": False, "median": med,
                    "ci95": [xs[0], xs[-1]], "samples": x, "mean": sum(x) / n, "min": xs[0],
                    "max": xs[-1], "stddev": 0, "mad": 0, "cv": 0, "outliers": 0, "nonfinite": 0}
        sp, fsi = 705 * (i + 1), 1160 * (i + 1)
        configs.append({
            "key": "%016x" % (s * 1000 + i + 1), "scene": "plane@96x54/s%d" % s,
            "params": {"mesh": "plane", "scene_no": s, "technique": "t%d" % i,
                       "steps": 8 * (i + 1), "resolution": "96x54"},
            "status": "ok", "reason": None,
            "counters": {"WallTime": timed(wall), "CPUTime": timed(cpu),
                         "SamplesPassed": {"unit": "items", "deterministic": True, "partial": False, "value": sp},
                         "FSInvocations": {"unit": "items", "deterministic": True, "partial": False, "value": fsi},
                         "ShadingEfficiency": {"unit": "ratio", "deterministic": True, "partial": False,
                                               "value": sp / fsi}}})
env = {"renderer": "llvmpipe (LLVM 15.0.6, 256 bits)", "gl_version": "4.5 (Core Profile) Mesa 22.3.6",
       "lp_num_threads": "1", "cpu": "Synthetic CPU", "cpu_count": "2",
       "load_average": "%.2f %.2f %.2f" % (a.load, a.load, a.load)}
run = {"id": a.id or "synth-%d" % a.seed, "sweep": "synthetic", "started": "2026-01-01T00:00:00Z",
       "environment": env, "timer": {"gpu_time_coverage": 0.01, "verdict": "partial"}}
json.dump({"schema_version": 1, "run": run, "configs": configs, "left_out": [], "fits": [],
           "warnings": []}, open(a.out, "w"), indent=1)
