#!/usr/bin/env python3
"""Makes anti-aliased segment guides from real pictures, with the standard library only.

usage: segment_guides.py CORPUS_FOLDER

A segment guide is a map of flat colours, one per segment. Here the segments are the tertiles of a
real picture's blurred brightness (dark, middle, light), so their layout is the picture's:

- chelsea_segments.png (451 x 300, the size of chelsea.png, its source guide A): the photo's
  brightness, blurred (box of 7 x 7), split at its tertiles, then the colours filtered by a 3 x 3
  box, as a soft brush paints them: every pixel on an edge holds a blend of two colours.
- stone_segments.png (78 x 78, a target guide B): GIMP's stone33.png the same way (blurred by a
  box of 9 x 9, split at its own tertiles), labelled at its full 156 x 156 and downsampled by 2
  with a 2 x 2 box (an anti-aliased render at half size).

Neither holds only its three segment colours: an exact palette sees their blends as segments of
their own, so these guides need `--segment-count 3` (nearest colour). The script prints how many
distinct colours each has.
"""
import os
import struct
import sys
import zlib

# Water, sand and paper: the dark, middle and light tertiles.
COLOURS = [(0x1E, 0x4B, 0x96), (0xD8, 0xB8, 0x6A), (0xF6, 0xF3, 0xEA)]


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def read_png(path):
    """An 8-bit, non-interlaced grey/RGB/grey-alpha/RGBA PNG as (width, height, depth, rows)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    at, idat, header = 8, b"", None
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, bits, colour_type, _, _, interlace = header
    depth = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour_type)
    if bits != 8 or depth is None or interlace:
        raise SystemExit(f"{path}: only 8-bit non-interlaced grey/RGB(A) PNGs are read")
    raw, stride, rows, previous = zlib.decompress(idat), width * depth, [], bytearray(width * depth)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - depth] if i >= depth else 0
            b, c = previous[i], previous[i - depth] if i >= depth else 0
            line[i] = (line[i] + [0, a, b, (a + b) // 2, paeth(a, b, c)][kind]) & 0xFF
        rows.append(line)
        previous = line
    return width, height, depth, rows


def write_png(path, width, height, rows):
    """An 8-bit RGB PNG from rows of (r, g, b) tuples."""
    raw = b"".join(b"\0" + bytes(v for pixel in row for v in pixel) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def brightness(width, height, depth, rows):
    """Integer luma (BT.601 weights × 1000) of every pixel."""
    if depth < 3:
        return [[1000 * row[x * depth] for x in range(width)] for row in rows]
    return [
        [299 * row[x * depth] + 587 * row[x * depth + 1] + 114 * row[x * depth + 2] for x in range(width)]
        for row in rows
    ]


def box(grid, radius):
    """Mean of each (2r+1)² window, the edges clamped; values are integers (floor)."""
    height, width = len(grid), len(grid[0])
    out = []
    for y in range(height):
        out.append([])
        for x in range(width):
            total = count = 0
            for j in range(max(0, y - radius), min(height, y + radius + 1)):
                for i in range(max(0, x - radius), min(width, x + radius + 1)):
                    total += grid[j][i]
                    count += 1
            out[-1].append(total // count)
    return out


def tertile_labels(values):
    """Label 0, 1 or 2 by the tertiles of all values."""
    ordered = sorted(v for row in values for v in row)
    low, high = ordered[len(ordered) // 3], ordered[2 * len(ordered) // 3]
    return [[0 if v < low else 1 if v < high else 2 for v in row] for row in values]


def colour_map(labels):
    return [[COLOURS[label] for label in row] for row in labels]


def channel(image, c):
    return [[pixel[c] for pixel in row] for row in image]


def soften(image, radius):
    """Each channel filtered by a box of (2r+1)², rounded to the nearest integer."""
    planes = []
    for c in range(3):
        plane = [[255 * v for v in row] for row in channel(image, c)]
        planes.append([[(v + 127) // 255 for v in row] for row in box(plane, radius)])
    return [list(zip(*(planes[c][y] for c in range(3)))) for y in range(len(image))]


def downsample(image, factor):
    """Mean of each factor × factor block, rounded half up."""
    height, width, area = len(image) // factor, len(image[0]) // factor, factor * factor
    out = []
    for y in range(height):
        out.append([])
        for x in range(width):
            block = [image[y * factor + j][x * factor + i] for j in range(factor) for i in range(factor)]
            out[-1].append(tuple((sum(p[c] for p in block) + area // 2) // area for c in range(3)))
    return out


def segments(path, blur):
    width, height, depth, rows = read_png(path)
    return colour_map(tertile_labels(box(brightness(width, height, depth, rows), blur)))


def save(path, image):
    write_png(path, len(image[0]), len(image), image)
    distinct = len({pixel for row in image for pixel in row})
    print(f"{path}: {len(image[0])} x {len(image)}, {distinct} distinct colours")


def main():
    (folder,) = sys.argv[1:]
    save(os.path.join(folder, "chelsea_segments.png"), soften(segments(os.path.join(folder, "chelsea.png"), 3), 1))
    save(os.path.join(folder, "stone_segments.png"), downsample(segments(os.path.join(folder, "stone33.png"), 4), 2))


if __name__ == "__main__":
    main()
