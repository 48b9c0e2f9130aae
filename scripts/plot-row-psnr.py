#!/usr/bin/python3
"""PSNR of each image row against a reference, drawn like aperture-bench filter's _rows.png.

Scores images of one view (for example the EXRs that `aperture-bench filter` writes, from
two builds) against one reference, row by row: the PSNR of the mean squared error over the row's
R, G and B, capped at 60 dB. Draws an 800 x 300 PNG, one line per image in the colour given,
rows from --first-row (left) to the bottom (right), grid every 10 dB from 0 to 60. Prints each
image's mean row PSNR; --csv also writes every row's figures.

  scripts/plot-row-psnr.py --reference ref.exr --first-row 327 --out rows.png \\
      trilinear.exr:2040c0 aniso.exr:d02020

Debian's python3 (/usr/bin/python3) with python3-openimageio and python3-numpy
(scripts/debian-packages.txt).
"""
import argparse
import sys

import numpy as np
import OpenImageIO as oiio

WIDTH, HEIGHT, TOP_DB = 800, 300, 60.0


def read_rgb(path):
    pixels = oiio.ImageBuf(path).get_pixels(oiio.FLOAT)
    if pixels is None or pixels.ndim != 3 or pixels.shape[2] < 3:
        sys.exit(f"plot-row-psnr: {path}: not a readable image with R, G and B")
    return pixels[:, :, :3].astype(np.float64)


def row_psnr(image, reference, first_row):
    mse = ((image - reference) ** 2)[first_row:].mean(axis=(1, 2))
    with np.errstate(divide="ignore"):
        return np.minimum(TOP_DB, -10.0 * np.log10(mse))


def draw(series, path):
    canvas = np.full((HEIGHT, WIDTH, 3), 255, np.uint8)
    to_y = lambda db: (HEIGHT - 1 - np.round(db / TOP_DB * (HEIGHT - 1))).astype(int)
    for db in range(0, int(TOP_DB) + 1, 10):
        canvas[to_y(np.float64(db)), :] = (220, 220, 220)
    for rows, colour in series:
        ys = to_y(rows[np.arange(WIDTH) * len(rows) // WIDTH])
        for x in range(WIDTH):  # a vertical run joins each column to the previous one
            lo, hi = sorted((ys[x], ys[max(x - 1, 0)]))
            canvas[lo:hi + 1, x] = colour
    out = oiio.ImageBuf(oiio.ImageSpec(WIDTH, HEIGHT, 3, oiio.UINT8))
    out.set_pixels(oiio.ROI(0, WIDTH, 0, HEIGHT), canvas)
    if not out.write(path):
        sys.exit(f"plot-row-psnr: {path}: {out.geterror()}")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--reference", required=True, help="the converged reference (EXR)")
    parser.add_argument("--first-row", type=int, default=0, help="first row scored (default 0)")
    parser.add_argument("--out", required=True, help="the PNG to write")
    parser.add_argument("--csv", help="also write row, then each image's PSNR, per row")
    parser.add_argument("images", nargs="+", metavar="IMAGE:RRGGBB",
                        help="an image of the same size and its line's colour in hex")
    args = parser.parse_args()
    reference = read_rgb(args.reference)
    if not 0 <= args.first_row < reference.shape[0]:
        sys.exit(f"plot-row-psnr: --first-row {args.first_row} is outside 0..{reference.shape[0] - 1}")
    series = []
    for spec in args.images:
        path, _, colour = spec.rpartition(":")
        if not path or len(colour) != 6:
            sys.exit(f"plot-row-psnr: {spec}: expected IMAGE:RRGGBB")
        image = read_rgb(path)
        if image.shape != reference.shape:
            sys.exit(f"plot-row-psnr: {path}: {image.shape[1]} x {image.shape[0]}, the reference "
                     f"is {reference.shape[1]} x {reference.shape[0]}")
        rows = row_psnr(image, reference, args.first_row)
        series.append((rows, tuple(int(colour[k:k + 2], 16) for k in (0, 2, 4))))
        print(f"{path}: mean row PSNR {rows.mean():.2f} dB over {len(rows)} rows")
    draw(series, args.out)
    if args.csv:
        table = np.column_stack([np.arange(args.first_row, reference.shape[0])] +
                                [rows for rows, _ in series])
        np.savetxt(args.csv, table, fmt=["%d"] + ["%.3f"] * len(series), delimiter=",",
                   header="row," + ",".join(s.rpartition(":")[0] for s in args.images))


if __name__ == "__main__":
    main()
