#!/usr/bin/env bash
# Rebuilds every file of this folder (the real stroke-pattern corpus) from public sources.
#
# Needs
#   Debian packages openclipart-svg (the drawings) and python3-skimage (the photograph); they
#   need not be installed: if they are not, this script fetches them with `apt-get download`
#   into a temporary folder and unpacks them there.
#   Python 3 with the pip packages svgelements (reads the SVG drawings) and Pillow (the
#   photograph), e.g.
#     python3 -m venv /tmp/venv && /tmp/venv/bin/pip install svgelements==1.9.6 Pillow==13.0.0
#     PYTHON=/tmp/venv/bin/python bash data/real/strokes/build.sh
# Made with openclipart-svg 1:0.18+dfsg-19, python3-skimage 0.19.3-8, Python 3.11.7,
# svgelements 1.9.6 and Pillow 13.0.0. Other Pillow (zlib) versions may change the PNG's bytes,
# not its pixels.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PYTHON="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# package_file PACKAGE PATH: a file of a Debian package (installed, or fetched into "$tmp").
# shellcheck source=../package_file.sh
source "$here/../package_file.sh"

"$PYTHON" "$here/extract.py" --list > "$tmp/sources.txt"
while read -r name package path; do
  "$PYTHON" "$here/extract.py" "$name" "$(package_file "$package" "$path")" "$here"
done < "$tmp/sources.txt"
