#!/usr/bin/env bash
# Rebuilds every file of this folder (the real point-pattern corpus) from public sources.
#
# Needs
#   Debian packages: r-base-core r-cran-spatstat.data r-cran-spatstat.geom (the point patterns),
#                    librsvg2-bin (rsvg-convert), openclipart-svg (the chain drawing) and
#                    pymol-data (the protein structure) and libcgal-demo (the fin sheet); the
#                    last three need not be installed:
#                    if they are not, this script fetches them with `apt-get download` into a
#                    temporary folder and unpacks them there.
#   Python 3 with the pip packages numpy, Pillow and scikit-image (the contour tracing), e.g.
#     python3 -m venv /tmp/venv && /tmp/venv/bin/pip install numpy Pillow scikit-image
#     PYTHON=/tmp/venv/bin/python bash data/real/points/build.sh
# Made with R 4.2.2, spatstat.data 3.0-0, spatstat.geom 3.0-6, librsvg 2.54.7, openclipart-svg
# 0.18+dfsg-19, pymol-data 2.5.0+dfsg-1, Python 3.11, numpy 2.4.6, Pillow 13.0.0, scikit-image 0.26.0. Other versions may
# change the last digits of the traced contour (and the PNG's bytes), not the spatstat files.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PYTHON="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# 1. Point patterns of the R package spatstat.data.
Rscript "$here/export.R" "$here" "$tmp/windows.tsv"

# package_file PACKAGE PATH: a file of a Debian package (installed, or fetched into "$tmp").
# shellcheck source=../package_file.sh
source "$here/../package_file.sh"

# 2. The traced chain: openclipart's "Gold Chain of Round Links" (public domain).
svg="$(package_file openclipart-svg \
  usr/share/openclipart/svg/signs_and_symbols/money/gold_chain_of_round_lin_01.svg)"
rsvg-convert -w 220 -h 220 "$svg" -o "$tmp/chain_220.png"
"$PYTHON" "$here/trace_contours.py" "$tmp/chain_220.png" "$here"

# 3. A cube of atoms of the crystal structure PDB 1TII.
"$PYTHON" "$here/pdb_atoms.py" "$(package_file pymol-data usr/share/pymol/data/demo/1tii.pdb)" "$here"

# 4. A real 3D sheet with normals: CGAL's fin (CC0), from Debian's libcgal-demo.
"$PYTHON" "$here/cgal_sheet.py" "$(package_file libcgal-demo usr/share/doc/libcgal-dev/data.tar.gz)" "$here"

# 5. Checks every CSV and writes cases.json.
"$PYTHON" "$here/make_manifest.py" "$here" "$tmp/windows.tsv"
