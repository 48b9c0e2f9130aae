#!/usr/bin/env python3
"""An independent reading of a glTF 2.0 file (.gltf with external or data-URI buffers) into an
Aperture scene JSON, with the standard library only (json, struct, base64): the reference the
glTF import is compared with, pixel for pixel (tests/tools/gltf_model_test.cc).

It follows the glTF 2.0 specification, not the importer's code: the default scene's nodes depth
first, node matrix or T * R * S, POSITION and TEXCOORD_0 (float), unsigned indices, triangle lists,
strips and fans, baseColorFactor, baseColorTexture with KHR_texture_transform. Arithmetic is in
doubles in the order the formulas are written, so equal inputs give equal bits.

Usage: gltf_to_scene.py MODEL.gltf [--as-mesh ID] > scene.json
(texture files become absolute paths; --as-mesh: every triangle in one mesh ID and no objects,
for a test to place)
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path

COMPONENT = {5120: ("b", 1), 5121: ("B", 1), 5122: ("h", 2), 5123: ("H", 2), 5125: ("I", 4),
             5126: ("f", 4)}
SIZE = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def load_buffers(gltf, folder):
    buffers = []
    for b in gltf["buffers"]:
        uri = b["uri"]
        if uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            buffers.append((folder / uri).read_bytes())
    return buffers


def read_accessor(gltf, buffers, index):
    a = gltf["accessors"][index]
    view = gltf["bufferViews"][a["bufferView"]]
    fmt, size = COMPONENT[a["componentType"]]
    n = SIZE[a["type"]]
    stride = view.get("byteStride", size * n)
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    data = buffers[view["buffer"]]
    return [struct.unpack_from("<%d%s" % (n, fmt), data, start + i * stride)
            for i in range(a["count"])]


def matmul(a, b):  # column-major 4 x 4, sums left to right
    return [((a[r] * b[c * 4] + a[4 + r] * b[c * 4 + 1]) + a[8 + r] * b[c * 4 + 2]) +
            a[12 + r] * b[c * 4 + 3] for c in range(4) for r in range(4)]


def local_matrix(node):
    if "matrix" in node:
        return [float(v) for v in node["matrix"]]
    x, y, z, w = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
    if "rotation" in node:
        norm = math.sqrt(x * x + y * y + z * z + w * w)
        x, y, z, w = x / norm, y / norm, z / norm, w / norm
    sx, sy, sz = node.get("scale", [1.0, 1.0, 1.0])
    tx, ty, tz = node.get("translation", [0.0, 0.0, 0.0])
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    s = [sx, sy, sz]
    m = [0.0] * 16
    for c in range(3):
        for row in range(3):
            m[c * 4 + row] = r[row][c] * s[c]
    m[12], m[13], m[14], m[15] = tx, ty, tz, 1.0
    return m


def apply(m, p):
    return [((m[r] * p[0] + m[4 + r] * p[1]) + m[8 + r] * p[2]) + m[12 + r] for r in range(3)]


def uv_map(info):
    ext = info.get("extensions", {}).get("KHR_texture_transform")
    if not ext:
        return None
    ox, oy = ext.get("offset", [0.0, 0.0])
    sx, sy = ext.get("scale", [1.0, 1.0])
    rot = ext.get("rotation", 0.0)
    c, s = math.cos(rot), math.sin(rot)

    def f(u, v):
        su, sv = u * sx, v * sy
        return (c * su + s * sv) + ox, (-s * su + c * sv) + oy
    return f


def main():
    path = Path(sys.argv[1]).resolve()
    as_mesh = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--as-mesh" else None
    gltf = json.loads(path.read_text())
    buffers = load_buffers(gltf, path.parent)
    scene = {"name": path.stem, "textures": [], "materials": [], "meshes": [], "objects": []}
    maps = []
    images = set()
    for i, m in enumerate(gltf.get("materials", [])):
        pbr = m.get("pbrMetallicRoughness", {})
        out = {"id": "material%d" % i}
        if not m.get("doubleSided", False):
            out["singleSided"] = True
        factor = pbr.get("baseColorFactor")
        info = pbr.get("baseColorTexture")
        if factor:
            out["baseColor"] = {"r": f32(factor[0]), "g": f32(factor[1]), "b": f32(factor[2])}
        elif info:
            out["baseColor"] = {"r": 1.0, "g": 1.0, "b": 1.0}
        mode = m.get("alphaMode", "OPAQUE")
        if mode in ("MASK", "BLEND"):
            out["alphaMode"] = "ALPHA_MODE_" + mode
        if mode == "MASK":
            cutoff = m.get("alphaCutoff", 0.5)
            out["alphaCutoff"] = f32(cutoff) if cutoff > 0 else 1.1754943508222875e-38
        if factor and len(factor) > 3 and factor[3] != 1:
            out["transparency"] = f32(1.0 - factor[3])
        maps.append(uv_map(info) if info else None)
        if info:
            image = gltf["textures"][info["index"]]["source"]
            out["textureId"] = "image%d" % image
            if image not in images:
                images.add(image)
                uri = gltf["images"][image]["uri"]
                if uri.startswith("data:"):  # proto JSON bytes are base64 too
                    scene["textures"].append({"id": "image%d" % image,
                                              "encoded": uri.split(",", 1)[1]})
                else:
                    scene["textures"].append({"id": "image%d" % image,
                                              "file": str(path.parent / uri)})
        scene["materials"].append(out)

    def visit(index, parent):
        node = gltf["nodes"][index]
        world = matmul(parent, local_matrix(node))
        if "mesh" in node:
            mesh_id = "node%d-mesh%d" % (index, node["mesh"])
            polygons = []
            for prim in gltf["meshes"][node["mesh"]]["primitives"]:
                pos = read_accessor(gltf, buffers, prim["attributes"]["POSITION"])
                uvs = (read_accessor(gltf, buffers, prim["attributes"]["TEXCOORD_0"])
                       if "TEXCOORD_0" in prim["attributes"] else None)
                idx = ([i[0] for i in read_accessor(gltf, buffers, prim["indices"])]
                       if "indices" in prim else list(range(len(pos))))
                mode = prim.get("mode", 4)
                if mode == 4:
                    tris = [idx[i:i + 3] for i in range(0, len(idx) - 2, 3)]
                elif mode == 5:
                    tris = [[idx[i], idx[i + 1], idx[i + 2]] if i % 2 == 0 else
                            [idx[i + 1], idx[i], idx[i + 2]] for i in range(len(idx) - 2)]
                elif mode == 6:
                    tris = [[idx[0], idx[i], idx[i + 1]] for i in range(1, len(idx) - 1)]
                else:
                    continue
                material = prim.get("material")
                f = maps[material] if material is not None else None
                m = world
                det = (m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
                       m[8] * (m[1] * m[6] - m[5] * m[2]))
                if det < 0:  # a mirroring transform turns the winding: keep fronts CCW
                    tris = [[t[0], t[2], t[1]] for t in tris]
                for t in tris:
                    poly = {"materialId": "material%d" % material if material is not None
                            else "default",
                            "vertices": [dict(zip("xyz", apply(world, pos[k]))) for k in t]}
                    if uvs is not None:
                        pairs = [(float(uvs[k][0]), float(uvs[k][1])) for k in t]
                        if f:
                            pairs = [f(u, v) for u, v in pairs]
                        poly["uvs"] = [{"u": u, "v": v} for u, v in pairs]
                    polygons.append(poly)
            scene["meshes"].append({"id": mesh_id, "polygons": polygons})
            scene["objects"].append({"meshId": mesh_id})
        for child in node.get("children", []):
            visit(child, world)

    identity = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]
    roots = gltf["scenes"][gltf.get("scene", 0)]["nodes"]
    for root in roots:
        visit(root, identity)
    used = {p["materialId"] for m in scene["meshes"] for p in m["polygons"]}
    if "default" in used:  # the specification's default material: white
        scene["materials"].append({"id": "default", "singleSided": True,
                                   "baseColor": {"r": 1.0, "g": 1.0, "b": 1.0}})
    if as_mesh:
        polygons = [p for m in scene["meshes"] for p in m["polygons"]]
        scene["meshes"] = [{"id": as_mesh, "polygons": polygons}]
        scene["objects"] = []
    json.dump(scene, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
