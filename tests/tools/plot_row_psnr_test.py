#!/usr/bin/python3
"""scripts/plot-row-psnr.py against analytic figures: an image off its reference by 0.01 on one
row scores 40 dB there and the 60 dB cap elsewhere; the PNG is written at 800 x 300; a size
mismatch, an unreadable image and a bad colour each exit 1 naming the problem and write no PNG.
Debian's python3 with python3-openimageio and python3-numpy."""
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "plot-row-psnr.py")


def write_exr(path, pixels):
    h, w, c = pixels.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(0, w, 0, h), pixels.astype(np.float32))
    assert buf.write(path), buf.geterror()


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


def expect(condition, message):
    if not condition:
        print(f"FAIL: {message}")
        sys.exit(1)


with tempfile.TemporaryDirectory() as tmp:
    ref = np.full((6, 8, 3), 0.5)
    off = ref.copy()
    off[3] += 0.01  # row 3: MSE 1e-4, 40 dB
    paths = {name: os.path.join(tmp, name) for name in
             ("ref.exr", "off.exr", "small.exr", "rows.png", "rows.csv", "bad.png")}
    write_exr(paths["ref.exr"], ref)
    write_exr(paths["off.exr"], off)
    write_exr(paths["small.exr"], ref[:4])

    r = run("--reference", paths["ref.exr"], "--first-row", "1", "--out", paths["rows.png"],
            "--csv", paths["rows.csv"], paths["off.exr"] + ":d02020")
    expect(r.returncode == 0, f"a good run failed: {r.stderr}")
    table = np.loadtxt(paths["rows.csv"], delimiter=",")
    expect(list(table[:, 0]) == [1, 2, 3, 4, 5], f"rows {table[:, 0]}, expected 1..5")
    expected = [60, 60, 40, 60, 60]
    expect(np.allclose(table[:, 1], expected, atol=1e-3), f"PSNR {table[:, 1]}, expected {expected}")
    expect("mean row PSNR 56.00 dB over 5 rows" in r.stdout, f"summary: {r.stdout}")
    spec = oiio.ImageInput.open(paths["rows.png"]).spec()
    expect((spec.width, spec.height) == (800, 300), f"PNG {spec.width} x {spec.height}")

    for args, said in (
        ([paths["small.exr"] + ":ffffff"], "8 x 4, the reference is 8 x 6"),
        ([os.path.join(tmp, "missing.exr") + ":ffffff"], "not a readable image"),
        ([paths["off.exr"] + ":fff"], "expected IMAGE:RRGGBB"),
    ):
        r = run("--reference", paths["ref.exr"], "--out", paths["bad.png"], *args)
        expect(r.returncode == 1 and said in r.stderr, f"{args}: rc {r.returncode}, {r.stderr!r}")
        expect(not os.path.exists(paths["bad.png"]), f"{args}: wrote a PNG anyway")
print("plot-row-psnr: analytic rows, PNG size and three bad inputs checked")
