#!/usr/bin/env python3
"""flip_reference.py - LDR-FLIP transcribed from the paper (Andersson et
al., HPG 2020) in plain Python, with full 2-D kernels, as a check on
imaging/flip.c that shares no code with it.  Prints the values that
tests/test_reports_flip.c asserts (run: python3 tests/flip_reference.py).
Slow on purpose: direct 2-D convolution, small images only."""
import math

PPD = 3840 * 0.7 / 0.7 * math.pi / 180          # 0.7 m from a 0.7 m wide 3840-px monitor
CSF = [((1.0, 0.0047), (0.0, 1e-5)),            # achromatic   (a1, b1), (a2, b2)
       ((1.0, 0.0053), (0.0, 1e-5)),            # red-green
       ((34.1, 0.04), (13.5, 0.025))]           # blue-yellow
QC, PC, PT, W, QF = 0.7, 0.4, 0.95, 0.082, 0.5
M = [[0.4124564, 0.3575761, 0.1804375],
     [0.2126729, 0.7151522, 0.0721750],
     [0.0193339, 0.1191920, 0.9503041]]
MI = [[3.2404542, -1.5371385, -0.4985314],
      [-0.9692660, 1.8760108, 0.0415560],
      [0.0556434, -0.2040259, 1.0572252]]
WHITE = [sum(r) for r in M]


def mul(m, v):
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def lin(v):
    v = min(max(v, 0.0), 1.0)
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


def ycxcz(rgb):
    x, y, z = [c / w for c, w in zip(mul(M, rgb), WHITE)]
    return [116 * y - 16, 500 * (x - y), 200 * (y - z)]


def from_ycxcz(c):
    y = (c[0] + 16) / 116
    return mul(MI, [(c[1] / 500 + y) * WHITE[0], y * WHITE[1], (y - c[2] / 200) * WHITE[2]])


def hunt_lab(rgb):
    rgb = [min(max(v, 0.0), 1.0) for v in rgb]
    d = 6 / 29
    f = [t ** (1 / 3) if t > d ** 3 else t / (3 * d * d) + 4 / 29
         for t in [c / w for c, w in zip(mul(M, rgb), WHITE)]]
    L = 116 * f[1] - 16
    return [L, 0.01 * L * 500 * (f[0] - f[1]), 0.01 * L * 200 * (f[1] - f[2])]


def hyab(a, b):
    return abs(a[0] - b[0]) + math.hypot(a[1] - b[1], a[2] - b[2])


def color_error(h):
    cmax = hyab(hunt_lab([0, 1, 0]), hunt_lab([0, 0, 1])) ** QC
    e = h ** QC
    return PT / (PC * cmax) * e if e < PC * cmax else PT + (e - PC * cmax) / (cmax - PC * cmax) * (1 - PT)


def conv(img, k, r):
    h, w = len(img), len(img[0])
    out = [[0.0] * w for _ in range(h)]
    for y in range(h):
        for x in range(w):
            s = 0.0
            for j in range(-r, r + 1):
                yy = min(max(y + j, 0), h - 1)
                for i in range(-r, r + 1):
                    s += k[j + r][i + r] * img[yy][min(max(x + i, 0), w - 1)]
            out[y][x] = s
    return out


def csf_kernel(c):
    r = math.ceil(3 * math.sqrt(0.04 / (2 * math.pi ** 2)) * PPD)
    k = [[sum(a * math.sqrt(math.pi / b) * math.exp(-math.pi ** 2 * ((i * i + j * j) / PPD ** 2) / b)
              for a, b in CSF[c] if a > 0) for i in range(-r, r + 1)] for j in range(-r, r + 1)]
    s = sum(map(sum, k))
    return [[v / s for v in row] for row in k], r


def norm_pos_neg(k):
    p = sum(v for row in k for v in row if v > 0)
    n = -sum(v for row in k for v in row if v < 0)
    return [[v / p if v > 0 else v / n for v in row] for row in k]


def feature_kernels():
    sd = 0.5 * W * PPD
    r = math.ceil(3 * sd)
    g = lambda x, y: math.exp(-(x * x + y * y) / (2 * sd * sd))
    ex = norm_pos_neg([[-x * g(x, y) for x in range(-r, r + 1)] for y in range(-r, r + 1)])
    px = norm_pos_neg([[(x * x / (sd * sd) - 1) * g(x, y) for x in range(-r, r + 1)] for y in range(-r, r + 1)])
    t = lambda k: [list(col) for col in zip(*k)]
    return ex, t(ex), px, t(px), r


def flip(ref, test):
    out = []
    ex, ey, pxx, pyy, rf = feature_kernels()
    per = []
    for im in (ref, test):
        ycc = [[ycxcz([lin(v) for v in p]) for p in row] for row in im]
        ch = []
        for c in range(3):
            k, r = csf_kernel(c)
            ch.append(conv([[p[c] for p in row] for row in ycc], k, r))
        lum = [[(p[0] + 16) / 116 for p in row] for row in ycc]
        e = [conv(lum, ex, rf), conv(lum, ey, rf)]
        q = [conv(lum, pxx, rf), conv(lum, pyy, rf)]
        per.append((ch, e, q))
    h, w = len(ref), len(ref[0])
    for y in range(h):
        row = []
        for x in range(w):
            labs = [hunt_lab(from_ycxcz([ch[c][y][x] for c in range(3)])) for ch, _, _ in per]
            ce = color_error(hyab(*labs))
            em = [math.hypot(e[0][y][x], e[1][y][x]) for _, e, _ in per]
            pm = [math.hypot(q[0][y][x], q[1][y][x]) for _, _, q in per]
            fd = (max(abs(em[0] - em[1]), abs(pm[0] - pm[1])) / math.sqrt(2)) ** QF
            row.append((ce ** (1 - fd), ce, fd))
        out.append(row)
    return out


def flat(w, h, c):
    return [[list(c) for _ in range(w)] for _ in range(h)]


if __name__ == "__main__":
    # An isolated dot: white pixel (16,16) on black, 33x33.
    a, b = flat(33, 33, (0, 0, 0)), flat(33, 33, (0, 0, 0))
    b[16][16] = [1, 1, 1]
    m = flip(a, b)
    for x, y in ((16, 16), (19, 16), (16, 22)):
        print("dot (%d,%d): flip %.6f colour %.6f feature %.6f" % ((x, y) + m[y][x]))
    # A step edge moved by one pixel: grey 0.2 | 0.8 at x = 16 vs x = 17, 33x17.
    a = [[[0.2] * 3 if x < 16 else [0.8] * 3 for x in range(33)] for _ in range(17)]
    b = [[[0.2] * 3 if x < 17 else [0.8] * 3 for x in range(33)] for _ in range(17)]
    m = flip(a, b)
    for x in (12, 16, 20):
        print("edge (%d,%d): flip %.6f colour %.6f feature %.6f" % ((x, 8) + m[8][x]))
