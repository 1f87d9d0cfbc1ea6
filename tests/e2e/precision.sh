#!/usr/bin/env bash
# End to end (issue 50): a --quick run stores, for every configuration,
# the raw WallTime median and CI and, per scene, either the figures with
# the machine's drift removed for all its configurations or the reason it
# kept the raw ones only (which happens depends on the host's drift; the
# unit tests test_models_drift and test_run_precision force both); it
# prints the precision, noise floor and predictor lines; the rounds are on
# record, each configuration's WallTime samples one per round naming it,
# in orders that differ between rounds; a second run with the same --seed
# visits the first round of every scene in the same order, another seed
# in another.  --quick takes no extra rounds unless asked (the default
# sweep's 60 s are the bench's to measure: bench/precision.sh).
# The three runs are the suite's (tests/e2e/quick_runs.sh: a and b with
# --seed 7, c with --seed 8; a's progress in a.log).
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"

RUNS=$(bash "$SRC/tests/e2e/quick_runs.sh" --use "$OUT/runs")
# lines wrap at 100 columns with continuations four columns in: join them
sed ':a;N;$!ba;s/\n    */ /g' "$RUNS/a.log" > "$OUT/a.log"
grep -q "^dmbench: precision (WallTime, 95 % CI within ±5 %): [0-9]* of [0-9]* raw, [0-9]* of [0-9]* with the machine's drift removed" "$OUT/a.log"
grep -q "^dmbench: noise floor ±[0-9.]* %" "$OUT/a.log"
grep -q "^dmbench: the machine's speed moved ±" "$OUT/a.log"
# the default sweep spends 60 s of extra rounds by default; --quick none
if grep "extra rounds" "$OUT/a.log"; then echo "extra rounds in a --quick run without --extra-time"; exit 1; fi
[ -z "$(sqlite3 "$RUNS/a/dmbench.sqlite" "SELECT value FROM run_env WHERE key = 'extra_time_s'")" ]
python3 - "$RUNS" <<'PY'
import math, os, sqlite3, sys
def load(d):
    db = sqlite3.connect(os.path.join(sys.argv[1], d, "dmbench.sqlite"))
    run = db.execute("SELECT id FROM runs").fetchone()[0]
    return db, run
db, run = load("a")
wall = db.execute("SELECT c.key, c.scene, k.median, k.ci_lo, k.ci_hi, k.corrected, k.corr_median, k.corr_ci_lo,"
                  " k.corr_ci_hi, length(s.data) / 8 FROM configs c JOIN counters k ON k.run = c.run AND"
                  " k.key = c.key AND k.name = 'WallTime' JOIN samples s ON s.run = c.run AND s.key = c.key AND"
                  " s.counter = 'WallTime' WHERE c.run = ? AND c.status = 'ok'", (run,)).fetchall()
assert len(wall) == 18, len(wall)
prec = {r[0]: r[1:] for r in db.execute("SELECT scene, corrected, reason, n_rounds, machine_spread,"
                                         " raw_noise, loo_noise, resolvable FROM scene_precision WHERE run = ?", (run,))}
assert set(prec) == {w[1] for w in wall}, (prec.keys(), {w[1] for w in wall})
for key, scene, m, lo, hi, corr, cm, clo, chi, n in wall:
    assert m is not None and lo <= m <= hi, (key, m, lo, hi)          # raw always there
    corrected, reason = prec[scene][0], prec[scene][1]
    if corrected:
        assert corr == 1 and clo <= cm <= chi, (key, cm, clo, chi)
    else:
        assert corr == 0 and reason, (key, scene, reason)
for scene, (corrected, reason, n_rounds, spread, raw, loo, resolvable) in prec.items():
    assert resolvable is not None and resolvable > 0, (scene, resolvable)
    print(f"{scene}: corrected {corrected}, machine ±{100 * (spread or 0):.2f} %, raw {100 * (raw or 0):.2f} %,"
          f" after {100 * (loo or 0):.2f} %, resolvable {100 * resolvable:.2f} %{', ' + reason if reason else ''}")
rounds = {}
for scene, seq, keys in db.execute("SELECT scene, seq, keys FROM rounds WHERE run = ? ORDER BY scene, seq", (run,)):
    rounds.setdefault(scene, []).append(keys.split())
for key, scene, *_, n in wall:
    assert sum(key in r for r in rounds[scene]) == n, (key, n)      # one sample per round naming it
for scene, rs in rounds.items():
    full = [tuple(r) for r in rs if len(r) == len(rs[0])]
    assert len(full) >= 2 and len(set(full)) >= 2, (scene, full)     # the order differs between rounds
    assert len(set(rs[0])) == len(rs[0]) == sum(w[1] == scene for w in wall)
assert db.execute("SELECT value FROM run_env WHERE run = ? AND key = 'seed'", (run,)).fetchone()[0] == "7"
first = {s: r[0] for s, r in rounds.items()}
for d, same in (("b", True), ("c", False)):
    db2, run2 = load(d)
    other = {s: k.split() for s, k in db2.execute("SELECT scene, keys FROM rounds WHERE run = ? AND seq = 0", (run2,))}
    assert (other == first) == same, (d, other, first)
print("precision e2e: raw and corrected-or-reason for", len(wall), "configurations;", len(rounds), "scenes' rounds on record")
PY
