# tests/lib.sh — what the shell tests share.  Each sources it right after
# its own `set` line:
#     . "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
# It sets BIN (the dmbench binary) and SRC (the source tree) from ctest's
# environment and OUT, a scratch directory removed on exit, and defines the
# checks below.  Nothing here depends on `set -e` being on or off.
BIN=${DMBENCH_BINARY:?}
SRC=${DMBENCH_SOURCE_DIR:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

# Checks that go on after a failure count here; the script ends with `tally`.
pass=0; fail=0

# expect_refused CODE PATTERN -- command...: the command exits CODE within
# 60 s and its stderr matches the grep PATTERN; a FAIL line says otherwise.
expect_refused() {
  local code=$1 pat=$2; shift 3
  local err rc=0; err=$(timeout 60 "$@" 2>&1 >/dev/null) || rc=$?
  if [ "$rc" -eq "$code" ] && grep -q -- "$pat" <<<"$err"; then pass=$((pass+1))
  else fail=$((fail+1)); echo "FAIL: ${*:1:4} -> rc $rc (want $code), stderr: $(head -c 400 <<<"$err") (want /$pat/)"; fi
}

# Prints the count of checks passed and failed; false when one failed.
tally() {
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}

# expect_compare WANT ARGS...: `dmbench compare ARGS` exits with one of the
# codes in WANT ("0", or "0 1 3"), its output in $OUT/stdout and
# $OUT/stderr; otherwise both are printed and the script exits 1.
expect_compare() {
  local want=$1 rc=0; shift
  "$BIN" compare "$@" >"$OUT/stdout" 2>"$OUT/stderr" || rc=$?
  case " $want " in *" $rc "*) ;; *)
    echo "compare $* -> exit $rc, expected $want"; cat "$OUT/stdout" "$OUT/stderr"; exit 1;; esac
}
