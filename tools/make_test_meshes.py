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


# ---- The hostile corpus (tests/data/meshes/hostile/): every accepted format empty, truncated, garbage, with
# absurd declared counts, non-finite and huge coordinates, degenerate triangles and out-of-range indices, and
# the glTF attacks on the importer (node cycles, a 100-deep chain, buffers naming /dev/zero or ../). Each line
# of expect.txt names a file and a fragment of the MeshError import_mesh must throw for it.

def tri_ply(rows, faces, fmt="ascii", count_vertex=None, count_face=None):
    head = ["ply", f"format {fmt} 1.0", f"element vertex {count_vertex if count_vertex is not None else len(rows)}",
            "property float x", "property float y", "property float z",
            f"element face {count_face if count_face is not None else len(faces)}",
            "property list uchar int vertex_indices", "end_header"]
    body = [" ".join(str(c) for c in r) for r in rows] + [" ".join(str(i) for i in (len(f),) + tuple(f)) for f in faces]
    return ("\n".join(head + body) + "\n").encode()


def tri_off(rows, faces, nv=None, nf=None):
    lines = ["OFF", f"{nv if nv is not None else len(rows)} {nf if nf is not None else len(faces)} 0"]
    lines += [" ".join(str(c) for c in r) for r in rows] + [" ".join(str(i) for i in (len(f),) + tuple(f)) for f in faces]
    return ("\n".join(lines) + "\n").encode()


def tri_stl_binary(triangles, declared=None):
    out = b"peg3d hostile".ljust(80, b" ") + struct.pack("<I", declared if declared is not None else len(triangles))
    for t in triangles:
        out += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v) for v in t) + b"\0\0"
    return out


def tri_gltf(positions, indices=None, count=None, nodes=None, uri=None, byte_length=None):
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = b"".join(struct.pack("<H", i) for i in indices) if indices else b""
    data = pos + idx
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": nodes if nodes is not None else [{"mesh": 0}],
           "meshes": [{"primitives": [dict({"attributes": {"POSITION": 0}, "mode": 4}, **({"indices": 1} if indices else {}))]}],
           "buffers": [{"byteLength": byte_length if byte_length is not None else len(data),
                        "uri": uri if uri is not None else "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}] +
                          ([{"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}] if indices else []),
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": count if count is not None else len(positions),
                          "type": "VEC3"}] +
                        ([{"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}] if indices else [])}
    return json.dumps(doc).encode()


def glb(json_bytes, bin_bytes=b""):
    json_bytes += b" " * (-len(json_bytes) % 4)
    bin_bytes += b"\0" * (-len(bin_bytes) % 4)
    chunks = struct.pack("<I4s", len(json_bytes), b"JSON") + json_bytes
    if bin_bytes:
        chunks += struct.pack("<I4s", len(bin_bytes), b"BIN\0") + bin_bytes
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def chunk(cid, payload):
    return struct.pack("<HI", cid, 6 + len(payload)) + payload


def tri_3ds(points, faces, declared_vertices=None):
    verts = struct.pack("<H", declared_vertices if declared_vertices is not None else len(points)) + \
        b"".join(struct.pack("<3f", *p) for p in points)
    tris = struct.pack("<H", len(faces)) + b"".join(struct.pack("<4H", *f, 0) for f in faces)
    mesh = chunk(0x4100, chunk(0x4110, verts) + chunk(0x4120, tris))
    return chunk(0x4D4D, chunk(0x3D3D, chunk(0x4000, b"hostile\0" + mesh)))


def write_hostile(out):
    out.mkdir(parents=True, exist_ok=True)
    tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    nan = [(0, 0, 0), (1, 0, float("nan")), (0, 1, 0)]
    huge = [(0, 0, 0), (1e39, 0, 0), (0, 1, 0)]  # beyond float: assimp reads inf
    same = [(1, 1, 1), (1, 1, 1), (1, 1, 1)]
    garbage = bytes((i * 73 + 41) % 256 for i in range(600))
    cube = {e: (out.parent / f"cube.{e}").read_bytes() for e in ("obj", "stl", "ply", "off", "gltf", "3ds")}
    files = {
        # every format: empty, garbage, truncated
        **{f"empty.{e}": b"" for e in ("obj", "stl", "ply", "off", "gltf", "glb", "3ds")},
        **{f"garbage.{e}": garbage for e in ("obj", "stl", "ply", "off", "gltf", "glb", "3ds")},
        "truncated.obj": cube["obj"][:cube["obj"].index(b"\nf ")],
        "truncated.stl": tri_stl_binary([tri, tri])[:-30],
        "truncated.ply": cube["ply"][:len(cube["ply"]) * 2 // 3],
        "truncated.off": cube["off"][:len(cube["off"]) // 2],
        "truncated.gltf": cube["gltf"][:len(cube["gltf"]) // 2],
        "truncated.glb": glb(tri_gltf(tri))[:60],
        "truncated.3ds": cube["3ds"][:len(cube["3ds"]) // 2],
        # absurd declared counts: a few hundred bytes asking for billions of elements
        "huge_count.ply": tri_ply(tri, [(0, 1, 2)], count_vertex=4000000000, count_face=4000000000),
        "huge_count_binary.ply": tri_ply([], [], fmt="binary_little_endian", count_vertex=400000000, count_face=1)
                                 + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + b"\x03" + struct.pack("<3i", 0, 1, 2),
        "huge_list.ply": tri_ply([], [], fmt="binary_little_endian", count_vertex=3, count_face=1).replace(b"uchar int", b"uint int")
                         + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<I", 0xFFFFFFF0) + struct.pack("<3i", 0, 1, 2),
        "huge_count.off": tri_off(tri, [(0, 1, 2)], nv=1000000000, nf=1000000000),
        "huge_count.stl": tri_stl_binary([tri], declared=0xFFFFFFFF),
        "huge_count.gltf": tri_gltf(tri, count=4000000000),
        "huge_buffer.gltf": tri_gltf(tri, byte_length=100000000000),
        "huge_count.glb": glb(json.dumps({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 1 << 40}]}).encode(), b"\0" * 36),
        "huge_count.3ds": tri_3ds(tri, [(0, 1, 2)], declared_vertices=65535),
        "huge_chunk.3ds": struct.pack("<HI", 0x4D4D, 0xFFFFFFFF) + chunk(0x3D3D, b"\0" * 64),
        # non-finite and huge coordinates
        "nan.obj": b"v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n",
        "huge.obj": b"v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n",
        "nan.ply": tri_ply(nan, [(0, 1, 2)]),
        "huge.ply": tri_ply(huge, [(0, 1, 2)]),
        "nan.off": tri_off([(0, 0, 0), (1, 0, "inf"), (0, 1, 0)], [(0, 1, 2)]),
        "nan.stl": tri_stl_binary([nan]),
        "huge.stl": b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e300 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n",
        "nan.gltf": tri_gltf(nan),
        "nan.glb": glb(json.dumps({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
                                   "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 4}]}],
                                   "buffers": [{"byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
                                   "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}]}).encode(),
                       b"".join(struct.pack("<3f", *p) for p in nan)),
        "nan.3ds": tri_3ds(nan, [(0, 1, 2)]),
        # degenerate triangles: all three corners at one point
        "degenerate.obj": b"v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n",
        "degenerate.ply": tri_ply(same, [(0, 1, 2)]),
        "degenerate.off": tri_off(same, [(0, 1, 2)]),
        "degenerate.stl": tri_stl_binary([same]),
        "degenerate.gltf": tri_gltf(same),
        "degenerate.3ds": tri_3ds(same, [(0, 1, 2)]),
        # out-of-range indices
        "bad_index.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n",
        "negative_index.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n",
        "bad_index.ply": tri_ply(tri, [(0, 1, 99)]),
        "bad_index.off": tri_off(tri, [(0, 1, 99)]),
        "bad_index.gltf": tri_gltf(tri, indices=[0, 1, 99]),
        "bad_index.3ds": tri_3ds(tri, [(0, 1, 99)]),
        # attacks on the glTF importer's node walk and file access
        "self_child.gltf": tri_gltf(tri, nodes=[{"mesh": 0, "children": [0]}]),
        "cycle.gltf": tri_gltf(tri, nodes=[{"mesh": 0, "children": [1]}, {"children": [0]}]),
        "deep_nodes.gltf": tri_gltf(tri, nodes=[{"mesh": 0, "children": [i + 1]} for i in range(100)] + [{}]),
        "dev_zero.gltf": tri_gltf(tri, uri="/dev/zero"),
        "climbs_out.gltf": tri_gltf(tri, uri="../../../../../../etc/hostname"),
        "unsupported.dae": b"<?xml version=\"1.0\"?><COLLADA></COLLADA>\n",
    }
    for name, data in files.items():
        (out / name).write_bytes(data)


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
    write_hostile(out / "hostile")


if __name__ == "__main__":
    main()
