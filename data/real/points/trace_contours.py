"""Traces the alpha = 128 iso-line of a real drawing into points with outward normals.

Usage: python trace_contours.py RENDERED.png OUTDIR

RENDERED.png is openclipart's "Gold Chain of Round Links" (Jonadab, public domain;
Debian package openclipart-svg, signs_and_symbols/money/gold_chain_of_round_lin_01.svg)
rendered by `rsvg-convert -w 220 -h 220` (see build.sh): a diagonal chain of six round links,
each about 60 px across. This script

1. crops the 200 x 200 px window whose top-left pixel is (CROP_X, CROP_Y) and saves it as
   OUTDIR/chain_contours_source.png (what was traced);
2. finds the alpha = 128 iso-lines of the crop by marching squares (skimage.measure.find_contours);
3. resamples every iso-line at equal steps of about STEP (1.75) px of arc length;
4. gives each point the unit normal of the iso-line that points out of the drawing (towards
   lower alpha), and writes OUTDIR/chain_contours.csv with columns x,y,nx,ny.

Coordinates are pixels with y pointing down (y = row), pixel (c, r) covering [c, c+1] x [r, r+1],
so the window is [0, 200] x [0, 200]. Needs numpy, Pillow and scikit-image.
"""

import os
import sys

import numpy as np
from PIL import Image
from skimage.measure import find_contours

CROP_X, CROP_Y, SIZE = 2, 2, 200
LEVEL = 128.0
STEP = 1.75


def bilinear(img, x, y):
    """img sampled at pixel-centre coordinates (x = col, y = row), clamped to the image."""
    h, w = img.shape
    x = np.clip(x, 0.0, w - 1.0)
    y = np.clip(y, 0.0, h - 1.0)
    x0 = np.minimum(np.floor(x).astype(int), w - 2)
    y0 = np.minimum(np.floor(y).astype(int), h - 2)
    fx, fy = x - x0, y - y0
    return (img[y0, x0] * (1 - fx) * (1 - fy) + img[y0, x0 + 1] * fx * (1 - fy)
            + img[y0 + 1, x0] * (1 - fx) * fy + img[y0 + 1, x0 + 1] * fx * fy)


def at_arclength(poly, cum, s):
    """Points of the polyline poly (cumulative length cum) at arc lengths s."""
    i = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(poly) - 2)
    seg = cum[i + 1] - cum[i]
    t = np.where(seg > 0, (s - cum[i]) / np.where(seg > 0, seg, 1.0), 0.0)
    return poly[i] + (poly[i + 1] - poly[i]) * t[:, None]


def main():
    rendered, outdir = sys.argv[1], sys.argv[2]
    img = Image.open(rendered).convert("RGBA")
    crop = img.crop((CROP_X, CROP_Y, CROP_X + SIZE, CROP_Y + SIZE))
    crop.save(os.path.join(outdir, "chain_contours_source.png"), optimize=True)
    alpha = np.asarray(crop, dtype=np.float64)[:, :, 3]

    rows = []
    agree = total = 0
    for c in find_contours(alpha, LEVEL):
        poly = c[:, ::-1].copy()  # (x = col, y = row), pixel-centre coordinates
        closed = np.allclose(poly[0], poly[-1])
        cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(poly, axis=0).T))])
        length = cum[-1]
        if length < 2 * STEP:
            continue
        n = max(3, int(round(length / STEP)))
        if closed:
            s = np.arange(n) * (length / n)
            ahead, behind = (s + 1.0) % length, (s - 1.0) % length
        else:
            s = np.arange(n + 1) * (length / n)
            ahead, behind = np.minimum(s + 1.0, length), np.maximum(s - 1.0, 0.0)
        p = at_arclength(poly, cum, s)
        tang = at_arclength(poly, cum, ahead) - at_arclength(poly, cum, behind)
        tang /= np.linalg.norm(tang, axis=1)[:, None]
        normal = np.stack([tang[:, 1], -tang[:, 0]], axis=1)
        # Outward = towards lower alpha. One side for the whole iso-line (it is a simple curve),
        # chosen by the majority of the points.
        drop = (bilinear(alpha, *(p + normal).T) - bilinear(alpha, *(p - normal).T))
        if np.sum(drop < 0) < np.sum(drop > 0):
            normal = -normal
            drop = -drop
        agree += int(np.sum(drop < 0))
        total += len(p)
        xy = p + 0.5  # pixel centres -> continuous window coordinates
        for (x, y), (nx, ny) in zip(xy, normal):
            rows.append(f"{x:.3f},{y:.3f},{nx:.4f},{ny:.4f}")

    with open(os.path.join(outdir, "chain_contours.csv"), "w", newline="\n") as f:
        f.write("x,y,nx,ny\n")
        f.write("\n".join(rows) + "\n")
    print(f"chain_contours: {total} points, normals pointing to lower alpha at {agree}/{total}")
    if agree < 0.98 * total:
        sys.exit("chain_contours: outward normals disagree with the alpha gradient")


if __name__ == "__main__":
    main()
