#!/usr/bin/env bash
# Rebuilds bull.obj (the real triangle-mesh corpus) from Debian's libcgal-demo.
#
# Needs Python 3 (standard library only) and apt-get/dpkg-deb: libcgal-demo need not be
# installed; if it is not, this script fetches it with `apt-get download` into a temporary
# folder and unpacks it there. Made with libcgal-demo 5.5.1-2 (Debian bookworm), Python 3.11.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
PYTHON="${PYTHON:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# package_file PACKAGE PATH: a file of a Debian package (installed, or fetched into "$tmp").
# shellcheck source=../package_file.sh
source "$here/../package_file.sh"

data="$(package_file libcgal-demo usr/share/doc/libcgal-dev/data.tar.gz)"
"$PYTHON" "$here/off_to_obj.py" "$data" data/meshes/bull.off "$here/bull.obj" \
  "bull: CGAL 5.5.1 data/meshes/bull.off, from Debian libcgal-demo 5.5.1-2" \
  "(usr/share/doc/libcgal-dev/data.tar.gz, member data/meshes/bull.off)." \
  "Licence: CC0 1.0 (CGAL's LICENSE, quoted in /usr/share/doc/libcgal-dev/copyright: files" \
  "without an explicit copyright notice are under Creative Commons CC0 1.0)." \
  "Converted OFF -> OBJ by data/real/meshes/off_to_obj.py: coordinates copied verbatim," \
  "faces 1-based in the original order. 6200 vertices, 12396 triangles, closed 2-manifold, genus 0."

"$PYTHON" "$here/off_to_obj.py" "$data" data/meshes/tripod.off "$here/tripod.obj" \
  "tripod: CGAL 5.5.1 data/meshes/tripod.off, from Debian libcgal-demo 5.5.1-2" \
  "(usr/share/doc/libcgal-dev/data.tar.gz, member data/meshes/tripod.off)." \
  "Licence: CC0 1.0 (CGAL's LICENSE, quoted in /usr/share/doc/libcgal-dev/copyright: files" \
  "without an explicit copyright notice are under Creative Commons CC0 1.0)." \
  "Converted OFF -> OBJ by data/real/meshes/off_to_obj.py: coordinates copied verbatim," \
  "faces 1-based in the original order. 24 vertices, 44 triangles, closed 2-manifold, genus 0."
