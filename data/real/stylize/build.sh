#!/usr/bin/env bash
# Rebuilds the real textures of the stylize corpus (PNG) from GIMP's patterns in Debian's
# gimp-data, and copies scikit-image's CC0 photo of a cat (chelsea.png) from python3-skimage. Needs Python 3 (standard library only) and apt-get/dpkg-deb: gimp-data need not be
# installed; if it is not, this script fetches it with `apt-get download` into a temporary folder
# (the same for python3-skimage). Then makes the anti-aliased segment guides
# chelsea_segments.png and stone_segments.png from them with segment_guides.py.
# Also copies GNOME's 4096 x 4096 wood wallpaper (wood-4096.webp) from gnome-backgrounds.
# Made with gimp-data 2.10.34-1+deb12u10, python3-skimage 0.19.3-8 and gnome-backgrounds 43.1-1
# (Debian bookworm), Python 3.11.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PYTHON="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# shellcheck source=../package_file.sh
source "$here/../package_file.sh"

for pattern in Stone/brick Stone/stone33 Wood/bark Wood/walnut Fabric/burlap Plant/leaves Wood/parque1 Wood/parque2; do
  file="$(package_file gimp-data "usr/share/gimp/2.0/patterns/$pattern.pat")"
  name="$(basename "$pattern" | tr '[:upper:]' '[:lower:]')"
  "$PYTHON" "$here/pat_to_png.py" "$file" "$here/$name.png"
done

# The photo the video footage is filmed over (`motif demo`, `motif bench --case video`): copied
# byte for byte.
cp "$(package_file python3-skimage usr/lib/python3/dist-packages/skimage/data/chelsea.png)" "$here/chelsea.png"

# A texture at its native size for the speed of large exemplars (`motif bench --case
# texture-native`): GNOME's wood panel wallpaper, 4096 x 4096 WebP, copied byte for byte.
cp "$(package_file gnome-backgrounds usr/share/backgrounds/gnome/wood-l.webp)" "$here/wood-4096.webp"

# Anti-aliased segment guides made from the photo and the stone wall (standard library only).
"$PYTHON" "$here/segment_guides.py" "$here"
