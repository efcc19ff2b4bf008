"""Checks every CSV of the corpus and writes cases.json.

Usage: python make_manifest.py DIR WINDOWS_TSV

WINDOWS_TSV (written by export.R) gives each spatstat case's window; the contour case's window
is the 200 x 200 px crop. Standard library only.
"""

import csv
import json
import math
import os
import re
import sys

SPATSTAT = "R package spatstat.data 3.0-0 (Debian r-cran-spatstat.data), data set "
GPL = "GPL (>= 2) (spatstat.data)"

# name -> (kind, use, source). Listed in the order of cases.json.
CASES = [
    ("longleaf", "clustered, marked (dbh: trunk diameter at breast height, cm)", "bench",
     SPATSTAT + "`longleaf`: Platt, Evans and Rathbun (1988), The American Naturalist 131, 491-525"),
    ("amacrine", "multi-type (label 0 = off cell, 1 = on cell), each type regular", "bench",
     SPATSTAT + "`amacrine`: Austin Hughes' data, Diggle (1986), J. Neurosci. Meth. 18, 115-125"),
    ("anemones", "marked with sizes: disc centres with diameters (diameter, same units as x, y)",
     "bench",
     SPATSTAT + "`anemones`: Kooijman (1979), via Upton and Fingleton (1985), Spatial data analysis "
     "by example, Vol. 1, Table 1.11"),
    ("bei_subset", "inhomogeneous: density falls steadily along x", "bench",
     SPATSTAT + "`bei`, sub-window [0,250] x [50,300] m: Barro Colorado Island forest dynamics "
     "plot, Hubbell and Foster (1983), Condit, Hubbell and Foster (1996), Condit (1998)"),
    ("lansing_subset", "multi-type, six species (label 0..5: blackoak, hickory, maple, misc, "
     "redoak, whiteoak)", "bench",
     SPATSTAT + "`lansing`, sub-window [0,0.5] x [0,0.5]: Lansing Woods, Michigan, D.J. Gerrard "
     "(1969), Research Bulletin 20, Michigan State University"),
    ("spruces", "marked (diameter: trunk diameter at breast height, m)", "bench",
     SPATSTAT + "`spruces`: Stoyan et al. (1987), Stochastic Geometry and its Applications; "
     "Fiksel (1984)"),
    ("swedishpines", "regular (inhibited), unmarked", "test",
     SPATSTAT + "`swedishpines`: Strand (1972), Ripley (1981), Spatial statistics"),
    ("redwood", "clustered, unmarked", "test",
     SPATSTAT + "`redwood`: Strauss (1975), Biometrika 62, 467-475, subset by Ripley (1977)"),
    ("finpines", "clustered, marked (diameter: at breast height, cm; height: m)", "bench",
     SPATSTAT + "`finpines`: Penttinen, Stoyan and Henttonen (1992), Forest Science 38, 806-824; "
     "Stoyan and Stoyan (1994), Fractals, Random Shapes and Point Fields"),
    ("japanesepines", "close to complete spatial randomness, unmarked", "test",
     SPATSTAT + "`japanesepines`: Numata (1961), via Diggle (2003), Statistical Analysis of "
     "Spatial Point Patterns"),
    ("osteo_brick", "3D, unmarked (osteocyte lacunae in bone, microns)", "bench",
     SPATSTAT + "`osteo`, row 36 (bone c77za9, brick 6): Baddeley, Howard, Boyde and Reid (1987), "
     "Acta Stereologica 6, 87-100; Baddeley et al. (1993), Applied Statistics 42, 641-668"),
    ("protein_atoms", "3D, multi-type: protein atoms by element (label 0 = C, 1 = N, 2 = O, "
     "3 = S), Å", "bench",
     "PDB entry 1TII (E. coli heat-labile enterotoxin type IIB, X-ray 2.25 Å, F. van den Akker "
     "and W.G.J. Hol, deposited 1996) as shipped in Debian pymol-data 2.5.0 "
     "(usr/share/pymol/data/demo/1tii.pdb), atoms in the cube [18,33] x [12,27] x [-21,-6] Å"),
    ("fin_sheet", "3D continuous structure: a curved sheet (CGAL's fin) sampled with unit normals "
     "(nx, ny, nz)", "bench",
     "CGAL 5.5.1 data/points_3/fin90_with_PCA_normals.xyz, via Debian libcgal-demo 5.5.1-2 "
     "(usr/share/doc/libcgal-dev/data.tar.gz), moved to the origin (cgal_sheet.py)"),
    ("chain_contours", "continuous structure: alpha = 128 contour samples every 1.75 px with unit "
     "outward normals (nx, ny), px, y down", "bench",
     "openclipart 'Gold Chain of Round Links' by Jonadab (Debian openclipart-svg 0.18, "
     "signs_and_symbols/money/gold_chain_of_round_lin_01.svg), rendered by rsvg-convert at "
     "220 x 220 px, cropped at (2, 2) to 200 x 200 px (chain_contours_source.png)"),
]
LICENCE = {
    "chain_contours": "public domain (openclipart)",
    "fin_sheet": "CC0 1.0 (CGAL's LICENSE: files without a copyright notice)",
    "protein_atoms": "CC0 1.0 (wwPDB data policy); file shipped in Debian pymol-data (PyMOL "
                     "licence, permissive)",
}
NEIGHBOURHOOD = {"chain_contours": 30.0}
INT = re.compile(r"^-?[0-9]+$")
FLOAT = re.compile(r"^-?[0-9]+\.[0-9]+$")


def sig(v, digits):
    return float(f"{v:.{digits}g}")


def mean_nn(pts):
    total = 0.0
    for i, p in enumerate(pts):
        best = math.inf
        for j, q in enumerate(pts):
            if i != j:
                best = min(best, sum((a - b) ** 2 for a, b in zip(p, q)))
        total += math.sqrt(best)
    return total / len(pts)


def main():
    folder, windows_tsv = sys.argv[1], sys.argv[2]
    windows = {"chain_contours": [200.0, 200.0], "protein_atoms": [15.0, 15.0, 15.0],
               "fin_sheet": [1.1593, 0.7426, 0.7861]}
    with open(windows_tsv) as f:
        for line in f:
            name, *w = line.split("\t")
            windows[name] = [float(v) for v in w]
    manifest = []
    print(f"{'name':16} {'points':>6} {'window':>24} {'mean_spacing':>12} {'neighbourhood':>13}")
    for name, kind, use, source in CASES:
        path = os.path.join(folder, name + ".csv")
        assert os.path.getsize(path) < 200_000, f"{name}: file too large"
        window = windows[name]
        dim = len(window)
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        header, body = rows[0], rows[1:]
        axes = ["x", "y", "z"][:dim]
        assert header[:dim] == axes, f"{name}: header {header}"
        for col, column in enumerate(zip(*body)):
            is_label = header[col] == "label"
            pattern = INT if is_label else FLOAT
            bad = [v for v in column if not pattern.match(v)]
            assert not bad, f"{name}.{header[col]}: {bad[:3]}"
        pts = []
        for r in body:
            assert len(r) == len(header), f"{name}: ragged row {r}"
            vals = [float(v) for v in r]
            assert all(math.isfinite(v) for v in vals), f"{name}: {r}"
            p = vals[:dim]
            assert all(0.0 <= c <= w for c, w in zip(p, window)), f"{name}: {r} outside {window}"
            pts.append(p)
        spacing = mean_nn(pts)
        assert spacing > 0, f"{name}: duplicated points"
        entry = {
            "name": name,
            "file": name + ".csv",
            "kind": kind,
            "dimension": dim,
            "window": window,
            "points": len(pts),
            "mean_spacing": sig(spacing, 4),
            # 3D windows of 4 spacings hold ~270 neighbours (a 2D one ~50): 2 spacings and a
            # domain 1.5x the window keep the 3D cases at a few seconds.
            "neighbourhood": NEIGHBOURHOOD.get(name, sig((4 if dim == 2 else 2) * spacing, 2)),
            "domain": [(2 if dim == 2 else 1.5) * w for w in window],
            "use": use,
            "source": source,
            "licence": LICENCE.get(name, GPL),
        }
        manifest.append(entry)
        print(f"{name:16} {len(pts):6} {str(window):>24} {entry['mean_spacing']:12} "
              f"{entry['neighbourhood']:13}")
    with open(os.path.join(folder, "cases.json"), "w", newline="\n") as f:
        f.write("[\n")
        for i, entry in enumerate(manifest):
            fields = ",\n".join(f"    {json.dumps(k)}: {json.dumps(v, ensure_ascii=False)}"
                                 for k, v in entry.items())
            f.write("  {\n" + fields + "\n  }" + (",\n" if i + 1 < len(manifest) else "\n"))
        f.write("]\n")


if __name__ == "__main__":
    main()
