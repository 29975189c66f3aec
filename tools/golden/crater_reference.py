#!/usr/bin/env python3
"""Independent golden values for the crater fractal (type craters) at seed 0 with the reference
hash (tests/noise_golden_test.cpp, NoiseGolden.CratersMatchReferenceAtSeed0).

Written from the crater model as shaders/common/noise.glsl documents it above cratersNoise, not
from its code, in plain double precision:
- octave i samples q_i = p * L^i (float products, as the shader's walk) and is weighted
  w_i = (L^-H)^i; each unit lattice cell holds a crater when the low 16 bits of a second mix of
  the cell's hash fall below 0.8 of 2^16; its size s in [0.5, 1) from that mix's high 16 bits,
  radius r = 0.3 s, centre jittered inside the cell (16 bits per axis) a margin
  max(0, 1.5 r (1 + eps) - 1/2) away from the cell's faces;
- a crater adds s * profile(d / r'), with r' = r (1 + eps n) and rim height 0.3 (1 + eps n),
  n the simplex noise at 2 q_i: the bowl R - (1 + R)(1 - rho^2)^2 inside, then the ejecta
  R (1 - u)^3 (1 + 3 u) with u = (rho^2 - 1) / (1.5^2 - 1), zero from u = 1 on;
- the cell hash at the reference hash: three permutation chains over Perlin's table, the axes
  rotated (i, j, k), (j, k, i), (k, i, j), one byte each, finished by Wellons' lowbias32.

Where the shader visits only the 2 x 2 x 2 cells around the lattice corner nearest the point
(and relies on the margin for that to be enough), this sums every cell within two of the
point's own cell and needs no cut-off at the reach: agreement also checks that bound.
Run: python3 tools/golden/crater_reference.py
"""
import itertools
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simplex_reference import PERM, simplex3, to_float32  # noqa: E402

PRESENCE = 0.8    # fraction of cells with a crater
RADIUS_MAX = 0.3  # largest radius, in cells
RADIUS_MIN = 0.5  # smallest radius, as a fraction of the largest
RIM = 0.3         # rim height over the floor depth of 1
REACH = 1.5       # ejecta reach, in radii


def lowbias32(h):
    h &= 0xffffffff
    h ^= h >> 16
    h = (h * 0x7feb352d) & 0xffffffff
    h ^= h >> 15
    h = (h * 0x846ca68b) & 0xffffffff
    h ^= h >> 16
    return h


def cell_hash(i, j, k):
    def chain(a, b, c):
        return PERM[(a & 255) + PERM[(b & 255) + PERM[c & 255]]]

    return lowbias32(chain(i, j, k) | (chain(j, k, i) << 8) | (chain(k, i, j) << 16))


def crater_in_cell(cell, eps):
    """(centre, radius, size) of the crater of `cell`, or None."""
    h = cell_hash(*cell)
    h2 = lowbias32(h)
    if (h2 & 0xffff) / 65536.0 >= PRESENCE:
        return None
    size = RADIUS_MIN + (1.0 - RADIUS_MIN) * (h2 >> 16) / 65536.0
    radius = RADIUS_MAX * size
    margin = max(REACH * radius * (1.0 + eps) - 0.5, 0.0)
    span = 1.0 - 2.0 * margin
    jitter = ((h >> 16), (h & 0xffff), (lowbias32(h2) >> 16))
    centre = [cell[a] + margin + span * jitter[a] / 65536.0 for a in range(3)]
    return centre, radius, size


def profile(rho, rim):
    if rho <= 1.0:
        return rim - (1.0 + rim) * (1.0 - rho * rho) ** 2
    u = min((rho * rho - 1.0) / (REACH * REACH - 1.0), 1.0)
    return rim * (1.0 - u) ** 3 * (1.0 + 3.0 * u)


def crater_octave(q, eps, n):
    own = [math.floor(c) for c in q]
    total = 0.0
    for step in itertools.product(range(-2, 3), repeat=3):
        found = crater_in_cell([own[a] + step[a] for a in range(3)], eps)
        if found is None:
            continue
        centre, radius, size = found
        distance = math.dist(q, centre)
        scale = 1.0 + eps * n
        total += size * profile(distance / (radius * scale), RIM * scale)
    return total


def craters(p, octaves, lacunarity, H, eps):
    q = [to_float32(c) for c in p]
    L = to_float32(lacunarity)
    ratio = to_float32(lacunarity ** -H)
    weight = 1.0
    total = 0.0
    for _ in range(octaves):
        n = simplex3(*[2.0 * c for c in q])
        total += weight * crater_octave(q, eps, n)
        q = [to_float32(c * L) for c in q]
        weight = to_float32(weight * ratio)
    return total


# (point, octaves, lacunarity, H, rim perturbation). __main__ puts two more first: the centre
# and a rim point of the first crater in the cells (i, 1, 4), i = 0, 1, ...
CASES = [
    ((0.1, 0.2, 0.3), 1, 2.0, 1.0, 0.25),  # between craters: 0
    ((111.51, 97.13, 16.59), 1, 2.0, 1.0, 0.25),
    ((1.69, -16.51, 52.87), 1, 2.0, 1.0, 0.0),
    ((30.56, -8.1, 43.03), 4, 2.0, 1.0, 0.25),
    ((85.33, -79.37, -39.19), 8, 2.0, 1.0, 0.25),
    ((4.56, -50.63, -38.14), 6, 2.0, 0.8, 0.1),
    ((96.87, 46.49, 101.73), 5, 2.7, 0.5, 0.35),
    ((-48.03, 39.1, 5.99), 8, 1.97, 0.9, 0.5),
    ((13.33, 51.85, -28.74), 3, 2.0, 1.0, 0.25),
    ((25.06, 67.83, -28.74), 8, 2.0, 1.0, 0.25),
]

if __name__ == "__main__":
    i = next(i for i in itertools.count() if crater_in_cell([i, 1, 4], 0.0) is not None)
    centre, radius, size = crater_in_cell([i, 1, 4], 0.0)
    print("// cell (%d, 1, 4): centre (%.9g, %.9g, %.9g), radius %.9g, size %.9g" % (i, *centre, radius, size))
    # The test passes coordinates as floats: the crater's points rounded to float here already.
    rim = (centre[0] + radius, centre[1], centre[2])
    special = [(tuple(to_float32(c) for c in point), 1, 2.0, 1.0, 0.0) for point in (tuple(centre), rim)]
    for p, octaves, lacunarity, H, eps in special + CASES:
        q = [to_float32(c) for c in p]
        value = craters(q, octaves, lacunarity, H, eps)
        print("{%r, %r, %r, %d, %r, %r, %r, %.17g}," % (*p, octaves, lacunarity, H, eps, value))
