"""Cuts a cube of protein atoms out of a real crystal structure.

Usage: python pdb_atoms.py 1tii.pdb OUTDIR

1tii.pdb is PDB entry 1TII (heat-labile enterotoxin type IIB of E. coli, X-ray, 2.25 Å;
F. van den Akker, W.G.J. Hol), as shipped in Debian's pymol-data (usr/share/pymol/data/demo/).
Writes OUTDIR/protein_atoms.csv: the protein atoms (ATOM records, first alternate location)
inside the cube CORNER + [0, SIDE]^3 Å, moved to the origin, with columns x,y,z (Å) and the
chemical element as an integer label (0 = C, 1 = N, 2 = O, 3 = S). Standard library only.
"""

import os
import sys

CORNER = (18.0, 12.0, -21.0)
SIDE = 15.0
ELEMENTS = ["C", "N", "O", "S"]


def main():
    pdb, outdir = sys.argv[1], sys.argv[2]
    rows = []
    with open(pdb) as f:
        for line in f:
            if not line.startswith("ATOM") or line[16] not in " A":
                continue
            p = [float(line[30:38]), float(line[38:46]), float(line[46:54])]
            q = [round(a - c, 3) for a, c in zip(p, CORNER)]
            if all(0.0 <= v <= SIDE for v in q):
                element = line[76:78].strip()
                rows.append(f"{q[0]:.3f},{q[1]:.3f},{q[2]:.3f},{ELEMENTS.index(element)}")
    with open(os.path.join(outdir, "protein_atoms.csv"), "w", newline="\n") as f:
        f.write("x,y,z,label\n")
        f.write("\n".join(rows) + "\n")
    print(f"protein_atoms: {len(rows)} atoms; label " +
          ", ".join(f"{i} = {e}" for i, e in enumerate(ELEMENTS)))


if __name__ == "__main__":
    main()
