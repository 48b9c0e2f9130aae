#!/usr/bin/env python3
"""The L2 distance between a seed 000 copy's kernel and the pixel's box, in one dimension.

A copy of half-extent c is read by bilinear interpolation between texels c apart: its kernel is
the box of half-width c (height 1 / 2c) convolved with the tent of half-width c (area 1). For a
long aperture the pixel's box on the bilinear base is, up to a tent of one texel that is then
negligible, the box of half-width 1 (height 1/2). Prints, for copy extents c, the L2 distance of
the kernels (the error on white noise), the L2 distance of their integrals (the error on an
edge: a step's spectrum falls as 1/f, so its power as 1/f^2) and the kernel's variance (the
box's is 1/3). texture/aniso_selection.h (CopyExtent) cites these figures.
Pure Python, a few seconds.
"""

STEP = 0.004
N = int(3 / STEP)
XS = [i * STEP for i in range(-N, N + 1)]
BOX = [0.5 if abs(x) <= 1 else 0.0 for x in XS]


def copy_kernel(c):
    half = int(c / STEP)
    tent = [max(0.0, 1 - abs(j * STEP) / c) / c for j in range(-half, half + 1)]
    box = [0.5 / c if abs(x) <= c else 0.0 for x in XS]
    out = [0.0] * len(XS)
    for i in range(len(XS)):
        total = 0.0
        for j, t in enumerate(tent):
            k = i + j - half
            if 0 <= k < len(XS):
                total += box[k] * t
        out[i] = total * STEP
    return out


def integral(f):
    out, total = [], 0.0
    for v in f:
        total += v * STEP
        out.append(total)
    return out


def main():
    box_integral = integral(BOX)
    print("| c | white noise | edge | variance |")
    print("|---:|---:|---:|---:|")
    for c in (1.0, 0.95, 0.9, 0.85, 0.8165, 0.8, 0.75, 0.7):
        k = copy_kernel(c)
        flat = sum((a - b) ** 2 for a, b in zip(k, BOX)) * STEP
        edge = sum((a - b) ** 2 for a, b in zip(integral(k), box_integral)) * STEP
        variance = sum(v * x * x for v, x in zip(k, XS)) * STEP
        print(f"| {c:.4f} | {flat:.4f} | {edge:.5f} | {variance:.3f} |")


if __name__ == "__main__":
    main()
