#!/usr/bin/env python3
"""Writes the crafted files of crates/motif-io/tests/regressions/ (each named after what it checks).

Usage: scripts/regression_files.py [folder]   (default: crates/motif-io/tests/regressions)
"""
import os
import struct
import sys
import zlib


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(width, height, idat=None):
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
    if idat is not None:
        out += chunk(b"IDAT", idat)
    return out + chunk(b"IEND", b"")


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "crates", "motif-io", "tests", "regressions")
    os.makedirs(folder, exist_ok=True)
    files = {}
    files["png-header-declares-20000x20000.png"] = png(20000, 20000, zlib.compress(b"\x00" * 64))
    raw = b"".join(b"\x00" + bytes((x * 7 + y * 3) % 256 for x in range(4 * 20)) for y in range(20))
    full = png(20, 20, zlib.compress(raw))
    files["png-cut-to-a-third.png"] = full[: len(full) // 3]
    files["png-zero-width.png"] = png(0, 20, zlib.compress(b""))
    files["text-named-png.png"] = b"this is a text file, not an image\n"
    header = "ply\nformat {}\nelement vertex 2000000000\nproperty float x\nproperty float y\nend_header\n"
    files["ply-declares-two-billion-vertices.ply"] = (header.format("ascii 1.0") + "0 0\n1 1\n").encode()
    files["ply-binary-declares-two-billion-vertices.ply"] = header.format("binary_little_endian 1.0").encode() + struct.pack("<4f", 0, 0, 1, 1)
    files["ply-without-vertex-element.ply"] = b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n"
    files["ply-list-length-255-without-data.ply"] = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty list uchar float normals\nend_header\n0 255 1\n"
    files["csv-word-in-a-number-column.csv"] = b"x,y\n0,0\n1,one\n"
    files["csv-ragged-row.csv"] = b"x,y\n0,0\n1,2,3\n"
    files["csv-header-only.csv"] = b"x,y\n"
    files["csv-empty.csv"] = b""
    files["svg-without-a-path.svg"] = b'<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><text x="1" y="5">no path</text></svg>'
    files["svg-not-xml.svg"] = b"<svg <<< not xml"
    entities = "".join(f'<!ENTITY {chr(98 + i)} "{("&" + chr(97 + i) + ";") * 10}">\n' for i in range(8))
    laughs = (
        '<?xml version="1.0"?>\n<!DOCTYPE svg [\n<!ENTITY a "aaaaaaaaaa">\n' + entities + "]>\n"
        '<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><text>&i;</text><path d="M0 0 L 5 5"/></svg>'
    )
    files["svg-billion-laughs.svg"] = laughs.encode()
    for name, data in files.items():
        with open(os.path.join(folder, name), "wb") as handle:
            handle.write(data)
    print(f"{len(files)} files in {folder}")


if __name__ == "__main__":
    main()
