#!/usr/bin/env python3
"""study_claims.py — recompute the conclusions docs/reproductions.md draws in
prose from the tables beside them, so prose and tables cannot drift apart.

Usage: bench/study_claims.py [REPO]     (REPO: the repository root; default:
       this file's parent's parent)
       bench/study_claims.py --self-test [REPO]   (each drift in DRIFTS, applied
       to a copy of the pages, must be caught)

What it checks (every check prints one line; a failure names the section,
the figure the tables give and the text it expected):

  1. every ratio column ("time ratio", "instructions ratio") against the
     value column beside it (WallTime, instructions / frame) divided by the
     row's baseline, the nearest row above it whose verdict is "baseline";
  2. every verdict against the ±5 % / ×2 rule (docs/reproductions.md, "How
     to read the tables") applied to the row's published and measured
     ratios, the factor in "(×k)" included;
  3. every published ratio against the `published:` block of the sweep the
     section names for the table (a frame rate inverted), to the row's own
     baseline row;
  4. the prose figures listed in CLAIMS below, each generated from the
     tables (or the tessellation ring rule) and required, as written, in
     the section's prose.

  5. docs/displacement.md (S3's and S4's tables on llvmpipe: level 1
     against normal mapping, S3's own range from the s3-table7-1 sweep, the
     exact evaluation counts by the ring rule, the cylinder against the
     sphere per vertex, the distance LOD's cuts, S4's 1.25× and 1.7 % from
     the s4 sweeps), docs/textures.md (S1's ranking of bc1 > bc3nm > bc5 in
     error, every "×" of the virtual texture's cost table) and
     docs/studies.md (which draws no conclusion from a table: a ratio or a
     direction in its prose fails until a check is added here).

Exit status: 0 all hold, 1 a figure disagrees, 2 the document could not be
read (a table or a section the checks need is missing).
"""
import math
import os
import re
import sys

ARGS = [a for a in sys.argv[1:] if a != "--self-test"]
ROOT = ARGS[0] if ARGS else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "docs", "reproductions.md")

failures = []
checked = [0]


class ParseError(Exception):
    pass


def ok(cond, where, msg):
    checked[0] += 1
    if not cond:
        failures.append(f"{where}: {msg}")


# ---- reading the document ------------------------------------------------

def row_name(r):
    """A row's configuration without its marks (†, ‡: re-timed or to be)."""
    return r[0].replace("†", "").replace("‡", "").strip()


def number(cell):
    """The number in a table cell: '2 673.05 ms' -> 2673.05, '57 981' -> 57981;
    None when the cell holds no number."""
    t = cell.replace("\u202f", "").replace("\u00a0", "").replace("†", "").replace("‡", "")
    m = re.search(r"-?\d[\d ]*(?:\.\d+)?", t)
    if not m:
        return None
    return float(m.group(0).replace(" ", ""))


def decimals(cell):
    m = re.search(r"\d\.(\d+)", cell)
    return len(m.group(1)) if m else 0


def split_row(line):
    cells = line.strip().strip("|").split("|")
    return [c.strip() for c in cells]


def sections(text):
    """[(heading, body)] of the level-2 sections."""
    parts = re.split(r"^## ", text, flags=re.M)
    out = []
    for p in parts[1:]:
        head, _, body = p.partition("\n")
        out.append((head.strip(), body))
    return out


def tables(body):
    """[(header, rows, prose_before)] of a section: rows as lists of cells."""
    out, lines, i = [], body.split("\n"), 0
    prose = []
    while i < len(lines):
        if lines[i].startswith("|") and i + 1 < len(lines) and re.match(r"^\|[-:| ]+\|$", lines[i + 1].strip()):
            header = split_row(lines[i])
            rows = []
            i += 2
            while i < len(lines) and lines[i].startswith("|"):
                rows.append(split_row(lines[i]))
                i += 1
            out.append((header, rows, "\n".join(prose)))
            continue
        prose.append(lines[i])
        i += 1
    return out


def prose_of(body):
    """The section's text outside its tables, whitespace collapsed."""
    keep = [l for l in body.split("\n") if not l.startswith("|")]
    return re.sub(r"\s+", " ", " ".join(keep))


def col(header, *prefixes):
    for j, h in enumerate(header):
        for p in prefixes:
            if h.lower().startswith(p.lower()):
                return j
    return None


# ---- the rule -------------------------------------------------------------

def side(x):
    return 1 if x > 1.05 else (-1 if x < 0.95 else 0)


def verdict(published, measured):
    """('agrees' | 'size differs' | 'direction differs', factor)."""
    if side(published) != side(measured):
        return "direction differs", None
    k = max(published, measured) / min(published, measured)
    return ("agrees" if k <= 2.0 else "size differs"), k


# ---- generic checks -------------------------------------------------------

def check_ratios(where, header, rows):
    vcol = col(header, "verdict")
    for rcol, valcol in ((col(header, "time ratio"), col(header, "WallTime")),
                         (col(header, "instructions ratio"), col(header, "instructions / frame"))):
        if rcol is None or valcol is None or vcol is None:
            continue
        base = None
        for r in rows:
            if r[vcol].startswith("baseline"):
                base = number(r[valcol])
            v, printed = number(r[valcol]), number(r[rcol])
            if base is None or v is None or printed is None:
                continue
            want = v / base
            # the printed values are rounded: their half-unit bounds the ratio
            slack = 0.5 * 10 ** -decimals(r[rcol]) + want * 0.5 * 10 ** -decimals(r[valcol]) * (1 / v + 1 / base)
            ok(abs(printed - want) <= slack + 1e-9, where,
               f"row '{r[0]}': {header[rcol]} printed {r[rcol]}, {header[valcol]} gives {want:.4f}")


def check_verdicts(where, header, rows):
    pcol, vcol = col(header, "published ratio"), col(header, "verdict")
    mcol = col(header, "time ratio", "instructions ratio")
    if pcol is None or vcol is None or mcol is None:
        return
    for r in rows:
        text = r[vcol]
        if text.startswith(("baseline", "to measure")) or number(r[mcol]) is None:
            continue
        p, m = number(r[pcol]), number(r[mcol])
        label, k = verdict(p, m)
        ok(text.startswith(label), where, f"row '{r[0]}': verdict '{text}', the rule gives '{label}' "
           f"(published {p}, measured {m})")
        fm = re.search(r"×(\d+(?:\.\d+)?)", text)
        if fm and k is not None:
            d = decimals(fm.group(1))
            # the printed ratios are rounded to 3 decimals: allow that too
            slack = 0.5 * 10 ** -d + k * 2e-3
            ok(abs(float(fm.group(1)) - k) <= slack, where,
               f"row '{r[0]}': factor ×{fm.group(1)}, the ratios give ×{k:.3f}")


def sweep_published(name):
    """{configuration: value}, unit, or None: the sweep's `published:` block
    (read line by line; the block's values are one 'key: number' a line)."""
    path = os.path.join(ROOT, "sweeps", name + ".yaml")
    if not os.path.exists(path):
        return None
    vals, unit, inside = {}, None, False
    for line in open(path, encoding="utf-8"):
        if line.startswith("published:"):
            inside = True
            continue
        if inside and re.match(r"^\S", line):
            break
        if not inside:
            continue
        m = re.match(r"^\s+unit:\s*(\S+)", line)
        if m:
            unit = m.group(1)
        m = re.match(r"^\s{4}(.+?):\s*([0-9.]+)\s*$", line)
        if m:
            vals[m.group(1).strip()] = float(m.group(2))
    return (vals, unit) if vals else None


def check_published(where, header, rows, prose):
    pcol, vcol = col(header, "published ratio"), col(header, "verdict")
    names = re.findall(r"`(?:sweeps/)?(s[1-4]-[a-z0-9-]+?)(?:\.yaml)?`", prose)
    if pcol is None or vcol is None or not names:
        return
    pub = sweep_published(names[-1])
    if not pub:
        return
    vals, unit = pub
    base = None
    for r in rows:
        cfg = row_name(r)
        if r[vcol].startswith("baseline"):
            base = cfg
        if base not in vals or cfg not in vals:
            continue
        want = vals[base] / vals[cfg] if unit == "fps" else vals[cfg] / vals[base]
        ok(abs(number(r[pcol]) - want) <= 0.5 * 10 ** -decimals(r[pcol]) + 1e-9, where,
           f"row '{cfg}': published ratio {r[pcol]}, sweep {names[-1]} gives {want:.4f} "
           f"against '{base}'")


# ---- prose claims ---------------------------------------------------------

def fmt(x, d):
    return f"{x:.{d}f}"


def rng(xs, d, sep="–"):
    return f"{fmt(min(xs), d)}{sep}{fmt(max(xs), d)}"


def thousands(n):
    """57981 -> '57 981' (the docs' digit grouping)."""
    s = str(int(round(n)))
    out = ""
    while len(s) > 3:
        out = " " + s[-3:] + out
        s = s[:-3]
    return s + out


def ring(level):
    """Vertices of one triangle patch with every level = L, equal spacing
    (docs/displacement.md, the ring rule); an odd L > 1 does not occur."""
    if level == 1:
        return 3
    assert level % 2 == 0
    return 3 * level * level // 4 + 3 * level // 2 + 1


def rows_of(tabs, *want_cols):
    """The first table whose header has every column prefix in want_cols."""
    for header, rows, _ in tabs:
        if all(col(header, w) is not None for w in want_cols):
            return header, rows
    raise ParseError(f"no table with columns {want_cols}")


def nth_table(tabs, n, *want_cols):
    found = [(h, r) for h, r, _ in tabs if all(col(h, w) is not None for w in want_cols)]
    if len(found) <= n:
        raise ParseError(f"no table #{n + 1} with columns {want_cols}")
    return found[n]


def cell(header, rows, config, column):
    for r in rows:
        if row_name(r) == config:
            return number(r[col(header, column)])
    raise ParseError(f"no row '{config}'")


def level_rows(header, rows, level):
    pc, mc = col(header, "published ratio"), col(header, "time ratio")
    out = []
    for r in rows:
        if f"tess_level={level}" in r[0].split():
            out.append((r[0], number(r[pc]), number(r[mc])))
    return out


def claims_s1(tabs):
    h2, t2 = nth_table(tabs, 0, "instructions ratio")
    yield "1 : " + " : ".join(r[col(h2, "instructions ratio")] for r in t2[1:])
    yield "1 : " + " : ".join(r[col(h2, "published ratio")] for r in t2[1:])
    h3, t3 = nth_table(tabs, 1, "instructions ratio")
    near = cell(h3, t3, "vertex_filter=nearest", "instructions / frame")
    hw = cell(h3, t3, "vertex_filter=bilinear-hw", "instructions / frame") / near
    man = cell(h3, t3, "vertex_filter=bilinear-manual", "instructions / frame") / near
    ok(abs(hw - 1) <= 0.001, "S1", f"bilinear-hw within 0.1 % claimed, table {hw:.5f}")
    yield f"+{fmt((man - 1) * 100, 1)} % for four fetches"
    h4, t4 = nth_table(tabs, 2, "instructions ratio")
    r4 = [number(r[col(h4, "instructions ratio")]) for r in t4[1:]]
    yield f"costs {fmt((min(r4) - 1) * 100, 0)}–{fmt((max(r4) - 1) * 100, 0)} % more instructions"
    h5, t5 = nth_table(tabs, 3, "instructions ratio")
    vs = col(h5, "VS + TES")
    off = number(t5[0][vs])
    on = number(t5[1][vs])
    yield f"skips {fmt((1 - on / off) * 100, 1)} % of the vertex invocations ({thousands(off)} → {thousands(on)})"
    ins = col(h5, "instructions / frame")
    saves = [1 - number(t5[i + 1][ins]) / number(t5[i][ins]) for i in (0, 2, 4)]
    yield f"lowers the frame's instructions by {fmt(min(saves) * 100, 2)}–{fmt(max(saves) * 100, 2)} %"
    faster = [1 - number(r[col(h5, 'published ratio')]) for r in t5[1:]
              if side(number(r[col(h5, 'published ratio')])) == -1]
    yield f"{fmt(min(faster) * 100, 0)}–{fmt(max(faster) * 100, 0)} % faster do not"
    # the times table: one table, a 'table' column
    ht, tt = rows_of(tabs, "table", "WallTime")
    wt, tc, cc = col(ht, "WallTime"), col(ht, "table"), col(ht, "configuration")
    by = {(r[tc], r[cc]): number(r[wt]) for r in tt}
    yield f"saves {fmt((1 - by[('5', 'bilinear-manual, visibility test on')] / by[('5', 'bilinear-manual, visibility test off')]) * 100, 1)} % of the time with the manual filter"
    yield (f"(mip +{fmt((by[('5', 'mip, on')] / by[('5', 'mip, off')] - 1) * 100, 1)} %, "
           f"mip-lerp +{fmt((by[('5', 'mip-lerp, on')] / by[('5', 'mip-lerp, off')] - 1) * 100, 1)} %)")
    t4t = [number(r[col(ht, "time ratio")]) for r in tt if r[tc] == "4" and "nearest" not in r[cc]]
    yield f"{fmt((t4t[0] - 1) * 100, 1)} % and {fmt((t4t[1] - 1) * 100, 1)} % slower in time"
    # row for row: the time verdicts equal the instruction verdicts
    inst = {}
    for (h, t) in ((h2, t2), (h3, t3), (h4, t4), (h5, t5)):
        for r in t:
            inst[r[0]] = r[col(h, "verdict")].split(" (")[0]
    short = {"bilinear-manual, visibility test off": "vertex_filter=bilinear-manual visibility_test=off",
             "bilinear-manual, visibility test on": "vertex_filter=bilinear-manual visibility_test=on"}
    for r in tt:
        name = short.get(r[cc], r[cc])
        m = re.match(r"(mip|mip-lerp), (on|off)$", name)
        if m:
            name = f"vertex_filter={m.group(1)} visibility_test={m.group(2)}"
        if name in inst:
            ok(inst[name] == r[col(ht, "verdict")].split(" (")[0], "S1",
               f"'row for row': {name} is '{inst[name]}' by instructions, '{r[col(ht, 'verdict')]}' by time")
    # Fig. 28: instructions per added vertex between S1's densities
    hf, tf = [(h, r) for h, r, _ in tabs if col(h, "published ratio") is None and col(h, "VS + TES") is not None][0]
    pts = sorted((number(r[col(hf, "VS + TES")]), number(r[col(hf, "instructions / frame")])) for r in tf)
    slope = lambda i, j: (pts[j][1] - pts[i][1]) / (pts[j][0] - pts[i][0])
    yield (f"about {thousands(round(slope(0, 2), -2))} instructions per added vertex up to the "
           f"31 000-vertex grid and {thousands(round(slope(2, 3), -2))} beyond it")
    yield f"does {fmt(pts[-1][1] / pts[0][1], 1)}× the 5 000-vertex grid's work"


def claims_s2(tabs):
    h, t = rows_of(tabs, "WallTime", "time ratio")
    steep = cell(h, t, "steep-parallax", "WallTime")
    pom = cell(h, t, "pom shadow=none", "WallTime")
    ok(abs(pom / steep - 1) < 0.02, "S2", f"steep and POM 'within 2 %': {pom / steep:.4f}")
    last = t[-1]
    k = verdict(number(last[col(h, "published ratio")]), number(last[col(h, "time ratio")]))[1]
    yield f"(×{fmt(k, 1)} off)"


def claims_s3(tabs):
    h, t = nth_table(tabs, 0, "WallTime", "time ratio")
    l1 = level_rows(h, t, 1)
    yield f"here it costs {rng([m for _, _, m in l1], 3)}× normal mapping"
    yield f"on every mesh ({rng([p for _, p, _ in l1], 3)})"
    hi = level_rows(h, t, 32) + level_rows(h, t, 64)
    yield f"llvmpipe climbs {rng([m / p for _, p, m in hi], 2)}× further than the GTX 660 Ti"
    agree = [c for c, p, m in hi if verdict(p, m)[0] == "agrees"]
    ok(agree == ["tess-displacement mesh=cube tess_level=32"], "S3",
       f"'Only the cube's level 32 agrees in size': the table's agreeing rows at 32/64 are {agree}")
    cube1 = cell(h, t, "tess-displacement mesh=cube tess_level=1", "time ratio")
    yield f"llvmpipe: {fmt(cube1, 3)})"
    yield f"level 1 costs {rng([m for _, _, m in l1], 3)}× normal mapping on the same mesh"
    hs, ts = nth_table(tabs, 1, "WallTime", "time ratio")
    his = level_rows(hs, ts, 32) + level_rows(hs, ts, 64)
    yield f"as on llvmpipe, {rng([m / p for _, p, m in his], 2)}× further"
    nm = cell(hs, ts, "normal mesh=cube", "WallTime")
    l1s = cell(hs, ts, "tess-displacement mesh=cube tess_level=1", "WallTime")
    yield f"normal mapping 30.8 → {fmt(nm, 1)} ms on the cube; level 1 50.3 → {fmt(l1s, 1)} ms"
    yield f"1.63× its normal mapping with plain textures (50.3 / 30.8 ms"
    ok(abs(50.3 / 30.8 - 1.63) < 0.005, "S3", f"zink plain level 1 / normal = {50.3 / 30.8:.4f}")
    # the counts: the ring rule, S3's setting and the long-edge factor's
    patches = {"cube": 12, "cylinder": 1508, "sphere": 5120}
    for mesh, n in patches.items():
        yield f"{thousands(n)} evaluate " if mesh != "cube" else "12 patches evaluate "
        yield " / ".join(thousands(n * ring(L)) for L in (1, 32, 64))
    hc, tc = rows_of(tabs, "cylinder row")
    caps, sides = 116, 1508 - 116
    for r in tc:
        L = int(re.search(r"tess_level=(\d+)", r[0]).group(1))
        before = sides * ring(L) + caps * ring(min(6 * L, 64))
        now = 1508 * ring(L)
        ok(number(r[1]) == before, "S3", f"{r[0]}: lod uniform count {r[1]}, the ring rule with the long-edge factor gives {before}")
        ok(number(r[2]) == now, "S3", f"{r[0]}: lod constant count {r[2]}, the ring rule gives {now}")


def claims_s4(tabs):
    hb, tb = rows_of(tabs, "S4 reading")
    sums, shares = [], []
    for r in tb:
        v = [float(x) for x in re.findall(r"(?:VS|DS|PS) busy (\d+\.\d)", r[1])]
        g = float(re.search(r"geometry (\d+\.\d)", r[2]).group(1))
        sums.append(v[0] + v[1])
        shares.append(g / v[0])
    ok(len(sums) == 4, "S4", f"four readings with busy figures expected, found {len(sums)}")
    yield f"in S4's {['no', 'one', 'two', 'three', 'four'][len(sums)]} readings"
    yield f"{rng(sums, 1)} %"
    ha, ta = nth_table(tabs, 0, "instructions ratio")
    vs = col(ha, "VS + TES")
    yield f"({fmt((number(ta[1][vs]) / number(ta[0][vs]) - 1) * 100, 2)} %".replace("(-", "(−")
    yield f"here {fmt(number(ta[1][col(ha, 'instructions ratio')]), 2)}× the instructions"
    hb2, tb2 = nth_table(tabs, 1, "instructions ratio")
    vs = col(hb2, "VS + TES")
    ins = col(hb2, "instructions / frame")
    yield f"8.4 evaluates {fmt((number(tb2[1][vs]) / number(tb2[0][vs]) - 1) * 100, 2)} % more vertices"
    yield f"executes {fmt((number(tb2[1][ins]) / number(tb2[0][ins]) - 1) * 100, 2)} % more instructions"
    s4_83, s4_84 = 393508, 393176   # S4 Tables 8.3 / 8.4, VSVerticesIn (median)
    yield f"processed {fmt((1 - s4_84 / s4_83) * 100, 2)} % *fewer* vertices"
    yield f"the geometry stages are {rng(shares, 2)}× S4's shares"


# ---- the other pages: docs/displacement.md, docs/textures.md, docs/studies.md

def subsection(text, title):
    """The body of the '### title' (or '## title') section of a page."""
    m = re.search(r"^#{2,3} " + re.escape(title) + r"\s*$", text, flags=re.M)
    if not m:
        raise ParseError(f"no section '{title}'")
    rest = text[m.end():]
    end = re.search(r"^#{2,3} ", rest, flags=re.M)
    return rest[:end.start()] if end else rest


def published_ratio(sweep, num, den):
    """num / den of a sweep's published values, as times (a frame rate
    inverted)."""
    pub = sweep_published(sweep)
    if not pub:
        raise ParseError(f"sweeps/{sweep}.yaml has no published values")
    vals, unit = pub
    return vals[den] / vals[num] if unit == "fps" else vals[num] / vals[den]


def claims_displacement(text):
    """docs/displacement.md: S3's table on llvmpipe and S4 on llvmpipe."""
    body = subsection(text, "S3's table on llvmpipe")
    h, t = rows_of(tables(body), "mesh", "normal", "tess 1", "tess 64")
    ms = {r[0].split()[0]: {c: number(r[col(h, c)]) for c in ("normal", "tess 1", "tess 32", "tess 64")}
          for r in t}
    yield body, f"({rng([m['tess 1'] / m['normal'] for m in ms.values()], 2)}×;"
    s3 = [published_ratio("s3-table7-1", f"tess-displacement mesh={m} tess_level=1", f"normal mesh={m}")
          for m in ("cube", "cylinder", "sphere")]
    yield body, f"S3 measured {rng(s3, 2)}× on its GTX 660 Ti"
    patches = {"cube": 12, "cylinder": 1508, "sphere": 5120}
    tes = {m: [n * ring(L) for L in (1, 32, 64)] for m, n in patches.items()}
    yield body, ", ".join(f"{m} " + " / ".join(thousands(v) for v in tes[m]) for m in patches)
    cyl, sph = ms["cylinder"]["tess 64"], ms["sphere"]["tess 64"]
    vert = tes["cylinder"][2] / tes["sphere"][2]
    yield body, (f"costs {fmt(cyl / sph, 1)}× the sphere with {fmt(vert, 2)}× its vertices, "
                 f"{fmt(cyl / sph / vert, 0)}× per vertex")

    body = subsection(text, "S4 on llvmpipe")
    h, t = rows_of(tables(body), "configuration", "ms", "TESInvocations")
    mc, vc, tc = col(h, "ms"), col(h, "VSInvocations"), col(h, "TESInvocations")

    def row(prefix):
        for r in t:
            if r[0].startswith(prefix):
                return r
        raise ParseError(f"S4 on llvmpipe: no row '{prefix}'")

    orig, l12 = row("original asteroid"), row("reduced, level 12 uniform")
    work = (number(l12[vc]) + number(l12[tc])) / number(orig[vc])
    ok(f"{fmt(work, 3)} of the original's vertex work" in l12[0], "displacement.md",
       f"row '{l12[0]}': (VS + TES) / the original's VS gives {work:.4f}")
    yield body, f"the reduced body cost about {fmt(number(l12[mc]) / number(orig[mc]), 0)}× the original"
    pairs = [(l12[mc], row("reduced, level 12, lod distance")[mc], l12[tc], row("reduced, level 12, lod distance")[tc]),
             (row("terrain 16")[mc], row("terrain, level 12, lod distance")[mc],
              row("terrain 16")[tc], row("terrain, level 12, lod distance")[tc])]
    t32 = row("terrain, level 32")
    pairs.append(tuple(x for c in (mc, tc) for x in t32[c].split(" / ")))
    tes_cut = [number(p[2]) / number(p[3]) for p in pairs]
    ms_cut = [number(p[0]) / number(p[1]) for p in pairs]
    yield body, (f"cuts TESInvocations {math.floor(min(tes_cut))}–{math.ceil(max(tes_cut))}× and time "
                 f"{rng(ms_cut, 1)}×")
    yield body, f"about {fmt(published_ratio('s4-table8-1-2', 'tess-displacement', 'phong'), 2)}×"
    yield body, f"differed by {fmt((published_ratio('s4-table8-3-4', 'lod=object-cpu', 'lod=object-points') - 1) * 100, 1)} %"


def claims_textures(text):
    """docs/textures.md: the normal formats' ranking and the virtual
    texture's cost table."""
    m = re.search(r"\*\*bc1 (\d+\.\d+)°, bc3nm (\d+\.\d+)°, bc5 (\d+\.\d+)°\*\* — S1's ranking", text)
    if not m:
        raise ParseError("textures.md: the bc1/bc3nm/bc5 figures are missing")
    bc1, bc3nm, bc5 = (float(x) for x in m.groups())
    ok(bc1 > bc3nm > bc5, "textures.md", f"S1's ranking (bc1 worst, bc5 best) against {bc1}°, {bc3nm}°, {bc5}°")
    h, t = rows_of(tables(text), "technique", "instructions, off")
    for r in t:
        for j in (1, 3):
            a, b = (number(x) for x in r[j].split("→"))
            printed = number(r[j + 1])
            want = b / a
            slack = 0.5 * 10 ** -decimals(r[j + 1]) + want * 0.5 * 10 ** -decimals(r[j]) * (1 / a + 1 / b)
            ok(abs(printed - want) <= slack + 1e-9, "textures.md",
               f"row '{r[0]}': × {r[j + 1]} beside {r[j]}, which gives {want:.3f}")
    return iter(())


def claims_studies(text):
    """docs/studies.md draws no conclusion from a table: a ratio or a
    direction in its prose needs a check here first."""
    prose = " ".join(l for l in text.split("\n") if not l.startswith("|"))
    found = re.findall(r"\d(?:\.\d+)?×(?!\d)|\b(?:faster|slower|cheaper|dearer)\b", prose)
    ok(not found, "studies.md", f"a conclusion without a check in bench/study_claims.py: {found}")
    return iter(())


PAGES = {"displacement.md": claims_displacement, "textures.md": claims_textures,
         "studies.md": claims_studies}


def check_pages():
    for name, fn in PAGES.items():
        path = os.path.join(ROOT, "docs", name)
        text = open(path, encoding="utf-8").read()
        for where, want in fn(text):
            ok(re.sub(r"\s+", " ", want) in prose_of(where), name,
               f"the tables give '{want}', which the prose does not say")


CLAIMS = {"S1": claims_s1, "S2": claims_s2, "S3": claims_s3, "S4": claims_s4}


def main():
    try:
        text = open(DOC, encoding="utf-8").read()
    except OSError as e:
        print(f"study_claims: {e}", file=sys.stderr)
        return 2
    secs = sections(text)
    try:
        for head, body in secs:
            tabs = tables(body)
            where = head.split(" — ")[0]
            for header, rows, prose in tabs:
                check_ratios(where, header, rows)
                check_verdicts(where, header, rows)
                check_published(where, header, rows, prose)
            key = head[:2]
            if key in CLAIMS:
                text_of = prose_of(body)
                for want in CLAIMS[key](tabs):
                    ok(re.sub(r"\s+", " ", want) in text_of, where,
                       f"the tables give '{want}', which the prose does not say")
        missing = [k for k in CLAIMS if not any(h.startswith(k) for h, _ in secs)]
        if missing:
            raise ParseError(f"no section {missing}")
        check_pages()
    except (ParseError, IndexError, KeyError, AttributeError, ZeroDivisionError, ValueError) as e:
        print(f"study_claims: cannot read the tables the checks need: {e!r}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"study_claims: {e}", file=sys.stderr)
        return 2
    for f in failures:
        print("MISMATCH " + f)
    print(f"study_claims: {checked[0]} figures checked, {len(failures)} disagree")
    return 1 if failures else 0


# One edit of a page per drift the checks must catch: (page, text, replacement).
DRIFTS = [("reproductions.md", "1 : 2.621 : 3.142", "1 : 2.621 : 3.412"),
          ("displacement.md", "costs 3.3× the sphere", "costs 3× the sphere"),
          ("displacement.md", "| 130.8 | 151.3 |", "| 130.8 | 171.3 |"),
          ("textures.md", "| 3.41 M → 6.74 M | 1.97 |", "| 3.41 M → 6.74 M | 1.87 |"),
          ("studies.md", "llvmpipe.", "llvmpipe; S1 was 2× faster.")]


def self_test():
    """Runs the checks on copies of the pages with each of DRIFTS applied:
    each must be caught (exit 1).  0 when all are, 1 otherwise."""
    import shutil
    import subprocess
    import tempfile
    missed = 0
    for page, old, new in DRIFTS:
        with tempfile.TemporaryDirectory() as tmp:
            shutil.copytree(os.path.join(ROOT, "docs"), os.path.join(tmp, "docs"))
            shutil.copytree(os.path.join(ROOT, "sweeps"), os.path.join(tmp, "sweeps"))
            path = os.path.join(tmp, "docs", page)
            text = open(path, encoding="utf-8").read()
            if old not in text:
                print(f"self-test: docs/{page} no longer holds '{old}': update DRIFTS")
                missed += 1
                continue
            open(path, "w", encoding="utf-8").write(text.replace(old, new, 1))
            rc = subprocess.run([sys.executable, os.path.abspath(__file__), tmp],
                                capture_output=True).returncode
            print(f"self-test: docs/{page}: '{old}' -> '{new}': exit {rc} (want 1)")
            missed += rc != 1
    return 1 if missed else 0


if __name__ == "__main__":
    if "--self-test" in sys.argv[1:]:
        sys.exit(self_test())
    sys.exit(main())
