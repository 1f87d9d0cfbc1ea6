#!/bin/sh
# bench/report_identical.sh — are the reports and exports of stored runs
# byte-identical to a baseline?  The check of issue 44's "move before you
# change": store a baseline once with the binary before a change, then after
# every step rebuild the same files from the same stored run and compare.
#
#   bench/report_identical.sh save  DMBENCH ROOT BASE   ROOT: an output root of `dmbench run --out ROOT`
#   bench/report_identical.sh check DMBENCH BASE        0 when identical, 1 with the diff otherwise
#
# save copies ROOT (its dmbench.sqlite and run directories) to BASE and
# writes there, from the stored run `latest` points to, the four report files
# (`dmbench report`) and every `dmbench export` format under exports/.
# check copies BASE again, deletes those files, rebuilds them with DMBENCH
# and runs `diff -r` against BASE.  Nothing in ROOT or BASE is changed by a
# check.
set -eu

FILES="report.html summary.md results.json results.csv front.tex"
FORMATS="gbench bmf gab-smaller gab-bigger"

usage() {
    echo "usage: $0 save DMBENCH ROOT BASE | check DMBENCH BASE" >&2
    exit 2
}

# Rebuilds the report files and exports of the run root/latest with $1.
rebuild() {
    run=$(cd "$2/latest" && pwd -P)
    for f in $FILES; do rm -f "$run/$f"; done
    rm -rf "$run/exports"
    "$1" report "$run" >/dev/null
    mkdir -p "$run/exports"
    for fmt in $FORMATS; do
        # export says on stderr what it wrote (the path differs per copy)
        if ! "$1" export "$run" --format "$fmt" -o "$run/exports/$fmt.json" >/dev/null 2>"$run/exports.log"; then
            cat "$run/exports.log" >&2
            exit 1
        fi
        rm -f "$run/exports.log"
    done
}

[ $# -ge 1 ] || usage
case "$1" in
save)
    [ $# -eq 4 ] || usage
    [ -e "$4" ] && { echo "$0: $4 exists; pick a new baseline directory" >&2; exit 2; }
    cp -a "$3" "$4"
    rebuild "$2" "$4"
    echo "baseline stored in $4"
    ;;
check)
    [ $# -eq 3 ] || usage
    [ -d "$3" ] || { echo "$0: $3: no baseline (run save first)" >&2; exit 2; }
    work=$(mktemp -d "${TMPDIR:-/tmp}/report_identical.XXXXXX")
    cp -a "$3" "$work/root"
    rebuild "$2" "$work/root"
    if diff -r "$3" "$work/root"; then
        echo "identical: $3"
        rm -rf "$work"
    else
        echo "differs: $3 (rebuilt copy kept in $work/root)" >&2
        exit 1
    fi
    ;;
*) usage ;;
esac
