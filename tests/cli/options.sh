#!/usr/bin/env bash
# Every option the parser accepts is in `dmbench CMD --help`, `dmbench help
# CMD`, the "valid options" list, the man page and the bash completion — and
# the other way round — and equals the list written out below (the options
# each command had before the tables, plus --help).  Then all options are
# fed to the parser followed by a bogus option: the error must name the
# bogus one, which proves the parser took the option (and its value).
set -uo pipefail
export LC_ALL=C
BIN=${DMBENCH_BINARY:?}
MAN=${DMBENCH_MAN:?}
COMPLETION=${DMBENCH_BASH_COMPLETION:?}
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }

declare -A expected=(
  [run]="--budget --count-jobs --dry-run --extra-time --help --out --print-default --quick --quiet --resume --seed --shard --tag --verbose"
  [report]="--budget-ms --flip-ppd --help --metric --out"
  [fit]="--data --formula --group-by --help --json --loss --model --response"
  [predict]="--allow-env-mismatch --csv --from --help --json"
  [compare]="--allow-env-mismatch --alpha --base-run --base-store --base-tag --baseline --counters-only --flip-rise --help --json --junit --markdown --new-run --new-store --new-tag --no-blocking --only-changed --paired --psnr-drop --quiet --rounds --run-spread --seed --ssim-drop --store --threshold --time-counter --time-threshold --tolerance"
  [baseline]="--help --reason --store"
  [merge]="--allow-missing --help"
  [slurm]="--collect --help --job --out --partition --print --resume --shards --time"
  [export]="--format --help --output --store"
  [history]="--help --run --scene --store --technique"
  [list]="--help --json --passes"
  [info]="--help --json"
  [render]="--debug --exr --frame --help --png --supersample"
  [diff]="--heatmap --help --json --ppd"
  [drivers]="--drivers --help --interleave --out --quiet --seed"
  [view]="--config --frames --help --keys --results --screenshot --timed-seconds"
  [help]="--help"
)
# A valid value for options whose value is checked; others take "x".
declare -A value=(
  [--shard]=1/2 [--budget]=1 [--extra-time]=1 [--seed]=1 [--metric]=rmse [--loss]=huber [--passes]=WallTime
  [--time-threshold]=5% [--threshold]=1% [--alpha]=0.1 [--psnr-drop]=1 [--ssim-drop]=0.1 [--flip-rise]=0.01 [--tolerance]=FSInvocations=1 [--run-spread]=10%
  [--rounds]=1 [--interleave]=2 [--count-jobs]=1 [--supersample]=2 [--debug]=normals [--frames]=1 [--frame]=0 [--timed-seconds]=1
  [--paired]="a b c" [--budget-ms]=16 [--shards]=2 [--format]=gbench [--ppd]=30 [--flip-ppd]=30
)

sorted() { tr ' ' '\n' | grep -v '^$' | sort -u | tr '\n' ' ' | sed 's/ $//'; }

# commands listed by `dmbench help`
cmds=$("$BIN" help | sed -n '/^commands:/,/^$/p' | awk 'NF>1 && $1!="commands:" {print $1}' | sorted)
[ "$cmds" = "$(printf '%s\n' "${!expected[@]}" | sort | tr '\n' ' ' | sed 's/ $//')" ] && ok \
  || bad "commands in help: '$cmds'"

source "$COMPLETION"
for cmd in "${!expected[@]}"; do
  want=$(echo "${expected[$cmd]}" | sorted)
  help=$("$BIN" "$cmd" --help); rc=$?
  [ $rc -eq 0 ] && ok || bad "$cmd --help exited $rc"
  [ "$help" = "$("$BIN" help "$cmd")" ] && ok || bad "help $cmd differs from $cmd --help"
  from_help=$(sed -n '/^options:/,$p' <<<"$help" | grep -oE '^  (-[a-z], )?--[a-z-]+' | grep -oE -- '--[a-z-]+' | sorted)
  err=$("$BIN" "$cmd" --zz-bogus 2>&1 >/dev/null); rc=$?
  [ $rc -eq 2 ] && ok || bad "$cmd --zz-bogus exited $rc"
  from_valid=$(sed -n 's/.*valid options: //p' <<<"$err" | tr -d ',' | sorted)
  from_man=$(awk -v s=".SS \"dmbench $cmd\"" '$0==s {on=1; next} /^\.S[SH]/ {on=0} on' "$MAN" \
             | sed 's/\\-/-/g; s/\\f[BRI]//g' | grep -oE '^(-[a-z], )?--[a-z-]+' | grep -oE -- '--[a-z-]+' | sorted)
  COMP_WORDS=(dmbench "$cmd" --); COMP_CWORD=2; _dmbench
  from_comp=$(echo "${COMPREPLY[@]}" | sorted)
  for src in help valid man comp; do
    v="from_$src"
    [ "${!v}" = "$want" ] && ok || bad "$cmd: options in $src: '${!v}', want '$want'"
  done
  # all options at once, then a bogus one: the parser must reach the bogus one
  args=()
  for opt in $want; do
    [ "$opt" = --help ] && continue
    args+=("$opt")
    if grep -qE "^  (-[a-z], )?$opt [A-Z]" <<<"$help"; then
      read -r -a v <<<"${value[$opt]:-x}"; args+=("${v[@]}")
    fi
  done
  err=$("$BIN" "$cmd" "${args[@]}" --zz-bogus 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 2 ] && grep -q "unknown option '--zz-bogus'" <<<"$err"; then ok
  else bad "$cmd ${args[*]} --zz-bogus: rc $rc, $err"; fi
done

# dmbench --version carries the git revision the build recorded
"$BIN" --version | grep -qE '^dmbench [0-9]+\.[0-9]+\.[0-9]+ \(git [0-9a-f]{7,}|unknown\)' && ok \
  || bad "--version: $("$BIN" --version)"
# a value after '=' and a missing value
err=$("$BIN" fit --loss=bogus x 2>&1)
grep -q "fit: --loss 'bogus': expected one of: huber, cauchy, none" <<<"$err" && ok || bad "--loss=bogus: $err"
err=$("$BIN" run --out 2>&1)
grep -q "run: --out needs a value" <<<"$err" && ok || bad "run --out without a value: $err"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
