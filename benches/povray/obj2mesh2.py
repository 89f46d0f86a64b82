#!/usr/bin/env python3
"""Writes an OBJ mesh as a POV-Ray mesh2 declaration, z negated (glint's scenes are
right-handed, POV-Ray is left-handed: mirroring z gives the same image with the same
camera). Polygons are fan-triangulated as glint does; `a`, `a/b`, `a/b/c`, `a//c` and
negative indices are read.

Usage: obj2mesh2.py MESH.obj NAME > NAME.inc
"""
import sys


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                x, y, z = (float(v) for v in fields[1:4])
                vertices.append((x, y, -z))
            elif fields[0] == "f":
                corners = []
                for c in fields[1:]:
                    i = int(c.split("/")[0])
                    corners.append(i - 1 if i > 0 else len(vertices) + i)
                if len(corners) < 3:
                    sys.exit(f"{path}:{number}: a face needs 3 corners")
                for k in range(1, len(corners) - 1):
                    faces.append((corners[0], corners[k], corners[k + 1]))
    return vertices, faces


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    vertices, faces = read_obj(sys.argv[1])
    out = [f"#declare {sys.argv[2]} = mesh2 {{", f"  vertex_vectors {{ {len(vertices)},"]
    out += [f"    <{x!r}, {y!r}, {z!r}>," for x, y, z in vertices]
    out += ["  }", f"  face_indices {{ {len(faces)},"]
    out += [f"    <{a}, {b}, {c}>," for a, b, c in faces]
    out += ["  }", "}"]
    print("\n".join(out))


if __name__ == "__main__":
    main()
