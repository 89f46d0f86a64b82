#!/usr/bin/env python3
"""Writes a bumpy torus of 2·U·V triangles as an OBJ: a U×V grid of quads over a torus
(major radius 1, minor radius 0.35) whose minor radius is displaced by a few sine bumps, each
quad split into two triangles sharing its diagonal, every vertex shared by six triangles. A
well-shaped, closed surface of small triangles, like a scan. Deterministic for (U, V).

Usage: bumpy_torus.py U V > torus.obj      (1000 1000: 2×10⁶ triangles, about 72 MiB)
"""
import math
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    nu, nv = int(sys.argv[1]), int(sys.argv[2])
    out = sys.stdout
    lines = []
    for i in range(nu):
        u = 2.0 * math.pi * i / nu
        cu, su = math.cos(u), math.sin(u)
        for j in range(nv):
            v = 2.0 * math.pi * j / nv
            r = 0.35 * (1.0 + 0.08 * math.sin(7.0 * u) * math.sin(5.0 * v))
            rho = 1.0 + r * math.cos(v)
            lines.append("v %.6f %.6f %.6f\n" % (rho * cu, rho * su, r * math.sin(v)))
        if len(lines) > 65536:
            out.write("".join(lines))
            lines = []
    out.write("".join(lines))
    lines = []
    for i in range(nu):
        i1 = (i + 1) % nu
        for j in range(nv):
            j1 = (j + 1) % nv
            a, b = i * nv + j + 1, i1 * nv + j + 1
            c, d = i1 * nv + j1 + 1, i * nv + j1 + 1
            lines.append("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d))
        if len(lines) > 65536:
            out.write("".join(lines))
            lines = []
    out.write("".join(lines))


if __name__ == "__main__":
    main()
