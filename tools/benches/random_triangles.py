#!/usr/bin/env python3
"""Writes N random triangles in the unit cube as an OBJ: the same triangles as glint's
`random_triangle_scene(N, seed)` (src/bin/glint/bench/cmd.rs, splitmix64 in src/bench/splitmix.rs):
each centred at a uniform point, its corners within ±size/2 of the centre, size =
N^(-1/3), so depth complexity does not grow with N. Deterministic for (N, seed).

Usage: random_triangles.py N SEED [DECIMALS] > random-triangles.obj

DECIMALS: write coordinates with that many decimals (6: the 10⁶-triangle file is about
107 MiB, as a scan exporter writes it) instead of Python's shortest exact form (195 MiB).
"""
import sys

MASK = (1 << 64) - 1


class SplitMix:
    def __init__(self, seed):
        self.state = seed & MASK

    def unit(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return ((z ^ (z >> 31)) >> 11) / float(1 << 53)

    def vec(self):
        return (self.unit(), self.unit(), self.unit())


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    n, seed = int(sys.argv[1]), int(sys.argv[2])
    coordinate = "%%.%df" % int(sys.argv[3]) if len(sys.argv) == 4 else "%r"
    vertex_line = "v %s %s %s\n" % (coordinate, coordinate, coordinate)
    rng = SplitMix(seed)
    size = n ** (-1.0 / 3.0)
    out = sys.stdout
    for _ in range(n):
        centre = rng.vec()
        for _corner in range(3):
            offset = rng.vec()
            out.write(vertex_line % tuple(c + (o - 0.5) * size for c, o in zip(centre, offset)))
    for i in range(n):
        out.write("f %d %d %d\n" % (3 * i + 1, 3 * i + 2, 3 * i + 3))


if __name__ == "__main__":
    main()
