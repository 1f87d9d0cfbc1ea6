#!/usr/bin/env bash
# `cmake --install` puts the binary, the man page and the completions in
# place; the installed man page renders without a single groff warning and
# shows every command; the installed binary runs.
set -uo pipefail
BUILD=${1:?build directory}
PREFIX=$(mktemp -d); trap 'rm -rf "$PREFIX"' EXIT
pass=0; fail=0
ok() { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*"; }

cmake --install "$BUILD" --prefix "$PREFIX" >/dev/null || bad "cmake --install failed"
for f in bin/dmbench share/man/man1/dmbench.1 share/bash-completion/completions/dmbench \
         share/zsh/site-functions/_dmbench; do
  [ -s "$PREFIX/$f" ] && ok || bad "$f not installed"
done
"$PREFIX/bin/dmbench" --version | grep -q '^dmbench ' && ok || bad "installed binary does not run"
warn=$(groff -man -Tutf8 -ww -z "$PREFIX/share/man/man1/dmbench.1" 2>&1)
[ -z "$warn" ] && ok || bad "groff warnings: $warn"
page=$(MANWIDTH=100 man -l "$PREFIX/share/man/man1/dmbench.1" 2>&1)
grep -q "warning" <<<"$page" && bad "man warnings: $(grep warning <<<"$page")" || ok
for cmd in $("$PREFIX/bin/dmbench" help | sed -n '/^commands:/,/^$/p' | awk 'NF>1 && $1!="commands:" {print $1}'); do
  grep -q "^   dmbench $cmd\$" <<<"$page" && ok || bad "man page lacks a section for $cmd"
done
grep -qE '^ +4 +environment failure' <<<"$page" && ok || bad "man page lacks exit code 4"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
