"""Checks the exemplars and curves of this folder and writes cases.json.

    python make_manifest.py DIR

Every exemplar must be an RGBA PNG under 100 KB (150 KB for the native-size speed case) with a
transparent background; its pattern height
(rows holding a pixel of alpha > 8, the default --cut-alpha of `motif curve`) must be below the
case's ribbon width. A frieze whose motif fills the strip (opaque pixels in its first and last
rows) gets width = strip height + 16. Every curve must parse: an SVG with one <path>, or a CSV
with header x,y. The notes' timings were measured with `run_cases.py` (see README.md).
"""

import csv
import json
import sys
from pathlib import Path

import numpy as np
from PIL import Image

sys.dont_write_bytecode = True  # no __pycache__ in the data folder
sys.path.insert(0, str(Path(__file__).resolve().parent))
from curves import first_path_d, parse_path  # noqa: E402

CASES = [
    {
        "name": "chain_round_heart",
        "exemplar": "chain_round.png",
        "path": "heart.svg",
        "width": 108,
        "piece_length": 25,
        "kind": "chain of round links (shaded, anti-aliased) on a closed curve with a cusp and a corner",
        "notes": (
            "58 pieces; dp_row_ms median 72-85, total 3.7-4.9 s; valid_fraction 0.072; 9 empty pieces (fold-overs at the cusp and the bottom tip). Output: links chopped into C shapes on the lobes, gaps at the cusp and the tip."
        ),
    },
    {
        "name": "helix_heart",
        "exemplar": "helix.png",
        "path": "heart.svg",
        "width": 134,
        "piece_length": 30,
        "kind": "frieze filling the strip height (double helix) on a closed curve with a cusp and a corner",
        "notes": (
            "48 pieces; dp_row_ms median 109-210, total 5.2-9.8 s; valid_fraction 0.042; 12 empty pieces (cusp and tip). Output: the helix is continuous and clean on both lobes, with gaps at the cusp and the tip."
        ),
    },
    {
        "name": "chain_oval_flourish",
        "exemplar": "chain_oval.png",
        "path": "flourish.svg",
        "width": 140,
        "piece_length": 40,
        "kind": "chain of long (oval) links, three links only, on a hand-drawn open curve",
        "notes": (
            "36 pieces; dp_row_ms median 173-214, total 6.2-7.8 s; valid_fraction 0.099; no empty piece. Piece length 40, not 20-30: at 20 and 30 the links came out chopped and merged almost everywhere. Output: a clean chain of interlocked links along the middle; on the tight curl at the end the link outlines merge into one garbled band."
        ),
    },
    {
        "name": "fretwork_flourish",
        "exemplar": "fretwork.png",
        "path": "flourish.svg",
        "width": 116,
        "piece_length": 35,
        "kind": "openwork frieze filling the strip height (hand-traced lattice, mostly opaque) on a hand-drawn open curve",
        "notes": (
            "41 pieces; dp_row_ms median 65-69, total 2.8-3.0 s; valid_fraction 0.044; no empty piece. Piece length 35: at 25 the optimum repeated a sliver of the bars between two tiles along most of the curve. Output: reads as fretwork, but the lattice is rearranged and many seams show."
        ),
    },
    {
        "name": "filigree_flourish",
        "exemplar": "filigree.png",
        "path": "flourish.svg",
        "width": 132,
        "piece_length": 30,
        "kind": "lace / filigree frieze filling the strip height, with translucent glows (semi-transparent pixels) on a hand-drawn open curve",
        "notes": (
            "48 pieces; dp_row_ms median 293-360, total 13-20 s (the slowest case); valid_fraction 0.045; no empty piece. Output: a dense filigree band, pinwheels along the middle; the texture hides most seams."
        ),
    },
    {
        "name": "rope_rhine",
        "exemplar": "rope.png",
        "path": "rhine.csv",
        "width": 72,
        "piece_length": 25,
        "kind": "twisted rope on a map polyline (the Rhine from Basel to the delta)",
        "notes": (
            "48 pieces; dp_row_ms median 15-20, total 0.8-1.2 s; valid_fraction 0.046; 4 empty pieces at the sharp bend at Bingen. Output: a continuous twisted rope except for the gap at Bingen; some strands are shorter or longer than in the drawing."
        ),
    },
    {
        "name": "vine_letter_s",
        "exemplar": "vine.png",
        "path": "letter_s.svg",
        "width": 62,
        "piece_length": 30,
        "variety": 300,
        "kind": "vine (intertwined stems with leaves, thin) on a glyph outline (closed, with corners)",
        "notes": (
            "59 pieces; dp_row_ms median 25-36, total 1.4-2.1 s; valid_fraction 0.131; 2 empty pieces at corners of the terminals of the S. Output: one stem along the outline (the optimum avoids the intertwined part), slightly zigzag at seams, a few leaves; gaps at two corners."
        ),
    },
    {
        "name": "beads_sweep",
        "exemplar": "beads.png",
        "path": "flourish_sweep.svg",
        "width": 44,
        "piece_length": 20,
        "kind": "beads (a row of touching discs, period 40 px) on a short hand-drawn S sweep; small, for tests",
        "notes": (
            "21 pieces; dp_row_ms median 1.3, total 0.05 s; valid_fraction 0.078; no empty piece. Output: clean, evenly spaced beads."
        ),
        "test": True,
    },
    {
        "name": "teeth_sweep",
        "exemplar": "teeth.png",
        "path": "flourish_sweep.svg",
        "width": 68,
        "piece_length": 25,
        "kind": "frieze filling the strip height (a row of triangles, period 50 px) on a short hand-drawn S sweep; small, for tests",
        "notes": (
            "17 pieces; dp_row_ms median 6.6-9.5, total 0.14-0.20 s; valid_fraction 0.131; no empty piece. Output: clean; the triangles turn with the curve, so on the slope one side looks vertical."
        ),
        "test": True,
    },
    {
        "name": "chain_wide_sweep",
        "exemplar": "chain_wide.png",
        "path": "flourish_sweep.svg",
        "width": 140,
        "piece_length": 20,
        "kind": "speed case: round links 344 × 121 (the size of the issue's chain_round_links.png), width 140",
        "notes": "Speed target: at most 60 ms per DP row.",
    },
    {
        "name": "chain_small_sweep",
        "exemplar": "chain_small.png",
        "path": "flourish_sweep.svg",
        "width": 82,
        "piece_length": 24,
        "kind": "speed case: round links 200 × 82 (the paper's first exemplar size), C = 82",
        "notes": "Speed target: at most 15 ms per DP row.",
    },
    {
        "name": "filigree_wide_sweep",
        "exemplar": "filigree_wide.png",
        "path": "flourish_sweep.svg",
        "width": 80,
        "piece_length": 24,
        "kind": "speed case: a lace frieze filling its strip, 325 × 64 (the paper's second exemplar size), width 80",
        "notes": "Speed target: at most 100 ms per DP row.",
    },
    {
        "name": "chain_dense_sweep",
        "exemplar": "chain_dense.png",
        "path": "flourish_sweep.svg",
        "width": 124,
        "piece_length": 20,
        "kind": "hard speed case: a densely drawn chain of small round links, 200 × 82, on a ribbon wide enough to leave 27 % of the positions valid",
        "notes": "Speed target (issue 34): at most 15 ms per DP row.",
    },
    {
        "name": "chain_large_flourish",
        "exemplar": "chain_large.png",
        "path": "flourish.svg",
        "width": 92,
        "piece_length": 14.3,
        "scale": 2.5,
        "max_bytes": 150_000,
        "kind": "hard speed case: the round-link chain at a native 600 × 250 (C = 230) in 100 pieces along the flourish",
        "notes": "Speed target (issue 34): at most 60 ms per DP row and 10 s in all.",
    },
]


def check_exemplar(path: Path, max_bytes: int = 100_000):
    if path.stat().st_size > max_bytes:
        raise SystemExit(f"{path.name}: {path.stat().st_size} bytes, over {max_bytes // 1000} KB")
    im = Image.open(path)
    if im.mode != "RGBA":
        raise SystemExit(f"{path.name}: mode {im.mode}, expected RGBA")
    a = np.asarray(im)[..., 3]
    rows = np.nonzero((a > 8).any(axis=1))[0]
    pattern_height = int(rows[-1] - rows[0] + 1)
    fills = bool((a[0] >= 128).any() and (a[-1] >= 128).any())
    if (a == 0).mean() < 0.2:
        raise SystemExit(f"{path.name}: under 20 % transparent pixels")
    return im.size, pattern_height, fills


def check_curve(path: Path) -> bool:
    """Returns whether the curve is closed."""
    if path.suffix == ".csv":
        with path.open() as fh:
            rows = list(csv.reader(fh))
        if rows[0] != ["x", "y"] or len(rows) < 3:
            raise SystemExit(f"{path.name}: expected a header x,y and points")
        pts = [(float(x), float(y)) for x, y in rows[1:]]
        return pts[0] == pts[-1]
    sub = parse_path(first_path_d(path))[0]
    if path.read_text().count("<path") != 1:
        raise SystemExit(f"{path.name}: expected exactly one <path>")
    return sub[2]


def main() -> None:
    here = Path(sys.argv[1])
    out = []
    for case in CASES:
        size, pattern_height, fills = check_exemplar(here / case["exemplar"], case.get("max_bytes", 100_000))
        closed = check_curve(here / case["path"])
        scale = case.get("scale", 1.0)
        if case["width"] * scale <= pattern_height:
            raise SystemExit(f"{case['name']}: width × scale {case['width'] * scale} <= pattern height {pattern_height}")
        if fills and case["width"] * scale != size[1] + 16:
            raise SystemExit(f"{case['name']}: a frieze filling its strip wants width = {size[1]} + 16")
        out.append(
            {
                "name": case["name"],
                "exemplar": case["exemplar"],
                "path": case["path"],
                "width": case["width"],
                "piece_length": case["piece_length"],
                "scale": scale,
                "variety": case.get("variety", 0),
                "kind": case["kind"],
                "exemplar_size": list(size),
                "pattern_height": pattern_height,
                "fills_height": fills,
                "closed": closed,
                "test": case.get("test", False),
                "notes": case["notes"],
            }
        )
    (here / "cases.json").write_text(json.dumps(out, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    print(f"cases.json: {len(out)} cases")


if __name__ == "__main__":
    main()
