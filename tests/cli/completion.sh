#!/usr/bin/env bash
# The generated bash completion under bash: it registers itself for
# dmbench, and COMPREPLY for partial words holds exactly the commands,
# options, choices and files that fit.  The installed script is what the
# binary generates.
set -uo pipefail
export LC_ALL=C
BIN=${DMBENCH_BINARY:?}
COMPLETION=${DMBENCH_BASH_COMPLETION:?}
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }

cmp -s "$COMPLETION" <("$BIN" __gen-completion bash) && ok || bad "$COMPLETION is not what the binary generates"
source "$COMPLETION"
[[ $(complete -p dmbench) == "complete -F _dmbench dmbench" ]] && ok || bad "complete -p: $(complete -p dmbench 2>&1)"

# expect "WORDS..." "COMPREPLY sorted": the last word is the one completed
expect() {
  read -r -a COMP_WORDS <<<"$1"
  [[ $1 == *" " ]] && COMP_WORDS+=("")
  COMP_CWORD=$(( ${#COMP_WORDS[@]} - 1 ))
  COMPREPLY=()
  _dmbench
  local got; got=$(printf '%s\n' "${COMPREPLY[@]}" | grep -v '^$' | sort | tr '\n' ' ' | sed 's/ $//')
  [ "$got" = "$2" ] && ok || bad "'$1' -> '$got', want '$2'"
}
WORK=$(mktemp -d); trap 'rm -rf "$WORK"' EXIT
cd "$WORK" && mkdir subdir && touch subfile sweep.yaml

expect "dmbench ru" "run"
expect "dmbench re" "render report"
expect "dmbench --v" "--version"
expect "dmbench run --sh" "--shard"
expect "dmbench run --q" "--quick --quiet"
expect "dmbench compare --base-" "--base-run --base-store --base-tag"
expect "dmbench fit --loss " "cauchy huber none"
expect "dmbench fit --loss h" "huber"
expect "dmbench render --debug n" "none normals"
expect "dmbench list te" "techniques textures"
expect "dmbench list --json c" "counters"
expect "dmbench list --passes WallTime m" "meshes models"
expect "dmbench list counters t" ""
expect "dmbench baseline " "accept show"
expect "dmbench help com" "compare"
expect "dmbench run --out sub" "subdir"
expect "dmbench run sw" "sweep.yaml"
expect "dmbench run --tag " ""
expect "dmbench compare --paired a b c --ro" "--rounds"
expect "dmbench compare --junit sub" "subdir subfile"
expect "dmbench view --keys " ""
expect "dmbench nosuch --" ""
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
