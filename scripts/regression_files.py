#!/usr/bin/env python3
"""Writes the crafted files of crates/motif-io/tests/regressions/ (each named after what it checks).

Usage: scripts/regression_files.py [folder]   (default: crates/motif-io/tests/regressions)
"""
import os
import struct
import sys
import zlib


# A 24 × 16 JPEG (quality 90) written by the `image` crate, which this script cannot encode itself.
JPEG_24X16 = bytes.fromhex(
    "ffd8ffe000104a46494600010200000100010000ffc00011080010001803011100021101031101ffdb004300030202030202"
    "0303030304030304050805050404050a070706080c0a0c0c0b0a0b0b0d0e12100d0e110e0b0b1016101113141515150c0f17"
    "1816141812141514ffdb00430103040405040509050509140d0b0d1414141414141414141414141414141414141414141414"
    "141414141414141414141414141414141414141414141414141414ffc4001f00000105010101010101000000000000000001"
    "02030405060708090a0bffc400b5100002010303020403050504040000017d01020300041105122131410613516107227114"
    "328191a1082342b1c11552d1f02433627282090a161718191a25262728292a3435363738393a434445464748494a53545556"
    "5758595a636465666768696a737475767778797a838485868788898a92939495969798999aa2a3a4a5a6a7a8a9aab2b3b4b5"
    "b6b7b8b9bac2c3c4c5c6c7c8c9cad2d3d4d5d6d7d8d9dae1e2e3e4e5e6e7e8e9eaf1f2f3f4f5f6f7f8f9faffc4001f010003"
    "0101010101010101010000000000000102030405060708090a0bffc400b51100020102040403040705040400010277000102"
    "031104052131061241510761711322328108144291a1b1c109233352f0156272d10a162434e125f11718191a262728292a35"
    "363738393a434445464748494a535455565758595a636465666768696a737475767778797a82838485868788898a92939495"
    "969798999aa2a3a4a5a6a7a8a9aab2b3b4b5b6b7b8b9bac2c3c4c5c6c7c8c9cad2d3d4d5d6d7d8d9dae2e3e4e5e6e7e8e9ea"
    "f2f3f4f5f6f7f8f9faffda000c03010002110311003f00fcfad1b44fbbf2d7eb55f105e5589d8ee746d13eefcb5f3f5f107e"
    "c19562763bad1f44fbbf2d7cf57c41fb065589d8e2b46d13eefcb5ef57c41fc2595e2b63bad1f44fbbf2d7cf57c41fb06578"
    "ad8ee746d13eefcb5f3f5f107ec195e2b63fffd9"
)


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
    files["png-header-declares-16384x16384.png"] = png(16384, 16384, zlib.compress(b"\x00" * 64))
    files["jpeg-cut-before-its-end.jpg"] = JPEG_24X16[: len(JPEG_24X16) * 2 // 3]
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
