#!/usr/bin/env bash
# Rebuilds every file of this folder (the real exemplar and curve corpus of `motif curve`) from
# public sources.
#
# Needs
#   Debian packages: librsvg2-bin (rsvg-convert, the SVG renderer) and r-base-core (Rscript).
#                    The sources, openclipart-svg (drawings), inkscape (one example drawing),
#                    fonts-dejavu-core (a glyph), r-cran-maps and r-cran-mapdata (the Rhine), need
#                    not be installed: for each one that is not, this script fetches it with
#                    `apt-get download` into a temporary folder and unpacks it there.
#   Python 3 with the pip packages numpy, Pillow and fonttools, e.g.
#     python3 -m venv /tmp/venv && /tmp/venv/bin/pip install numpy Pillow fonttools
#     PYTHON=/tmp/venv/bin/python bash data/real/curve/build.sh
# Made on Debian 12 (bookworm) with librsvg 2.54.7 (rsvg-convert 2.54.7), openclipart-svg
# 1:0.18+dfsg-19, inkscape 1.2.2-2+deb12u1, fonts-dejavu-core 2.37-6, R 4.2.2, maps 3.4.1
# (r-cran-maps 3.4.1-1), mapdata 2.3.1 (r-cran-mapdata 2.3.1-1), Python 3.11, numpy 2.4.6,
# Pillow 13.0.0, fonttools 4.68.0. resvg is not packaged in bookworm, so rsvg-convert renders.
# Another librsvg or Pillow may change the PNGs' pixels or bytes slightly; the curves depend only
# on the sources and Python's float formatting.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PYTHON="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# package_file PACKAGE PATH: a file of a Debian package (installed, or fetched into "$tmp").
# shellcheck source=../package_file.sh
source "$here/../package_file.sh"

# 1. Exemplars: render each drawing with rsvg-convert at a fixed width (height from the aspect
#    ratio), then exemplars.py rotates and crops it into a horizontal strip.
oc=usr/share/openclipart/svg
mkdir -p "$tmp/render"
while read -r name package rel width; do
  svg="$(package_file "$package" "$rel")"
  rsvg-convert -a -w "$width" "$svg" -o "$tmp/render/$name.png"
done <<TABLE
chain_round openclipart-svg $oc/signs_and_symbols/money/gold_chain_of_round_lin_01.svg 300
chain_oval  openclipart-svg $oc/signs_and_symbols/chain_nicu_buculei_01.svg 280
rope        openclipart-svg $oc/transportation/boating/knot_figure_eight.svg 1400
vine        openclipart-svg $oc/recreation/games/cards/celtic-vine-corner_steve_01.svg 700
beads       openclipart-svg $oc/special/patterns/pattern-dots-square-grid-09.svg 400
helix       openclipart-svg $oc/science/double_helix_anthony_lie_01.svg 684
fretwork    openclipart-svg $oc/decorations/motivo_geometrico_archit_01.svg 300
filigree    inkscape        usr/share/inkscape/examples/eastern-motive-P4G.svg 1000
teeth       openclipart-svg $oc/special/patterns/pattern-triangles-1.svg 250
chain_wide  openclipart-svg $oc/signs_and_symbols/money/gold_chain_of_round_lin_01.svg 400
chain_small openclipart-svg $oc/signs_and_symbols/money/gold_chain_of_round_lin_01.svg 258
filigree_wide inkscape      usr/share/inkscape/examples/eastern-motive-P4G.svg 560
chain_dense openclipart-svg $oc/signs_and_symbols/money/gold_chain_curved_as_a__01.svg 1000
chain_large openclipart-svg $oc/signs_and_symbols/money/gold_chain_of_round_lin_01.svg 700
TABLE
"$PYTHON" "$here/exemplars.py" "$tmp/render" "$here"

# 2. The Rhine polyline of mapdata's `rivers` database (lon, lat).
maps_lib="$(dirname "$(dirname "$(package_file r-cran-maps usr/lib/R/site-library/maps/DESCRIPTION)")")"
mapdata_lib="$(dirname "$(dirname "$(package_file r-cran-mapdata usr/lib/R/site-library/mapdata/DESCRIPTION)")")"
Rscript "$here/rhine.R" "$maps_lib:$mapdata_lib" "$tmp/rhine_lonlat.csv"

# 3. Curves: a hand-drawn flourish, a glyph outline, the Rhine and a heart with a cusp.
"$PYTHON" "$here/curves.py" "$here" \
  "$(package_file openclipart-svg $oc/decorations/flourish_one_horizontal_01.svg)" \
  "$(package_file openclipart-svg $oc/shapes/heart_jon_phillips_01.svg)" \
  "$(package_file fonts-dejavu-core usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf)" \
  "$tmp/rhine_lonlat.csv"

# 4. Checks every file and writes cases.json.
"$PYTHON" "$here/make_manifest.py" "$here"
