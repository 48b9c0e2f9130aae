#!/usr/bin/env python3
"""Writes the scenes of scripts/bench-hostile.sh's content cases, each with a twin whose polygons
are the same but spread apart in depth (every triangle on a plane of its own), the frame that a
crowd of coplanar polygons is measured against:

  coplanar.json         8,000 triangles 1 cm across in one plane, 27 deep (decals over decals)
  coplanar-spread.json  the same triangles, each 0.01 mm behind the one before
  stacked.json          10 overlapping triangles 10 cm across, placed 20 times 1 mm apart in depth
  stacked-spread.json   the same 200 triangles, each 1 mm behind the one before
  copies.json           10,000 named objects of one quad, all at one place (a mesh placed
                        10,000 times, as an update that moves every object to one spot leaves it)

Every scene is seen from the origin looking along -z (camera 0,0,0,0,0,0): the coplanar patch
lies 0.15 m away, the stacks 1 m away, the copies 2 m away.

    tests/bench/make_hostile_scenes.py OUT_DIR
"""
import json
import math
import os
import random
import sys

COLOURS = 8


def scene(name, triangles):
    """Unlit triangles, each with one of a few flat colours, in scene order."""
    materials = [{"id": "m%d" % i,
                  "base_color": {"r": (37 * i % 255) / 255, "g": (91 * i % 255) / 255,
                                 "b": (53 * i % 255) / 255},
                  "unlit": True} for i in range(COLOURS)]
    polygons = [{"vertices": [{"x": x, "y": y, "z": z} for (x, y, z) in t],
                 "material_id": "m%d" % (k % COLOURS)} for k, t in enumerate(triangles)]
    return {"name": name, "sky": {"r": 0.5, "g": 0.7, "b": 0.9}, "materials": materials,
            "meshes": [{"id": "triangles", "polygons": polygons}]}


def triangle(cx, cy, radius, turn, z):
    """An equilateral triangle (counter-clockwise seen from +z) of circumradius `radius`."""
    return [(cx + radius * math.cos(turn + k * 2 * math.pi / 3),
             cy + radius * math.sin(turn + k * 2 * math.pi / 3), z) for k in range(3)]


def coplanar(spread):
    random.seed(47)
    count, side, depth = 8000, 0.01, 27
    area = math.sqrt(3) / 4 * side * side
    patch = math.sqrt(count * area / depth)  # the square their centres fill, 27 deep
    radius = side / math.sqrt(3)
    triangles = []
    for k in range(count):
        z = -0.15 - (1e-5 * k if spread else 0)
        triangles.append(triangle(random.uniform(-patch / 2, patch / 2),
                                  random.uniform(-patch / 2, patch / 2), radius,
                                  random.uniform(0, 2 * math.pi), z))
    return triangles


def stacked(spread):
    random.seed(48)
    shapes = [(random.uniform(-0.05, 0.05), random.uniform(-0.05, 0.05),
               random.uniform(0, 2 * math.pi)) for _ in range(10)]
    triangles = []
    for layer in range(20):
        for k, (cx, cy, turn) in enumerate(shapes):
            z = -1.0 - 0.001 * (10 * layer + k if spread else layer)
            triangles.append(triangle(cx, cy, 0.1, turn, z))
    return triangles


def copies():
    quad = [{"x": -0.5, "y": -0.4, "z": 0}, {"x": 0.5, "y": -0.4, "z": 0},
            {"x": 0.5, "y": 0.4, "z": 0}, {"x": -0.5, "y": 0.4, "z": 0}]
    objects = [{"mesh_id": "quad", "name": "object%d" % k, "material_id": "m%d" % (k % COLOURS),
                "transform": {"translation": {"x": 0, "y": 0, "z": -2}, "yaw_deg": 0}}
               for k in range(10000)]
    result = scene("copies", [])
    result["meshes"] = [{"id": "quad", "material_id": "m0", "polygons": [{"vertices": quad}]}]
    result["objects"] = objects
    return result


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_hostile_scenes.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    scenes = {
        "coplanar": scene("coplanar", coplanar(False)),
        "coplanar-spread": scene("coplanar-spread", coplanar(True)),
        "stacked": scene("stacked", stacked(False)),
        "stacked-spread": scene("stacked-spread", stacked(True)),
        "copies": copies(),
    }
    for name, content in scenes.items():
        with open(os.path.join(out, name + ".json"), "w") as f:
            json.dump(content, f)


if __name__ == "__main__":
    main()
