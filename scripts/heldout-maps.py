# Synthetic maps that no fit or bake setting has seen (issue #29): two small suns, a thin
# bright strip, a sun on a cube corner, a 1e6 sun on a cube edge, a sun near the pole, 24
# lamps on a dark sky; four maps of thin bright lines (tubes, neon, frames, arcs); 400 small
# city lamps (citylights); texel noise (noise, sparks); and cornerdim, a diagnostic (below). 1024 x 512 Radiance .hdr, flat RGBE, the same bytes every run (seeded).
#   python3 scripts/heldout-maps.py OUT_DIR [NAME ...]      (scripts/fit-lobe-loo.sh calls it)
import math, os, random, sys
W, H = 1024, 512
def direction(x, y):
    phi = ((x + 0.5) / W - 0.5) * 2 * math.pi
    th = (y + 0.5) / H * math.pi
    s = math.sin(th)
    return (s * math.sin(phi), math.cos(th), -s * math.cos(phi))
def norm(v):
    l = math.sqrt(sum(c * c for c in v)); return tuple(c / l for c in v)
def ea(el, az):
    el, az = math.radians(el), math.radians(az)
    return (math.cos(el) * math.sin(az), math.sin(el), -math.cos(el) * math.cos(az))
def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32: return b'\0\0\0\0'
    e = math.frexp(m)[1]; sc = 256.0 / 2 ** e
    return bytes((min(255, int(r * sc)), min(255, int(g * sc)), min(255, int(b * sc)), e + 128))
def write(name, fn):
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (H, W))
    for y in range(H):
        for x in range(W):
            out += rgbe(*fn(direction(x, y)))
    open(name, "wb").write(out)
def disc(d, c, deg):
    return sum(a * b for a, b in zip(d, c)) > math.cos(math.radians(deg / 2))
def sky(d, lo, hi):  # a gradient sky, bluish
    t = 0.5 * (d[1] + 1)
    v = lo + (hi - lo) * t
    return (0.7 * v, 0.85 * v, v)
random.seed(29)
maps = {}
s1, s2 = ea(30, 20), ea(12, -140)
maps["twosuns"] = lambda d: tuple(a + (2e4 if disc(d, s1, 0.5) else 0) + (5e3 if disc(d, s2, 0.5) else 0) for a in sky(d, 0.02, 0.3))
ax = norm((1, 0.02, -0.3))
def strip(d):
    # a thin arc: within 0.2 degrees of a great circle through ax and +y, 40 degrees long
    n = norm((ax[2], 0, -ax[0]))
    dist = abs(sum(a * b for a, b in zip(d, n)))
    on = dist < math.sin(math.radians(0.1)) and d[1] > 0 and d[1] < math.sin(math.radians(40)) and sum(a * b for a, b in zip(d, ax)) > 0
    return tuple(a + (800 if on else 0) for a in sky(d, 0.05, 0.5))
maps["strip"] = strip
corner = norm((1, 1, 1))
maps["corner"] = lambda d: tuple(a + (1e5 if disc(d, corner, 0.5) else 0) for a in sky(d, 0.2, 1.0))
# A diagnostic, not one of the held-out six: corner with its sky ten times dimmer, so that the
# sun dominates every highlight (docs/accuracy-study.md, "Compact sources").
maps["cornerdim"] = lambda d: tuple(a + (1e5 if disc(d, corner, 0.5) else 0) for a in sky(d, 0.02, 0.1))
yaw = random.uniform(0, 360)
edge = ea(0.3, 45 + yaw % 1)  # near the vertical edge between two side faces
maps["edge1e6"] = lambda d: tuple(a + (1e6 if disc(d, edge, 0.5) else 0) for a in sky(d, 0.5, 2.0))
pole = ea(84, random.uniform(0, 360))
maps["pole"] = lambda d: tuple(a + (3e4 if disc(d, pole, 0.5) else 0) for a in sky(d, 0.05, 0.4))
lamps = [ea(random.uniform(-10, 60), random.uniform(0, 360)) for _ in range(24)]
maps["lamps"] = lambda d: tuple(a + (300 if any(disc(d, c, 2) for c in lamps) else 0) for a in sky(d, 0.01, 0.05))
# Thin bright lines, none of them builtin:slits' vertical slits on black (docs/bake.md, "What
# is not met"), which chose mip 2's refinement spread: these four judge it.
def near_great_circle(d, normal, half_width_deg):
    return abs(sum(a * b for a, b in zip(d, normal))) < math.sin(math.radians(half_width_deg))
# tubes: 16 fluorescent tubes on a dim ceiling, 0.4 degrees wide and 12 long, along azimuth.
tubes = [(random.uniform(25, 70), random.uniform(0, 360)) for _ in range(16)]
def tube(d):
    el = math.degrees(math.asin(max(-1.0, min(1.0, d[1]))))
    az = math.degrees(math.atan2(d[0], -d[2])) % 360
    for tel, taz in tubes:
        daz = (az - taz + 180) % 360 - 180
        if abs(el - tel) < 0.2 and abs(daz) * math.cos(math.radians(tel)) < 6:
            return (150.0, 160.0, 170.0)
    return (0.08, 0.07, 0.06) if d[1] > 0 else (0.03, 0.03, 0.03)
maps["tubes"] = tube
# neon: 6 tilted great-circle segments, 0.25 degrees wide, 30 degrees long, on a night sky.
neon = [(norm((random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1))), ea(random.uniform(0, 30), random.uniform(0, 360)), random.choice([(60, 10, 40), (10, 50, 60), (70, 40, 5)])) for _ in range(6)]
def neon_sign(d):
    for normal, centre, colour in neon:
        if near_great_circle(d, normal, 0.125) and sum(a * b for a, b in zip(d, centre)) > math.cos(math.radians(15)):
            return colour
    return sky(d, 0.005, 0.05)
maps["neon"] = neon_sign
# frames: a bright overcast sky through a window grid of dark bars 0.5 degrees wide, 8 apart.
def frames(d):
    el = math.degrees(math.asin(max(-1.0, min(1.0, d[1]))))
    az = math.degrees(math.atan2(d[0], -d[2])) % 360
    if d[1] < 0:
        return (0.1, 0.09, 0.08)
    bar = (az % 8.0) < 0.5 or (el % 8.0) < 0.5
    return (0.02, 0.02, 0.02) if bar else (4.0, 4.2, 4.5)
maps["frames"] = frames
# arcs: 3 rings of latitude 0.3 degrees wide at elevations 10, 30 and 50, of 80, on dim ground.
def arcs(d):
    el = math.degrees(math.asin(max(-1.0, min(1.0, d[1]))))
    if any(abs(el - e) < 0.15 for e in (10, 30, 50)):
        return (80.0, 80.0, 80.0)
    return sky(d, 0.02, 0.1)
maps["arcs"] = arcs
# citylights: 400 lamps of 0.2-0.5 degrees (one or two texels) at 100-3000 below the horizon,
# on a dim sky: so many that the split's threshold rises to the lamps' own level (docs/bake.md,
# "Small lamps", and "What is not met" for its mip 1).
city_lamps = [(ea(random.uniform(-25, -2), random.uniform(0, 360)), random.choice([0.2, 0.3, 0.5]), random.uniform(100, 3000)) for _ in range(400)]
def citylights(d):
    if d[1] > -0.05:
        return sky(d, 0.01, 0.08)
    for centre, size, intensity in city_lamps:
        if disc(d, centre, size):
            return (intensity, 0.8 * intensity, 0.5 * intensity)
    return (0.02, 0.02, 0.025)
maps["citylights"] = citylights
# Texel noise (docs/bake.md, "Mip 1's local lights"): every texel its own random value, so that
# no threshold leaves mip 1's samples a smooth base. noise: u^8 x 1000 (a tenth of the texels
# above 4 times the mean); sparks: u^30 x 20000 (one in fifteen above it, most of them dim).
# Each draws from its own generator, in texel order, so the bytes do not depend on which
# maps are written.
def texel_noise(seed, power, scale):
    rng = random.Random(seed)
    return lambda d: (lambda v: (v, v, v))(scale * rng.random() ** power)
maps["noise"] = texel_noise(1, 8, 1000.0)
maps["sparks"] = texel_noise(2, 30, 20000.0)
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
for name in sys.argv[2:] or maps:
    write(os.path.join(out, "%s.hdr" % name), maps[name])
    print(name, flush=True)
