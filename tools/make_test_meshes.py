#!/usr/bin/env python3
"""Writes the mesh corpus of the world tests into tests/data/meshes/ (committed; rerun to regenerate).

  cube.{obj,off,ply,stl,gltf,3ds}  a 2 m cube centred on the origin, 12 triangles in every format (OBJ and OFF
                                   hold quads, so the import must triangulate); cube.3ds is converted from
                                   cube.obj with assimp's own exporter (Debian package assimp-utils)
  wall.obj                         a zero-thickness wall: the square x = 0, |y| <= 5, 0 <= z <= 10 (2 triangles)
  ridge.obj                        a height field over [0, 20] x [0, 10] m: flat at z = 0 with a sharp ridge
                                   along x = 10 rising to z = 4 (the ridge line is a mesh edge)
  empty.obj, garbage.obj, lines_only.obj, nan_vertex.obj, truncated.ply, truncated_header.ply   broken inputs

Usage: tools/make_test_meshes.py [OUT_DIR]   (default: tests/data/meshes next to this script's repo)
"""

import base64
import json
import pathlib
import shutil
import struct
import subprocess
import sys

CUBE_VERTICES = [(x, y, z) for z in (-1.0, 1.0) for y in (-1.0, 1.0) for x in (-1.0, 1.0)]
# Quads, counter-clockwise seen from outside.
CUBE_QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
CUBE_TRIANGLES = [t for q in CUBE_QUADS for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = sum(x * x for x in n) ** 0.5
    return tuple(x / length for x in n)


def write_obj(path, vertices, faces, comment):
    lines = [f"# {comment}"] + [f"v {x:g} {y:g} {z:g}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    path.write_text("\n".join(lines) + "\n")


def write_off(path):
    lines = ["OFF", f"{len(CUBE_VERTICES)} {len(CUBE_QUADS)} 0"]
    lines += [f"{x:g} {y:g} {z:g}" for x, y, z in CUBE_VERTICES]
    lines += [f"4 {' '.join(map(str, q))}" for q in CUBE_QUADS]
    path.write_text("\n".join(lines) + "\n")


def write_ply(path, truncated=False):
    lines = ["ply", "format ascii 1.0", f"element vertex {len(CUBE_VERTICES)}", "property float x",
             "property float y", "property float z", f"element face {len(CUBE_TRIANGLES)}",
             "property list uchar int vertex_indices", "end_header"]
    lines += [f"{x:g} {y:g} {z:g}" for x, y, z in CUBE_VERTICES]
    lines += [f"3 {a} {b} {c}" for a, b, c in CUBE_TRIANGLES]
    if truncated:
        lines = lines[:len(lines) - len(CUBE_TRIANGLES) - 3]  # header promises more than the file holds
    path.write_text("\n".join(lines) + "\n")


def write_stl(path):
    lines = ["solid cube"]
    for t in CUBE_TRIANGLES:
        a, b, c = (CUBE_VERTICES[i] for i in t)
        lines.append("  facet normal {:g} {:g} {:g}".format(*normal(a, b, c)))
        lines.append("    outer loop")
        lines += ["      vertex {:g} {:g} {:g}".format(*p) for p in (a, b, c)]
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append("endsolid cube")
    path.write_text("\n".join(lines) + "\n")


def write_gltf(path):
    positions = b"".join(struct.pack("<3f", *v) for v in CUBE_VERTICES)
    indices = b"".join(struct.pack("<3H", *t) for t in CUBE_TRIANGLES)
    buffer = positions + indices
    doc = {
        "asset": {"version": "2.0", "generator": "peg3d tools/make_test_meshes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions), "target": 34962},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(CUBE_VERTICES), "type": "VEC3",
                       "min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3 * len(CUBE_TRIANGLES), "type": "SCALAR"}],
    }
    path.write_text(json.dumps(doc, indent=1) + "\n")


def write_ridge(path):
    # Columns at x = 0, 9.9, 10, 10.1, 20 would make a thick ridge; a single apex vertex row at x = 10 gives a
    # knife edge: z = 4 there, 0 at x = 0 and x = 20 beyond two flat strips.
    xs = [0.0, 6.0, 10.0, 14.0, 20.0]
    zs = [0.0, 0.0, 4.0, 0.0, 0.0]
    ys = [0.0, 10.0]
    vertices = [(x, y, z) for y in ys for x, z in zip(xs, zs)]
    n = len(xs)
    faces = []
    for i in range(n - 1):
        a, b, c, d = i, i + 1, n + i + 1, n + i
        faces += [(a, b, c), (a, c, d)]
    write_obj(path, vertices, faces, "ridge: flat strips and a knife-edge ridge at x = 10, z = 4 (make_test_meshes.py)")


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "tests" / "data" / "meshes"
    out.mkdir(parents=True, exist_ok=True)
    write_obj(out / "cube.obj", CUBE_VERTICES, CUBE_QUADS, "2 m cube as 6 quads (make_test_meshes.py)")
    write_off(out / "cube.off")
    write_ply(out / "cube.ply")
    write_stl(out / "cube.stl")
    write_gltf(out / "cube.gltf")
    if shutil.which("assimp") is None:
        sys.exit("assimp (Debian package assimp-utils) is needed to write cube.3ds")
    subprocess.run(["assimp", "export", str(out / "cube.obj"), str(out / "cube.3ds")], check=True,
                   stdout=subprocess.DEVNULL)
    write_obj(out / "wall.obj", [(0, -5, 0), (0, 5, 0), (0, 5, 10), (0, -5, 10)], [(0, 1, 2), (0, 2, 3)],
              "zero-thickness wall x = 0, |y| <= 5, 0 <= z <= 10 (make_test_meshes.py)")
    write_ridge(out / "ridge.obj")
    (out / "empty.obj").write_text("")
    (out / "garbage.obj").write_bytes(b"\x00\x01\x02 this is not a mesh \xff\xfe\n" * 4)
    write_obj(out / "lines_only.obj", [(0, 0, 0), (1, 0, 0), (1, 1, 0)], [], "vertices and a polyline, no faces")
    with open(out / "lines_only.obj", "a") as f:
        f.write("l 1 2 3\n")
    (out / "nan_vertex.obj").write_text("# a triangle with a NaN coordinate\nv 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n")
    write_ply(out / "truncated.ply", truncated=True)
    (out / "truncated_header.ply").write_text("ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\n")


if __name__ == "__main__":
    main()
