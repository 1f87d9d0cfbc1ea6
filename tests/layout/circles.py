#!/usr/bin/env python3
"""tests/layout/circles.py — the layout check: rooms, their includes, circles.

    python3 tests/layout/circles.py SOURCE_DIR BUILD_DIR

A room is a top-level folder whose CMakeLists.txt builds a library or an
executable (core/, cli/, run/, ...; tests/ and bench/ are not rooms).  Two
checks, both from what the build says rather than from a list kept here:

1. Includes.  Every `#include "room/x.h"` (or `"x.h"` of the same folder) of
   a file must name a room its CMake target declares with
   target_link_libraries, directly.  A header belongs to the target of the
   source of the same stem (run/measure.h -> dm_run); a header without one
   is shared by the room's targets.  Within a room, a file may include a
   header of another target of the room only if its target links that one
   (run/protocol.c, of dm_protocol, may not include run/runner.h, of dm_run).
   One exception, listed apart: a header read for its macros and inline
   functions only (run/calibrate.h's calibrate_key in gate/, the metric
   names of reports/metric.h in sweep/) -- the includer's object uses no
   name the header's target defines, so nothing is linked.

2. Circles of files inside a room.  File A depends on file B of the same
   room when A's object file uses a name with external linkage that B's
   object file defines (`nm`: an undefined symbol of A that is a T/D/B/R/...
   symbol of B).  The objects are the ones CMake lists for each target in
   BUILD_DIR/ROOM/CMakeFiles/TARGET.dir/DependInfo.cmake, so a stale object
   of a removed file does not count.  A circle is a strongly connected
   component of more than one file.  A circle is a sign of a missing model:
   two files that call each other compute something that deserves a file of
   its own.

3. Header guards.  Every header of a room guards with ROOM_FILE_H (run/measure.h:
   RUN_MEASURE_H, core/dm_util.h: CORE_DM_UTIL_H), so no name from before a
   folder was split or renamed is left behind.

A circle fails the check unless it lies wholly inside one entry of ALLOWED
below: the circles known when the check was written, each to be removed as
its room is cut along its seams.  An entry that no longer covers any circle
fails too ("remove it"), so the list can only shrink.

Prints the layout summary (rooms, files, lines, files over 800 lines,
circles with the names that close them) and exits 0 when the checks pass,
1 when one fails, 2 on a usage or build-tree error.
"""
import os
import re
import subprocess
import sys

# Circles known when the check was written (issue 44), each (room, files or
# None for "any circle inside the room", why it is left); a current circle
# is allowed if all its files are in one entry.  Empty: every room is free
# of circles, and a new one fails.
ALLOWED = []

NOT_ROOMS = {"tests", "bench", "build", "cmake", "scripts", "docs", "ci", "examples"}
LONG_FILE = 800
DEFINED = set("TDBRGSVWCiu")  # uppercase/global kinds of nm -P; lowercase locals are skipped below


def cmake_calls(text, command):
    """Yields the argument lists of every `command(...)` call of a CMake file."""
    text = re.sub(r"#[^\n]*", "", text)
    for m in re.finditer(r"\b%s\s*\(" % command, text):
        depth, i = 1, m.end()
        while depth and i < len(text):
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            i += 1
        yield text[m.end():i - 1].split()


def read_rooms(src):
    """Returns (targets: name -> room, deps: name -> set of direct target deps)."""
    targets, deps = {}, {}
    for room in sorted(os.listdir(src)):
        cml = os.path.join(src, room, "CMakeLists.txt")
        if room in NOT_ROOMS or room.startswith(".") or not os.path.isfile(cml):
            continue
        text = open(cml).read()
        for cmd in ("add_library", "add_executable"):
            for args in cmake_calls(text, cmd):
                targets[args[0]] = room
                deps.setdefault(args[0], set())
        for args in cmake_calls(text, "target_link_libraries"):
            deps.setdefault(args[0], set()).update(
                a for a in args[1:] if a not in ("PUBLIC", "PRIVATE", "INTERFACE"))
    for t in deps:
        deps[t] = {d for d in deps[t] if d in targets}
    return targets, deps


def read_sources(build, targets):
    """Returns {target: {source path relative to the room: object path}}."""
    out = {}
    for t, room in targets.items():
        info = os.path.join(build, room, "CMakeFiles", t + ".dir", "DependInfo.cmake")
        if not os.path.isfile(info):
            sys.exit("circles.py: %s is missing: build the tree first" % info)
        out[t] = {}
        for src_path, obj in re.findall(r'"([^"]+)"\s+"([^"]+\.o)"', open(info).read()):
            out[t][src_path] = os.path.join(build, obj)
    return out


def nm_symbols(objs):
    """Returns {object: (defined, undefined)}: the external names of each
    object file, from one `nm -P -A` over all of them."""
    res = subprocess.run(["nm", "-P", "-A"] + objs, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit("circles.py: nm: %s" % res.stderr.strip())
    out = {o: (set(), set()) for o in objs}
    for line in res.stdout.splitlines():
        where, _, rest = line.partition(": ")
        f = rest.split()
        if len(f) < 2 or where not in out:
            continue
        if f[1] == "U":
            out[where][1].add(f[0])
        elif f[1] in DEFINED and f[1].isupper():
            out[where][0].add(f[0])
    return out


def sccs(nodes, edges):
    """Tarjan's strongly connected components of a small graph, as sorted lists."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            out.append(sorted(comp))

    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return out


INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def check_includes(src, targets, deps, sources, symbols):
    """Returns (problems, header_only): include problems and includes of
    undeclared headers used only for their macros and inlines, one string
    each.  symbols: {"room/file.c": (defined, undefined)} of every object."""
    rooms = set(targets.values())
    owner = {}  # "room/stem" -> target, for sources and their headers
    for t, files in sources.items():
        for path in files:
            rel = os.path.relpath(path, src)
            owner[os.path.splitext(rel)[0]] = t
    room_targets = {}
    for t, r in targets.items():
        room_targets.setdefault(r, set()).add(t)
    target_defs = {}
    for rel, (defined, _) in symbols.items():
        target_defs.setdefault(owner[os.path.splitext(rel)[0]], set()).update(defined)
    problems, header_only = [], []

    def undeclared(rel, inc, it, text):
        used = symbols.get(rel, (set(), None))[1]
        if used is not None and it and not (used & target_defs.get(it, set())):
            header_only.append("%s includes %s (%s) for its macros and inlines only" % (rel, inc, it))
        else:
            problems.append(text)

    for room in sorted(rooms):
        for name in sorted(os.listdir(os.path.join(src, room))):
            if not name.endswith((".c", ".cc", ".h", ".hh")):
                continue
            rel = room + "/" + name
            t = owner.get(os.path.splitext(rel)[0])
            mine = {t} if t else room_targets[room]
            allowed_t = set(mine)
            for m in mine:
                allowed_t |= deps.get(m, set())
            allowed_rooms = {targets[a] for a in allowed_t} | {room}
            for inc in INCLUDE.findall(open(os.path.join(src, rel), errors="replace").read()):
                if os.path.isfile(os.path.join(src, room, inc)):
                    inc = room + "/" + inc
                top = inc.split("/")[0]
                if "/" not in inc or not os.path.isdir(os.path.join(src, top)):
                    continue
                if top not in rooms:
                    problems.append("%s includes %s: %s/ is not a room" % (rel, inc, top))
                    continue
                it = owner.get(os.path.splitext(inc)[0])
                if top not in allowed_rooms:
                    undeclared(rel, inc, it, "%s includes %s, but %s does not link a target of %s/"
                               % (rel, inc, "/".join(sorted(mine)), top))
                elif it and it not in allowed_t:
                    undeclared(rel, inc, it, "%s (%s) includes %s, of %s, which it does not link"
                               % (rel, "/".join(sorted(mine)), inc, it))
    return problems, header_only


def read_symbols(src, sources):
    """Returns {"room/file.c": (defined, undefined)} of every object of the rooms."""
    rels = {}
    for t, files in sources.items():
        for path, obj in files.items():
            rel = os.path.relpath(path, src)
            if rel.startswith("..") or "/" not in rel:
                continue  # generated sources (embedded GLSL) are data, not rooms
            rels[obj] = rel
    missing = [o for o in rels if not os.path.isfile(o)]
    if missing:
        sys.exit("circles.py: %s is missing: build the tree first" % missing[0])
    return {rels[o]: syms for o, syms in nm_symbols(sorted(rels)).items()}


def room_circles(symbols):
    """Returns {room: [(files, [(a, b, symbol)])]} of the circles of each room."""
    by_room = {}
    for rel, syms in symbols.items():
        room, name = rel.split("/", 1)
        by_room.setdefault(room, {})[name] = syms
    out = {}
    for room, files in sorted(by_room.items()):
        definer = {}
        for f, (defined, _) in files.items():
            for s in defined:
                definer.setdefault(s, f)
        edges, why = {}, {}
        for f, (_, undefined) in files.items():
            for s in sorted(undefined):
                g = definer.get(s)
                if g and g != f:
                    edges.setdefault(f, set()).add(g)
                    why.setdefault((f, g), s)
        comps = [c for c in sccs(files, edges) if len(c) > 1]
        out[room] = [(c, sorted((a, b, why[(a, b)]) for a in c for b in c if (a, b) in why))
                     for c in comps]
    return out


GUARD = re.compile(r"^#ifndef\s+(\w+)\s*\n#define\s+\1\b", re.M)


def check_guards(src, rooms):
    """Returns the headers whose include guard is not ROOM_FILE_H, one string each."""
    problems = []
    for room in rooms:
        for name in sorted(os.listdir(os.path.join(src, room))):
            if not name.endswith((".h", ".hh")):
                continue
            want = (room + "_" + name).upper().replace(".", "_")
            m = GUARD.search(open(os.path.join(src, room, name), errors="replace").read())
            if not m or m.group(1) != want:
                problems.append("%s/%s guards with %s, not %s"
                                % (room, name, m.group(1) if m else "nothing", want))
    return problems


def allowed_entry(room, files):
    for i, (r, allowed, _) in enumerate(ALLOWED):
        if r == room and (allowed is None or set(files) <= allowed):
            return i
    return None


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    src, build = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    targets, deps = read_rooms(src)
    sources = read_sources(build, targets)
    symbols = read_symbols(src, sources)
    circles = room_circles(symbols)
    include_problems, header_only = check_includes(src, targets, deps, sources, symbols)

    rooms = sorted(set(targets.values()))
    long_files, total_files, total_lines = [], 0, 0
    print("rooms (%d):" % len(rooms))
    for room in rooms:
        names = [n for n in os.listdir(os.path.join(src, room)) if n.endswith((".c", ".cc", ".h", ".hh"))]
        lines = 0
        for n in names:
            k = sum(1 for _ in open(os.path.join(src, room, n), errors="replace"))
            lines += k
            if k > LONG_FILE:
                long_files.append((k, room + "/" + n))
        total_files += len(names)
        total_lines += lines
        may = sorted({targets[d] for t, r in targets.items() if r == room for d in deps[t]} - {room})
        print("  %-11s %3d files %6d lines  may include: %s"
              % (room + "/", len(names), lines, " ".join(m + "/" for m in may) or "-"))
    print("  %d files, %d lines" % (total_files, total_lines))

    print("files over %d lines (%d):" % (LONG_FILE, len(long_files)))
    for k, f in sorted(long_files, reverse=True):
        print("  %5d  %s" % (k, f))

    failed = False
    used = set()
    n = sum(len(c) for c in circles.values())
    print("circles of files inside a room (%d):" % n)
    for room, comps in circles.items():
        for files, edges in comps:
            entry = allowed_entry(room, files)
            mark = "allowed" if entry is not None else "NEW"
            if entry is None:
                failed = True
            else:
                used.add(entry)
            print("  %s/ (%d files, %s): %s" % (room, len(files), mark, " ".join(files)))
            for a, b, s in edges:
                print("      %s -> %s (%s)" % (a, b, s))
    for i, (room, files, why) in enumerate(ALLOWED):
        if i not in used:
            failed = True
            print("FAIL: the allowed circle %s/%s is gone: remove it from ALLOWED in %s"
                  % (room, "{" + ",".join(sorted(files)) + "}" if files else "*", argv[0]))
    left = [ALLOWED[i] for i in sorted(used)]
    if left:
        print("allowed circles left (%d), to be removed:" % len(left))
        for room, files, why in left:
            print("  %s/%s: %s" % (room, "{" + ",".join(sorted(files)) + "}" if files else "*", why))

    print("includes of undeclared rooms for macros and inlines only (%d):" % len(header_only))
    for h in header_only:
        print("  " + h)
    print("includes outside the declared dependencies (%d):" % len(include_problems))
    for p in include_problems:
        print("  FAIL: " + p)
    failed = failed or bool(include_problems)
    guard_problems = check_guards(src, rooms)
    print("headers without their room's include guard (%d):" % len(guard_problems))
    for p in guard_problems:
        print("  FAIL: " + p)
    failed = failed or bool(guard_problems)
    print("layout check: %s" % ("FAILED" if failed else "passed"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
