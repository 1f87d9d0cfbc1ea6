#!/usr/bin/env python3
"""bench/precision_offline.py STORE [STORE ...] — why configurations of
stored runs miss ±3 % with the drift removed, recomputed offline from the
stored samples and rounds (docs/measurement.md, "Drift removed"); it times
nothing.

STORE is a run directory's dmbench.sqlite (bench/precision.sh leaves
OUT/run-K/dmbench.sqlite; bench/precision_recompute.sh OUT/run-K/... after
a re-merge with other code).  Per run it prints:

- the WallTime configurations within ±3 % raw, as stored and as recomputed
  here from the samples with dmbench's own interval (models/stats.c: the
  binomial order-statistic interval of the median for n >= 6; below 6 the
  stored seeded bootstrap interval is read, not recomputed), and within ±3 %
  corrected as stored (what the run printed);
- the point correction recomputed here (median polish, each sample divided
  by its round's common mode without it, models/drift.c) and the
  order-statistic CI of each configuration's corrected samples alone;
- alternatives to the corrected CI, each on a configuration's corrected
  samples alone (without the bootstrap hull, so comparable with one
  another): today's median with its order-statistic interval; the common
  mode scaled by the configuration's own slope on it (a control variate);
  the Hodges-Lehmann location with its signed-rank interval; the 20 %
  trimmed mean with the Tukey-McLaughlin interval;
- every configuration that misses ±3 % corrected, with its samples, raw and
  corrected half-widths, the half-width of its corrected samples alone, and
  the cause: "bootstrap" (its corrected samples alone are within ±3 %: the
  bootstrap of the whole procedure widened the CI), "few samples" (it
  stopped, converged on its raw CI, with under 20), or "noise" (its
  corrected samples alone are wider than ±3 %);
- per scene: rounds, samples, extra samples taken beyond samples.max (30,
  the default sweep's; its configurations did not reach the time cap),
  and the configurations within ±3 % raw / corrected;
- the stored extra rounds replayed under the rule run/measure.c follows
  now (a configuration whose CI with the drift removed is within half the
  target stops): how many extra samples, and about how many seconds, went
  to configurations already that precise.  What that time would have
  bought elsewhere cannot be recomputed from stored samples: it needs a
  new run.

It asserts that the recomputed raw count equals the stored one for n >= 6.
"""
import math
import sqlite3
import statistics
import struct
import sys

TARGET = 0.03
SAMPLES_MAX = 30


def binom_rank(n, level=0.95):
    """stats_median_ci_rank: the largest k with 1 - 2 P(B <= k-1) >= level."""
    best = 0
    for k in range(1, n // 2 + 1):
        cdf = sum(math.comb(n, i) for i in range(k)) / 2.0 ** n
        if 1 - 2 * cdf < level:
            break
        best = k
    return best


def median(v):
    v = sorted(v)
    m = len(v)
    if not m:
        return math.nan
    return v[m // 2] if m % 2 else (v[m // 2 - 1] + v[m // 2]) / 2


def order_ci(v):
    """(median, lo, hi) of the finite v by the order-statistic interval;
    None below 6 samples (dmbench bootstraps there)."""
    s = sorted(x for x in v if math.isfinite(x))
    k = binom_rank(len(s))
    if not k:
        return None
    return median(s), s[k - 1], s[len(s) - k]


def hw(t):
    return (t[2] - t[1]) / 2 / t[0]


def polish(lx, nc, nr):
    """models/drift.c drift__polish and drift__loo_round: levels a, round
    effects b, and loo[c][r], the round's common mode without c."""
    cell = lambda c, r: lx[c][r]
    a = [median([x for x in lx[c] if math.isfinite(x)]) for c in range(nc)]
    b = [math.nan] * nr
    for it in range(20):
        for r in range(nr):
            v = [cell(c, r) - a[c] for c in range(nc) if math.isfinite(cell(c, r)) and math.isfinite(a[c])]
            b[r] = median(v) if len(v) >= 3 else math.nan
        centre = median([x for x in b if math.isfinite(x)])
        b = [x - centre if math.isfinite(x) else x for x in b]
        moved = 0
        for c in range(nc):
            na = median([cell(c, r) - (b[r] if math.isfinite(b[r]) else 0) for r in range(nr)
                         if math.isfinite(cell(c, r))])
            if math.isfinite(na) and math.isfinite(a[c]):
                moved = max(moved, abs(na - a[c]))
            a[c] = na
        if it > 0 and moved < 1e-9:
            break
    loo = [[math.nan] * nr for _ in range(nc)]
    for r in range(nr):
        items = [(cell(c, r) - a[c], c) for c in range(nc) if math.isfinite(cell(c, r)) and math.isfinite(a[c])]
        if len(items) < 3:
            continue
        for _, c in items:
            loo[c][r] = median([v for v, k in items if k != c])
    return a, b, loo


def robust_sd(v):
    v = [x for x in v if math.isfinite(x)]
    if len(v) < 2:
        return math.nan
    m = median(v)
    return 1.4826 * median([abs(x - m) for x in v])


def preview(lx, nc, nr):
    """run/protocol.c protocol_extra_corrected on the first nr rounds: each
    configuration's CI half-width with the drift removed (the point
    correction, order-statistic CI of its corrected samples; None below 6
    samples, where dmbench bootstraps), or None for all when the scene's
    drift would not be removed (models/drift.c: fewer than 3 rounds with a
    common mode, or round factors within twice what noise gives them)."""
    sub = [row[:nr] for row in lx]
    a, b, loo = polish(sub, nc, nr)
    fb = [x for x in b if math.isfinite(x)]
    if len(fb) < 3:
        return None
    spread = math.sqrt(sum(x * x for x in fb) / len(fb))
    res = [sub[c][r] - a[c] - loo[c][r] for c in range(nc) for r in range(nr)
           if math.isfinite(sub[c][r]) and math.isfinite(loo[c][r]) and math.isfinite(a[c])]
    per = median([sum(math.isfinite(sub[c][r]) for c in range(nc)) for r in range(nr) if math.isfinite(b[r])])
    if not spread > 2 * math.sqrt(math.pi / 2) * robust_sd(res) / math.sqrt(per):
        return None
    out = []
    for c in range(nc):
        y = [math.exp(sub[c][r] - (loo[c][r] if math.isfinite(loo[c][r]) else 0)) for r in range(nr)
             if math.isfinite(sub[c][r])]
        o = order_ci(y)
        out.append(hw(o) if o else None)
    return out


def replay(cfgs, lx, extra):
    """The stored extra rounds replayed under the rule run/measure.c follows
    now: before each extra round, a configuration whose CI with the drift
    removed is within half the target stops.  extra[c]: c's samples taken
    in extra rounds (its last ones).  Returns the extra samples and their
    estimated seconds (a sample lasts max(16 frames, 20 ms)) the rule would
    have saved, and the configurations it would have stopped."""
    nc, nr = len(cfgs), len(lx[0])
    firsts = []
    for c in range(nc):
        if extra[c]:
            idx = [r for r in range(nr) if math.isfinite(lx[c][r])]
            firsts.append(idx[len(idx) - extra[c]])
    if not firsts:
        return 0, 0.0, 0.0, []
    stopped_at = {}
    for r in range(min(firsts), nr):
        pv = preview(lx, nc, r)
        if pv is None:
            continue
        for c in range(nc):
            if extra[c] and c not in stopped_at and pv[c] is not None and pv[c] <= TARGET / 2:
                stopped_at[c] = r
    saved = secs = total = 0
    for c in range(nc):
        idx = [r for r in range(nr) if math.isfinite(lx[c][r])]
        for r in idx[len(idx) - extra[c]:] if extra[c] else []:
            t = max(16 * math.exp(lx[c][r]), 20e6) / 1e9
            total += t
            if c in stopped_at and r >= stopped_at[c]:
                saved += 1
                secs += t
    return saved, secs, total, sorted(cfgs[c]["label"] for c in stopped_at)


def t975(df):
    """The 97.5 % point of Student's t (Cornish-Fisher expansion about the
    normal's 1.95996; within 0.2 % from 4 degrees of freedom)."""
    z = 1.959964
    return z + (z ** 3 + z) / (4 * df) + (5 * z ** 5 + 16 * z ** 3 + 3 * z) / (96 * df * df)


def hl_ci(y):
    """Hodges-Lehmann location of y with its Wilcoxon signed-rank 95 %
    interval (normal approximation of the rank), as (centre, lo, hi)."""
    n = len(y)
    w = sorted((y[i] + y[j]) / 2 for i in range(n) for j in range(i, n))
    k = max(0, int(math.floor(n * (n + 1) / 4 - 1.959964 * math.sqrt(n * (n + 1) * (2 * n + 1) / 24))))
    return median(w), w[k], w[len(w) - 1 - k]


def trimmed_ci(y, g=0.2):
    """20 % trimmed mean with the Tukey-McLaughlin interval (winsorized SD)."""
    s = sorted(y)
    n, k = len(s), int(math.floor(g * len(s)))
    t = s[k:n - k]
    wz = [min(max(x, s[k]), s[n - 1 - k]) for x in s]
    mw = sum(wz) / n
    se = math.sqrt(sum((x - mw) ** 2 for x in wz) / (n - 1)) / ((1 - 2 * g) * math.sqrt(n))
    m = sum(t) / len(t)
    q = t975(len(t) - 1)
    return m, m - q * se, m + q * se


def alternatives(lx, a, loo, c):
    """Half-widths of c's CI by each alternative, on its corrected log
    samples (no bootstrap, so comparable with one another, not with the
    stored hull): median (order statistics, today's part (a)), the common
    mode scaled by c's own least-squares slope on it (clamped to [0, 2]),
    Hodges-Lehmann, 20 % trimmed mean.  None below 6 samples."""
    rs = [r for r in range(len(lx[c])) if math.isfinite(lx[c][r])]
    if len(rs) < 6:
        return None
    z = [loo[c][r] if math.isfinite(loo[c][r]) else 0 for r in rs]
    y = [lx[c][r] - z[i] for i, r in enumerate(rs)]
    v, mz = [lx[c][r] - a[c] for r in rs], sum(z) / len(z)
    mv, szz = sum(v) / len(v), sum((q - mz) ** 2 for q in z)
    beta = min(2.0, max(0.0, sum((p - mv) * (q - mz) for p, q in zip(v, z)) / szz)) if szz > 0 else 1.0
    yb = [lx[c][r] - beta * z[i] for i, r in enumerate(rs)]
    lhw = lambda t: (math.exp(t[2]) - math.exp(t[1])) / 2 / math.exp(t[0])
    return dict(median=lhw(order_ci(y)), slope=lhw(order_ci(yb)), hl=lhw(hl_ci(y)), trimmed=lhw(trimmed_ci(y)))


def load(path):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    run = db.execute("SELECT id FROM runs ORDER BY started DESC LIMIT 1").fetchone()[0]
    rows = db.execute(
        "SELECT c.key, c.scene, c.seq, k.median, k.ci_lo, k.ci_hi, k.corrected, k.corr_median, k.corr_ci_lo,"
        " k.corr_ci_hi, s.data FROM configs c JOIN counters k ON k.run=c.run AND k.key=c.key AND"
        " k.name='WallTime' JOIN samples s ON s.run=c.run AND s.key=c.key AND s.counter='WallTime'"
        " WHERE c.run=? AND c.status='ok' ORDER BY c.seq", (run,)).fetchall()
    labels = {}
    for key, name, value in db.execute("SELECT key, name, value FROM config_params WHERE run=?", (run,)):
        if name in ("technique", "steps", "tess_level"):
            labels.setdefault(key, {})[name] = value
    cfgs = []
    for key, scene, seq, m, lo, hi, corr, cm, clo, chi, data in rows:
        p = labels.get(key, {})
        label = " ".join(x for x in (p.get("technique", key), p.get("steps") and "steps=" + p["steps"],
                                     p.get("tess_level") and "tess_level=" + p["tess_level"]) if x)
        cfgs.append(dict(key=key, scene=scene, label=label, raw=(m, lo, hi),
                         corr=(cm, clo, chi) if corr else None,
                         x=list(struct.unpack(f"<{len(data) // 8}d", data))))
    rounds = {}
    for scene, keys in db.execute("SELECT scene, keys FROM rounds WHERE run=? ORDER BY scene, seq", (run,)):
        rounds.setdefault(scene, []).append(set(keys.split()))
    return run, cfgs, rounds


def scene_layout(cfgs, rounds):
    """x[c][r] by the recorded rounds (run/precision.c precision__layout);
    by sample index when they do not match."""
    nr = len(rounds)
    lx = [[math.nan] * nr for _ in cfgs]
    for c, k in enumerate(cfgs):
        idx = [r for r, keys in enumerate(rounds) if k["key"] in keys]
        if len(idx) != len(k["x"]):
            return None
        for j, r in enumerate(idx):
            lx[c][r] = math.log(k["x"][j]) if k["x"][j] > 0 else math.nan
    return lx


def analyse(path):
    run, cfgs, rounds = load(path)
    scenes = sorted({k["scene"] for k in cfgs}, key=lambda s: [k["scene"] for k in cfgs].index(s))
    raw_in = raw_in_re = corr_in = 0
    misses, per_scene, alts = [], [], {}
    for s in scenes:
        ks = [k for k in cfgs if k["scene"] == s]
        lx = scene_layout(ks, rounds.get(s, []))
        own = [None] * len(ks)
        if lx is not None and all(k["corr"] for k in ks):
            a, b, loo = polish(lx, len(ks), len(lx[0]))
            for c in range(len(ks)):
                alt = alternatives(lx, a, loo, c)
                for name, h in (alt or {}).items():
                    alts.setdefault(name, []).append(h)
                y = [math.exp(lx[c][r] - (loo[c][r] if math.isfinite(loo[c][r]) else 0))
                     for r in range(len(lx[c])) if math.isfinite(lx[c][r])]
                own[c] = order_ci(y)
        s_raw = s_corr = extra = 0
        for c, k in enumerate(ks):
            n = len(k["x"])
            re = order_ci(k["x"])
            if re is not None:
                assert abs(re[1] - k["raw"][1]) <= 1e-9 * k["raw"][1] and abs(re[2] - k["raw"][2]) <= 1e-9 * k["raw"][2], \
                    f"{path}: {k['label']}: raw CI recomputed {re} against stored {k['raw']}"
            r_in = hw(k["raw"]) <= TARGET
            c_fig = k["corr"] or k["raw"]
            c_in = hw(c_fig) <= TARGET
            raw_in += r_in
            raw_in_re += (hw(re) <= TARGET) if re else r_in
            corr_in += c_in
            s_raw += r_in
            s_corr += c_in
            extra += max(0, n - SAMPLES_MAX)
            if not c_in:
                o = own[c]
                if o is not None and hw(o) <= TARGET:
                    cause = "bootstrap"
                elif r_in and n < 20:
                    cause = "few samples"
                else:
                    cause = "noise"
                misses.append((s, k["label"], n, hw(k["raw"]), hw(c_fig), hw(o) if o else math.nan, cause))
        saved = replay(ks, lx, [max(0, len(k["x"]) - SAMPLES_MAX) for k in ks]) if lx else (0, 0.0, 0.0, [])
        per_scene.append((s, len(rounds.get(s, [])), sum(len(k["x"]) for k in ks), extra, s_raw, s_corr, len(ks),
                          saved))
    return run, len(cfgs), raw_in, raw_in_re, corr_in, misses, per_scene, alts


def main(paths):
    causes_all = {}
    for path in paths:
        run, n, raw_in, raw_re, corr_in, misses, per_scene, alts = analyse(path)
        print(f"{path} (run {run}): within ±3 %: raw {raw_in} of {n} stored, {raw_re} recomputed; "
              f"corrected {corr_in} of {n} ({100 * corr_in / n:.0f} %)")
        if alts:
            print("    alternatives, on the corrected samples alone (no bootstrap; configurations with 6 "
                  "samples or more): " + "; ".join(
                      f"{k} {sum(h <= TARGET for h in v)} of {len(v)} (median ±{100 * median(v):.2f} %)"
                      for k, v in alts.items()))
        total_saved = total_extra = 0.0
        for s, nr, ns, extra, sr, sc, k, (saved, secs, tot, who) in per_scene:
            print(f"    {s.split(',')[0]}: {nr} rounds, {ns} samples ({extra} beyond {SAMPLES_MAX} a "
                  f"configuration), within ±3 %: {sr} raw, {sc} corrected of {k}")
            if saved:
                print(f"        extra rounds replayed with the new rule: {saved} of its {extra} extra samples "
                      f"({100 * secs / tot:.0f} % of their sampling time) not needed; stopped early: "
                      f"{', '.join(who)}")
            total_saved += secs
            total_extra += tot
        if total_extra:
            print(f"    extra rounds: {100 * total_saved / total_extra:.0f} % of their sampling time went to "
                  f"configurations already within ±{100 * TARGET / 2:g} % with the drift removed (a sample's "
                  f"time estimated as max(16 frames, 20 ms))")
        causes = {}
        for s, label, ns, rh, ch, oh, cause in misses:
            causes[cause] = causes.get(cause, 0) + 1
            print(f"    miss: {s.split(',')[0]} · {label}: {ns} samples, raw ±{100 * rh:.2f} %, corrected "
                  f"±{100 * ch:.2f} %, its corrected samples alone ±{100 * oh:.2f} % -> {cause}")
        print("    causes: " + (", ".join(f"{k} {v}" for k, v in sorted(causes.items())) or "none"))
        for k, v in causes.items():
            causes_all[k] = causes_all.get(k, 0) + v
    print("all runs, misses by cause: " + ", ".join(f"{k} {v}" for k, v in sorted(causes_all.items())))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: bench/precision_offline.py STORE [STORE ...]")
    main(sys.argv[1:])
