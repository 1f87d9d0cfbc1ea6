# corpus.d/numbers.sh — numbers read back (non-finite or missing values in a
# store, results.json or CSV), `predict`, replicated `compare`; sourced by
# corpus.sh.

# ---- a value read back missing or not finite: "unavailable", never a PASS ----
# results.json: SamplesPassed null (NaN written by a tool) or 1e999 (+inf)
python3 - "$R" "$OUT/spnull.json" "$OUT/spinf.json" <<'PY'
import json, sys
for path, val in ((sys.argv[2], "null"), (sys.argv[3], "1e999")):
    d = json.load(open(sys.argv[1]))
    for c in d["configs"]:
        c["counters"]["SamplesPassed"]["value"] = "@@"
    open(path, "w").write(json.dumps(d).replace('"@@"', val))
PY
# gate_unreadable ID BASE NEW WORDS: compare is REGRESSION (1), its
# report names the read-back reason, and prints no "nan" or "inf" ratio.
gate_unreadable() {
  local id=$1 words=$2; shift 2
  hcase "$id" 1 "" -- "$BIN" compare "$@"
  [ "$case_ok" = 1 ] || return
  local out; out=$("$BIN" compare "$@" 2>&1 | sed -e ':a;N;$!ba;s/\n    / /g')   # joins the wrapped lines
  if grep -qF -- "$words" <<<"$out" && ! grep -qE -- "(^| |\+|-> )(nan|inf)( |%|$)" <<<"$out"; then pass=$((pass+1))
  else echo "FAIL: $id: report lacks '$words' or prints a non-number: $out"; fail=$((fail+1)); fi
}
if wanted gate; then
gate_unreadable gate/json-null "SamplesPassed unavailable on NEW: the value read back from results.json is missing or NaN" "$R" "$OUT/spnull.json"
gate_unreadable gate/json-inf "SamplesPassed unavailable on BASE: the value read back from results.json is +inf" "$OUT/spinf.json" "$R"
gate_unreadable gate/json-both "unavailable on BASE" "$OUT/spnull.json" "$OUT/spnull.json"
S=$(copy nullstore)
KEYS=$(python3 -c "import json,sys; [print(c['key']) for c in json.load(open(sys.argv[1]))['configs']]" "$R")
sql "$S/dmbench.sqlite" "UPDATE counters SET value = NULL WHERE name = 'SamplesPassed'"
gate_unreadable gate/store-null "the value read back from the results store is missing or NaN" \
  --store "$S/dmbench.sqlite" --base-run "$RUNID" "$R"
# fit leaves the points out and says so: none is left to fit
hcase gate/fit-store-null 1 "" -- "$BIN" fit "$S/latest" --formula "a + b*SamplesPassed"
sql "$S/dmbench.sqlite" "UPDATE counters SET value = 232 WHERE name = 'SamplesPassed' AND key = '$(sed -n 1p <<<"$KEYS")'"
fo=$("$BIN" fit "$S/latest" --formula "a + b*SamplesPassed" 2>&1)
if grep -q "excluded 1" <<<"$fo" && grep -q "± unavailable" <<<"$fo" && ! grep -qiw "nan" <<<"$fo"; then pass=$((pass+1))
else echo "FAIL: fit over unreadable SamplesPassed: $fo"; fail=$((fail+1)); fi
fi

# ---- lists of runs: empty entries, one run twice, a comma in a path ----
hcase predict/from-empty 2 "predict: --from '': no path" -- "$BIN" predict "$OUT/ok.yaml" --from ""
hcase predict/from-comma 2 "predict: --from ',': an empty entry" -- "$BIN" predict "$OUT/ok.yaml" --from ","
hcase predict/same-run-twice 2 "predict: --from names run $RUNID twice" -- \
  "$BIN" predict "$OUT/ok.yaml" --from "$OUT/ok/latest,$OUT/ok/$RUNID"
hcase compare/same-run-twice 2 "are the same run ($RUNID)" -- \
  "$BIN" compare "$R,$R" "$OUT/ok/latest,$OUT/ok/$RUNID"
hcase compare/empty-entry 2 "compare: the list '$R,': an empty entry" -- "$BIN" compare "$R," "$R,"
if wanted compare/comma || wanted predict/comma; then
  rm -rf "$OUT/a,b"; cp -a "$OUT/ok" "$OUT/a,b"
fi
hcase compare/comma-dir 0 "" -- "$BIN" compare "$OUT/a,b/latest" "$OUT/a,b/latest"
hcase predict/comma-dir 2 "has no counter 'Instructions'" -- "$BIN" predict "$OUT/ok.yaml" --from "$OUT/a,b/latest"
hcase drivers/twice 2 "names llvmpipe twice" -- "$BIN" drivers "$OUT/ok.yaml" --drivers llvmpipe,llvmpipe --out "$NEVER"

# ---- an --out whose store path SQLite cannot open: refused before it is made ----
if wanted cli/out-sqlite; then
  d="$OUT/L"; while [ ${#d} -lt 495 ]; do d="$d/$(printf 'd%.0s' {1..60})"; done
fi
hcase cli/out-sqlite-long 2 "SQLite opens at most 504" -- "$BIN" run "$OUT/ok.yaml" --out "${d:-$OUT/L}" --quiet
if wanted cli/out-sqlite; then
  if [ -e "$OUT/L" ]; then echo "FAIL: cli/out-sqlite-long created $OUT/L"; fail=$((fail+1)); else pass=$((pass+1)); fi
fi

# ---- user text with control bytes: never raw on the terminal ----
if wanted baseline/reason; then
  S=$(copy ansibase)
  "$BIN" baseline accept "$S/latest" --reason $'ok \e]0;pwned\a \e[31mred' >/dev/null 2>&1
fi
hcase baseline/reason-ansi 0 "" -- "$BIN" baseline show --store "${S:-}/dmbench.sqlite"
if wanted baseline/reason; then
  o=$("$BIN" baseline show --store "$S/dmbench.sqlite" 2>&1; "$BIN" compare --baseline "$R" 2>&1 --store "$S/dmbench.sqlite")
  if grep -q $'\e' <<<"$o"; then echo "FAIL: baseline reason reached the terminal raw"; fail=$((fail+1))
  elif grep -qF "ok ?]0;pwned? ?[31mred" <<<"$o"; then pass=$((pass+1))
  else echo "FAIL: baseline reason not shown: $o"; fail=$((fail+1)); fi
fi

# ---- predict over a store with one count read back missing: the fits leave
# that configuration out and say so; an interval they cannot make is
# "unavailable", never [nan, nan] (the counts a predict needs are written
# into a small timed run's store: the cube's exact counts, Instructions a
# known linear cost of the fragments) ----
if wanted predict/unreadable; then
  cat > "$OUT/pr.yaml" <<'YAML'
name: corpus-predict
measure:
  warmup_frames: 1
  frames_per_sample: 1
  samples: { min: 3, max: 3 }
  max_seconds: 1
  counters: [WallTime, SamplesPassed]
scene:
  mesh: cube
sweep:
  technique: [normal]
  resolution: ["16x16", "24x24", "32x32"]
YAML
  "$BIN" run "$OUT/pr.yaml" --out "$OUT/pr" --quiet >/dev/null 2>&1
  python3 - "$OUT/pr/dmbench.sqlite" <<'PY'
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
run = c.execute("select id from runs").fetchone()[0]
keys = [r[0] for r in c.execute("select key from configs order by seq")]
for k in keys:
    fs = c.execute("select value from counters where key=? and name='SamplesPassed'", (k,)).fetchone()[0]
    vals = {"VSInvocations": 24, "TESInvocations": 0, "ClippingOutputPrimitives": 16, "FSInvocations": fs,
            "Instructions": 1000 * fs + 50 * 24 + 7}
    for n, v in vals.items():
        c.execute("insert or replace into counters(run,key,name,unit,available,deterministic,partial,value,has_samples)"
                  " values(?,?,?,'items',1,1,0,?,0)", (run, k, n, v))
c.execute("update counters set value = NULL where name = 'Instructions' and key = ?", (keys[0],))
c.commit()
PY
fi
hcase predict/unreadable 0 "" -- "$BIN" predict "$OUT/pr.yaml" --from "$OUT/pr/latest"
if wanted predict/unreadable; then
  po=$("$BIN" predict "$OUT/pr.yaml" --from "$OUT/pr/latest" 2>&1)
  k0=$(python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select key from configs order by seq').fetchone()[0])" "$OUT/pr/dmbench.sqlite")
  if grep -q "^left out of the fits" <<<"$po" &&
     grep -qF "$k0  cube 16×16 · normal: Instructions unavailable (the value read back from the results store is missing or NaN" <<<"$po" &&
     grep -q "Instructions interval unavailable: the runs measured 3 configurations of variant" <<<"$po" &&
     grep -q "WallTime interval unavailable" <<<"$po" &&
     ! grep -qE "(\[| )(nan|-?inf)(,|\]| |%|$)" <<<"$po"; then pass=$((pass+1))
  else echo "FAIL: predict/unreadable: $po"; fail=$((fail+1)); fi
fi
