#!/usr/bin/env python3
"""Writes the big concave polygon of the triangulation benchmark: one star-shaped ground polygon
of N vertices (radii 20-35 m at jittered angles around (0, 0, -40)), a checkerboard texture, as
an Aperture scene file.

    tests/bench/make_star_scene.py 200000 /tmp/star200k.json
    build/engine/aperture-render --scene /tmp/star200k.json --camera 0,30,0,0,-45,0 --size 640x480
"""
import json
import math
import random
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_star_scene.py N OUT.json")
    n = int(sys.argv[1])
    random.seed(1)
    vertices = []
    for i in range(n):
        a = 2 * math.pi * (i + random.random()) / n
        r = 20 + 15 * random.random()
        vertices.append({"x": r * math.cos(a), "y": 0, "z": -40 + r * math.sin(a)})
    vertices.reverse()
    scene = {
        "name": "star%d" % n,
        "sky": {"r": 0.5, "g": 0.7, "b": 0.9},
        "textures": [{"id": "checker", "checkerboard": {"size": 256, "cells": 8}}],
        "materials": [{"id": "ground", "texture_id": "checker",
                       "texture_transform": {"repeat_u": 4}}],
        "meshes": [{"id": "star", "material_id": "ground",
                    "polygons": [{"vertices": vertices}]}],
    }
    with open(sys.argv[2], "w") as out:
        json.dump(scene, out)


if __name__ == "__main__":
    main()
