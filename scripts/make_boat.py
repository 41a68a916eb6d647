#!/usr/bin/env python3
"""Writes samples/meshes/fishing_boat.obj: a small fishing boat (a hull lofted from half
ellipses, a deck, and an arched awning amidships) for the moving-boat sample scene (issue
26). Deterministic; run from the repository root. Units: metres, x along the boat, z up."""
import math

L, W, D = 8.0, 1.6, 0.7          # hull length, beam, depth
verts, faces = [], []


def add(v):
    verts.append(v)
    return len(verts) - 1


# Hull: sections along x, each a half ellipse below the deck line (z = 0), the beam and the
# depth narrowing towards raised ends.
n, m = 28, 12
rings = []
for i in range(n + 1):
    x = -L / 2 + L * i / n
    s = 1.0 - (2.0 * x / L) ** 4
    sheer = 0.35 * (2.0 * x / L) ** 2          # the ends rise
    ring = []
    for j in range(m + 1):
        a = math.pi * j / m                     # 0 .. pi: starboard deck edge, keel, port deck edge
        y = 0.5 * W * s * math.cos(a)
        z = -D * max(s, 0.05) * math.sin(a) + sheer
        ring.append(add((x, y, z)))
    rings.append(ring)
for i in range(n):
    for j in range(m):
        a, b, c, d = rings[i][j], rings[i + 1][j], rings[i + 1][j + 1], rings[i][j + 1]
        faces += [(a, c, b), (a, d, c)]
# Deck: a strip between the two deck edges.
for i in range(n):
    a, b, c, d = rings[i][0], rings[i + 1][0], rings[i + 1][m], rings[i][m]
    faces += [(a, b, c), (a, c, d)]
# Awning: a half cylinder over the middle third, its ends open.
k, q = 10, 10
arch = []
for i in range(k + 1):
    x = -L / 6 + (L / 3) * i / k
    row = []
    for j in range(q + 1):
        a = math.pi * j / q
        row.append(add((x, 0.55 * W * math.cos(a), 0.15 + 0.9 * math.sin(a))))
    arch.append(row)
for i in range(k):
    for j in range(q):
        a, b, c, d = arch[i][j], arch[i + 1][j], arch[i + 1][j + 1], arch[i][j + 1]
        faces += [(a, b, c), (a, c, d)]
with open("samples/meshes/fishing_boat.obj", "w") as f:
    f.write("# fishing_boat.obj: written by scripts/make_boat.py (shanshui's moving-boat sample)\n")
    for v in verts:
        f.write("v %.4f %.4f %.4f\n" % v)
    for a, b, c in faces:
        f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
