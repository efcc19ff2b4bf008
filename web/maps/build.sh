#!/usr/bin/env bash
# Builds the slippy map page into web/maps/dist: Leaflet from the npm registry (the version that
# package-lock.json pins), the page and its script. Serve it with any static server, e.g.
#   python3 -m http.server --bind 127.0.0.1 -d web/maps/dist 8001
# and open http://127.0.0.1:8001/?tiles=http://127.0.0.1:8081 beside `motif tiles serve --port 8081`.
set -euo pipefail
cd "$(dirname "$0")"
npm ci --no-audit --no-fund --silent
rm -rf dist.tmp
mkdir -p dist.tmp
cp node_modules/leaflet/dist/leaflet.js node_modules/leaflet/dist/leaflet.css dist.tmp/
cp -r node_modules/leaflet/dist/images dist.tmp/
cp index.html maps.js dist.tmp/
rm -rf dist
mv dist.tmp dist
echo "built web/maps/dist (Leaflet $(node -p "require('./node_modules/leaflet/package.json').version"))"
