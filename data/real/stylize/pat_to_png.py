#!/usr/bin/env python3
"""Converts a GIMP pattern (.pat) into a PNG, both read and written with the standard library.

usage: pat_to_png.py PATTERN.pat OUT.png

A .pat file is a big-endian header (header size, version 1, width, height, bytes per pixel,
the magic "GPAT", the pattern's name ending in a zero byte) followed by the pixels, row by row
(1 byte: grey, 2: grey and alpha, 3: RGB, 4: RGBA). The PNG keeps the pixels exactly, as an
8-bit grey, grey-alpha, RGB or RGBA image. Prints the name and size.
"""
import struct
import sys
import zlib


def read_pat(path):
    data = open(path, "rb").read()
    header_size, version, width, height, depth = struct.unpack(">5I", data[:20])
    if version != 1 or data[20:24] != b"GPAT" or depth not in (1, 2, 3, 4):
        raise SystemExit(f"{path}: not a version-1 GIMP pattern")
    name = data[24:header_size].rstrip(b"\0").decode("utf-8")
    pixels = data[header_size:header_size + width * height * depth]
    if len(pixels) != width * height * depth:
        raise SystemExit(f"{path}: {len(pixels)} pixel bytes for {width} x {height} x {depth}")
    return name, width, height, depth, pixels


def write_png(path, width, height, depth, pixels):
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[depth]
    row = width * depth
    raw = b"".join(b"\0" + pixels[y * row:(y + 1) * row] for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    source, out = sys.argv[1:]
    name, width, height, depth, pixels = read_pat(source)
    write_png(out, width, height, depth, pixels)
    print(f"{out}: {name!r}, {width} x {height}, {depth} bytes per pixel")


if __name__ == "__main__":
    main()
