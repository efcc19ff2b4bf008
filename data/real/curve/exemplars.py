"""Cuts the rendered exemplar drawings of the curve corpus into horizontal strips.

    python exemplars.py RENDER_DIR OUT_DIR [NAME ...]

RENDER_DIR holds the PNG renderings made by build.sh (rsvg-convert), one per exemplar, named
`<name>.png`; this script crops, rotates (bicubic) and crops again as the table STRIPS says and
writes `<OUT_DIR>/<name>.png` (RGBA, straight alpha, fully transparent pixels black, Pillow's
default zlib settings: byte-identical for the same Pillow version). build.sh holds the sources and
rendering widths; README.md repeats both tables.
"""

import sys
from pathlib import Path

import numpy as np
from PIL import Image

# name: (crop box before rotating or None, rotation in degrees counter-clockwise (Pillow's
#        rotate, bicubic, expand=True), crop box (left, top, right, bottom) after rotating)
STRIPS = {
    "chain_round": (None, 43.2, (38, 165, 359, 260)),
    "chain_oval": (None, -37.7, (34, 144, 348, 271)),
    "rope": ((1200, 20, 1350, 300), 86.7, (40, 46, 268, 122)),
    "vine": (None, 0.0, (180, 32, 470, 86)),
    "beads": (None, 0.0, (0, 0, 200, 40)),
    "helix": (None, 0.0, (0, 81, 320, 199)),
    "fretwork": (None, 0.0, (10, 25, 290, 125)),
    "filigree": (None, 0.0, (270, 393, 610, 509)),
    "teeth": (None, 0.0, (0, 0, 200, 52)),
    # The speed cases of `motif bench` (the sizes the curve issue names).
    "chain_wide": (None, 43.2, (51, 223, 395, 344)),
    "chain_small": (None, 43.2, (33, 142, 233, 224)),
    "filigree_wide": (None, 0.0, (138, 220, 463, 284)),
    # The hard speed cases (issue 34): a densely drawn chain of small links, where a wide ribbon
    # leaves over 20 % of the positions valid, and the round-link chain at its native size.
    "chain_dense": (None, 0.0, (350, 262, 550, 344)),
    "chain_large": (None, 43.2, (110, 370, 710, 620)),
}


def strip(src: Path, before, angle: float, box) -> Image.Image:
    im = Image.open(src).convert("RGBA")
    if before is not None:
        im = im.crop(before)
    if angle:
        # Rotate premultiplied colour ("RGBa") so that transparent pixels' colour does not bleed in.
        im = im.convert("RGBa").rotate(angle, resample=Image.Resampling.BICUBIC, expand=True).convert("RGBA")
    if box is not None:
        im = im.crop(box)
    # Fully transparent pixels get colour 0 (their colour is meaningless; this keeps the bytes stable).
    a = np.asarray(im).copy()
    a[a[..., 3] == 0] = 0
    return Image.fromarray(a)


def main() -> None:
    render, out = Path(sys.argv[1]), Path(sys.argv[2])
    names = sys.argv[3:] or list(STRIPS)
    for name in names:
        before, angle, box = STRIPS[name]
        im = strip(render / f"{name}.png", before, angle, box)
        im.save(out / f"{name}.png", optimize=False)
        print(f"{name}: {im.size[0]} x {im.size[1]}, bbox {im.getbbox()}")


if __name__ == "__main__":
    main()
