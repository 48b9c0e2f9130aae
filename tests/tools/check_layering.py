#!/usr/bin/env python3
"""The engine's layers run one way: a folder of engine/ includes only its own folder
and the folders above it in LAYERS, never a later one. Reads every `#include "x/..."` in
engine/<folder>/ (subfolders included) and exits 1 naming each back-edge, 0 when there is none.
Also fails on an engine folder missing from LAYERS, on an edge in FORBIDDEN_EDGES (the installed
tools including the lab's testing/), on engine/ including server/, client/ or tests/, and on any
gRPC header in engine/ (DESIGN.md: the engine is a plain library).

    check_layering.py [--root REPO]     (default: the repository this script is in)

The same table is drawn in docs/ENGINE.md ("Layers"); keep the two in step.
Python 3 standard library only.
"""

import argparse
import os
import re
import sys

# Dependency order, first to last: a folder may include itself and the folders before it.
LAYERS = [
    ("base", "Image, Rgba (base/image.h), PixelRect (base/pixel_rect.h), Stopwatch "
             "(base/stopwatch.h)"),
    ("store", "the shared store: entry files and the shared directory, generic"),
    ("texture", "samplers, prefilters (seed 000 tables, mip-maps, summed-area tables), packed "
                "textures (seed 001), image files, their store entries"),
    ("scene", "the built scene (it holds its textures), builders, built-in scenes, cameras"),
    ("raster", "projection, clipping, Warnock subdivision, exact cell coverage"),
    ("trace", "seed 003's parts: Embree scene, fragments, texture integrals, mappings"),
    ("cost", "the window cost model (seed 002) and the task and region planners"),
    ("render", "the renderers: render/renderer.h (settings, frame, stop test), the raster "
               "renderer (frame_renderer) and the ray tracer (trace_renderer), shading"),
    ("io", "OpenEXR and PNG output, the frame's header"),
    ("frame", "the frame request as the engine's job: every conversion of a RenderFrameRequest "
              "(camera, render options, EXR options) into frame_job, and render_frame_job, the "
              "one entry that renders a job, raster or raytrace"),
    ("testing", "what only tests and benchmarks use: dense references, benchmark scenes, the "
                "scheduling replay, the packed access benchmark (aperture_testing)"),
    ("tools", "the installed command-line tools and what only they use (calibration, arguments): "
              "may include everything but testing/"),
]

# Back-edges allowed anyway, (folder, included folder) -> why. Empty: none is needed.
ALLOWED_BACK_EDGES = {}

# Forward edges refused anyway, (folder, included folder) -> why.
FORBIDDEN_EDGES = {
    ("tools", "testing"): "the installed programs ship no lab code (the benchmarks are "
                          "aperture-bench's, tests/bench/)",
}

# Top-level folders of the repository that engine/ must never include.
FORBIDDEN_TOP_LEVEL = ("server", "client", "tests")

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
ANY_INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')
SOURCE_SUFFIXES = (".h", ".hh", ".hpp", ".cc", ".cpp", ".inc")


def check(root):
    engine = os.path.join(root, "engine")
    if not os.path.isdir(engine):
        return [f"{engine}: no engine/ folder"], 0
    rank = {name: i for i, (name, _) in enumerate(LAYERS)}
    folders = sorted(d for d in os.listdir(engine) if os.path.isdir(os.path.join(engine, d)))
    errors = []
    for folder in folders:
        if folder not in rank:
            errors.append(f"engine/{folder}/: not in the layering table (LAYERS in {__file__})")
    files = 0
    for folder in folders:
        for dirpath, _, names in os.walk(os.path.join(engine, folder)):
            for name in sorted(names):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(dirpath, name)
                files += 1
                shown = os.path.relpath(path, root)
                with open(path, encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        match = ANY_INCLUDE.match(line)
                        if match and "grpc" in match.group(1).lower():
                            errors.append(f"{shown}:{number}: engine/ includes gRPC "
                                          f"({match.group(1)})")
                        match = INCLUDE.match(line)
                        if not match or "/" not in match.group(1):
                            continue
                        target = match.group(1).split("/", 1)[0]
                        if target in FORBIDDEN_TOP_LEVEL:
                            errors.append(f"{shown}:{number}: engine/ includes {target}/ "
                                          f"({match.group(1)})")
                        if target == folder or target not in folders:
                            continue  # its own folder, or not an engine folder (absl/, aperture/)
                        if folder not in rank or target not in rank:
                            continue  # reported above
                        if (folder, target) in FORBIDDEN_EDGES:
                            errors.append(f"{shown}:{number}: {folder}/ includes {target}/ "
                                          f"({match.group(1)}): "
                                          f"{FORBIDDEN_EDGES[(folder, target)]}")
                        if rank[target] > rank[folder] and (
                                (folder, target) not in ALLOWED_BACK_EDGES):
                            errors.append(
                                f"{shown}:{number}: back-edge {folder}/ -> {target}/ "
                                f"({match.group(1)}): {target}/ comes after {folder}/")
    return errors, files


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(__file__), "..", ".."),
                        help="the repository (default: this script's)")
    args = parser.parse_args()
    errors, files = check(os.path.abspath(args.root))
    for error in errors:
        print(error)
    if errors:
        print(f"layering: {len(errors)} violation(s) in {files} files; the layers, first to "
              f"last: {' -> '.join(n for n, _ in LAYERS)}")
        return 1
    print(f"layering: {files} files, no back-edge ({' -> '.join(n for n, _ in LAYERS)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
