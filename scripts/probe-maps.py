#!/usr/bin/env python3
# The synthetic probe maps on which the default bake's per-mip bound (README: every mip of every
# held-out map within 0.050) is checked: star fields, squares, lattices, lines, suns, noise. None
# of the bake's settings, caps or fits was chosen on them, so they judge the bake rather than
# tune it; `scripts/measure-bake.sh unseen DIR` measures every map in DIR.
#   python3 scripts/probe-maps.py OUT_DIR [--only NAME ...] [--list] [-j N]
# Written as float32 PFM (about 2.6 GB for the set, 30 s on 2 cores). Each map has its own
# random.Random and draws in scan order (a star field: one number per texel, one more per star
# for its value), so the bytes depend neither on -j nor on which other maps are made. A file
# already present at its full size is kept, so a rerun resumes.
# License: the repository's.
import argparse, math, os, random, signal, sys, time
from array import array
from multiprocessing import Pool

MAPS = {}  # name -> (width, height, class, rows(W, H): yields one row of W RGB floats per y, top first)


def add(cls, name, W, rows):  # every map is 2:1
    MAPS[name] = (W, W // 2, cls, rows)


def texels(W, H, fn):  # fn(x, y, W, H) -> (r, g, b), called in scan order
    for y in range(H):
        yield array('f', [c for x in range(W) for c in fn(x, y, W, H)])


def pixels(fn):
    return lambda W, H: texels(W, H, fn)


def latitude(fn):  # fn(y, H) -> (r, g, b): one colour per row
    return lambda W, H: (array('f', fn(y, H)) * W for y in range(H))


def grey(v):
    return (v, v, v)


# Two direction conventions, each family keeping the one its maps were probed with: dirn (phi 0
# at the image centre, -z) and dirof (phi 0 at the left edge, +x).
def dirn(x, y, W, H):
    phi = ((x + 0.5) / W - 0.5) * 2 * math.pi; th = (y + 0.5) / H * math.pi; s = math.sin(th)
    return (s * math.sin(phi), math.cos(th), -s * math.cos(phi))


def ea(el, az):
    el, az = math.radians(el), math.radians(az)
    return (math.cos(el) * math.sin(az), math.sin(el), -math.cos(el) * math.cos(az))


def dot(a, b):
    return sum(p * q for p, q in zip(a, b))


def dirof(x, y, W, H):
    phi = 2 * math.pi * (x + 0.5) / W; th = math.pi * (y + 0.5) / H
    return (math.sin(th) * math.cos(phi), math.cos(th), math.sin(th) * math.sin(phi))


# Star fields: one-texel lights, 260 to 53000 a map, over a bluish gradient; the dense ones are
# past the split's caps (its candidates, the lights per tile) and left to tiles and samples.
def stars(seed, frac, lo, hi=None, sky=1.0, uniform=0):
    """hi None: every star is lo and takes no draw; else each is
    log-uniform in [lo, hi]. uniform: equal density per solid angle, not per texel."""
    def rows(W, H):
        r = random.Random(seed); rnd = r.random
        for y in range(H):
            base = sky * (0.05 + 0.5 * (1 - y / H))
            p = frac * math.sin(math.pi * (y + 0.5) / H) * math.pi / 2 if uniform else frac
            row = array('f', (0.7 * base, 0.85 * base, base)) * W
            for x in range(W):
                if rnd() < p:
                    v = lo if hi is None else math.exp(r.uniform(math.log(lo), math.log(hi)))
                    row[3 * x:3 * x + 3] = array('f', (0.7 * base + v, 0.85 * base + v, base + v))
            yield row
    return rows


for name, W, seed, frac, lo, hi, sky, uni in (  # frac: of texels lit; sky: the gradient's scale
        ('dust', 1024, 103, 0.004, 3e3, None, 1, 0), ('dust2', 1024, 106, 0.004, 300, 1e4, 1, 0),
        ('dust3', 1024, 107, 0.02, 100, 1e3, 1, 0), ('dust01', 1024, 108, 0.001, 3e3, 3.01e3, 1, 0),
        ('dust1', 1024, 109, 0.01, 50, 5e3, 1, 0),
        ('s1', 1024, 201, 0.002, 3000, 3000, 1, 0), ('s2', 1024, 202, 0.003, 3000, 3000, 1, 0),
        ('s3', 1024, 203, 0.006, 3000, 3000, 1, 0), ('s4', 1024, 204, 0.008, 1000, 1e4, 1, 0),
        ('s5', 1024, 205, 0.004, 1e4, 1e4, 0.1, 0), ('s6', 1024, 206, 0.005, 3000, 3000, 1, 1),
        ('s7', 1024, 207, 0.01, 3000, 3000, 1, 1), ('s8', 1024, 208, 0.015, 500, 5000, 1, 0),
        ('s9', 2048, 209, 0.001, 3000, 3000, 1, 0), ('s10', 2048, 210, 0.003, 1000, 1e4, 1, 1),
        ('s11', 512, 211, 0.01, 3000, 3000, 1, 0), ('s12', 1024, 212, 0.0025, 2e4, 2e4, 0.02, 1),
        ('s21', 1024, 221, 0.005, 3000, 3000, 1, 0), ('s22', 1024, 222, 0.007, 3000, 3000, 1, 0),
        ('s23', 1024, 223, 0.009, 3000, 3000, 1, 0), ('s24', 512, 224, 0.005, 3000, 3000, 1, 0),
        ('s25', 512, 225, 0.02, 3000, 3000, 1, 0), ('s26', 512, 226, 0.01, 1e4, 1e4, 0.1, 0),
        ('s27', 256, 227, 0.01, 3000, 3000, 1, 0), ('s28', 512, 228, 0.003, 3000, 3000, 1, 0),
        ('s31', 1024, 231, 0.0042, 3000, 3000, 1, 0), ('s32', 1024, 232, 0.0045, 3000, 3000, 1, 0),
        ('s33', 1024, 233, 0.0048, 3000, 3000, 1, 0), ('s34', 1024, 234, 0.0045, 3000, 3000, 0.3, 0),
        ('s41', 1024, 341, 0.0045, 1e4, 1e4, 0.1, 0), ('s42', 1024, 342, 0.005, 1000, 1e4, 1, 0),
        ('s43', 2048, 343, 0.0012, 3000, 3000, 1, 0), ('s44', 1024, 344, 0.0045, 3000, 3000, 1, 1),
        ('s45', 1024, 345, 0.0048, 3000, 3000, 0.02, 0), ('s46', 1024, 346, 0.0044, 3000, 3000, 1, 0),
        ('t1', 1024, 501, 0.01, 3000, 3000, 1, 0), ('t2', 1024, 502, 0.02, 3000, 3000, 1, 0),
        ('t3', 1024, 503, 0.05, 3000, 3000, 1, 0), ('t4', 2048, 504, 0.005, 3000, 3000, 1, 0),
        ('t5', 1024, 505, 0.03, 3000, 3000, 1, 0), ('t6', 1024, 506, 0.1, 3000, 3000, 1, 0),
        ('t7', 1024, 507, 0.05, 300, 3e4, 1, 0),
        ('stars4k_01', 4096, 601, 0.001, 3000, None, 1, 0), ('stars4k_05', 4096, 602, 0.005, 3000, None, 1, 0),
        ('stars3000', 3000, 603, 0.004, 3000, None, 1, 0),
        ('stars4k_05u', 4096, 611, 0.005, 3000, 3000, 1, 1),  # about 42000 stars
        ('stars4k_var', 4096, 612, 0.005, 100, 1e4, 1, 1)):
    add('stars', name, W, stars(seed, frac, lo, hi, sky, uni))


def sprinkled(seed, frac, value):  # one texel in 1/frac at value over a flat sky, one draw per texel
    def rows(W, H):
        r = random.Random(seed)
        return texels(W, H, lambda x, y, W, H: grey(value) if r.random() < frac else (1, 1.2, 1.5))
    return rows


add('stars', 'negnan', 1024, sprinkled(7, 0.0005, 3e4))  # named for the negatives RGBE could not hold


# Texel noise: every texel its own value, refined only where the samples' own standard error says so.
def grain(seed):  # exp(2 N(0, 1)) per texel
    def rows(W, H):
        r = random.Random(seed)

        def f(x, y, W, H):
            v = math.exp(2.0 * r.gauss(0, 1))
            return (v, 0.9 * v, 0.8 * v)
        return texels(W, H, f)
    return rows


def speckle(seed, p, s):
    def rows(W, H):
        r = random.Random(seed)

        def f(x, y, W, H):
            v = r.random() ** p * s; c = r.random()
            return (v * (0.5 + c), v, v * (1.5 - c))
        return texels(W, H, f)
    return rows


def blotch(seed):  # 4 x 4 cells, each drawn when scan order first reaches it
    def rows(W, H):
        r = random.Random(seed); cells = {}

        def f(x, y, W, H):
            k = (x // 4, y // 4)
            if k not in cells: cells[k] = r.random() ** 6 * 300
            return grey(cells[k])
        return texels(W, H, f)
    return rows


add('noise', 'grain', 1024, grain(101))
add('noise', 'speckle2k', 2048, speckle(102, 12, 5000))
add('noise', 'noise512', 512, speckle(105, 8, 1000))
add('noise', 'blotch', 1024, blotch(104))


# Lattices of one-texel dots: many equal lights in a regular pattern, no list holds them alone.
def lattice(step, value, sky):
    return pixels(lambda x, y, W, H: grey(value) if x % step == step // 2 and y % step == step // 2 else grey(sky))


add('dots', 'lattice', 1024, lattice(16, 2000, 0.2))
add('dots', 'lattice8', 1024, lattice(8, 1e4, 0.2))
add('dots', 'lattice2k', 2048, lattice(12, 3000, 0.1))
add('dots', 'lattice1000', 1000, lattice(10, 2500, 0.1))


# Meridians 1 to 24 texels wide meeting at the poles: lines a fraction of mip 1's footprint wide.
def meridians(period, width, value, sky):  # every row alike: x % period < width is lit
    def rows(W, H):
        row = array('f', [value if x % period < width else sky for x in range(W) for _ in range(3)])
        return (row for _ in range(H))
    return rows


for name, W, period, width, value, sky in (
        ('stripes', 1024, 12, 6, 100, 1), ('meridians', 1024, 43, 1, 2000, 0.5),
        ('meridians2', 1024, 43, 2, 2000, 0.5), ('meridians2k', 2048, 57, 1, 2000, 0.5),
        ('meridians3', 1024, 64, 3, 800, 0.5), ('mer4', 1024, 64, 4, 800, 0.5),
        ('mer3x32', 1024, 32, 3, 400, 0.5), ('mer3b', 1024, 64, 3, 5000, 0.05),
        ('mer8', 1024, 128, 8, 300, 0.5), ('mer4_2k', 2048, 128, 4, 800, 0.5),
        ('mer6_2k', 2048, 128, 6, 800, 0.5), ('mer10_2k', 2048, 128, 10, 800, 0.5),
        ('mer6b_2k', 2048, 128, 6, 8000, 0.05), ('mer6x32_2k', 2048, 64, 6, 800, 0.5),
        ('m5_2k', 2048, 128, 5, 800, 0.5), ('m7_2k', 2048, 128, 7, 800, 0.5),
        ('m6c_2k', 2048, 128, 6, 3000, 0.05), ('m6x16_2k', 2048, 128, 6, 300, 1.0),
        ('m12_2k', 2048, 128, 12, 800, 0.5), ('m16_2k', 2048, 128, 16, 800, 0.5),
        ('m8_4k', 4096, 256, 8, 800, 0.5), ('m12_4k', 4096, 256, 12, 800, 0.5),
        ('m16_4k', 4096, 256, 16, 800, 0.5), ('m24_4k', 4096, 256, 24, 800, 0.5)):
    add('meridians', name, W, meridians(period, width, value, sky))


# Other thin lines: rings, bands, grids, hatching, great circles, cube edges, the seam, a pole cap.
def great_circles(count, width, value, sky, tilt):
    """`count` meridians of an axis tilted by `tilt` degrees about x, and its equator, `width` degrees wide."""
    def rows(W, H):
        t = math.radians(tilt); ct, st = math.cos(t), math.sin(t)
        cph = [math.cos(2 * math.pi * (x + 0.5) / W) for x in range(W)]
        sph = [math.sin(2 * math.pi * (x + 0.5) / W) for x in range(W)]
        step, half = 360.0 / count, math.sin(math.radians(width / 2))
        for y in range(H):
            th = math.pi * (y + 0.5) / H; s, c = math.sin(th), math.cos(th)
            row = array('f', [sky] * (3 * W))
            for x in range(W):
                d2 = s * sph[x]; dy = c * ct - d2 * st; dz = c * st + d2 * ct
                if math.degrees(math.atan2(dz, s * cph[x])) % step < width or abs(dy) < half:
                    row[3 * x] = row[3 * x + 1] = row[3 * x + 2] = value
            yield row
    return rows


def thin_great_circles(seed, count):  # one texel wide-ish: |n.d| under half a texel
    def rows(W, H):
        r = random.Random(seed); normals = []
        for _ in range(count):
            a, b = r.uniform(0, 2 * math.pi), r.uniform(-1, 1)
            normals.append((math.sqrt(1 - b * b) * math.cos(a), b, math.sqrt(1 - b * b) * math.sin(a)))

        def f(x, y, W, H):
            d = dirn(x, y, W, H); w = math.pi / H * 0.5
            return (1500, 1400, 1300) if any(abs(dot(d, n)) < w for n in normals) else (0.2, 0.25, 0.3)
        return texels(W, H, f)
    return rows


add('lines', 'ring', 1024, latitude(lambda y, H: (500, 480, 450) if abs((0.5 - (y + 0.5) / H) * 180 - 20) < 1
                                     else (0.3, 0.4, 0.6)))  # 2 degrees wide at 20 degrees elevation
add('lines', 'ring1', 1024, latitude(lambda y, H: grey(5000) if y == int(H * (80 / 180)) else (0.3, 0.4, 0.6)))
add('lines', 'parallels', 1024, latitude(lambda y, H: grey(1500) if y % 25 == 12 else grey(0.3)))
add('lines', 'bands3', 1024, latitude(lambda y, H: grey(800) if y % 42 < 3 else grey(0.5)))
add('lines', 'grid2k', 2048, pixels(lambda x, y, W, H: grey(600) if x % 32 == 0 or y % 32 == 0 else grey(0.2)))
add('lines', 'hatch', 1024, pixels(lambda x, y, W, H: (400, 380, 360) if y < H // 2 and (x + y) % 5 == 0
                                   else grey(0.5)))  # diagonals every 5 texels, upper hemisphere
add('lines', 'seamline', 1024, pixels(lambda x, y, W, H: (3000, 2500, 2000) if (x < 2 or x > W - 2)
                                      else (grey(200) if y == H // 2 else grey(0.5))))  # the seam and the equator
add('lines', 'polecap', 1024, pixels(lambda x, y, W, H: grey(5000) if y < 3
                                     else (grey(800) if y == 20 and x % 8 == 0 else grey(0.3))))  # top 3 rows lit
add('lines', 'cubeedges', 1024, pixels(lambda x, y, W, H: (lambda d: grey(1000) if d[0] - d[1] < 0.004 else grey(0.3))(
    sorted(map(abs, dirn(x, y, W, H)), reverse=True))))
add('lines', 'greatcircles', 1024, thin_great_circles(604, 6))
add('lines', 'gc1_2k', 2048, great_circles(6, 1.0, 500, 0.3, 30))
add('lines', 'gc05_2k', 2048, great_circles(8, 0.5, 2000, 0.2, 60))


# Suns and small discs: one colour channel, black ground, the horizon, 64- to 4096-wide maps, cube corners, a grille.
def suns(base, discs):
    """base(y, H) -> rgb; discs: (elevation, azimuth, diameter in degrees, rgb), texel centres inside lit."""
    def rows(W, H):
        cs = []
        for el, az, deg, c in discs:
            e, a = math.radians(el), math.radians(az)
            cs.append(((math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a)),
                       math.cos(math.radians(deg / 2)), c, math.pi / 2 - e))
        for y in range(H):
            row = array('f', base(y, H) * W); th = math.pi * (y + 0.5) / H
            for d0, cosr, c, th0 in cs:
                if math.cos(th - th0) < cosr - 1e-9: continue  # the row passes wide of the disc
                for x in range(W):
                    d = dirof(x, y, W, H)
                    if d[0] * d0[0] + d[1] * d0[1] + d[2] * d0[2] > cosr:
                        for k in range(3): row[3 * x + k] += c[k]
            yield row
    return rows


def sky(lo, hi, ground=None):
    def base(y, H):
        t = math.cos(math.pi * (y + 0.5) / H)
        if ground is not None and t < 0: return ground
        v = lo + (hi - lo) * max(0.0, t)
        return (0.6 * v, 0.8 * v, v)
    return base


for name, W, base, discs in (
        ('bluesun', 1024, sky(0.2, 1.0), [(30, 40, 0.6, (0, 0, 3e4))]),
        ('redsun_dark', 1024, sky(0.01, 0.05), [(10, 200, 0.6, (5e4, 0, 0))]),
        ('blackground_sun', 2048, sky(0.1, 0.6, (0, 0, 0)), [(20, 100, 0.5, (4e4, 3.6e4, 3e4))]),
        ('lowsun_horizon', 2048, sky(0.1, 0.6, grey(0.02)), [(0.3, 100, 0.5, (4e4, 3.6e4, 3e4))]),
        ('tiny64', 64, sky(0.1, 1.0), [(40, 10, 3.0, grey(2e3))]),
        ('tiny128_sun', 128, sky(0.1, 1.0), [(40, 10, 1.5, grey(1e4))]),
        ('big4k_sun', 4096, sky(0.05, 0.5, (0.03, 0.03, 0.025)), [(35, 250, 0.53, (1e5, 9e4, 8e4))]),
        ('twocolor', 1024, sky(0.05, 0.2), [(25, 30, 1.0, (2e4, 0, 0)), (25, 33, 1.0, (0, 0, 2e4))]),
        ('suns9', 2048, sky(0.05, 0.3), [(el, az, 0.5, grey(3e3 * (1 + i))) for i, (el, az) in enumerate(
            [(-60, 0), (-30, 40), (0, 80), (30, 120), (60, 160), (80, 200), (-80, 240), (10, 280), (45, 320)])]),
        ('bigdisc20', 1024, sky(0.02, 0.1), [(30, 60, 20, grey(50))]),
        ('ring_halo', 2048, sky(0.05, 0.3), [(40, 100, 4, grey(300)), (40, 100, 0.4, grey(5e4))])):
    add('suns', name, W, suns(base, discs))

COLORED = [(ea(20, 30), 1.0, (3e4, 0, 0)), (ea(35, 150), 2.0, (0, 0, 2e4)), (ea(10, -80), 5.0, (0, 800, 0))]


def colored(x, y, W, H):  # three suns, each of one channel
    d = dirn(x, y, W, H); t = 0.5 * (d[1] + 1); c = [0.1 + 0.2 * t] * 3
    for s, size, rgb in COLORED:
        if dot(d, s) > math.cos(math.radians(size / 2)):
            c = [a + b for a, b in zip(c, rgb)]
    return tuple(c)


SKYSUN = ea(35, -60)


def skysun(x, y, W, H):  # gradient, circumsolar glow, a 0.53 degree sun of 5e4
    d = dirn(x, y, W, H); a = math.degrees(math.acos(max(-1, min(1, dot(d, SKYSUN)))))
    if d[1] < 0: return (0.3, 0.25, 0.2)
    s = 1.0 + 3.0 * (1 - d[1]) + 200.0 * math.exp(-a / 3.0)
    sun = 5e4 if a < 0.265 else 0
    return (s * 0.8 + sun, s * 0.9 + sun, s * 1.1 + sun)


def grille(x, y, W, H):  # a 6 degree lamp of 2e4 behind one-texel dark bars every 3 texels
    d = dirn(x, y, W, H); c = d[1] * math.sin(math.radians(50)) + (-d[2]) * math.cos(math.radians(50))
    return grey(2e4) if c > math.cos(math.radians(3)) and x % 3 != 0 else (0.2, 0.2, 0.25)


CORNERS = [(sx / math.sqrt(3), sy / math.sqrt(3), sz / math.sqrt(3))
           for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def cubecorners(x, y, W, H):  # 0.4 degree spots of 1e5 on the cube's 8 corners
    d = dirn(x, y, W, H)
    return grey(1e5) if any(dot(d, c) > math.cos(math.radians(0.2)) for c in CORNERS) else (0.5, 0.6, 0.7)


add('suns', 'colored', 1024, pixels(colored))
add('suns', 'skysun', 2048, pixels(skysun))
add('suns', 'tinysun', 128, pixels(lambda x, y, W, H: (1e4, 9e3, 8e3) if (x, y) == (40, 20) else (0.5, 0.6, 0.8)))
add('suns', 'grille', 1024, pixels(grille))
add('suns', 'cubecorners', 2048, pixels(cubecorners))


# Large areas with sharp edges: a lit hemisphere, softboxes, lit windows, a checkerboard.
BOXES = [(100, 200, 60, 120, 400), (400, 520, 150, 200, 50), (700, 760, 80, 300, 200), (900, 1000, 300, 340, 120)]


def softboxes(x, y, W, H):
    for x0, x1, y0, y1, v in BOXES:
        if x0 <= x < x1 and y0 <= y < y1: return grey(v)
    return (0.01, 0.01, 0.012)


WINDOWS = [math.degrees(math.atan2(w[0], -w[2])) for w in (ea(15, az) for az in range(-150, 180, 60))]


def windows(x, y, W, H):  # six windows 20 x 12 degrees at 15 degrees elevation
    d = dirn(x, y, W, H); c = 0.05
    el = math.degrees(math.asin(max(-1, min(1, d[1])))); az = math.degrees(math.atan2(d[0], -d[2]))
    for waz in WINDOWS:
        if abs(el - 15) < 10 and abs((az - waz + 180) % 360 - 180) < 6: c += 60.0
    return (c, c * 0.95, c * 0.9)


def windows2k(seed):  # 3000 lit 2 x 3 windows of 50-800 in the lower half
    def rows(W, H):
        r = random.Random(seed); lit = {}
        for _ in range(3000):
            x0, y0 = r.randrange(0, 2046), r.randrange(560, 1000); v = r.uniform(50, 800)
            for dx in range(2):
                for dy in range(3): lit[(x0 + dx, y0 + dy)] = v
        return texels(W, H, lambda x, y, W, H: (lambda v: (v, 0.8 * v, 0.5 * v))(
            lit.get((x, y), 0.02 if y > H // 2 else 0.1)))
    return rows


add('areas', 'hemi', 1024, latitude(lambda y, H: (800, 850, 900) if y < H // 2 else (2, 1.5, 1)))
add('areas', 'softboxes', 1024, pixels(softboxes))
add('areas', 'windows', 1024, pixels(windows))
add('areas', 'windows2k', 2048, windows2k(702))
add('areas', 'checker', 1024, pixels(lambda x, y, W, H: grey(500.0 if ((x // 8) + (y // 8)) % 2 else 0.5)))


# Smooth but of high dynamic range: six decades top to bottom, exp of plane waves, fine rings.
def smoothhdr(seed):  # exp(2.5 n), n a sum of 24 random plane waves on the sphere (3-10 degrees)
    def rows(W, H):
        r = random.Random(seed); waves = []
        for _ in range(24):
            a, b = r.uniform(0, 2 * math.pi), r.uniform(-1, 1); k = r.uniform(10, 40)
            waves.append(((math.sqrt(1 - b * b) * math.cos(a) * k, b * k, math.sqrt(1 - b * b) * math.sin(a) * k),
                          r.uniform(0, 6.3)))

        def f(x, y, W, H):
            d = dirn(x, y, W, H)
            n = sum(math.sin(dot(d, w) + p) for w, p in waves) / math.sqrt(len(waves) / 2)
            v = math.exp(2.5 * n)
            return (v, 0.9 * v, 0.8 * v)
        return texels(W, H, f)
    return rows


MOIRE = ea(30, 40)


def moire(x, y, W, H):  # rings of period 1.5 degrees around one direction
    a = math.acos(max(-1, min(1, dot(dirn(x, y, W, H), MOIRE))))
    return grey(50 * (1 + math.sin(a / math.radians(1.5) * 2 * math.pi)) + 0.1)


add('smooth', 'logramp', 1024, latitude(lambda y, H: grey(10 ** (6 * (1 - (y + 0.5) / H) - 2))))
add('smooth', 'smoothhdr', 1024, smoothhdr(701))
add('smooth', 'moire', 1024, pixels(moire))


# Fields of squares 2 to 12 texels wide: lights of a few texels, between one-texel stars and suns.
def blobs(count, size, value, sky, seed):
    """`count` squares of size x size texels at value * U(0.5, 1.5); later ones cover earlier ones."""
    def rows(W, H):
        rng = random.Random(seed); spans = [[] for _ in range(H)]
        for _ in range(count):
            x0, y0 = rng.randrange(W), rng.randrange(H - size)
            v = value * rng.uniform(0.5, 1.5)
            for y in range(y0, y0 + size): spans[y].append((x0, v))
        for y in range(H):
            row = array('f', [sky] * (3 * W))
            for x0, v in spans[y]:
                for x in range(x0, x0 + size):
                    row[3 * (x % W)] = row[3 * (x % W) + 1] = row[3 * (x % W) + 2] = v
            yield row
    return rows


for name, W, count, size, value, sky_v, seed in (
        ('blobs3_2k', 2048, 3000, 3, 500, 0.3, 1), ('blobs5_2k', 2048, 1500, 5, 300, 0.3, 2),
        ('blobs8_4k', 4096, 2000, 8, 300, 0.3, 3), ('blobs2_1k', 1024, 4000, 2, 2000, 0.2, 4),
        ('b8c_4k', 4096, 2000, 8, 3000, 0.1, 5), ('b6_4k', 4096, 3000, 6, 500, 0.3, 6),
        ('b12_4k', 4096, 1000, 12, 300, 0.3, 7), ('b8x4k_4k', 4096, 4000, 8, 300, 0.3, 8),
        ('b4_2k', 2048, 3000, 4, 1000, 0.2, 9), ('b8_2k', 2048, 800, 8, 500, 0.3, 10)):
    add('blobs', name, W, blobs(count, size, value, sky_v, seed))


def header(W, H):
    return b'PF\n%d %d\n-1.0\n' % (W, H)


def done(path, W, H):
    return os.path.isfile(path) and os.path.getsize(path) == len(header(W, H)) + 12 * W * H


def make(job):
    """Writes one map; rows come top first and go to their place from the file's end (PFM is bottom-to-top)."""
    name, out_dir = job
    W, H, _, rows = MAPS[name]
    path = os.path.join(out_dir, name + '.pfm'); start = time.time()
    with open(path + '.tmp', 'wb') as f:
        f.write(header(W, H))
        for y, row in enumerate(rows(W, H)):
            if sys.byteorder == 'big': row = array('f', row); row.byteswap()  # a copy: rows may be shared
            f.seek(len(header(W, H)) + 12 * W * (H - 1 - y))
            f.write(row.tobytes())
    os.replace(path + '.tmp', path)
    return '%s %dx%d %.1f s' % (name, W, H, time.time() - start)


def main():
    ap = argparse.ArgumentParser(description='Writes the synthetic probe maps as OUT_DIR/NAME.pfm.')
    ap.add_argument('out_dir', nargs='?')
    ap.add_argument('--only', nargs='+', metavar='NAME', help='only these maps')
    ap.add_argument('--list', action='store_true', help='print "name width height class" and exit')
    ap.add_argument('-j', type=int, metavar='N', default=os.cpu_count(), help='processes (default: every CPU)')
    args = ap.parse_args()
    names = args.only or list(MAPS)
    unknown = [n for n in names if n not in MAPS]
    if unknown: ap.error('no such map: ' + ' '.join(unknown))
    if args.list:
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `--list | head` ends quietly
        for n in names: print(n, *MAPS[n][:3])
        return
    if not args.out_dir: ap.error('OUT_DIR is required')
    os.makedirs(args.out_dir, exist_ok=True)
    todo = [n for n in names if not done(os.path.join(args.out_dir, n + '.pfm'), *MAPS[n][:2])]
    todo.sort(key=lambda n: -MAPS[n][0] * MAPS[n][1])  # largest first, so the processes finish together
    start = time.time()
    with Pool(max(1, args.j)) as pool:
        for line in pool.imap_unordered(make, [(n, args.out_dir) for n in todo]):
            print('probe-maps:', line, flush=True)
    print('probe-maps: %d made, %d already there, %.0f s' % (len(todo), len(names) - len(todo), time.time() - start))


if __name__ == '__main__':
    main()
