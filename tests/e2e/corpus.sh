#!/usr/bin/env bash
# The hostile corpus (docs/reliability.md, "Conditions and exit codes"): each
# case is hostile input or a hostile environment given to one command, with
# the exit code it must end with and the first words of its message (the
# first "dmbench: error:" line must contain them).  A case also fails when the
# command is killed by a signal it did not ask for (a crash), runs past 60 s
# (a hang), or — for the store cases — changes the store it refused.
#
#   hcase ID CODE 'WORDS' -- COMMAND...     one case; WORDS '' for an exit 0
#
# Large or binary inputs are written at test time by corpus_gen.py.  Cases
# refused at parse or plan time never render; the few that render use 16x16
# images.  CORPUS_PROBE=1 prints what each case did instead of judging it
# (for writing new cases).  CORPUS_ONLY='ID...' runs the cases whose id
# starts with one of the IDs.  Run alone, the script runs every case and
# then checks the conditions table of docs/reliability.md row by row: each
# row names a case, which must have run with the code the row gives.
#
# ctest runs it in shares (tests/e2e.cmake), side by side:
#   CORPUS_CLASSES='sweep/ map/ ...'  this share's classes (id prefixes), or
#   CORPUS_EXCEPT='sweep/ map/ ...'   every class but these (the last share,
#                                     so a new class always runs somewhere)
#   CORPUS_RAN=FILE                   where the share writes each case's id
#                                     and exit code
#   CORPUS_TABLE='FILE...'            no cases: the table check, on the
#                                     cases the shares' FILEs say ran
#   CORPUS_FIXTURE=DIR                the small real run the cases damage,
#                                     made once for the suite in DIR/ok by
#                                     `corpus.sh fixture DIR` (test
#                                     test_e2e_corpus_fixture) and copied,
#                                     where the script otherwise makes it;
#                                     `none` for a share whose cases need
#                                     no run (sweep/: refused at parse time)
# The share's name is the script's argument (for its output only).
set -uo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
declare -A RAN=()           # id -> exit code seen
n_cases=0

# table_check: the conditions table of docs/reliability.md, one row at a
# time, against RAN; and the corpus as a whole has >= 100 cases.
table_check() {
  local rows=0 _ cond code id
  while IFS='|' read -r _ cond code id _; do
    id=$(sed 's/[` ]//g' <<<"$id"); code=$(tr -d ' ' <<<"$code")
    rows=$((rows+1))
    if [ -z "${RAN[$id]+x}" ]; then echo "FAIL: docs row '$cond': case '$id' is not in the corpus"; fail=$((fail+1))
    elif [ "${RAN[$id]}" != "$code" ]; then echo "FAIL: docs row '$cond': case $id exited ${RAN[$id]}, the table says $code"; fail=$((fail+1))
    else pass=$((pass+1)); fi
  done < <(sed -n '/^<!-- corpus-table -->/,/^<!-- \/corpus-table -->/p' "$SRC/docs/reliability.md" | grep '^| ' | tail -n +2 | grep -v '^|---')
  [ "$rows" -ge 20 ] || { echo "FAIL: the conditions table of docs/reliability.md has $rows rows"; fail=$((fail+1)); }
  echo "$n_cases cases"
  [ "$n_cases" -ge 100 ] || { echo "FAIL: only $n_cases cases (want >= 100)"; fail=$((fail+1)); }
}

# The table check over the shares' cases: each share's FILE must exist, and
# no case id may have run in two shares.
if [ -n "${CORPUS_TABLE:-}" ]; then
  for f in $CORPUS_TABLE; do
    [ -s "$f" ] || { echo "FAIL: $f: no cases recorded (did its share run?)"; fail=$((fail+1)); continue; }
    while read -r id rc; do
      if [ -n "${RAN[$id]+x}" ]; then echo "FAIL: case id $id ran in two shares"; fail=$((fail+1)); fi
      RAN[$id]=$rc; n_cases=$((n_cases+1))
    done < "$f"
  done
  table_check
  tally
  exit
fi
G="$OUT/gen"
mkdir -p "$G"
python3 "$SRC/tests/e2e/corpus_gen.py" "$G" || { echo "corpus_gen.py failed"; exit 1; }
NEVER="$OUT/never"          # refused runs must not create their --out
[ -z "${CORPUS_RAN:-}" ] || { mkdir -p "$(dirname "$CORPUS_RAN")"; rm -f "$CORPUS_RAN"; }

# in_list ID 'PREFIX...': ID starts with one of the prefixes.
in_list() { local p; for p in $2; do [[ $1 == "$p"* ]] && return 0; done; return 1; }
# selected ID: case ID is to run here (CORPUS_CLASSES, CORPUS_EXCEPT, CORPUS_ONLY).
selected() {
  { [ -z "${CORPUS_CLASSES:-}" ] || in_list "$1" "$CORPUS_CLASSES"; } &&
  { [ -z "${CORPUS_EXCEPT:-}" ] || ! in_list "$1" "$CORPUS_EXCEPT"; } &&
  { [ -z "${CORPUS_ONLY:-}" ] || in_list "$1" "$CORPUS_ONLY"; }
}

# hcase ID CODE WORDS -- COMMAND...
hcase() {
  local id=$1 code=$2 words=$3; shift 4
  case_ok=0
  if ! selected "$id"; then case_ok=1; return; fi
  if [ -n "${RAN[$id]+x}" ]; then echo "FAIL: case id $id used twice"; fail=$((fail+1)); return; fi
  n_cases=$((n_cases+1))
  local err rc=0 t0=$SECONDS
  err=$(timeout -k 5 60 "$@" 2>&1 >/dev/null) || rc=$?
  RAN[$id]=$rc
  [ -z "${CORPUS_RAN:-}" ] || echo "$id $rc" >> "$CORPUS_RAN"
  local line; line=$(grep -m1 "^dmbench: error: " <<<"$err")
  if [ -n "${CORPUS_PROBE:-}" ]; then
    printf '%s\t%s\t%ss\t%s\n' "$id" "$rc" "$((SECONDS-t0))" "$(head -c 300 <<<"${line:-$err}")"; return
  fi
  if [ "$rc" -ne "$code" ]; then
    echo "FAIL: $id: exit $rc, want $code: $(head -c 400 <<<"$err")"; fail=$((fail+1)); return
  fi
  if [ -n "$words" ] && ! grep -qF -- "$words" <<<"$line"; then
    echo "FAIL: $id: message '$(head -c 300 <<<"${line:-$err}")' lacks '$words'"; fail=$((fail+1)); return
  fi
  pass=$((pass+1)); case_ok=1
}

# wanted PREFIX: some cases of PREFIX are to run here (a block of cases
# that share a set-up is skipped as a whole otherwise).
overlaps() { local p; for p in $2; do [[ $1 == "$p"* || $p == "$1"* ]] && return 0; done; return 1; }
wanted() {
  { [ -z "${CORPUS_CLASSES:-}" ] || overlaps "$1" "$CORPUS_CLASSES"; } &&
  { [ -z "${CORPUS_EXCEPT:-}" ] || ! in_list "$1/" "$CORPUS_EXCEPT"; } &&
  { [ -z "${CORPUS_ONLY:-}" ] || overlaps "$1" "$CORPUS_ONLY"; }
}

# unchanged FILE SUM: a refused command left FILE as it was (data kept).
unchanged() {
  if [ "$(sha256sum < "$1")" = "$2" ]; then pass=$((pass+1))
  else echo "FAIL: $1 changed by a refused command"; fail=$((fail+1)); fi
}
LIMIT=(bash -c 'ulimit $0; exec "$@"')   # "${LIMIT[@]}" "-v 600000" COMMAND...
digest() { sha256sum < "$1"; }
sweep() { local f="$OUT/$1.yaml"; shift; printf '%s\n' "name: corpus" "$@" > "$f"; echo "$f"; }

# ---- a small real run: the stores and results the later cases damage ----
cat > "$OUT/ok.yaml" <<'EOF'
name: corpus
resolution: [16, 16]
measure:
  warmup_frames: 1
  frames_per_sample: 1
  samples: { min: 3, max: 3 }
  max_seconds: 1
  counters: [WallTime, SamplesPassed]
sweep:
  mesh: [plane, cube]
  technique: [normal]
EOF
if [ "${1:-}" = fixture ]; then   # corpus.sh fixture DIR: the run alone, into DIR/ok
  DIR=${2:?usage: corpus.sh fixture DIR}
  rm -rf "$DIR"; mkdir -p "$DIR"
  "$BIN" run "$OUT/ok.yaml" --out "$DIR/ok" --quiet || { echo "FAIL: the fixture run failed"; exit 1; }
  echo "the fixture run: $DIR/ok"; exit 0
fi
case ${CORPUS_FIXTURE:-} in
  none) ;;
  "") "$BIN" run "$OUT/ok.yaml" --out "$OUT/ok" --quiet >/dev/null 2>&1 || { echo "FAIL: the fixture run failed"; exit 1; } ;;
  *) cp -a "$CORPUS_FIXTURE/ok" "$OUT/ok" || { echo "FAIL: no fixture run in $CORPUS_FIXTURE (test_e2e_corpus_fixture)"; exit 1; } ;;
esac
RUNID=$( [ -e "$OUT/ok/latest" ] && basename "$(readlink -f "$OUT/ok/latest")")
# copy NAME: a copy of the fixture's output root (store and run directory)
copy() { rm -rf "$OUT/$1"; cp -a "$OUT/ok" "$OUT/$1"; echo "$OUT/$1"; }
sql() { python3 -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); c.executescript(sys.argv[2]); c.commit()" "$@"; }

# ---- sweep files: the committed bad-sweep corpus through the real binary ----
for f in "$SRC"/tests/data/bad-sweeps/*.yaml; do
  want=$(sed -n '1s/^# expect: [0-9]*: //p' "$f")
  hcase "sweep/$(basename "$f" .yaml)" 2 "$want" -- "$BIN" run "$f" --out "$NEVER"
done
# ---- sweep files: encodings, binary, size, aliases, cartesian size ----
hcase sweep/utf16le 2 "UTF-16" -- "$BIN" run "$G/utf16le.yaml" --out "$NEVER"
hcase sweep/utf16be 2 "UTF-16" -- "$BIN" run "$G/utf16be.yaml" --out "$NEVER"
hcase sweep/binary 2 "binary.yaml" -- "$BIN" run "$G/binary.yaml" --out "$NEVER"
hcase sweep/longline 2 "name: 2097152 bytes long; at most 200" -- "$BIN" run "$G/longline.yaml" --out "$NEVER"
hcase sweep/aliasbomb 2 "aliasbomb.yaml" -- "$BIN" run "$G/aliasbomb.yaml" --out "$NEVER"
hcase sweep/toomany 2 "exceeds 1e6 combinations" -- "$BIN" run "$G/toomany.yaml" --out "$NEVER"
hcase sweep/directory 2 "not a regular file" -- "$BIN" run "$OUT" --out "$NEVER"
hcase sweep/devnull 2 "not a regular file" -- "$BIN" run /dev/null --out "$NEVER"
f=$(sweep nanres "resolution: [.nan, 16]" "sweep:" "  technique: [normal]")
hcase sweep/nan-resolution 2 "nanres.yaml:2" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep hugeres "resolution: [16384, 16384]" "sweep:" "  technique: [normal]")
hcase sweep/huge-resolution 2 "hugeres.yaml" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep negres "resolution: [-16, 16]" "sweep:" "  technique: [normal]")
hcase sweep/negative-resolution 2 "negres.yaml:2" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep pytag "resolution: [16, 16]" "sweep: !!python/object:os.system" "  technique: [normal]")
hcase sweep/yaml-tag 0 "" -- "$BIN" run "$f" --dry-run --out "$OUT/tag"   # a tag is a label, never run
f=$(sweep ansi $'name2: \e]0;pwned\a' "sweep:" "  technique: [normal]")
hcase sweep/ansi-key 2 "control characters are not allowed" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep hugeint "sweep:" "  technique: [normal]" "  tess_level: [99999999999999999999999]")
hcase sweep/huge-integer 2 "hugeint.yaml:4" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep inf "sweep:" "  technique: [pom]" "  height_scale: [.inf]")
hcase sweep/infinite-float 2 "inf.yaml:4" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep badmesh "sweep:" "  technique: [normal]" "  mesh: [file:/nonexistent/x.obj]")
hcase sweep/missing-mesh 2 "x.obj" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep density "sweep:" "  technique: [normal]" "  mesh: [plane, sphere]" "  mesh_density: [9]")
hcase sweep/density-range 2 "density.yaml:5: mesh_density 9 is out of range for mesh 'sphere': valid are 1..7" \
  -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep pathref "scene:" "  camera.path: dolly" "  camera.path_frames: 8" "  camera.path_ref_every: 9" \
  "sweep:" "  technique: [normal]")
hcase sweep/path-ref-past-end 2 "pathref.yaml:5: camera.path_ref_every 9 is past the path's last frame" \
  -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep dollystill "scene:" "  camera.path: dolly" "  camera.distance: 3" "  camera.dolly_to: 3" \
  "sweep:" "  technique: [normal]")
hcase sweep/dolly-still 2 "dollystill.yaml:5: camera.dolly_to 3 equals camera.distance 3: the dolly would not move" \
  -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep flysphere "scene:" "  camera.path: flyover" "sweep:" "  technique: [normal]" "  mesh: [plane, sphere]")
hcase sweep/flyover-sphere 2 "flysphere.yaml:6: camera.path flyover flies at a height over a ground, and mesh 'sphere'" \
  -- "$BIN" run "$f" --out "$NEVER"
# ---- maps (plan time: every resource is read before anything is measured) ----
for m in huge-png wide-png zero-png truncated-png empty-png text-png random-png truncated-exr; do
  hcase "map/$m" 2 "height map" -- "$BIN" run "$G/map-$m.yaml" --out "$NEVER"
done
f=$(sweep mapdir "sweep:" "  technique: [pom]" "scene:" "  material: { height: $OUT }")
hcase map/directory 2 "not a regular file" -- "$BIN" run "$f" --out "$NEVER"
f=$(sweep mapdev "sweep:" "  technique: [pom]" "scene:" "  material: { height: /dev/null }")
hcase map/device 2 "not a regular file" -- "$BIN" run "$f" --out "$NEVER"
hcase map/render-huge 2 "huge.png" -- "$BIN" render technique=pom "maps=height=$G/huge.png" --png "$OUT/x.png"
# ---- meshes ----
for m in truncated-obj empty-obj badindex-obj nan-obj nofaces-obj binary-obj garbage-ply; do
  hcase "mesh/$m" 2 "mesh file" -- "$BIN" run "$G/mesh-$m.yaml" --out "$NEVER"
done
hcase mesh/render-binary 2 "mesh file" -- "$BIN" render "mesh=file:$G/binary.obj" --png "$OUT/x.png"
hcase mesh/render-directory 2 "mesh file" -- "$BIN" render "mesh=file:$OUT" --png "$OUT/x.png"
if [ -e "$NEVER" ]; then echo "FAIL: a refused run wrote $NEVER"; fail=$((fail+1)); else pass=$((pass+1)); fi

# ---- results files (compare, export) ----
R="$OUT/ok/latest/results.json"
hcase results/deep-array 2 "deep.json" -- "$BIN" compare "$G/deep.json" "$R"
hcase results/deep-object 2 "deepobj.json" -- "$BIN" compare "$R" "$G/deepobj.json"
hcase results/utf16 2 "utf16.json" -- "$BIN" compare "$G/utf16.json" "$R"
hcase results/truncated 2 "truncated.json" -- "$BIN" export "$G/truncated.json" --format gbench
printf '' > "$OUT/empty.json"
hcase results/empty 2 "empty.json" -- "$BIN" export "$OUT/empty.json" --format bmf
python3 - "$R" "$OUT/negtime.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
for c in d["configs"]:
        c["counters"]["WallTime"]["median"] = -1.0
json.dump(d, open(sys.argv[2], "w"))
EOF
hcase results/negative-time 2 "negtime.json" -- "$BIN" compare "$OUT/negtime.json" "$R"
python3 - "$R" "$OUT/types.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1])); d["configs"] = "many"; json.dump(d, open(sys.argv[2], "w"))
EOF
hcase results/wrong-types 2 "types.json" -- "$BIN" compare "$OUT/types.json" "$R"
hcase results/directory-not-run 2 "" -- "$BIN" compare "$G" "$R"
hcase results/fifo 2 "" -- "$BIN" compare /dev/null "$R"
hcase results/fit-no-response 2 "has no counter 'FragmentInstructions' (the response of model fragment-instructions)" -- \
  "$BIN" fit "$OUT/ok/latest" --model fragment-instructions
hcase results/fit-no-required 2 "has no counter 'LoopTrips', which model fragment-trips is about: add LoopTrips to measure.counters" -- \
  "$BIN" fit "$OUT/ok/latest" --model fragment-trips
hcase results/fit-no-groups 2 "has no counter 'FragmentGroups', which model fragment-groups is about: add FragmentGroups to measure.counters" -- \
  "$BIN" fit "$OUT/ok/latest" --model fragment-groups

# ---- CSV tables (fit --data) ----
hcase csv/wide 0 "" -- "$BIN" fit --data "$G/wide.csv" --formula "a*c1"
hcase csv/binary 2 "binary.csv" -- "$BIN" fit --data "$G/binary.csv" --formula "a*x"
hcase csv/longcell 2 "usable point" -- "$BIN" fit --data "$G/longcell.csv" --formula "a*x"
printf '' > "$OUT/empty.csv"
hcase csv/empty 2 "empty.csv" -- "$BIN" fit --data "$OUT/empty.csv" --formula "a*x"
printf 'x,WallTime\n' > "$OUT/header.csv"
hcase csv/header-only 2 "only 0 usable point" -- "$BIN" fit --data "$OUT/header.csv" --formula "a*x"
printf 'x,WallTime\n1,2\n2\n3,4,5\n' > "$OUT/ragged.csv"
hcase csv/ragged 2 "ragged.csv:3" -- "$BIN" fit --data "$OUT/ragged.csv" --formula "a*x"
printf 'x,WallTime\n1,nan\n2,3\n3,4\n' > "$OUT/nan.csv"
hcase csv/nan 0 "" -- "$BIN" fit --data "$OUT/nan.csv" --formula "a*x"
printf 'x,WallTime\n1,2\n2,4\n3,6\n' > "$OUT/fit.csv"
printf 'x,WallTime\n1,1e308\n2,1.5e308\n3,1.7e308\n4,1.2e308\n' > "$OUT/overflow.csv"
hcase csv/overflow 1 "the fit is not finite" -- "$BIN" fit --data "$OUT/overflow.csv" --formula "a + b*x"
hcase csv/empty-formula 2 "formula" -- "$BIN" fit --data "$OUT/fit.csv" --formula ""
hcase csv/unknown-function 2 "frobnicate" -- "$BIN" fit --data "$OUT/fit.csv" --formula "a*frobnicate(x)"
hcase csv/unknown-response 2 "Nope" -- "$BIN" fit --data "$OUT/fit.csv" --formula "a*x" --response Nope

# ---- stores ----
S=$(copy newer); sql "$S/dmbench.sqlite" "PRAGMA user_version=99"; h=$(digest "$S/dmbench.sqlite")
hcase store/newer-report 4 "written by a newer dmbench" -- "$BIN" report "$S/latest"
hcase store/newer-resume 4 "written by a newer dmbench" -- "$BIN" run "$OUT/ok.yaml" --out "$S" --resume --quiet
hcase store/newer-fit 4 "written by a newer dmbench" -- "$BIN" fit "$S/latest"
hcase store/newer-merge 4 "written by a newer dmbench" -- "$BIN" merge "$OUT/m1" "$S/latest"
hcase store/newer-history 4 "written by a newer dmbench" -- "$BIN" history --store "$S/dmbench.sqlite"
hcase store/newer-compare 4 "written by a newer dmbench" -- "$BIN" compare --store "$S/dmbench.sqlite" --base-run "$RUNID" "$R"
unchanged "$S/dmbench.sqlite" "$h"
S=$(copy notable); sql "$S/dmbench.sqlite" "DROP TABLE samples"; h=$(digest "$S/dmbench.sqlite")
hcase store/table-report 4 "the results store is damaged: table 'samples' is missing" -- "$BIN" report "$S/latest"
hcase store/table-resume 4 "the results store is damaged: table 'samples'" -- "$BIN" run "$OUT/ok.yaml" --out "$S" --resume --quiet
hcase store/table-fit 4 "the results store is damaged" -- "$BIN" fit "$S/latest"
hcase store/table-export 4 "the results store is damaged" -- "$BIN" export "$RUNID" --store "$S/dmbench.sqlite" --format gbench
hcase store/table-baseline 4 "the results store is damaged" -- "$BIN" baseline accept "$S/latest" --reason x
unchanged "$S/dmbench.sqlite" "$h"
S=$(copy nocolumn); sql "$S/dmbench.sqlite" "ALTER TABLE configs DROP COLUMN q_ssim"; h=$(digest "$S/dmbench.sqlite")
hcase store/column-report 4 "column 'q_ssim' of table 'configs' is missing" -- "$BIN" report "$S/latest"
hcase store/column-run 4 "column 'q_ssim'" -- "$BIN" run "$OUT/ok.yaml" --out "$S" --quiet
unchanged "$S/dmbench.sqlite" "$h"
S=$(copy garbage); head -c 8192 /dev/urandom > "$S/dmbench.sqlite"; h=$(digest "$S/dmbench.sqlite")
hcase store/not-a-database 4 "not a database" -- "$BIN" report "$S/latest"
unchanged "$S/dmbench.sqlite" "$h"
S=$(copy truncated); sql "$S/dmbench.sqlite" "PRAGMA wal_checkpoint(TRUNCATE)"
truncate -s 12288 "$S/dmbench.sqlite"; h=$(digest "$S/dmbench.sqlite")
hcase store/truncated 4 "damaged" -- "$BIN" report "$S/latest"
hcase store/truncated-resume 4 "damaged" -- "$BIN" run "$OUT/ok.yaml" --out "$S" --resume --quiet
unchanged "$S/dmbench.sqlite" "$h"
S=$(copy empty); : > "$S/dmbench.sqlite"
hcase store/empty-file 2 "is not in" -- "$BIN" report "$S/latest"
S=$(copy gone); rm "$S/dmbench.sqlite"
hcase store/missing 2 "not a run directory" -- "$BIN" fit "$S/latest"
S=$(copy root)   # the --out of a run where one of its runs is meant: refused, naming DIR/latest
hcase store/root-report 2 "is a results root" -- "$BIN" report "$S"
hcase store/root-merge 2 "is a results root (it holds dmbench.sqlite)" -- "$BIN" merge "$OUT/root-merged" "$S"
hcase store/root-fit 2 "is a results root" -- "$BIN" fit "$S"
hcase store/resume-without 2 "--resume" -- "$BIN" run "$OUT/ok.yaml" --out "$OUT/nostore" --resume
f=$(sweep other "resolution: [16, 16]" "sweep:" "  technique: [normal]" "  mesh: [cube]")
S=$(copy othersweep); h=$(digest "$S/dmbench.sqlite")
hcase store/resume-other-sweep 2 "different sweep" -- "$BIN" run "$f" --out "$S" --resume --quiet
unchanged "$S/dmbench.sqlite" "$h"
S=$(copy locked)   # the holder the lock file names is alive: refused at once
hcase store/locked 4 "is in use by another dmbench run" -- flock "$S/dmbench.lock" \
  sh -c 'echo $PPID > "$0/dmbench.lock"; exec "$1" run "$2" --out "$0" --quiet' "$S" "$BIN" "$OUT/ok.yaml"
# the run the lock file names has ended, and a process it left (a child
# killed with it, still exiting) holds the lock 1.5 s more: the run waits
S=$(copy locked-orphan)
flock "$S/dmbench.lock" sleep 1.5 &
holder=$!
for _ in $(seq 50); do flock -n "$S/dmbench.lock" true 2>/dev/null || break; sleep 0.02; done
true & gone=$!; wait "$gone"; echo "$gone" > "$S/dmbench.lock"
hcase store/locked-orphan 0 "" -- "$BIN" run "$OUT/ok.yaml" --out "$S" --quiet
wait "$holder"
hcase store/history-none 2 "no such store" -- "$BIN" history --store "$OUT/none.sqlite"

# ---- command-line values ----
hcase cli/shard-zero 2 "expected K/N" -- "$BIN" run --shard 0/2 --out "$NEVER"
hcase cli/shard-text 2 "expected K/N" -- "$BIN" run --shard a/b --out "$NEVER"
hcase cli/seed-fraction 2 "expected a non-negative integer" -- "$BIN" run --seed 1.5 --out "$NEVER"
hcase cli/budget-nan 2 "--budget" -- "$BIN" run "$OUT/ok.yaml" --budget nan --out "$NEVER"
hcase cli/budget-inf 2 "--budget" -- "$BIN" run "$OUT/ok.yaml" --budget inf --out "$NEVER"
hcase cli/alpha-one 2 "--alpha" -- "$BIN" compare "$R" "$R" --alpha 1
hcase cli/alpha-nan 2 "--alpha" -- "$BIN" compare "$R" "$R" --alpha nan
hcase cli/tolerance 2 "--tolerance" -- "$BIN" compare "$R" "$R" --tolerance Bogus=0.1
hcase cli/metric-ansi 2 "unknown metric" -- "$BIN" report "$OUT/ok/latest" --metric $'\e[31mred'
hcase cli/command-ansi 2 "unknown command" -- "$BIN" $'\e]0;title\a'
hcase cli/render-zero 2 "resolution" -- "$BIN" render resolution=0x0 --png "$OUT/x.png"
hcase cli/render-huge 2 "resolution" -- "$BIN" render resolution=100000x100000 --png "$OUT/x.png"
hcase cli/render-unwritable 2 "" -- "$BIN" render resolution=16x16 --png /proc/x.png
hcase cli/diff-huge 2 "cannot read" -- "$BIN" diff "$G/huge.png" "$G/huge.png"
hcase cli/diff-truncated-exr 2 "cannot read" -- "$BIN" diff "$G/truncated.exr" "$G/random.png"
hcase cli/diff-text 2 "cannot read" -- "$BIN" diff "$G/text.png" "$G/text.png"
hcase cli/diff-map-unwritable 2 "cannot write" -- "$BIN" diff "$SRC/docs/img/pom.png" "$SRC/docs/img/pom.png" -o /proc/x.png
hcase cli/slurm-zero 2 "--shards" -- "$BIN" slurm "$OUT/ok.yaml" --shards 0 --print --out "$OUT/sl"
hcase cli/slurm-many 2 "--shards" -- "$BIN" slurm "$OUT/ok.yaml" --shards 1000000000 --print --out "$OUT/sl"
hcase cli/slurm-newline 2 "line break" -- "$BIN" slurm "$OUT/ok.yaml" --shards 1 --print --out "$OUT/a"$'\n'"b"
hcase cli/list-unknown 2 "" -- "$BIN" list frobnicate
hcase cli/out-proc 2 "cannot create or write the output directory" -- "$BIN" run "$OUT/ok.yaml" --out /proc/dmbench
hcase cli/out-long 2 "" -- "$BIN" run "$OUT/ok.yaml" --out "$OUT/$(printf 'd%.0s' {1..5000})"
hcase cli/empty-out 2 "" -- "$BIN" run "$OUT/ok.yaml" --out ""
hcase cli/many-args 2 "only one" -- "$BIN" report $(seq 1 20000)

# ---- slurm --print: what is pasted into a shell, and the #SBATCH lines ----
if wanted slurm; then
D="$OUT/o x; \$(touch $OUT/pwned) #%a"
f=$(sweep markup "resolution: [16, 16]" "sweep:" "  technique: [normal]" "  mesh: [plane, cube]")
sed -i 's|^name: corpus|name: "<b>x</b> y"|' "$f"
hcase slurm/print-quoted 0 "" -- "$BIN" slurm "$f" --shards 2 --print --out "$D"
line=$("$BIN" slurm "$f" --shards 2 --print --resume --out "$D" 2>/dev/null | sed -n 's/^submit with: //p')
sbatch() { printf '%s\n' "$@"; }
got=$(eval "${line%%, then *}")    # the first command as a shell runs it
want=$(printf '%s\n' "--array=1-2" "$D/slurm/shards.sbatch")
if [ "$got" = "$want" ] && [ ! -e "$OUT/pwned" ]; then pass=$((pass+1))
else echo "FAIL: slurm --print: 'submit with' runs as: $got"; fail=$((fail+1)); fi
unset -f sbatch
sb="$D/slurm/shards.sbatch"
if grep -qxF "#SBATCH --output=\"$OUT/o x; \$(touch $OUT/pwned) #%%a\"/slurm/logs/shard-%a.out" "$sb" &&
   grep -qxF "#SBATCH --job-name=dmbench-_b_x__b__y" "$sb" &&
   grep -qxF "#SBATCH --job-name=dmbench-_b_x__b__y-merge" "$D/slurm/merge.sbatch"; then pass=$((pass+1))
else echo "FAIL: slurm #SBATCH lines: $(grep '^#SBATCH' "$sb")"; fail=$((fail+1)); fi
bash -n "$sb" && bash -n "$D/slurm/merge.sbatch" && pass=$((pass+1)) || { echo "FAIL: slurm scripts do not parse"; fail=$((fail+1)); }
fi

# ---- environment ----
hcase env/ulimit-v-run 4 "address-space limit" -- "${LIMIT[@]}" "-v 600000" "$BIN" run "$OUT/ok.yaml" --out "$OUT/ulv" --quiet
# a limit below what the OpenImageIO modules need: the run loads them in its
# own process, before the driver probe, and stops there
hcase env/ulimit-v-modules 4 "OpenImageIO bridge unavailable" -- "${LIMIT[@]}" "-v 250000" "$BIN" run "$OUT/ok.yaml" --out "$OUT/ulm" --quiet
hcase env/ulimit-v-render 4 "address-space limit" -- "${LIMIT[@]}" "-v 600000" "$BIN" render resolution=16x16 --png "$OUT/x.png"
hcase env/lp-text 2 "LP_NUM_THREADS='abc'" -- env LP_NUM_THREADS=abc "$BIN" run "$OUT/ok.yaml" --out "$NEVER"
hcase env/lp-huge 2 "from 0 to 32" -- env LP_NUM_THREADS=100000 "$BIN" run "$OUT/ok.yaml" --out "$NEVER"
hcase env/lp-negative 2 "LP_NUM_THREADS='-1'" -- env LP_NUM_THREADS=-1 "$BIN" render resolution=16x16 --png "$OUT/x.png"
hcase env/lp-empty 2 "LP_NUM_THREADS=''" -- env LP_NUM_THREADS= "$BIN" info
hcase env/count-jobs-text 2 "DMBENCH_COUNT_JOBS=many: not a whole number of counting children in 0..256" -- env DMBENCH_COUNT_JOBS=many "$BIN" run "$OUT/ok.yaml" --out "$NEVER"
hcase env/count-jobs-huge 2 "DMBENCH_COUNT_JOBS=300: not a whole number of counting children in 0..256" -- env DMBENCH_COUNT_JOBS=300 "$BIN" info
hcase env/lp-zero 0 "" -- env LP_NUM_THREADS=0 "$BIN" render resolution=16x16 --png "$OUT/lp0.png"
hcase env/ulimit-n 0 "" -- "${LIMIT[@]}" "-n 16" "$BIN" run "$OUT/ok.yaml" --out "$OUT/uln" --quiet
hcase env/ulimit-f-run 4 "disk I/O error" -- "${LIMIT[@]}" "-f 8" "$BIN" run "$OUT/ok.yaml" --out "$OUT/ulf" --quiet
hcase env/sysfs-out 2 "cannot create or write the output directory" -- "$BIN" run "$OUT/ok.yaml" --out /sys/dmbench
hcase env/proc-report-out 2 "cannot create the directory" -- "$BIN" report "$OUT/ok/latest" --out /proc/dmbench
hcase env/proc-cache 0 "" -- env DMBENCH_CACHE_DIR=/proc/dmbench-cache "$BIN" run "$OUT/ok.yaml" --out "$OUT/pc" --quiet
hcase env/no-egl-vendor 4 "is Mesa's EGL installed" -- env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "$BIN" render resolution=16x16 --png "$OUT/x.png"
hcase env/no-driver 4 "is Mesa's EGL installed" -- env LIBGL_DRIVERS_PATH=/nonexistent "$BIN" run "$OUT/ok.yaml" --out "$OUT/nodrv" --quiet
hcase env/driver-unknown 2 "unknown driver; the drivers are" -- env DMBENCH_DRIVER=voodoo "$BIN" run "$OUT/ok.yaml" --out "$NEVER"
hcase env/driver-missing 2 "needs Mesa 25 in /nonexistent" -- env DMBENCH_DRIVER=llvmpipe-25 DMBENCH_MESA25_PREFIX=/nonexistent "$BIN" info
hcase env/no-home 0 "" -- env -u HOME -u XDG_CACHE_HOME "$BIN" list techniques
hcase env/tmpdir-missing 0 "" -- env TMPDIR=/nonexistent "$BIN" render resolution=16x16 --png "$OUT/tmp.png"
hcase env/cache-is-file 0 "" -- env DMBENCH_CACHE_DIR="$OUT/ok.yaml" "$BIN" render resolution=16x16 --png "$OUT/c.png"
hcase env/stdout-full 4 "cannot write the standard output" -- bash -c '"$0" list techniques > /dev/full' "$BIN"

# ---- signals: an interrupted run keeps what it committed; --resume ends it ----
S="$OUT/sig"
for sig in TERM INT HUP; do
  wanted "signal/$sig" || continue
  rm -rf "$S"
  "$BIN" run "$OUT/ok.yaml" --out "$S" --quiet >/dev/null 2>&1 &
  pid=$!   # killed once its run is in the store: mid-run, or just after it ended
  for _ in $(seq 100); do
    [ "$(python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*) from runs').fetchone()[0])" "$S/dmbench.sqlite" 2>/dev/null)" = 1 ] && break
    kill -0 "$pid" 2>/dev/null || break; sleep 0.1
  done
  kill -s "$sig" "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
  hcase "signal/$sig-resume" 0 "" -- "$BIN" run "$OUT/ok.yaml" --out "$S" --resume --quiet
  n=$(python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*), count(distinct key) from configs').fetchone())" "$S/dmbench.sqlite")
  if [ "$n" = "(2, 2)" ]; then pass=$((pass+1)); else echo "FAIL: signal $sig: configs after --resume $n, want (2, 2)"; fail=$((fail+1)); fi
done
hcase signal/pipe 0 "" -- bash -c 'set -o pipefail; "$0" list counters | head -c 1 >/dev/null; true' "$BIN"

# ---- the classes in corpus.d/: user GLSL, images, predict and numbers read
# back, children and signals, replicated compare (one file a class; each
# uses hcase and the fixture above) ----
for part in "$SRC"/tests/e2e/corpus.d/*.sh; do
  . "$part"
done

# ---- the conditions table of docs/reliability.md (a share leaves it to
# the table check, which reads what every share ran) ----
if [ -z "${CORPUS_ONLY:-}${CORPUS_PROBE:-}${CORPUS_CLASSES:-}${CORPUS_EXCEPT:-}" ]; then
  table_check
else
  echo "$n_cases cases${1:+ in share $1}"
  [ "$n_cases" -ge 1 ] || { echo "FAIL: no case selected"; fail=$((fail+1)); }
fi
tally
