#!/usr/bin/env python3
"""Writes assets/canyon.obj, the terrain of maps/canyon.yaml: a winding canyon cut into a plateau, over the
paper's 35 m x 35 m footprint.

The plateau's top lies 12 m up. The canyon runs from the west wall (x = 0) to the east wall (x = 35 m) along an
S-shaped centre line (y = 17.5 m + 5 m sin(2 pi x / 35 m), give or take 0.6 m), its floor 0.7-1.3 m up and
8-8.5 m wide along y (5.6-8.5 m across the canyon), its rims about 8 m apart along y. Its walls are no height
fields: each is undercut by an alcove 0.7 m deep below a ledge 1.2 m thick (its underside 6.3-7 m up), and
along four stretches the ledge juts up to 2.15 m out over the floor (the south wall around x = 9 m and
x = 28 m, the north wall around x = 3 m and x = 18 m), so that a flyer under a ledge is hidden from anyone
above the canyon. Inside it stand three rock pillars (hoodoos rising 5-8.6 m above the floor, their caps
wider than their necks) and a natural bridge spans it at x = 20.5-23.5 m (its underside 9.4-9.7 m up over the
canyon, its top at most 11.5 m), with its ends sunk into the plateau.

Mesh: the rock is one closed solid. Its top is a sheet over the whole footprint built from cross-sections
across y at 141 stations along x (the plateau from the wall to the rim, down the wall, across the floor, up the
other wall, to the far wall), so it has no holes and is no height field; the footprint's four sides (in the
planes of the arena's walls) and a bottom at z = 0 close it. The pillars and the bridge are closed solids of
their own standing in it. Every face is counter-clockwise seen from outside. The map keeps `solid_below` off
(it would fill the alcoves under the ledges and the canyon under the bridge). Smooth random undulations (fixed
seed) vary the centre line, rims, ledges and floor, and the pillars' outlines. Only the standard library is
used, so the output depends on nothing but the seed and this file.

Usage: tools/make_canyon_mesh.py [OUT.obj]   (default: assets/canyon.obj in this script's repository)
"""

import math
import pathlib
import random
import sys

SEED = 20261204
SIZE = 35.0            # m, side of the square footprint
NX = 141               # cross-sections along x (0.25 m apart)
TOP = 12.0             # m, the plateau's height
FLOOR = 1.0            # m, the canyon floor's mean height
AMPLITUDE = 5.0        # m, the centre line's swing in y
RIM = 4.0              # m, mean half-width of the canyon at its rims (in y)
UNDERCUT = 0.7         # m, how far the alcove under the ledge reaches behind the rim
LEDGE_HEIGHT = 6.6     # m, mean height of a ledge's underside
LEDGE_THICKNESS = 1.2  # m
# Stretches where a ledge juts out over the floor: (side, centre x, half-length, reach), side -1 south, +1 north.
LEDGES = [(-1, 9.0, 4.5, 2.0), (-1, 28.0, 4.0, 1.8), (+1, 18.0, 4.5, 2.0), (+1, 3.0, 3.0, 1.5)]
# Hoodoos: (x, offset from the centre line in y, height, radius of the base, the neck, the cap)
PILLARS = [(5.5, 0.6, 7.0, 1.1, 0.7, 1.3), (13.0, -0.5, 9.5, 1.2, 0.8, 1.4), (31.5, 0.4, 6.0, 1.0, 0.65, 1.2)]
PILLAR_SIDES = 10
# The natural bridge across the canyon: x of its middle, width along x, thickness, and the height of its
# centre line's middle and ends, its half-length in y from the canyon's centre line, segments.
BRIDGE = dict(x=22.0, width=3.0, thickness=1.8, z_mid=10.6, z_end=9.8, half_length=7.5, segments=14)


def smooth_noise(rng, terms=3):
    """A smooth function of x in about [-1, 1]: a few sines of random wavelength and phase."""
    waves = [(rng.uniform(0.6, 1.0), rng.uniform(0.15, 0.5), rng.uniform(0, 2 * math.pi)) for _ in range(terms)]
    total = sum(a for a, _, _ in waves)
    return lambda x: sum(a * math.sin(k * x + p) for a, k, p in waves) / total


def bump(x, centre, half):
    """1 at the centre, falling smoothly (cos^2) to 0 at half a length away."""
    u = (x - centre) / half
    return math.cos(0.5 * math.pi * u) ** 2 if abs(u) < 1 else 0.0


class Canyon:
    def __init__(self, seed):
        rng = random.Random(seed)
        self.rim = {s: smooth_noise(rng) for s in (-1, 1)}
        self.ledge = {s: smooth_noise(rng) for s in (-1, 1)}
        self.floor = smooth_noise(rng)
        self.wiggle = smooth_noise(rng)
        self.jitter = rng  # the pillars' rocky jitter, drawn after the above

    def centre(self, x):
        return SIZE / 2 + AMPLITUDE * math.sin(2 * math.pi * x / SIZE) + 0.6 * self.wiggle(x)

    def floor_z(self, x):
        return FLOOR + 0.3 * self.floor(x)

    def wall(self, x, side):
        """One wall's cross-section as (offset from the centre line in y, z), from the rim down to the floor."""
        r = RIM + 0.5 * self.rim[side](x)
        zl = LEDGE_HEIGHT + 0.5 * self.ledge[side](x)
        reach = 0.15 + sum(a * bump(x, m, h) for s, m, h, a in LEDGES if s == side)
        zf = self.floor_z(x)
        return [
            (r, TOP),                                   # the rim
            (r - 0.3, zl + LEDGE_THICKNESS),            # the wall leans in a little down to the ledge
            (r - 0.3 - reach, zl + LEDGE_THICKNESS),    # the ledge's top, out over the floor
            (r - 0.3 - reach, zl),                      # its front
            (r + UNDERCUT, zl - 0.4),                   # its underside, back into the alcove
            (r + UNDERCUT, zf + 0.9),                   # the alcove's back wall
            (r + UNDERCUT - 0.6, zf),                   # the foot of the wall
        ]

    def section(self, x):
        """The ground's cross-section at x, as (y, z) from y = 0 to y = SIZE."""
        c = self.centre(x)
        south, north = self.wall(x, -1), self.wall(x, 1)
        y_rim_s, y_rim_n = c - south[0][0], c + north[0][0]
        pts = [(0.0, TOP), (y_rim_s / 3, TOP), (2 * y_rim_s / 3, TOP)]
        pts += [(c - d, z) for d, z in south]
        y0, y1, zf = c - south[-1][0], c + north[-1][0], self.floor_z(x)
        pts += [(y0 + 0.25 * (y1 - y0), zf + 0.1), (y0 + 0.5 * (y1 - y0), zf), (y0 + 0.75 * (y1 - y0), zf + 0.1)]
        pts += [(c + d, z) for d, z in reversed(north)]
        pts += [(y_rim_n + (SIZE - y_rim_n) / 3, TOP), (y_rim_n + 2 * (SIZE - y_rim_n) / 3, TOP), (SIZE, TOP)]
        return pts


class Mesh:
    def __init__(self):
        self.v, self.f = [], []

    def vertex(self, p):
        self.v.append(p)
        return len(self.v)  # OBJ indices are 1-based

    def quad(self, a, b, c, d):  # counter-clockwise seen from outside
        self.f += [(a, b, c), (a, c, d)]


def ear_clip(points):
    """Triangles (index triples) of a simple polygon given counter-clockwise as 2-D points; collinear vertices kept."""
    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    left, triangles = list(range(len(points))), []
    while len(left) > 3:
        for k in range(len(left)):
            a, b, c = left[k - 1], left[k], left[(k + 1) % len(left)]
            pa, pb, pc = points[a], points[b], points[c]
            if cross(pa, pb, pc) <= 1e-12:
                continue  # reflex or flat: not an ear
            if any(cross(pa, pb, points[q]) >= 0 and cross(pb, pc, points[q]) >= 0 and cross(pc, pa, points[q]) >= 0
                   for q in left if q not in (a, b, c)):
                continue  # another vertex inside or on it
            triangles.append((a, b, c))
            del left[k]
            break
        else:
            raise ValueError("polygon is not simple")
    triangles.append(tuple(left))
    return triangles


def ground(mesh, canyon):
    """The rock: the sheet over the footprint, closed by the footprint's sides and its bottom (z = 0)."""
    xs = [SIZE * i / (NX - 1) for i in range(NX)]
    sections = [canyon.section(x) for x in xs]
    rows = [[mesh.vertex((x, y, z)) for y, z in section] for x, section in zip(xs, sections)]
    for i in range(NX - 1):
        for j in range(len(rows[i]) - 1):
            # x grows with i, the section runs from y = 0 to y = SIZE with j: (x, s) is counter-clockwise from above
            mesh.quad(rows[i][j], rows[i + 1][j], rows[i + 1][j + 1], rows[i][j + 1])
    south = [mesh.vertex((x, 0.0, 0.0)) for x in xs]
    north = [mesh.vertex((x, SIZE, 0.0)) for x in xs]
    for i in range(NX - 1):
        mesh.quad(south[i], south[i + 1], rows[i + 1][0], rows[i][0])        # the side y = 0, facing -y
        mesh.quad(north[i + 1], north[i], rows[i][-1], rows[i + 1][-1])      # the side y = SIZE, facing +y
        mesh.quad(south[i], north[i], north[i + 1], south[i + 1])            # the bottom, facing -z
    # The ends x = 0 (facing -x: seen from there, -y is to the right) and x = SIZE (facing +x: +y to the right).
    for ids, section, sign in ((rows[0] + [north[0], south[0]], sections[0], -1),
                               (rows[-1] + [north[-1], south[-1]], sections[-1], 1)):
        outline = [(sign * y, z) for y, z in section] + [(sign * SIZE, 0.0), (0.0, 0.0)]
        if sign > 0:
            ids, outline = ids[::-1], outline[::-1]
        mesh.f += [(ids[a], ids[b], ids[c]) for a, b, c in ear_clip(outline)]


def ring_solid(mesh, rings, top_z):
    """A closed solid from rings of points (each counter-clockwise seen from above, bottom first), capped."""
    ids = [[mesh.vertex(p) for p in ring] for ring in rings]
    n = len(rings[0])
    for lower, upper in zip(ids, ids[1:]):
        for k in range(n):
            mesh.quad(lower[k], lower[(k + 1) % n], upper[(k + 1) % n], upper[k])
    bottom = mesh.vertex((sum(p[0] for p in rings[0]) / n, sum(p[1] for p in rings[0]) / n, rings[0][0][2]))
    top = mesh.vertex((sum(p[0] for p in rings[-1]) / n, sum(p[1] for p in rings[-1]) / n, top_z))
    for k in range(n):
        mesh.f.append((bottom, ids[0][(k + 1) % n], ids[0][k]))
        mesh.f.append((top, ids[-1][k], ids[-1][(k + 1) % n]))


def pillar(mesh, canyon, x, offset, height, r_base, r_neck, r_cap):
    cx, cy = x, canyon.centre(x) + offset
    profile = [(0.0, r_base), (canyon.floor_z(x) + 0.5, r_base), (0.45 * height, 0.5 * (r_base + r_neck)),
               (0.75 * height, r_neck), (0.82 * height, r_cap), (0.95 * height, r_cap)]
    jitter = [[canyon.jitter.uniform(0.9, 1.1) for _ in range(PILLAR_SIDES)] for _ in profile]
    rings = []
    for (z, r), jr in zip(profile, jitter):
        rings.append([(cx + r * jr[k] * math.cos(2 * math.pi * k / PILLAR_SIDES),
                       cy + r * jr[k] * math.sin(2 * math.pi * k / PILLAR_SIDES), z) for k in range(PILLAR_SIDES)])
    ring_solid(mesh, rings, height)


def bridge(mesh, canyon, x, width, thickness, z_mid, z_end, half_length, segments):
    """A beam of rectangular section (width along x, thickness in z) along an arc across the canyon."""
    c = canyon.centre(x)
    sections = []
    for k in range(segments + 1):
        u = -1 + 2 * k / segments
        y, z = c + u * half_length, z_end + (z_mid - z_end) * math.cos(0.5 * math.pi * u)
        # corners (x0, z0), (x1, z0), (x1, z1), (x0, z1): counter-clockwise seen from -y
        sections.append([mesh.vertex((x + dx, y, z + dz)) for dx, dz in
                         ((-width / 2, -thickness / 2), (width / 2, -thickness / 2),
                          (width / 2, thickness / 2), (-width / 2, thickness / 2))])
    for a, b in zip(sections, sections[1:]):
        for k in range(4):
            mesh.quad(a[k], b[k], b[(k + 1) % 4], a[(k + 1) % 4])
    s, n = sections[0], sections[-1]
    mesh.quad(s[0], s[1], s[2], s[3])  # the south end faces -y
    mesh.quad(n[0], n[3], n[2], n[1])  # the north end faces +y


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "assets" / "canyon.obj"
    canyon = Canyon(SEED)
    mesh = Mesh()
    ground(mesh, canyon)
    rock = len(mesh.f)
    for p in PILLARS:
        pillar(mesh, canyon, *p)
    bridge(mesh, canyon, **BRIDGE)
    lines = [f"# canyon terrain for maps/canyon.yaml: the rock over [0, {SIZE:g}]^2 m ({rock} triangles), "
             f"{len(PILLARS)} pillars and a bridge, {len(mesh.f)} triangles in all",
             f"# generated by tools/make_canyon_mesh.py (seed {SEED}); do not edit by hand"]
    lines += [f"v {x:.4f} {y:.4f} {z:.4f}" for x, y, z in mesh.v]
    lines += [f"f {a} {b} {c}" for a, b, c in mesh.f]
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
