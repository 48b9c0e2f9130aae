#!/usr/bin/env python3
"""Writes the glTF test models of tests/data/models, with the standard library only.

hangar.gltf (+ hangar.bin, checker.png): a ground quad as a triangle strip without indices, and a
textured box (24 vertices, 36 unsigned-short indices, TEXCOORD_0) under a node with translation,
rotation and scale whose child has a matrix; a material with baseColorFactor, an external PNG and
KHR_texture_transform, another untextured; a perspective camera named "gate".
hangar.glb: the same model as one binary file with the PNG embedded in the buffer.
hangar_embedded.gltf: the same again, buffer and PNG as base64 data URIs.

Usage: make_gltf_fixture.py OUT_DIR
"""
import base64
import json
import math
import struct
import sys
import zlib
from pathlib import Path


def png(width, height, pixel):
    rows = b"".join(b"\x00" + b"".join(bytes(pixel(x, y)) for x in range(width))
                    for y in range(height))
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def checker_png():
    # 64 x 64, 8 x 8 cells; the top-left cell red, so that a flipped v shows.
    def pixel(x, y):
        if x < 8 and y < 8:
            return (230, 40, 30)
        return (220, 220, 210) if (x // 8 + y // 8) % 2 == 0 else (40, 60, 90)
    return png(64, 64, pixel)


def box():
    positions, uvs, indices = [], [], []
    faces = [((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0)),
             ((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1))]
    for n, u, v in faces:
        base = len(positions)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            positions.append(tuple(0.5 * (n[i] + su * u[i] + sv * v[i]) for i in range(3)))
            uvs.append(((su + 1) / 2, (1 - sv) / 2))
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, uvs, indices


def main():
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    positions, uvs, indices = box()
    ground = [(-20.0, 0.0, 20.0), (20.0, 0.0, 20.0), (-20.0, 0.0, -20.0), (20.0, 0.0, -20.0)]
    ground_uv = [(0.0, 0.0), (8.0, 0.0), (0.0, 8.0), (8.0, 8.0)]
    blob = bytearray()
    views = []
    def view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        if target:
            views[-1]["target"] = target
        blob.extend(data)
        return len(views) - 1
    pack = lambda fmt, items: b"".join(struct.pack(fmt, *item) for item in items)
    v_pos = view(pack("<3f", positions), 34962)
    v_uv = view(pack("<2f", uvs), 34962)
    v_idx = view(struct.pack("<%dH" % len(indices), *indices), 34963)
    v_gpos = view(pack("<3f", ground), 34962)
    v_guv = view(pack("<2f", ground_uv), 34962)
    def bounds(items):
        return ([min(p[i] for p in items) for i in range(3)],
                [max(p[i] for p in items) for i in range(3)])
    lo, hi = bounds(positions)
    glo, ghi = bounds(ground)
    accessors = [
        {"bufferView": v_pos, "componentType": 5126, "count": len(positions), "type": "VEC3",
         "min": lo, "max": hi},
        {"bufferView": v_uv, "componentType": 5126, "count": len(uvs), "type": "VEC2"},
        {"bufferView": v_idx, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        {"bufferView": v_gpos, "componentType": 5126, "count": 4, "type": "VEC3", "min": glo,
         "max": ghi},
        {"bufferView": v_guv, "componentType": 5126, "count": 4, "type": "VEC2"},
    ]
    half = math.radians(30) / 2
    tilt = math.radians(-5) / 2
    model = {
        "asset": {"version": "2.0", "generator": "aperture tests/tools/make_gltf_fixture.py"},
        "extensionsUsed": ["KHR_texture_transform"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 3]}],
        "nodes": [
            {"name": "ground", "mesh": 1},
            {"name": "hangar", "translation": [2.0, 0.0, -10.0],
             "rotation": [0.0, math.sin(half), 0.0, math.cos(half)], "scale": [3.0, 2.0, 4.0],
             "children": [2]},
            {"name": "hall", "mesh": 0,
             "matrix": [1.0, 0, 0, 0, 0, 1.5, 0, 0, 0, 0, 1.0, 0, 0.0, 0.75, 0.0, 1.0]},
            {"name": "gate", "camera": 0, "translation": [0.0, 1.7, 5.0],
             "rotation": [math.sin(tilt), 0.0, 0.0, math.cos(tilt)]},
        ],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.9, "znear": 0.1, "aspectRatio": 1.5}}],
        "meshes": [
            {"name": "box", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1},
                                            "indices": 2, "material": 0}]},
            {"name": "ground", "primitives": [{"attributes": {"POSITION": 3, "TEXCOORD_0": 4},
                                               "mode": 5, "material": 1}]},
        ],
        "materials": [
            {"name": "hall", "pbrMetallicRoughness": {
                "baseColorFactor": [0.9, 0.8, 0.7, 1.0],
                "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {
                    "offset": [0.25, 0.0], "rotation": 0.3, "scale": [2.0, 2.0]}}}}},
            {"name": "grass", "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.5, 0.25, 1.0]}},
        ],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "accessors": accessors,
    }
    texture = checker_png()
    gltf = dict(model, images=[{"uri": "checker.png"}],
                buffers=[{"uri": "hangar.bin", "byteLength": len(blob)}], bufferViews=views)
    (out / "hangar.bin").write_bytes(bytes(blob))
    (out / "checker.png").write_bytes(texture)
    (out / "hangar.gltf").write_text(json.dumps(gltf, indent=1) + "\n")
    data_uri = lambda kind, data: "data:%s;base64,%s" % (kind, base64.b64encode(data).decode())
    embedded = dict(model, images=[{"uri": data_uri("image/png", texture)}],
                    buffers=[{"uri": data_uri("application/octet-stream", bytes(blob)),
                              "byteLength": len(blob)}], bufferViews=views)
    (out / "hangar_embedded.gltf").write_text(json.dumps(embedded) + "\n")
    # The binary form: the PNG in the buffer too.
    v_img = view(texture)
    glb_model = dict(model, images=[{"bufferView": v_img, "mimeType": "image/png"}],
                     buffers=[{"byteLength": len(blob)}], bufferViews=views)
    while len(blob) % 4:
        blob.append(0)
    text = json.dumps(glb_model).encode()
    text += b" " * (-len(text) % 4)
    body = (struct.pack("<II", len(text), 0x4E4F534A) + text +
            struct.pack("<II", len(blob), 0x004E4942) + bytes(blob))
    (out / "hangar.glb").write_bytes(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


if __name__ == "__main__":
    main()
