#!/usr/bin/env bash
# Every mistyped command, action, option and value gets exit 2 and a
# did-you-mean naming the right word; a missing required option says "is
# required".  One --quick run gives history and export something to read.
set -uo pipefail
BIN=${DMBENCH_BINARY:?}
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }
work=$(mktemp -d /tmp/dm_didyoumean_XXXXXX)
trap 'rm -rf "$work"' EXIT INT TERM

"$BIN" run --quick --out "$work/res" --quiet 2>"$work/run.log" || { cat "$work/run.log"; exit 1; }
run="$work/res/latest"
store="$work/res/dmbench.sqlite"

# expect RC TEXT -- ARGS...: exit code RC and TEXT in stderr
expect() {
  local want=$1 text=$2; shift 3
  local err; err=$("$BIN" "$@" 2>&1 >/dev/null); local rc=$?
  if [ $rc -eq "$want" ] && grep -qF -- "$text" <<<"$err"; then ok
  else bad "dmbench $*: rc $rc, want $want and '$text' in: $err"; fi
}
expect 2 "did you mean 'run'?" -- rnu
expect 2 "unknown action 'shwo'; did you mean 'show'?" -- baseline shwo --store "$store"
expect 2 "did you mean 'techniques'?" -- list techniqes
expect 2 "did you mean '--metric'?" -- report "$run" --metirc ssim
expect 2 "did you mean '--quick'?" -- run --quik
expect 2 "--technique 'pomm' is not in run" -- history --technique pomm --store "$store"
expect 2 "did you mean 'pom'?" -- history --technique pomm --store "$store"
expect 2 "did you mean 'plane@80x45'?" -- history --scene plane@80x4 --store "$store"
expect 2 "--format is required" -- export "$run"
expect 2 "did you mean 'gbench'?" -- export "$run" --format gbenc
# the right words still work
"$BIN" history --technique pom --store "$store" >/dev/null 2>&1 && ok || bad "history --technique pom"
"$BIN" export "$run" --format gbench -o "$work/g.json" >/dev/null 2>&1 && ok || bad "export --format gbench"
# the default sweep printed as YAML plans as it is (the docs show it)
"$BIN" run --print-default > "$work/default.yaml" && "$BIN" run "$work/default.yaml" --dry-run \
  --out "$work/dry" >/dev/null 2>&1 && ok || bad "run --print-default does not plan back"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
