#!/usr/bin/env python3
"""Copies a triangle mesh from CGAL's data archive into an OBJ file, and checks it.

usage: off_to_obj.py DATA_TAR_GZ MEMBER OUT.obj HEADER_LINE...

Reads MEMBER (an OFF file) straight out of DATA_TAR_GZ (libcgal-demo's data.tar.gz) and writes
OUT.obj: the HEADER_LINEs as `#` comments, then one `v x y z` line a vertex and one `f i j k`
line a face (1-based). The conversion is textual: each coordinate is copied as the very token the
OFF file holds, faces keep their vertex order, nothing is welded, moved or dropped. Then it
prints the counts, the bounding box and the checks (every undirected edge shared by exactly two
triangles, each directed edge used once, every vertex's fan a single disc, signed volume).
Python 3 standard library only.
"""
import collections
import sys
import tarfile


def read_off(text):
    tokens = []
    for line in text.splitlines():
        tokens += line.split("#", 1)[0].split()
    if tokens[0] != "OFF":
        raise SystemExit("not a plain OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    i = 4
    verts = []
    for _ in range(nv):
        verts.append(tokens[i:i + 3])
        i += 3
    faces = []
    for _ in range(nf):
        n = int(tokens[i])
        faces.append([int(t) for t in tokens[i + 1:i + 1 + n]])
        i += 1 + n
    if i != len(tokens):
        raise SystemExit(f"{len(tokens) - i} tokens after the last face (colours?)")
    return verts, faces


def check(verts, faces):
    pts = [tuple(float(c) for c in v) for v in verts]
    undirected = collections.Counter()
    directed = collections.Counter()
    fans = collections.defaultdict(list)
    for f in faces:
        if len(f) != 3 or len(set(f)) != 3:
            raise SystemExit(f"not a proper triangle: {f}")
        for a, b, c in ((f[0], f[1], f[2]), (f[1], f[2], f[0]), (f[2], f[0], f[1])):
            undirected[(min(a, b), max(a, b))] += 1
            directed[(a, b)] += 1
            fans[a].append((b, c))
    odd = sum(1 for n in undirected.values() if n % 2)
    not_two = sum(1 for n in undirected.values() if n != 2)
    repeated_directed = sum(1 for n in directed.values() if n > 1)
    # a vertex is manifold when the edges (b -> c) of its fan form one cycle
    bad_vertices = 0
    for v, fan in fans.items():
        nxt = dict(fan)
        if len(nxt) != len(fan):
            bad_vertices += 1
            continue
        start, seen, cur = fan[0][0], 0, fan[0][0]
        while True:
            cur = nxt.get(cur)
            seen += 1
            if cur is None or cur == start or seen > len(fan):
                break
        if cur != start or seen != len(fan):
            bad_vertices += 1
    volume = 0.0
    for a, b, c in faces:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = pts[a], pts[b], pts[c]
        volume += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    euler = len(verts) - len(undirected) + len(faces)
    print(f"vertices {len(verts)}, triangles {len(faces)}, edges {len(undirected)}, "
          f"Euler characteristic {euler} (genus {(2 - euler) / 2:g} if closed and connected)")
    print(f"edges with an odd triangle count: {odd}; edges not shared by exactly two: {not_two}; "
          f"directed edges used twice: {repeated_directed}; non-manifold vertices: {bad_vertices}; "
          f"unused vertices: {len(verts) - len(fans)}; duplicate positions: "
          f"{len(verts) - len(set(map(tuple, verts)))}")
    print(f"signed volume {volume:.6g}")
    print("bounding box " + " x ".join(f"[{l:g}, {h:g}]" for l, h in zip(lo, hi)))
    if odd:
        raise SystemExit("not watertight")


def main():
    archive, member, out, *header = sys.argv[1:]
    with tarfile.open(archive) as tar:
        text = tar.extractfile(member).read().decode("ascii")
    verts, faces = read_off(text)
    check(verts, faces)
    with open(out, "w", newline="\n") as f:
        for line in header:
            f.write(f"# {line}\n")
        for v in verts:
            f.write(f"v {v[0]} {v[1]} {v[2]}\n")
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


if __name__ == "__main__":
    main()
