#!/usr/bin/env python3
"""Independent golden values for 3D simplex noise at seed 0 (tests/noise_golden_test.cpp).

A direct transcription of the algorithm as described in Stefan Gustavson, "Simplex noise
demystified" (2005): skew (x+y+z)/3, unskew (i+j+k)/6, rank-ordered simplex corners,
gradient = perm[ii+perm[jj+perm[kk]]] mod 12 over Perlin's permutation, kernel
(0.5 - r^2)^4 (the paper's code uses 0.6, which makes the noise jump across simplex faces; the
project uses 0.5), sum scaled by 75 (the project's scale for that kernel). Written from the paper's description in plain Python double
precision, sharing no code with the C++/GLSL implementation (which selects gradients
arithmetically and compiles one source for two languages), so agreement checks the noise
geometry, not a copy of it. Run: python3 tools/golden/simplex_reference.py
"""
import math
import struct

PERLIN = [151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99, 37,
          240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, 57, 177,
          33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146,
          158, 231, 83, 111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25,
          63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100,
          109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
          59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153,
          101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218,
          246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107,
          49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205,
          93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180]
PERM = PERLIN + PERLIN

# The 12 gradient directions: midpoints of the cube's edges, in the paper's order.
GRADIENTS = [(1, 1, 0), (-1, 1, 0), (1, -1, 0), (-1, -1, 0),
             (1, 0, 1), (-1, 0, 1), (1, 0, -1), (-1, 0, -1),
             (0, 1, 1), (0, -1, 1), (0, 1, -1), (0, -1, -1)]


def simplex3(x, y, z):
    skew = (x + y + z) / 3.0
    cell = [math.floor(x + skew), math.floor(y + skew), math.floor(z + skew)]
    unskew = sum(cell) / 6.0
    offset0 = [x - (cell[0] - unskew), y - (cell[1] - unskew), z - (cell[2] - unskew)]

    # Walk from the cell origin to the far corner along the axes in decreasing order of the
    # offset's components (ties broken towards x, then y, as in the paper's comparisons).
    order = sorted(range(3), key=lambda a: (-offset0[a], a))
    steps = [[0, 0, 0]]
    for axis in order:
        nxt = list(steps[-1])
        nxt[axis] = 1
        steps.append(nxt)

    total = 0.0
    for n, step in enumerate(steps):
        corner_offset = [offset0[a] - step[a] + n / 6.0 for a in range(3)]
        t = 0.5 - sum(c * c for c in corner_offset)
        if t <= 0.0:
            continue
        ii, jj, kk = [(cell[a] + step[a]) & 255 for a in range(3)]
        g = GRADIENTS[PERM[ii + PERM[jj + PERM[kk]]] % 12]
        total += t ** 4 * sum(g[a] * corner_offset[a] for a in range(3))
    return 75.0 * total


POINTS = [(0.1, 0.2, 0.3), (1.5, -2.25, 3.75), (-7.3, 4.1, 0.9), (12.34, -56.78, 90.12), (100.5, 200.25, -300.125),
          (0.71, 0.37, -0.43), (-0.5, -1.5, 2.5), (3.14159, 2.71828, 1.41421), (250.0, 13.5, 77.7), (-33.3, -66.6, -99.9)]


def to_float32(v):
    """The coordinate as the C++ test passes it (a float), so both evaluate the same point."""
    return struct.unpack("f", struct.pack("f", v))[0]


if __name__ == "__main__":
    for p in POINTS:
        q = [to_float32(c) for c in p]
        print("{%r, %r, %r, %.17g}," % (p[0], p[1], p[2], simplex3(*q)))
