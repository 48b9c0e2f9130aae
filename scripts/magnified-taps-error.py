#!/usr/bin/env python3
"""The error of rules for magnified footprints against the pixel box on a photo's bilinear texture.

A magnified footprint (half-axes under a texel) is a parallelogram {s X + t Y : |s|, |t| <= 1}
in texels; the pixel box's value is the mean of the bilinear texture over it (here by 20 x 20
stratified points). Each rule blends bilinear reads of the base and reads of the first copy, the
2 x 2 box (whose kernel is the box of half-width 1 on the bilinear texture, here by 16 x 16
points). For rectangles of half-extents H and L = H / elongation turned by an angle to the
texture's axes, at random positions, this prints the RMS error of each rule as PSNR (peak 1):

  blend   the readings' blend the magnified taps replaced: below sqrt(T) = 1/16 texel the base
          by 1 - H^2 and the first copy by H^2, above 1/8 the first copy by L^2 and two probes of
          the base at +-sqrt(T) along the long side, T = (H^2 - L^2) / (3 (1 - L^2)), faded
          between;
  gauss   the first copy by beta = det S and four base reads at +-M X / sqrt(3) +- M Y / sqrt(3)
          (the Gauss-Legendre grid of the pixel's parallelogram, turned with it), M = f(S),
          f(l)^2 = (l - beta) / ((1 - beta) l), S = X X^T + Y Y^T;
  cross   the first copy by beta = det S and four base reads at +-sqrt(2/3) R e_u and
          +-sqrt(2/3) R e_v, R the symmetric square root of (S - beta I) / (1 - beta): the rule
          texture/aniso_selection.cc (MagnifiedTaps) implements;
  cross with the first copy's weight beta = lambda2 f(lambda1) for other f (lambda1 >= lambda2
          S's eigenvalues; det S = lambda1 lambda2), with --shares.

texture/aniso_selection.cc cites its figures.
Needs numpy and OpenImageIO's Python module (Debian: python3-numpy, python3-openimageio);
about a minute a texture with the defaults.

  /usr/bin/python3 scripts/magnified-taps-error.py [--shares] [--positions N] [IMAGE ...]
"""

import argparse
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data",
                    "raster")
PHOTOS = ["grass_torcs_1024.png", "asphalt_torcs_1024.png", "brick_skimage_1024.png"]
ELONGATIONS = [1.0, 1.15, 1.5, 2.5]
HALF_EXTENTS = [0.3, 0.5, 0.7, 0.85]
ANGLES = [0.0, 22.5, 45.0]


def bilinear_sampler(path):
    pixels = oiio.ImageBuf(path).get_pixels(oiio.FLOAT)
    if pixels is None or pixels.ndim != 3:
        sys.exit(f"{path}: cannot read the image")
    tex = pixels[..., :3].mean(axis=2)
    n_y, n_x = tex.shape

    def bil(u, v):  # texel centres at +0.5, periodic
        x, y = u - 0.5, v - 0.5
        x0, y0 = np.floor(x), np.floor(y)
        fx, fy = x - x0, y - y0
        x0, y0 = x0.astype(int) % n_x, y0.astype(int) % n_y
        x1, y1 = (x0 + 1) % n_x, (y0 + 1) % n_y
        return ((1 - fx) * (1 - fy) * tex[y0, x0] + fx * (1 - fy) * tex[y0, x1] +
                (1 - fx) * fy * tex[y1, x0] + fx * fy * tex[y1, x1])

    return bil, n_x, n_y


def box_mean(bil, cu, cv, X, Y, n):
    s = (np.arange(n) + 0.5) / n * 2 - 1
    total = 0
    for a in s:
        for b in s:
            total = total + bil(cu + a * X[0] + b * Y[0], cv + a * X[1] + b * Y[1])
    return total / (n * n)


def sym_sqrt(S):
    w, V = np.linalg.eigh(S)
    return V @ np.diag(np.sqrt(np.maximum(w, 0))) @ V.T


def psnr(error):
    return 20 * math.log10(1 / math.sqrt(float(np.mean(error ** 2))))


def taps(bil, cu, cv, points):
    return sum(bil(cu + p[0], cv + p[1]) for p in points) / len(points)


def rules(bil, cu, cv, first, base, X, Y, H, L, e1, shares):
    """Each rule's estimate, by name."""
    out = {}
    T = (H * H - L * L) / (3 * (1 - L * L))
    d = math.sqrt(T)
    p = min(1.0, max(0.0, 16 * d - 1))
    probes = taps(bil, cu, cv, [d * e1, -d * e1])
    out["blend"] = ((1 - p) * (1 - H * H) * base + (p * L * L + (1 - p) * H * H) * first +
                    p * (1 - L * L) * probes)
    S = np.outer(X, X) + np.outer(Y, Y)
    beta = float(np.linalg.det(S))
    St = (S - beta * np.eye(2)) / (1 - beta)
    M = sym_sqrt(St) @ np.linalg.inv(sym_sqrt(S))
    A, B = M @ X / math.sqrt(3), M @ Y / math.sqrt(3)
    out["gauss"] = beta * first + (1 - beta) * taps(bil, cu, cv, [A + B, A - B, -A + B, -A - B])
    lambda1, lambda2 = H * H, L * L
    for name, f in shares:
        b = lambda2 * f(lambda1)
        R = sym_sqrt((S - b * np.eye(2)) / (1 - b)) * math.sqrt(2 / 3)
        out[name] = b * first + (1 - b) * taps(bil, cu, cv, [R[:, 0], -R[:, 0], R[:, 1], -R[:, 1]])
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("images", nargs="*", help="photos (default: the three in shared/data)")
    parser.add_argument("--positions", type=int, default=5000, help="random positions a shape")
    parser.add_argument("--shares", action="store_true",
                        help="also the cross rule with other first-copy shares")
    args = parser.parse_args()
    if args.positions < 10:
        sys.exit("--positions: at least 10")
    images = args.images or [os.path.join(DATA, name) for name in PHOTOS]
    shares = [("cross", lambda l1: l1)]
    if args.shares:
        shares += [("cross l1^0.75", lambda l1: l1 ** 0.75), ("cross l1^1.5", lambda l1: l1 ** 1.5),
                   ("cross l1^2", lambda l1: l1 ** 2), ("cross 0.75 l1", lambda l1: 0.75 * l1)]
    rng = np.random.default_rng(1)
    for path in images:
        if not os.path.exists(path):
            sys.exit(f"{path}: no such file")
        bil, n_x, n_y = bilinear_sampler(path)
        cu, cv = rng.uniform(0, n_x, args.positions), rng.uniform(0, n_y, args.positions)
        first = box_mean(bil, cu, cv, np.array([1.0, 0]), np.array([0, 1.0]), 16)
        base = bil(cu, cv)
        names = None
        sums = {}
        print(f"{os.path.basename(path)}: PSNR against the pixel box, by elongation H / L, "
              f"half-extent H and angle (degrees)")
        for elongation in ELONGATIONS:
            for H in HALF_EXTENTS:
                L = H / elongation
                cells = []
                for angle in ANGLES:
                    t = math.radians(angle)
                    e1 = np.array([math.cos(t), math.sin(t)])
                    e2 = np.array([-math.sin(t), math.cos(t)])
                    X, Y = H * e1, L * e2
                    ref = box_mean(bil, cu, cv, X, Y, 20)
                    got = rules(bil, cu, cv, first, base, X, Y, H, L, e1, shares)
                    names = list(got)
                    scores = [psnr(got[n] - ref) for n in names]
                    for n, s in zip(names, scores):
                        sums.setdefault((n, angle), []).append(s)
                    cells.append(f"{angle:4.1f}: " + " ".join(f"{s:6.2f}" for s in scores))
                print(f"  H/L {elongation:4.2f} H {H:4.2f} | " + " | ".join(cells), flush=True)
        print("  rules: " + ", ".join(names))
        for n in names:
            by_angle = [float(np.mean(sums[(n, a)])) for a in ANGLES]
            print(f"  {n:>14}: mean {np.mean(by_angle):6.2f} dB; by angle " +
                  " / ".join(f"{x:.2f}" for x in by_angle))


if __name__ == "__main__":
    main()
