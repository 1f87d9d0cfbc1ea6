#!/usr/bin/env python3
"""longest_functions.py — the ten longest functions of dmbench's C/C++
sources and the source files over 800 lines (issue 44's measure: no file over
800 lines unless it is one table or one concern, none over 1 000).

Usage: bench/longest_functions.py [--top N] [--over LINES] [--tests] [REPO]

  REPO      the repository root (default: this file's parent's parent)
  --top     how many functions to list (default 10)
  --over    the file length to report above (default 800)
  --tests   count tests/ too (default: the rooms only, since a test's body is
            a list of cases, not a design)

Sources are the git-tracked *.c, *.cc, *.cpp, *.h, *.hh files.  A function's
length is its definition's lines from the line with its name to its closing
brace, inclusive, as Universal Ctags reports them (`end:` field); a file's
length is its line count.  Prints two Markdown tables.

Exit status: 0 printed, 2 ctags (Universal Ctags, with the end: field) or
git is missing, or REPO is not a repository.
"""
import os
import subprocess
import sys

EXTS = (".c", ".cc", ".cpp", ".h", ".hh")


def longest_functions__usage(msg):
    sys.stderr.write(f"longest_functions.py: {msg}\n"
                     "usage: bench/longest_functions.py [--top N] [--over LINES] [--tests] [REPO]\n")
    sys.exit(2)


def longest_functions__args(argv):
    top, over, tests, root = 10, 800, False, None
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ("--top", "--over"):
            if i + 1 >= len(argv) or not argv[i + 1].isdigit():
                longest_functions__usage(f"{a} needs a whole number")
            if a == "--top":
                top = int(argv[i + 1])
            else:
                over = int(argv[i + 1])
            i += 2
            continue
        if a == "--tests":
            tests = True
        elif a.startswith("-"):
            longest_functions__usage(f"unknown option '{a}' (valid: --top, --over, --tests)")
        elif root is None:
            root = a
        else:
            longest_functions__usage(f"one REPO only, got '{root}' and '{a}'")
        i += 1
    if root is None:
        root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return top, over, tests, root


def longest_functions__sources(root, tests):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files"], check=True,
                             capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        longest_functions__usage(f"cannot list the files of '{root}' with git: {e}")
    files = [f for f in out.splitlines() if f.endswith(EXTS)]
    if not tests:
        files = [f for f in files if not f.startswith("tests/")]
    return files


def longest_functions__functions(root, files):
    """(lines, name, file) of every function definition in files."""
    cmd = ["ctags", "-o", "-", "--sort=no", "--fields=+ne", "--kinds-C=f",
           "--kinds-C++=f"]
    try:
        out = subprocess.run(cmd + files, check=True, capture_output=True,
                             text=True, cwd=root).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        longest_functions__usage(f"Universal Ctags failed: {e}")
    rows = []
    for line in out.splitlines():
        parts = line.split("\t")
        if len(parts) < 4:
            continue
        fields = dict(p.split(":", 1) for p in parts[3:] if ":" in p)
        if "line" not in fields or "end" not in fields:
            continue
        n = int(fields["end"]) - int(fields["line"]) + 1
        rows.append((n, parts[0], parts[1], int(fields["line"])))
    if files and not rows:
        longest_functions__usage("ctags reported no function with an end: field "
                                 "(Universal Ctags 5.9 or later is needed)")
    return rows


def longest_functions__file_lines(root, files):
    rows = []
    for f in files:
        with open(os.path.join(root, f), "rb") as fh:
            rows.append((fh.read().count(b"\n"), f))
    return rows


def main(argv):
    top, over, tests, root = longest_functions__args(argv)
    files = longest_functions__sources(root, tests)
    funcs = longest_functions__functions(root, files)
    funcs.sort(key=lambda r: (-r[0], r[2], r[3]))
    print(f"Ten longest functions ({len(funcs)} functions in {len(files)} files"
          f"{'' if tests else ', tests/ left out'}):\n")
    print("| lines | function | file:line |")
    print("| ---: | --- | --- |")
    for n, name, f, line in funcs[:top]:
        print(f"| {n} | `{name}` | {f}:{line} |")
    big = sorted((r for r in longest_functions__file_lines(root, files) if r[0] > over),
                 key=lambda r: (-r[0], r[1]))
    print(f"\nFiles over {over} lines ({len(big)}):\n")
    print("| lines | file |")
    print("| ---: | --- |")
    for n, f in big:
        print(f"| {n} | {f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
