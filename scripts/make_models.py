#!/usr/bin/env python3
"""Writes the small models a painting places among its hills (issue 45) into samples/meshes/:
a thatched hut, a pavilion with upturned eaves, a five-storey pagoda, an arched bridge and
three boulders. Each is a closed triangle mesh in metres, z up, its base at z = 0, at the
size such a thing has (a 4 m hut, a 24 m pagoda), so a scene places it at true scale on any
DEM. Deterministic (the boulders come from fixed seeds); run from the repository root."""
import math
import random


class Mesh:
    def __init__(self):
        self.verts, self.faces = [], []

    def add(self, v):
        self.verts.append(tuple(v))
        return len(self.verts) - 1

    def box(self, x0, y0, z0, x1, y1, z1):
        """An axis-aligned box, faces outwards."""
        v = [self.add((x, y, z)) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
        for a, b, c, d in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)):
            self.faces += [(v[a], v[b], v[c]), (v[a], v[c], v[d])]

    def roof(self, cx, cy, z_eave, half, rise, lift, sides=4, droop=0.25):
        """A hipped roof with upturned eaves: a fan from the apex to a ring of eave points whose
        corners are `lift` higher than their middles, closed underneath by a shallow fan."""
        ring = []
        for k in range(sides * 4):
            a = 2.0 * math.pi * k / (sides * 4) + math.pi / sides
            # a square (or polygon) outline: distance to the edge along this angle
            edge = math.cos(math.pi / sides) / math.cos((a - math.pi / sides) % (2 * math.pi / sides) - math.pi / sides)
            corner = abs(math.cos(sides * (a - math.pi / sides) / 2.0)) ** 8
            ring.append(self.add((cx + half * edge * math.cos(a), cy + half * edge * math.sin(a), z_eave + lift * corner)))
        apex = self.add((cx, cy, z_eave + rise))
        under = self.add((cx, cy, z_eave + droop * rise * 0.3))
        n = len(ring)
        for k in range(n):
            a, b = ring[k], ring[(k + 1) % n]
            self.faces += [(a, b, apex), (b, a, under)]

    def write(self, path, what):
        with open(path, "w") as f:
            f.write("# %s: written by scripts/make_models.py (shanshui's painting samples)\n" % what)
            for v in self.verts:
                f.write("v %.4f %.4f %.4f\n" % v)
            for a, b, c in self.faces:
                f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def hut():
    """A farmer's hut: walls 5 x 3.5 m, a steep thatched gable roof with deep eaves, 4.6 m high."""
    m = Mesh()
    m.box(-2.5, -1.75, 0.0, 2.5, 1.75, 2.2)
    # gable roof: a prism along x, overhanging walls and gables
    x0, x1, w, z0, z1 = -3.0, 3.0, 2.5, 2.0, 4.6
    v = [m.add(p) for p in ((x0, -w, z0), (x0, w, z0), (x0, 0.0, z1), (x1, -w, z0), (x1, w, z0), (x1, 0.0, z1))]
    m.faces += [(v[0], v[2], v[1]), (v[3], v[4], v[5]), (v[0], v[3], v[5]), (v[0], v[5], v[2]),
                (v[1], v[2], v[5]), (v[1], v[5], v[4]), (v[0], v[1], v[4]), (v[0], v[4], v[3])]
    return m


def pavilion():
    """An open pavilion (ting): a stone platform, four posts, a square roof with upturned corners; 6.5 m high."""
    m = Mesh()
    m.box(-3.2, -3.2, 0.0, 3.2, 3.2, 0.6)
    for sx in (-1, 1):
        for sy in (-1, 1):
            m.box(sx * 2.2 - 0.15, sy * 2.2 - 0.15, 0.6, sx * 2.2 + 0.15, sy * 2.2 + 0.15, 3.6)
    m.roof(0.0, 0.0, 3.4, 3.9, 3.1, 0.9)
    return m


def pagoda():
    """A five-storey pagoda on a base: each storey narrower, each under its own flared roof, a spire; 24 m."""
    m = Mesh()
    m.box(-4.0, -4.0, 0.0, 4.0, 4.0, 1.0)
    z, half = 1.0, 2.8
    for storey in range(5):
        h = 3.2 - 0.25 * storey
        m.box(-half, -half, z, half, half, z + h)
        m.roof(0.0, 0.0, z + h - 0.2, half + 1.3, 1.0, 0.6, sides=8)
        z += h + 0.55
        half *= 0.86
    m.box(-0.12, -0.12, z - 0.5, 0.12, 0.12, z + 3.5)  # the spire
    return m


def bridge():
    """An arched stone bridge over a stream: 16 m span, 2.8 m wide, the deck 3 m above its feet."""
    m = Mesh()
    n, span, width, rise, thick = 24, 16.0, 2.8, 3.0, 0.8
    rows = []
    for i in range(n + 1):
        x = -span / 2 + span * i / n
        top = rise * (1.0 - (2.0 * x / span) ** 2) ** 0.5 + 0.3
        bottom = max(top - thick, 0.0) if 0 < i < n else 0.0
        rows.append([m.add((x, y, z)) for y, z in ((-width / 2, bottom), (width / 2, bottom), (width / 2, top), (-width / 2, top))])
    for i in range(n):
        a, b = rows[i], rows[i + 1]
        for k in range(4):
            p, q = a[k], a[(k + 1) % 4]
            r, s = b[(k + 1) % 4], b[k]
            m.faces += [(p, r, s), (p, q, r)]
    for ring, flip in ((rows[0], False), (rows[n], True)):
        f = [(ring[0], ring[1], ring[2]), (ring[0], ring[2], ring[3])]
        m.faces += [(a, c, b) for a, b, c in f] if not flip else f
    return m


def boulder(seed, size, flat):
    """A boulder: a subdivided icosahedron pushed in and out by a few seeded waves, flattened
    underneath, `size` metres across."""
    rnd = random.Random(seed)
    t = (1.0 + 5 ** 0.5) / 2.0
    pts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
           (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    tris = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
            (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
            (8, 6, 7), (9, 8, 1)]
    pts = [tuple(c / math.sqrt(sum(q * q for q in p)) for c in p) for p in pts]
    for _ in range(3):
        mid, out = {}, []

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = [(pts[a][k] + pts[b][k]) / 2 for k in range(3)]
                r = math.sqrt(sum(q * q for q in p))
                pts.append(tuple(q / r for q in p))
                mid[key] = len(pts) - 1
            return mid[key]
        for a, b, c in tris:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        tris = out
    waves = [(tuple(rnd.gauss(0, 1) for _ in range(3)), rnd.uniform(1.5, 4.0), rnd.uniform(0, 6.3), rnd.uniform(0.04, 0.12))
             for _ in range(7)]
    m = Mesh()
    for p in pts:
        r = 1.0
        for d, freq, phase, amp in waves:
            n = math.sqrt(sum(q * q for q in d))
            r += amp * math.cos(freq * sum(p[k] * d[k] / n for k in range(3)) + phase)
        x, y, z = (size / 2 * r * c for c in p)
        z = max(z * flat, -0.15 * size)  # a flat underside: it rests on the ground
        m.add((x, y, z + 0.15 * size))
    m.faces = tris
    return m


if __name__ == "__main__":
    for name, model, what in (("hut", hut(), "a thatched hut, 6 x 5 m, 4.6 m high"),
                              ("pavilion", pavilion(), "a pavilion with upturned eaves, 7.8 m square, 6.5 m high"),
                              ("pagoda", pagoda(), "a five-storey pagoda, 24 m high"),
                              ("bridge", bridge(), "an arched stone bridge, 16 m span"),
                              ("boulder_a", boulder(11, 6.0, 0.7), "a boulder about 6 m across"),
                              ("boulder_b", boulder(23, 4.0, 0.8), "a boulder about 4 m across"),
                              ("boulder_c", boulder(37, 9.0, 0.55), "a low boulder about 9 m across")):
        model.write("samples/meshes/%s.obj" % name, what)
