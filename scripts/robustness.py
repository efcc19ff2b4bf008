#!/usr/bin/env python3
"""Replays the failure classes of issues 13 and 32 against a built `motif` binary and counts outcomes.

Usage: scripts/robustness.py [path/to/motif] [--timeout SECONDS] [--json OUT.json]

Every case runs in a fresh folder with inputs made by `motif demo` (so nothing here is drawn by
hand) plus a few crafted files (a PNG header declaring 16384 x 16384 pixels, a truncated JPEG, a
10 MB one-path SVG, 3 000 stroke paths, ...). Each run is classified as

  clean-error  exit 1, a message on stderr that is not an internal error
  success      exit 0 (only expected where the case says so)
  panic        an internal error, exit 101 or a signal
  hang         still running after the timeout (killed)
  data-loss    an input file (or a previous output, `previous.png`, `zoom-previous/`) changed or
               vanished, in any folder
  leftover     a new `.motif-*.tmp` file, one a case expects removed, or any new file of a failed
               run other than its --report, left behind

and the table of counts is printed (and written as JSON with --json). Every outcome other than
the expected one is listed with its command, so a regression names itself.
"""

import argparse
import hashlib
import json
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def png_with_header(width, height):
    """A PNG whose header declares width x height RGBA pixels but whose data holds one row."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    data = zlib.compress(b"\x00" + b"\x00" * 4 * min(width, 64))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", data) + chunk(b"IEND", b"")


def digest(path):
    with open(path, "rb") as handle:
        return hashlib.sha256(handle.read()).hexdigest()


def files_under(folder):
    """Every file under `folder`, as paths relative to it."""
    names = []
    for root, _, files in os.walk(folder):
        names.extend(os.path.relpath(os.path.join(root, f), folder) for f in files)
    return names


def prepare(folder, binary):
    """Inputs: the demo's files, and crafted ones."""
    subprocess.run([binary, "--quiet", "demo", "--out", folder], check=True, timeout=900)
    # A presynth cache mixing two runs: one texture replaced by another (an interrupted re-run).
    shutil.copytree(os.path.join(folder, "stylize-presynth"), os.path.join(folder, "mixed-presynth"))
    shutil.copy(os.path.join(folder, "mixed-presynth", "segment-2.png"), os.path.join(folder, "mixed-presynth", "segment-1.png"))
    with open(os.path.join(folder, "huge-header.png"), "wb") as handle:
        handle.write(png_with_header(16384, 16384))
    shutil.copy(os.path.join(folder, "huge-header.png"), os.path.join(folder, "huge-0.png"))
    # A real image cut to a third (a JPEG when the demo has none: re-encode is not available, so
    # a PNG cut short stands for a truncated file).
    with open(os.path.join(folder, "texture-exemplar.png"), "rb") as handle:
        data = handle.read()
    with open(os.path.join(folder, "truncated.png"), "wb") as handle:
        handle.write(data[: len(data) // 3])
    # A CSV curve with one coordinate far away.
    with open(os.path.join(folder, "far.csv"), "w") as handle:
        handle.write("x,y\n0,0\n100,10\n1e9,20\n300,0\n")
    # A 10 MB one-path SVG.
    points = " ".join(f"L {i % 997},{(i * 7) % 991}" for i in range(600_000))
    with open(os.path.join(folder, "big.svg"), "w") as handle:
        handle.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="1000" height="1000"><path d="M 0,0 {points}" stroke="black" fill="none"/></svg>')
    # 3 000 short strokes.
    paths = "".join(
        f'<path d="M {i % 60 * 16},{i // 60 * 16} l 8,8" stroke="black" stroke-width="1" fill="none"/>' for i in range(3000)
    )
    with open(os.path.join(folder, "many-strokes.svg"), "w") as handle:
        handle.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="960" height="800">{paths}</svg>')
    # Point sets: one coordinate at 1e300, and a non-integer element column.
    with open(os.path.join(folder, "far-points.csv"), "w") as handle:
        handle.write("x,y\n" + "".join(f"{i % 10},{i // 10}\n" for i in range(99)) + "1e300,5\n")
    # Three points, each nearer the window's border than its nearest neighbour: no counted
    # nearest-neighbour distance for the pair-statistics refinement.
    with open(os.path.join(folder, "three-points.csv"), "w") as handle:
        handle.write("x,y\n0.2,0.2\n1.8,0.2\n1.0,1.8\n")
    with open(os.path.join(folder, "bad-elements.csv"), "w") as handle:
        handle.write("x,y,element\n" + "".join(f"{i % 10},{i // 10},{i / 3}\n" for i in range(100)))
    # One point whose extent overflows the set's area (it looped forever), and a set of doubled points.
    with open(os.path.join(folder, "overflowing-points.csv"), "w") as handle:
        handle.write("x,y\n" + "".join(f"{i % 10},{i // 10}\n" for i in range(99)) + "1e200,-1e200\n")
    with open(os.path.join(folder, "doubled-points.csv"), "w") as handle:
        handle.write("x,y\n" + "".join(f"{i % 10},{i // 10}\n" * 2 for i in range(100)))
    # A 3D sheet with normals and a radius.
    with open(os.path.join(folder, "sheet-normals.csv"), "w") as handle:
        handle.write("x,y,z,nx,ny,nz,radius\n" + "".join(f"{i % 6},{i // 6 % 6},{i // 36},0,0,1,{0.1 + i % 7 / 100}\n" for i in range(216)))
    shutil.copy(os.path.join(ROOT, "crates", "motif-io", "tests", "regressions", "jpeg-cut-before-its-end.jpg"), os.path.join(folder, "truncated.jpg"))
    # Video frames numbered with a gap (the demo's frames, then 0050).
    shutil.copytree(os.path.join(folder, "video-in"), os.path.join(folder, "gap-video"))
    first = sorted(os.listdir(os.path.join(folder, "gap-video")))[0]
    shutil.copy(os.path.join(folder, "gap-video", first), os.path.join(folder, "gap-video", "0050.png"))
    with open(os.path.join(folder, "long-stroke.json"), "w") as handle:
        json.dump([[float(i), 0.0] for i in range(0, 200_001, 1000)], handle)
    # Previous outputs that a failed run must leave as they were (issue 32).
    shutil.copy(os.path.join(folder, "texture-exemplar.png"), os.path.join(folder, "previous.png"))
    os.makedirs(os.path.join(folder, "zoom-previous"))
    for level in (1, 2):
        shutil.copy(os.path.join(folder, "texture-exemplar.png"), os.path.join(folder, "zoom-previous", f"zoom-0{level}.png"))
    # A --debug-dir holding the exemplar under a debug file's name.
    os.makedirs(os.path.join(folder, "debug-in"))
    shutil.copy(os.path.join(folder, "texture-exemplar.png"), os.path.join(folder, "debug-in", "error.png"))
    # A presynth cache whose first texture is a link to a file outside its folder.
    shutil.copytree(os.path.join(folder, "stylize-presynth"), os.path.join(folder, "linked-presynth"))
    os.replace(os.path.join(folder, "linked-presynth", "segment-1.png"), os.path.join(folder, "outside-segment.png"))
    os.symlink(os.path.join("..", "outside-segment.png"), os.path.join(folder, "linked-presynth", "segment-1.png"))
    # Bad files for the sweep of every input of every subcommand (`input_sweep`).
    os.makedirs(os.path.join(folder, "a-folder"))
    open(os.path.join(folder, "empty.bin"), "wb").close()
    with open(os.path.join(folder, "garbage.bin"), "wb") as handle:
        handle.write(bytes((i * 7919 + 13) % 256 for i in range(4096)))
    # The temporary file of a run killed with SIGKILL (its pid above Linux's largest: gone).
    os.makedirs(os.path.join(folder, "stale"))
    stale = os.path.join(folder, "stale", ".motif-999999999-a1b2c3.tmp")
    with open(stale, "w") as handle:
        handle.write("left by a killed run")
    os.utime(stale, (time.time() - 600, time.time() - 600))


CURVE = ["curve", "--exemplar", "curve-chain.png", "--path", "curve-heart.svg", "--width", "40", "--piece-length", "16"]
TEXTURE = ["texture", "--exemplar", "texture-exemplar.png"]
STYLE = ["stylize", "--style", "stylize-A1.png", "--guide", "stylize-A.png", "stylize-B.png"]
POINTS = ["points", "--exemplar", "points-hex.ply", "--neighbourhood", "1.2"]
STROKES = ["strokes", "--reference", "strokes-hatch-reference.svg", "--scale", "6"]

ZOOM = ["zoom", "--exemplar", "texture-exemplar.png", "--size", "64x64", "--levels", "2"]
INPAINT = ["inpaint", "--image", "stylize-A1.png", "--mask", "stylize-A.png"]

# (name, arguments, expected outcome[, files the run must remove]). Outputs are named out*.
CASES = [
    # Inputs are never overwritten.
    ("report names an input", TEXTURE + ["--size", "64x64", "--out", "out.png", "--report", "texture-exemplar.png"], "clean-error"),
    ("stylize report names a guide", STYLE + ["--out", "out.png", "--report", "stylize-B.png"], "clean-error"),
    ("points out names its stroke", POINTS + ["--along", "points-stroke.svg", "--brush-width", "3", "--out", "points-stroke.svg"], "clean-error"),
    ("points out names its region", POINTS + ["--domain", "strokes-blob.svg", "--out", "strokes-blob.svg"], "clean-error"),
    ("presynth folder holds an input", ["presynth", "--style", "stylize-presynth/segment-1.png", "--guide", "stylize-A.png", "--size", "32x32", "--out-dir", "stylize-presynth"], "clean-error"),
    # Failed runs leave nothing.
    ("secondary output into a missing folder", CURVE + ["--out", "out.png", "--pieces", "missing/out.json"], "clean-error"),
    ("preview into a missing folder", POINTS + ["--domain", "box:8,8", "--out", "out.ply", "--preview", "missing/out.png"], "clean-error"),
    ("analysis onto a folder", STROKES + ["--rect", "100,100", "--out", "out.svg", "--analysis", "stylize-debug"], "clean-error"),
    # Panics and giant allocations.
    ("curve piece length 1e-300", CURVE[:-1] + ["1e-300", "--out", "out.png"], "clean-error"),
    ("curve tolerance 1e-300", CURVE + ["--tolerance", "1e-300", "--out", "out.png"], "clean-error"),
    # Tiles: an image given as a tile is checked like an exemplar and named by its flag.
    ("curve corner tile from an opaque image", CURVE + ["--corner-tile", "texture-exemplar.png", "--out", "out.png"], "clean-error"),
    ("curve corner tile from a truncated PNG", CURVE + ["--corner-tile", "truncated.png", "--out", "out.png"], "clean-error"),
    ("curve start tile from a missing PNG", CURVE + ["--closed", "no", "--start-tile", "missing-tile.png", "--out", "out.png"], "clean-error"),
    ("curve corner tile as columns and image", CURVE + ["--corner-tile", "0,10", "--corner-tile-image", "curve-chain.png", "--out", "out.png"], "clean-error"),
    ("curve corner angle 5", CURVE + ["--corner-tile", "0,10", "--corner-angle", "5", "--out", "out.png"], "clean-error"),
    ("points neighbourhood 1e-300", ["points", "--exemplar", "points-hex.ply", "--neighbourhood", "1e-300", "--domain", "box:8,8", "--out", "out.ply"], "clean-error"),
    ("curve coordinate 1e9", ["curve", "--exemplar", "curve-chain.png", "--path", "far.csv", "--width", "40", "--piece-length", "16", "--out", "out.png"], "clean-error"),
    ("texture from a 16384^2 header", ["texture", "--exemplar", "huge-header.png", "--size", "64x64", "--out", "out.png"], "clean-error"),
    ("stylize guide with a 16384^2 header", ["stylize", "--style", "stylize-A1.png", "--guide", "stylize-A.png", "huge-header.png", "--out", "out.png"], "clean-error"),
    ("curve canvas 16384x16384", CURVE + ["--canvas", "16384x16384", "--out", "out.png"], "clean-error"),
    # Memory estimated before allocating, and refused above --max-memory.
    ("texture 4096x4096 over --max-memory 100M", ["--max-memory", "100M"] + TEXTURE + ["--size", "4096x4096", "--out", "out.png"], "clean-error"),
    ("curve over --max-memory 2M", ["--max-memory", "2M"] + CURVE + ["--out", "out.png"], "clean-error"),
    ("points over --max-memory 1M", ["--max-memory", "1M"] + POINTS + ["--domain", "box:200,200", "--out", "out.ply"], "clean-error"),
    ("strokes over --max-memory 1M", ["--max-memory", "1M"] + STROKES + ["--rect", "20000,20000", "--out", "out.svg"], "clean-error"),
    ("--max-memory not a size", ["--max-memory", "lots"] + TEXTURE + ["--size", "64x64", "--out", "out.png"], "clean-error"),
    # Hangs.
    ("curve piece length 0.01", CURVE[:-1] + ["0.01", "--out", "out.png"], "clean-error"),
    ("10 MB one-path SVG curve", ["curve", "--exemplar", "curve-chain.png", "--path", "big.svg", "--width", "40", "--piece-length", "16", "--out", "out.png"], "clean-error"),
    ("texture 16384x16384", TEXTURE + ["--size", "16384x16384", "--out", "out.png"], "clean-error"),
    ("quilt block wider than the exemplar", TEXTURE + ["--size", "64x64", "--quilt-block", "4000", "--out", "out.png"], "clean-error"),
    ("quilted tileable texture", TEXTURE + ["--size", "64x64", "--quilt-block", "16", "--tileable", "--out", "out.png"], "clean-error"),
    ("quilted texture", TEXTURE + ["--size", "96x80", "--quilt-block", "16", "--out", "out.png"], "success"),
    ("zoom 64 levels of 4096x4096", ["zoom", "--exemplar", "texture-exemplar.png", "--size", "4096x4096", "--levels", "64", "--out-dir", "out-zoom"], "clean-error"),
    ("video keyframe of another size", ["video", "--frames", "video-in/%04d.png", "--key", "0:texture-exemplar.png", "--out", "video-out/%04d.png"], "clean-error"),
    ("video frames pattern without a number", ["video", "--frames", "video-in/0000.png", "--key", "0:video-key-0000.png", "--out", "video-out/%04d.png"], "clean-error"),
    ("video output over its own frames", ["video", "--frames", "video-in/%04d.png", "--key", "0:video-key-0000.png", "--out", "video-in/%04d.png"], "clean-error"),
    ("video frames with a numbering gap", ["video", "--frames", "gap-video/%04d.png", "--key", "0:video-key-0000.png", "--out", "out-%04d.png"], "clean-error"),
    ("video frame of 16384^2 header", ["video", "--frames", "huge-%d.png", "--key", "0:video-key-0000.png", "--out", "out-%d.png"], "clean-error"),
    ("inpaint with a mask of another size", ["inpaint", "--image", "stylize-A1.png", "--mask", "texture-exemplar.png", "--out", "out.png"], "clean-error"),
    ("presynth 4096x4096", ["presynth", "--style", "stylize-A1.png", "--guide", "stylize-A.png", "--size", "4096x4096", "--out-dir", "out-presynth"], "clean-error"),
    ("points coordinate 1e300", ["points", "--exemplar", "far-points.csv", "--neighbourhood", "2", "--domain", "box:20,20", "--out", "out.ply"], "clean-error"),
    ("points from three points", ["points", "--exemplar", "three-points.csv", "--neighbourhood", "1", "--domain", "box:6,6", "--out", "out.csv"], "success"),
    ("points scale 0.01", POINTS + ["--domain", "box:14,10", "--scale", "0.01", "--out", "out.ply"], "clean-error"),
    ("points long stroke", POINTS + ["--along", "long-stroke.json", "--brush-width", "3", "--out", "out.ply"], "clean-error"),
    ("points blob region (200 000 points)", POINTS + ["--domain", "strokes-blob.svg", "--out", "out.ply"], "clean-error"),
    ("strokes with 3000 paths", ["strokes", "--reference", "many-strokes.svg", "--scale", "6", "--rect", "400,400", "--out", "out.svg"], "success"),
    # Nonsense is refused.
    ("points neighbourhood 1e308", ["points", "--exemplar", "points-hex.ply", "--neighbourhood", "1e308", "--domain", "box:8,8", "--out", "out.ply"], "clean-error"),
    ("points sigma 1e300", POINTS + ["--domain", "box:8,8", "--sigma", "1e300", "--out", "out.ply"], "clean-error"),
    ("points non-integer elements", ["points", "--exemplar", "bad-elements.csv", "--neighbourhood", "2", "--domain", "box:20,20", "--out", "out.ply"], "clean-error"),
    ("truncated image", TEXTURE[:-1] + ["truncated.png", "--size", "64x64", "--out", "out.png"], "clean-error"),
    ("truncated JPEG", TEXTURE[:-1] + ["truncated.jpg", "--size", "64x64", "--out", "out.png"], "clean-error"),
    ("points exemplar at 1e200,-1e200", ["points", "--exemplar", "overflowing-points.csv", "--neighbourhood", "2", "--domain", "box:20,20", "--out", "out.ply"], "clean-error"),
    ("points exemplar of doubled points", ["points", "--exemplar", "doubled-points.csv", "--neighbourhood", "2", "--domain", "box:20,20", "--out", "out.ply"], "clean-error"),
    ("points scale-along 1e300,1", POINTS + ["--along", "points-stroke.svg", "--brush-width", "3", "--scale-along", "1e300,1", "--out", "out.ply"], "clean-error"),
    ("points scale-map with a 16384^2 header", POINTS + ["--domain", "box:6,6", "--scale-map", "huge-header.png", "--out", "out.ply"], "clean-error"),
    ("inpaint image with a 16384^2 header over --max-memory 50M", ["--max-memory", "50M", "inpaint", "--image", "huge-header.png", "--mask", "huge-header.png", "--out", "out.png"], "clean-error"),
    ("points surface-out without normals among the attributes", ["points", "--exemplar", "sheet-normals.csv", "--neighbourhood", "1.2", "--domain", "box:6,6,6", "--attributes", "radius", "--out", "out.csv", "--surface-out", "out.obj"], "clean-error"),
    ("curve canvas 1x1", CURVE + ["--canvas", "1x1", "--out", "out.png"], "clean-error"),
    # Caches: a partial presynth folder is detected, not used.
    ("stylize with a mixed presynth cache", STYLE + ["--presynth", "mixed-presynth", "--out", "out.png"], "clean-error"),
    # Messages name the flag, for negatives too.
    ("negative width", CURVE[:6] + ["-40", "--piece-length", "16", "--out", "out.png"], "clean-error"),
    ("negative scale", STROKES[:4] + ["-6", "--rect", "100,100", "--out", "out.svg"], "clean-error"),
    ("negative zoom factor", ["zoom", "--exemplar", "texture-exemplar.png", "--size", "64x64", "--factor", "-5", "--out-dir", "out-zoom"], "clean-error"),
    ("negative global seed", ["--seed", "-5"] + TEXTURE + ["--size", "64x64", "--out", "out.png"], "clean-error"),
    ("segment guide 2 of 1", STYLE + ["--segments", "--segment-guide", "2", "--out", "out.png"], "clean-error"),
    # One output plan, checked before work, committed last (issue 32).
    ("D1 report in /proc", ["--report", "/proc/r.json"] + TEXTURE + ["--size", "64x64", "--out", "previous.png"], "clean-error"),
    ("D1 report name too long", ["--report", "r" * 300 + ".json"] + TEXTURE + ["--size", "64x64", "--out", "previous.png"], "clean-error"),
    ("D1 zoom report in /proc", ["--report", "/proc/r.json"] + ZOOM + ["--out-dir", "zoom-previous"], "clean-error"),
    ("D1 inpaint report in /proc", ["--report", "/proc/r.json"] + INPAINT + ["--out", "previous.png"], "clean-error"),
    ("D2 texture debug file is the exemplar", TEXTURE[:-1] + ["debug-in/error.png", "--size", "64x64", "--debug-dir", "debug-in", "--out", "out.png"], "clean-error"),
    ("D2 stylize debug file is the style", ["stylize", "--style", "debug-in/error.png", "--guide", "stylize-A.png", "stylize-B.png", "--debug-dir", "debug-in", "--out", "out.png"], "clean-error"),
    ("D2 inpaint debug file is the image", ["inpaint", "--image", "debug-in/error.png", "--mask", "stylize-A.png", "--debug-dir", "debug-in", "--out", "out.png"], "clean-error"),
    ("D2 out is a debug file", TEXTURE + ["--size", "64x64", "--debug-dir", "debug-in", "--out", "debug-in/nnf.png"], "clean-error"),
    ("D3 stylize out in its presynth folder", STYLE + ["--presynth", "stylize-presynth", "--out", "stylize-presynth/segment-1.png"], "clean-error"),
    ("D9 zoom report is the exemplar, new folder", ["--report", "texture-exemplar.png"] + ZOOM + ["--out-dir", "out-zoom"], "clean-error"),
    ("D9 zoom report is a level", ["--report", "zoom-previous/zoom-01.png"] + ZOOM + ["--out-dir", "zoom-previous"], "clean-error"),
    ("out in /proc", TEXTURE + ["--size", "64x64", "--out", "/proc/out.png"], "clean-error"),
    ("debug-dir is a file", TEXTURE + ["--size", "64x64", "--debug-dir", "previous.png", "--out", "out.png"], "clean-error"),
    ("zoom out-dir is a file", ZOOM + ["--out-dir", "previous.png"], "clean-error"),
    ("presynth out-dir is a file", ["presynth", "--style", "stylize-A1.png", "--guide", "stylize-A.png", "--size", "32x32", "--out-dir", "previous.png"], "clean-error"),
    ("presynth report in its out-dir", ["--report", "zoom-previous/r.json", "presynth", "--style", "stylize-A1.png", "--guide", "stylize-A.png", "--size", "32x32", "--out-dir", "zoom-previous"], "clean-error"),
    ("presynth cache links out of its folder", STYLE + ["--presynth", "linked-presynth", "--out", "out.png"], "clean-error"),
    ("temporary file of a killed run", TEXTURE + ["--size", "64x64", "--out", "stale/out.png"], "success", ["stale/.motif-999999999-a1b2c3.tmp"]),
]

# Every file input of every subcommand, in a command that succeeds with the demo's files: the
# index of the input's value in the arguments, and the kind prefix it carries (`volume:`).
SWEPT = [
    ("curve", CURVE + ["--avoid", "stylize-A.png", "--out", "out.png"], ["--exemplar", "--path", "--avoid"]),
    ("curve tile image", CURVE + ["--corner-tile-image", "curve-chain.png", "--out", "out.png"], ["--corner-tile-image"]),
    ("points", POINTS + ["--domain", "box:8,8", "--rotation-map", "strokes-photo.png", "--scale-map", "strokes-photo.png", "--out", "out.ply"], ["--exemplar", "--rotation-map", "--scale-map"]),
    ("points region", POINTS + ["--domain", "strokes-blob.svg", "--scale", "40", "--out", "out.ply"], ["--domain"]),
    ("points volume", ["points", "--exemplar", "points-protein-atoms.csv", "--neighbourhood", "4", "--domain", "volume:points-bull-78.obj", "--out", "out.ply"], ["--domain"]),
    ("points surface", ["points", "--exemplar", "points-swedishpines.csv", "--neighbourhood", "32", "--domain", "surface:points-bull-400.obj", "--out", "out.ply"], ["--domain"]),
    ("points stroke", POINTS + ["--along", "points-stroke.svg", "--brush-width", "3", "--existing", "points-hex-box.ply", "--out", "out.ply"], ["--along", "--existing"]),
    ("points element mesh", POINTS + ["--domain", "box:8,8", "--out", "out.ply", "--surface-out", "out.obj", "--element-mesh", "points-tripod.obj"], ["--element-mesh"]),
    ("strokes along", STROKES + ["--along", "strokes-wave.svg", "--out", "out.svg"], ["--reference", "--along"]),
    ("strokes region", STROKES + ["--region", "strokes-blob.svg", "--out", "out.svg"], ["--region"]),
    ("strokes maps", STROKES + ["--rect", "400,400", "--density-map", "strokes-photo.png", "--scale-map", "strokes-photo.png", "--out", "out.svg"], ["--density-map", "--scale-map"]),
    ("stylize", STYLE + ["--out", "out.png"], ["--style", "--guide", "--guide+2"]),
    ("texture masked", TEXTURE + ["--size", "156x156", "--mask", "inpaint-stone-mask.png", "--keep", "inpaint-stone.png", "--out", "out.png"], ["--mask", "--keep"]),
    ("stylize apply-nnf", ["stylize", "--style", "stylize-A1.png", "--apply-nnf", "stylize-debug/nnf.png", "--out", "out.png"], ["--apply-nnf"]),
    ("presynth", ["presynth", "--style", "stylize-A1.png", "--guide", "stylize-A.png", "--size", "32x32", "--out-dir", "out-presynth"], ["--style", "--guide"]),
    ("texture", TEXTURE + ["--size", "64x64", "--out", "out.png"], ["--exemplar"]),
    ("inpaint", ["inpaint", "--image", "inpaint-stone.png", "--mask", "inpaint-stone-mask.png", "--out", "out.png"], ["--image", "--mask"]),
    ("zoom", ZOOM + ["--out-dir", "out-zoom"], ["--exemplar"]),
    ("video", ["video", "--frames", "video-in/%04d.png", "--key", "0:video-key-0000.png", "--out", "out-%04d.png"], ["--key"]),
]

# What each swept input is replaced by: a missing file, a folder, an empty file, random bytes, a
# truncated image and a PNG whose header declares 16384 x 16384 pixels.
BAD_FILES = [("missing", "missing.png"), ("a folder", "a-folder"), ("empty", "empty.bin"), ("garbage", "garbage.bin"),
             ("truncated image", "truncated.png"), ("16384^2 header", "huge-header.png")]


def input_sweep():
    """A clean error for every bad file in place of every input of every subcommand."""
    cases = []
    for name, arguments, inputs in SWEPT:
        for input_flag in inputs:
            flag, _, nth = input_flag.partition("+")
            index = arguments.index(flag) + int(nth or 1)
            value = arguments[index]
            kind = value.split(":", 1)[0] + ":" if ":" in value and not value[0].isdigit() else ""
            key = value.split(":", 1)[0] + ":" if value[0].isdigit() else ""
            for what, bad in BAD_FILES:
                swept = arguments[:index] + [kind + key + bad] + arguments[index + 1:]
                cases.append((f"sweep {name} {input_flag} {what}", swept, "clean-error"))
    return cases


SWEEP_CASES = input_sweep()


def classify(result, timed_out, changed, leftovers, expected):
    if timed_out:
        return "hang"
    if changed:
        return "data-loss"
    stderr = result.stderr
    if "internal error" in stderr or result.returncode not in (0, 1, 2):
        return "panic"
    if leftovers:
        return "leftover"
    if result.returncode == 0:
        return "success"
    return "clean-error" if stderr.strip().startswith("error") else "panic"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary", nargs="?", default=os.path.join(ROOT, "target", "release", "motif"))
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--json", help="also write the outcomes here")
    args = parser.parse_args()
    binary = os.path.abspath(args.binary)
    base = tempfile.mkdtemp(prefix="motif-robustness-")
    inputs = os.path.join(base, "inputs")
    prepare(inputs, binary)
    counts, unexpected, rows = {}, [], []
    cases = [case for case in CASES] + [("sweep works: " + name, arguments, "success") for name, arguments, _ in SWEPT]
    cases += SWEEP_CASES
    for name, arguments, expected, *removed in cases:
        removed = removed[0] if removed else []
        folder = os.path.join(base, "case")
        shutil.rmtree(folder, ignore_errors=True)
        # (Links stay links; copies keep their times.)
        shutil.copytree(inputs, folder, symlinks=True)
        before = {f: digest(os.path.join(folder, f)) for f in files_under(folder)}
        start = time.monotonic()
        process = subprocess.Popen([binary, "--quiet"] + arguments, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            stdout, stderr = process.communicate(timeout=args.timeout)
            timed_out = False
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            stdout, stderr = process.communicate()
            timed_out = True
        seconds = time.monotonic() - start
        result = subprocess.CompletedProcess(arguments, process.returncode, stdout, stderr)
        changed = [f for f, d in before.items() if f not in removed and (not os.path.exists(os.path.join(folder, f)) or digest(os.path.join(folder, f)) != d)]
        names = set(files_under(folder))
        leftovers = [f for f in names if os.path.basename(f).startswith(".motif-") and f.endswith(".tmp") and f not in before]
        leftovers += [f for f in removed if f in names]
        if process.returncode not in (0, None) and not timed_out:
            report = arguments[arguments.index("--report") + 1] if "--report" in arguments else None
            leftovers += [f for f in names if f not in before and f != report]
        outcome = classify(result, timed_out, changed, leftovers, expected)
        counts[outcome] = counts.get(outcome, 0) + 1
        message = (stderr.strip().splitlines() or [""])[0][:160]
        rows.append({"case": name, "expected": expected, "outcome": outcome, "seconds": round(seconds, 2), "message": message})
        if outcome != expected:
            unexpected.append(rows[-1] | {"command": "motif " + " ".join(arguments)})
        print(f"{outcome:12} {seconds:6.1f} s  {name}: {message}", flush=True)
    shutil.rmtree(base, ignore_errors=True)
    print("\noutcomes: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    print(f"unexpected: {len(unexpected)} of {len(cases)}")
    for row in unexpected:
        print(f"  {row['case']}: {row['outcome']} (expected {row['expected']}): {row['command']}")
    if args.json:
        with open(args.json, "w") as handle:
            json.dump({"counts": counts, "cases": rows, "unexpected": unexpected}, handle, indent=2)
    return 1 if unexpected else 0


if __name__ == "__main__":
    sys.exit(main())
