"""Writes a real 3D sheet with normals: CGAL's fin, a point set with PCA normals.

Usage: python cgal_sheet.py DATA_TAR_GZ OUTDIR

DATA_TAR_GZ is CGAL's data folder as shipped in Debian's libcgal-demo
(usr/share/doc/libcgal-dev/data.tar.gz); its member data/points_3/fin90_with_PCA_normals.xyz
(757 points, "x y z nx ny nz" per line, no header, no copyright notice: CC0 1.0 under CGAL's
LICENSE) is a curved fin sampled as a sheet. Writes OUTDIR/fin_sheet.csv with columns
x,y,z,nx,ny,nz: the positions moved so that the bounding box grown by PAD on every side starts at
the origin (rounded to 6 decimals), the normals' tokens copied verbatim. Standard library only.
"""

import os
import sys
import tarfile

MEMBER = "data/points_3/fin90_with_PCA_normals.xyz"
# Half the set's mean nearest-neighbour spacing (0.0289), so that each point owns a spacing-sized
# cell inside the window WINDOW (the bounding box grown by PAD on every side, rounded up).
PAD = 0.0145
WINDOW = (1.1593, 0.7426, 0.7861)


def main():
    archive, outdir = sys.argv[1], sys.argv[2]
    with tarfile.open(archive) as tar:
        text = tar.extractfile(MEMBER).read().decode("ascii")
    rows = [line.split() for line in text.splitlines() if line.strip()]
    assert all(len(r) == 6 for r in rows), "six numbers per line"
    low = [min(float(r[a]) for r in rows) for a in range(3)]
    with open(os.path.join(outdir, "fin_sheet.csv"), "w", newline="\n") as f:
        f.write("x,y,z,nx,ny,nz\n")
        for r in rows:
            p = [round(float(r[a]) - low[a] + PAD, 6) for a in range(3)]
            assert all(0.0 <= v <= w for v, w in zip(p, WINDOW)), (r, p)
            f.write(",".join(f"{v:.6f}" for v in p) + "," + ",".join(r[3:]) + "\n")
    print(f"fin_sheet: {len(rows)} points with normals, window {WINDOW}")


if __name__ == "__main__":
    main()
