#!/usr/bin/env python3
"""Writes an OBJ mesh as a POV-Ray mesh2 declaration, z negated (glint's scenes are
right-handed, POV-Ray is left-handed: mirroring z gives the same image with the same
camera). Polygons are fan-triangulated as glint does; `a`, `a/b`, `a/b/c`, `a//c` and
negative indices are read. When every corner names a `vn`, the normals go along
(`normal_vectors`, `normal_indices`, z negated too): POV-Ray then makes smooth
triangles, its `smooth_triangle` rendition, which glint's smooth shading is compared
with (tests/oracle/shading.rs).

Usage: obj2mesh2.py MESH.obj NAME > NAME.inc
"""
import sys


def read_obj(path):
    vertices, normals, faces, face_normals = [], [], [], []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                x, y, z = (float(v) for v in fields[1:4])
                vertices.append((x, y, -z))
            elif fields[0] == "vn":
                x, y, z = (float(v) for v in fields[1:4])
                normals.append((x, y, -z))
            elif fields[0] == "f":
                corners, corner_normals = [], []
                for c in fields[1:]:
                    parts = c.split("/")
                    i = int(parts[0])
                    corners.append(i - 1 if i > 0 else len(vertices) + i)
                    if len(parts) == 3 and parts[2]:
                        n = int(parts[2])
                        corner_normals.append(n - 1 if n > 0 else len(normals) + n)
                    else:
                        corner_normals.append(None)
                if len(corners) < 3:
                    sys.exit(f"{path}:{number}: a face needs 3 corners")
                for k in range(1, len(corners) - 1):
                    faces.append((corners[0], corners[k], corners[k + 1]))
                    face_normals.append(
                        (corner_normals[0], corner_normals[k], corner_normals[k + 1])
                    )
    return vertices, normals, faces, face_normals


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    vertices, normals, faces, face_normals = read_obj(sys.argv[1])
    smooth = bool(face_normals) and all(None not in f for f in face_normals)
    out = [f"#declare {sys.argv[2]} = mesh2 {{", f"  vertex_vectors {{ {len(vertices)},"]
    out += [f"    <{x!r}, {y!r}, {z!r}>," for x, y, z in vertices]
    if smooth:
        out += ["  }", f"  normal_vectors {{ {len(normals)},"]
        out += [f"    <{x!r}, {y!r}, {z!r}>," for x, y, z in normals]
    out += ["  }", f"  face_indices {{ {len(faces)},"]
    out += [f"    <{a}, {b}, {c}>," for a, b, c in faces]
    if smooth:
        out += ["  }", f"  normal_indices {{ {len(face_normals)},"]
        out += [f"    <{a}, {b}, {c}>," for a, b, c in face_normals]
    out += ["  }", "}"]
    print("\n".join(out))


if __name__ == "__main__":
    main()
