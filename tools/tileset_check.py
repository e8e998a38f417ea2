#!/usr/bin/env python3
"""tools/tileset_check.py TILESET.json: checks a 3D Tiles 1.1 tileset without the network.

1. The JSON against the 3D Tiles 1.1 JSON schema (tools/3d-tiles-schema, Draft 2020-12, with
   python3-jsonschema).
2. What the schema cannot say, as the 3D Tiles specification does: the root has "refine"; a
   tile's geometricError is not above its parent's, nor the root's above the tileset's; refine
   is ADD or REPLACE (the schema lets any string through); every content URI is a file next to
   tileset.json.
3. Bounding volumes (boxes: relief writes no other kind): every child's box lies inside its
   parent's, and a glb content's vertices (the POSITION accessors' min/max, through the node
   transforms, glTF y-up turned to the tileset's z-up) inside its tile's box.
Prints one line per problem and a summary; exit 0 when there is none, 1 when there is one.
"""
import json
import os
import struct
import sys

import warnings

from jsonschema import Draft202012Validator

with warnings.catch_warnings():  # deprecated since jsonschema 4.18 (Debian 12 has 4.10), still there
    warnings.simplefilter("ignore", DeprecationWarning)
    from jsonschema import RefResolver

HERE = os.path.dirname(os.path.abspath(__file__))
SCHEMA_DIR = os.path.join(HERE, "3d-tiles-schema")
TOL = 1e-6  # metres

# glTF y-up to the tile's z-up (3D Tiles 1.1, "glTF transforms"): (x, y, z) -> (x, -z, y).
Y_UP_TO_Z_UP = [[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]]


# 3-vectors and 4 x 4 matrices as lists (no numpy: the test may run a Python without it).
def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def scale(a, s):
    return [x * s for x in a]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def transform(m, p):
    return [sum(m[i][k] * v for k, v in enumerate(list(p) + [1.0])) for i in range(3)]


def rounded(p):
    return [round(x, 3) for x in p]


def schema_validator():
    # The schema's "$id"s are bare file names even in subdirectories, which their relative
    # "$ref"s contradict: each file is known by its own path instead.
    store = {}
    for d, _, files in os.walk(SCHEMA_DIR):
        for f in files:
            if f.endswith(".schema.json"):
                path = os.path.join(d, f)
                with open(path) as s:
                    doc = json.load(s)
                doc.pop("$id", None)
                store["file://" + path] = doc
    root_uri = "file://" + os.path.join(SCHEMA_DIR, "tileset.schema.json")
    resolver = RefResolver(base_uri=root_uri, referrer=store[root_uri], store=store)
    return Draft202012Validator(store[root_uri], resolver=resolver)


def box_corners(box):
    c, axes = box[0:3], [box[3 + 3 * i:6 + 3 * i] for i in range(3)]
    return [add(add(add(c, scale(axes[0], sx)), scale(axes[1], sy)), scale(axes[2], sz))
            for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def inside(box, p):
    """Whether point p lies in the oriented box (within TOL)."""
    d = sub(p, box[0:3])
    for i in range(3):
        a = box[3 + 3 * i:6 + 3 * i]
        n2 = dot(a, a)
        if abs(dot(d, a)) > n2 + TOL * n2 ** 0.5:
            return False
    return True


def node_matrix(node):
    if "matrix" in node:
        m = node["matrix"]  # column-major
        return [[m[4 * j + i] for j in range(4)] for i in range(4)]
    x, y, z, w = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
    sx, sy, sz = node.get("scale", [1.0, 1.0, 1.0])
    tx, ty, tz = node.get("translation", [0.0, 0.0, 0.0])
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[0][0] * sx, r[0][1] * sy, r[0][2] * sz, tx], [r[1][0] * sx, r[1][1] * sy, r[1][2] * sz, ty],
            [r[2][0] * sx, r[2][1] * sy, r[2][2] * sz, tz], [0.0, 0.0, 0.0, 1.0]]


def glb_corners(path):
    """The corners of every mesh primitive's POSITION box, in the tile's frame (z up), and the
    number of triangles."""
    with open(path, "rb") as f:
        data = f.read()
    magic, version, _ = struct.unpack("<4sII", data[:12])
    if magic != b"glTF" or version != 2:
        raise ValueError("not a glTF 2.0 binary")
    length, kind = struct.unpack("<II", data[12:20])
    if kind != 0x4E4F534A:
        raise ValueError("first chunk is not JSON")
    gltf = json.loads(data[20:20 + length])
    corners, triangles = [], 0

    def visit(i, parent):
        node = gltf["nodes"][i]
        m = matmul(parent, node_matrix(node))
        if "mesh" in node:
            for prim in gltf["meshes"][node["mesh"]]["primitives"]:
                acc = gltf["accessors"][prim["attributes"]["POSITION"]]
                lo, hi = acc["min"], acc["max"]
                for x in (lo[0], hi[0]):
                    for y in (lo[1], hi[1]):
                        for z in (lo[2], hi[2]):
                            corners.append(transform(m, [x, y, z]))
                nonlocal triangles
                count = gltf["accessors"][prim["indices"]]["count"] if "indices" in prim else acc["count"]
                triangles += count // 3
        for c in node.get("children", []):
            visit(c, m)

    for scene in gltf.get("scenes", []):
        for n in scene.get("nodes", []):
            visit(n, Y_UP_TO_Z_UP)
    return corners, triangles


def main(path):
    with open(path) as f:
        tileset = json.load(f)
    problems = []
    for e in sorted(schema_validator().iter_errors(tileset), key=lambda e: list(e.path)):
        problems.append("schema: /%s: %s" % ("/".join(str(p) for p in e.path), e.message))
    base = os.path.dirname(os.path.abspath(path))
    stats = {"tiles": 0, "contents": 0, "depth": 0}
    root = tileset.get("root", {})
    if "refine" not in root:
        problems.append("root: no refine")
    if root.get("geometricError", 0) > tileset.get("geometricError", 0):
        problems.append("root: geometricError above the tileset's")

    def visit(tile, where, parent_box, parent_error, depth):
        stats["tiles"] += 1
        stats["depth"] = max(stats["depth"], depth)
        if depth > 0 and "transform" in tile:
            problems.append("%s: a transform below the root (not handled by this check)" % where)
        box = tile.get("boundingVolume", {}).get("box")
        if box is None:
            problems.append("%s: no box (this check handles boxes only)" % where)
            return
        if parent_box is not None:
            for p in box_corners(box):
                if not inside(parent_box, p):
                    problems.append("%s: box not inside its parent's (corner %s)" % (where, rounded(p)))
                    break
        if parent_error is not None and tile.get("geometricError", 0) > parent_error:
            problems.append("%s: geometricError %g above its parent's %g" % (where, tile["geometricError"], parent_error))
        if tile.get("refine", "ADD") not in ("ADD", "REPLACE"):
            problems.append("%s: refine %r is neither ADD nor REPLACE" % (where, tile["refine"]))
        if "content" in tile:
            uri = tile["content"].get("uri", "")
            file = os.path.join(base, uri) if isinstance(uri, str) else ""
            if not os.path.isfile(file):
                problems.append("%s: content %s missing" % (where, uri))
            elif uri.endswith(".glb"):
                stats["contents"] += 1
                try:
                    corners, _ = glb_corners(file)
                except (ValueError, KeyError, IndexError, struct.error) as e:
                    problems.append("%s: %s: %s" % (where, uri, e))
                    corners = []
                for p in corners:
                    if not inside(box, p):
                        problems.append("%s: %s has a vertex box corner %s outside the tile's box"
                                        % (where, uri, rounded(p)))
                        break
        for i, child in enumerate(tile.get("children", [])):
            visit(child, "%s/children/%d" % (where, i), box, tile.get("geometricError", 0), depth + 1)

    visit(root, "root", None, None, 0)
    for p in problems:
        print("tileset_check: " + p)
    print(json.dumps({"file": path, "problems": len(problems), "tiles": stats["tiles"], "contents": stats["contents"],
                      "depth": stats["depth"], "geometricError": tileset.get("geometricError")}))
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: tileset_check.py TILESET.json")
    sys.exit(main(sys.argv[1]))
