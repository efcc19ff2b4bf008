"""Runs every case of cases.json twice through `motif curve --fidelity`: with the hand-picked
width and piece length, and with neither (inferred from the exemplar). Prints a Markdown table:
both fidelity figures (mean patch distance, share of broken patches), the size search's score
that combines them (distance × (1 + 4 × broken share)), whether the inferred run is no worse
on the score and on each figure, and the seconds of both runs (the inferred one includes every
trial of the size search).

    python compare_inferred.py MOTIF OUT_DIR [NAME ...]
"""

import json
import subprocess
import sys
from pathlib import Path


def run(motif: str, here: Path, case: dict, out: Path, sizes: list) -> dict:
    cmd = [
        motif, "curve",
        "--exemplar", str(here / case["exemplar"]),
        "--path", str(here / case["path"]),
        "--scale", str(case["scale"]),
        "--variety", str(case.get("variety", 0)),
        "--fidelity",
        "--out", str(out.with_suffix(".png")),
        "--report", str(out.with_suffix(".json")),
        "-q",
    ] + sizes
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"{case['name']}: FAILED: {result.stderr.strip()}")
    return json.loads(out.with_suffix(".json").read_text())


def score(fidelity: dict) -> float:
    """The size search's score (motif_jobs::curve::search::score)."""
    return fidelity["mean_distance"] * (1 + 4 * fidelity["broken_fraction"])


def main() -> None:
    motif, out = sys.argv[1], Path(sys.argv[2])
    names = set(sys.argv[3:])
    here = Path(__file__).resolve().parent
    out.mkdir(parents=True, exist_ok=True)
    print("| case | hand-picked w / δ | inferred w / δ (period) | trials | score hand / inferred "
          "| patch distance hand / inferred | broken hand / inferred | no worse: score / both figures "
          "| seconds hand / inferred |")
    print("|---|---|---|---|---|---|---|---|---|")
    for case in json.loads((here / "cases.json").read_text()):
        name = case["name"]
        if names and name not in names:
            continue
        hand = run(motif, here, case, out / f"{name}_hand",
                   ["--width", str(case["width"]), "--piece-length", str(case["piece_length"])])
        inferred = run(motif, here, case, out / f"{name}_inferred", [])
        fh, fi = hand["fidelity"], inferred["fidelity"]
        both = fi["mean_distance"] <= fh["mean_distance"] and fi["broken_fraction"] <= fh["broken_fraction"]
        sh, si = score(fh), score(fi)
        print(f"| {name} | {case['width']} / {case['piece_length']} | {inferred['width']:g} / "
              f"{inferred['piece_length']:g} ({inferred['pattern_period']}) | {len(inferred['size_search'])} | "
              f"{sh:.5f} / {si:.5f} | {fh['mean_distance']:.4f} / "
              f"{fi['mean_distance']:.4f} | {fh['broken_fraction']:.3f} / {fi['broken_fraction']:.3f} | "
              f"{'yes' if si <= sh else 'no'} / {'yes' if both else 'no'} | "
              f"{hand['total_ms'] / 1000:.1f} / {inferred['total_ms'] / 1000:.1f} |", flush=True)


if __name__ == "__main__":
    main()
