"""Runs every case of cases.json through `motif curve` and prints its figures.

    python run_cases.py MOTIF OUT_DIR [NAME ...]

For each case (or only the named ones) it runs
    MOTIF curve --exemplar E --path P --width W --piece-length D --scale S \
        --out OUT_DIR/NAME.png --report OUT_DIR/NAME.json -q
and prints pieces, the median DP row time, the total time, the valid fraction, the empty pieces
and the warnings from the report. Not part of build.sh: it checks the corpus, it does not make it.
"""

import json
import subprocess
import sys
from pathlib import Path


def main() -> None:
    motif, out = sys.argv[1], Path(sys.argv[2])
    names = set(sys.argv[3:])
    here = Path(__file__).resolve().parent
    out.mkdir(parents=True, exist_ok=True)
    failed = 0
    for case in json.loads((here / "cases.json").read_text()):
        if names and case["name"] not in names:
            continue
        name = case["name"]
        cmd = [
            motif, "curve",
            "--exemplar", str(here / case["exemplar"]),
            "--path", str(here / case["path"]),
            "--width", str(case["width"]),
            "--piece-length", str(case["piece_length"]),
            "--scale", str(case["scale"]),
            "--out", str(out / f"{name}.png"),
            "--report", str(out / f"{name}.json"),
            "-q",
        ]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"{name}: FAILED: {r.stderr.strip()}")
            failed += 1
            continue
        rep = json.loads((out / f"{name}.json").read_text())
        print(
            f"{name}: {case['exemplar']} {case['exemplar_size'][0]}x{case['exemplar_size'][1]} on {case['path']}, "
            f"width {case['width']}, piece length {case['piece_length']}: {rep['pieces']} pieces, "
            f"dp_row_ms median {rep['dp_row_ms']['median']:.1f} (max {rep['dp_row_ms']['max']:.1f}), "
            f"total {rep['total_ms'] / 1000:.2f} s, valid_fraction {rep['valid_fraction']:.4f}, "
            f"empty pieces {rep.get('empty_pieces', 0)}"
            + (f", warnings: {'; '.join(rep['warnings'])}" if rep.get("warnings") else "")
        )
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
