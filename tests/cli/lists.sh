#!/usr/bin/env bash
# `dmbench list WHAT --json` for every list: a non-empty JSON array whose
# names are exactly those of the text listing; the models are those `fit`
# accepts (both come from models/catalog.c, the text list is not typed in).
set -uo pipefail
BIN=${DMBENCH_BINARY:?}
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }

lists=$("$BIN" list --help | sed -n 's/^usage: dmbench list \([a-z|]*\).*/\1/p' | tr '|' ' ')
[ "$lists" = "techniques axes counters meshes textures models keys" ] && ok || bad "lists: '$lists'"
for w in $lists; do
  [ "$w" = keys ] && continue   # a table of rows, not names: tests/cli/keys.sh
  json=$("$BIN" list "$w" --json); rc=$?
  [ $rc -eq 0 ] && ok || bad "list $w --json exited $rc"
  names_json=$(python3 -c '
import json, sys
d = json.loads(sys.stdin.read())
assert isinstance(d, list) and d, "not a non-empty array"
print(" ".join(sorted(x if isinstance(x, str) else x["name"] for x in d)))' <<<"$json") \
    || { bad "list $w --json: $json"; continue; }
  text=$("$BIN" list "$w")
  case $w in
    counters) names_text=$(awk 'NR>1 && $1 !~ /^unavailable/ && substr($0,1,1)!=" " {print $1}' <<<"$text") ;;
    models)   names_text=$(awk 'substr($0,1,1)!=" " && $1 !~ /^\(/ {print $1}' <<<"$text") ;;
    *)        names_text=$(awk 'substr($0,1,1)!=" " {print $1}' <<<"$text") ;;
  esac
  names_text=$(sort <<<"$names_text" | tr '\n' ' ' | sed 's/ $//')
  [ "$names_json" = "$names_text" ] && ok || bad "list $w: json '$names_json' vs text '$names_text'"
done
models=$("$BIN" list models --json | python3 -c 'import json,sys; print(" ".join(m["name"] for m in json.load(sys.stdin)))')
err=$("$BIN" fit --data x.csv --model zz-bogus 2>&1)
[ "$(sed -n 's/.*valid models: //p' <<<"$err" | tr -d ',')" = "$models" ] && ok || bad "fit models: $err vs $models"
for m in $models; do
  err=$("$BIN" fit --data /nonexistent.csv --model "$m" 2>&1)
  grep -q "unknown model" <<<"$err" && bad "fit rejects listed model $m" || ok
done
err=$("$BIN" list techniques --passes WallTime 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q "applies to 'list counters' only" <<<"$err" && ok || bad "--passes on techniques: $rc $err"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
