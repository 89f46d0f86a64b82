#!/usr/bin/env python3
"""Writes torus.obj beside this script: a torus around the z axis (as gr.torus lies),
1 from its centre to the middle of the tube, tube radius 0.4, 32 segments around the
axis and 16 around the tube (1 024 triangles), with its exact unit normals as `vn`
(one per vertex, faces `a//a`). Coarse on purpose: flat shading shows every facet, so
smooth shading's interpolated normals make a visible difference (scenes/smooth.lua,
the POV-Ray comparison torus-povray.lua).

Usage: python3 scenes/meshes/make_torus.py   (rewrites scenes/meshes/torus.obj)
"""
import math
import os

R, r = 1.0, 0.4
AROUND, TUBE = 32, 16


def main():
    lines = [
        "# Torus around z: R = 1, r = 0.4, 32 x 16 segments, exact vertex normals.",
        "# Made by scenes/meshes/make_torus.py; do not edit.",
    ]
    normals = []
    for i in range(AROUND):
        theta = 2 * math.pi * i / AROUND
        for j in range(TUBE):
            phi = 2 * math.pi * j / TUBE
            n = (math.cos(phi) * math.cos(theta), math.cos(phi) * math.sin(theta), math.sin(phi))
            ring = R + r * math.cos(phi)
            p = (ring * math.cos(theta), ring * math.sin(theta), r * math.sin(phi))
            lines.append("v %.6f %.6f %.6f" % p)
            normals.append("vn %.6f %.6f %.6f" % n)
    lines += normals

    def index(i, j):
        return (i % AROUND) * TUBE + (j % TUBE) + 1

    for i in range(AROUND):
        for j in range(TUBE):
            a, b = index(i, j), index(i + 1, j)
            c, d = index(i + 1, j + 1), index(i, j + 1)
            # Counter-clockwise seen from outside: the winding's normal points out.
            lines.append("f %d//%d %d//%d %d//%d" % (a, a, b, b, c, c))
            lines.append("f %d//%d %d//%d %d//%d" % (a, a, c, c, d, d))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "torus.obj")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
