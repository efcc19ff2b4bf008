"""Figures of the Python package for docs/performance.md.

Usage: python python/bench.py DEMO_FOLDER [--quick]

DEMO_FOLDER is the output of `motif demo` (its map guides and crayon style). Prints JSON:
1. the overhead of a Python call against the `motif` CLI on the same work (texture 512² from a
   real photo, and the demo's map stylization), median of 5 runs each;
2. a 2048 × 2048 map (the demo's target map scaled up 8×, nearest neighbour) stylized in one piece
   and in 512² tiles on a LocalCluster of 2 single-thread workers: times, difference and seams.
Run it on a quiet machine; nothing else should be building.
"""

import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import motif
import motif.batch

ROOT = pathlib.Path(__file__).resolve().parents[1]
BINARY = pathlib.Path(os.environ.get("MOTIF_BIN", ROOT / "target" / "release" / "motif"))


def median_seconds(work, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        work()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times), max(times)


def cli_seconds(arguments, repeats, folder):
    def run():
        subprocess.run([str(BINARY), "--quiet", *arguments], cwd=folder, check=True)

    return median_seconds(run, repeats)


def main():
    demo = pathlib.Path(sys.argv[1])
    quick = "--quick" in sys.argv
    repeats = 2 if quick else 5
    figures = {}
    with tempfile.TemporaryDirectory() as folder:
        photo = motif.read_image(str(ROOT / "data" / "real" / "points" / "chain_contours_source.png"))
        exemplar = np.ascontiguousarray(photo[40:168, 40:168, :3])
        motif.write_png(os.path.join(folder, "exemplar.png"), exemplar)
        python = median_seconds(lambda: motif.texture(exemplar, (512, 512), seed=1), repeats)
        cli = cli_seconds(["texture", "--exemplar", "exemplar.png", "--size", "512x512", "--out", "t.png"], repeats, folder)
        figures["texture_512"] = {"python_s": python, "cli_s": cli, "overhead": python[0] / cli[0] - 1.0}
        style, source, target = (motif.read_image(str(demo / f"stylize-{n}.png")) for n in ("A1", "A", "B"))
        python = median_seconds(lambda: motif.stylize(style, [(source, target)], seed=1), repeats)
        arguments = ["stylize", "--style", str(demo / "stylize-A1.png"), "--guide", str(demo / "stylize-A.png")]
        cli = cli_seconds(arguments + [str(demo / "stylize-B.png"), "--out", "s.png"], repeats, folder)
        figures["stylize_demo_map"] = {"python_s": python, "cli_s": cli, "overhead": python[0] / cli[0] - 1.0}

    factor = 4 if quick else 8
    big_target = np.repeat(np.repeat(target, factor, axis=0), factor, axis=1)[: 256 * factor, : 256 * factor]
    big_target = np.ascontiguousarray(np.pad(big_target, ((0, 256 * factor - big_target.shape[0]), (0, 256 * factor - big_target.shape[1]), (0, 0)), mode="edge"))
    start = time.perf_counter()
    one = motif.stylize(style, [(source, big_target)], seed=1)
    one_s = time.perf_counter() - start
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(cluster)
    start = time.perf_counter()
    tiled = motif.batch.stylize_tiles(style, [(source, big_target)], tile=512, client=client, seed=1)
    tiled_s = time.perf_counter() - start
    client.close()
    cluster.close()
    other = motif.stylize(style, [(source, big_target)], seed=2)
    difference = lambda a, b: float(np.abs(a[16:-16, 16:-16, :3].astype(float) - b[16:-16, 16:-16, :3].astype(float)).mean())
    figures["tiled_map"] = {
        "size": list(big_target.shape[:2]),
        "one_piece_s": one_s,
        "tiled_2_workers_s": tiled_s,
        "tiled_to_one_piece": difference(tiled, one),
        "seed_to_seed": difference(other, one),
        "seam_error_tiled": motif.batch.seam_error(tiled, 512),
        "seam_error_one_piece": motif.batch.seam_error(one, 512),
    }
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
