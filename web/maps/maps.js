// The slippy map over `motif tiles serve`: the stylized and the plain layer of the server named by
// `?tiles=URL` (default http://127.0.0.1:8081), switchable in the layers control. The server's
// /tiles.json gives the map's bounds (the first view fits them) and zoom levels. `window.motifMap` holds the state the
// browser test reads: the map, its layers and the count of tiles loaded and failed.
'use strict';

(async function () {
  const status = document.getElementById('status');
  const base = (new URLSearchParams(location.search).get('tiles') || 'http://127.0.0.1:8081').replace(/\/+$/, '');
  let info;
  try {
    const response = await fetch(`${base}/tiles.json`);
    info = await response.json();
  } catch (error) {
    status.textContent = `no tile server at ${base} (start one: motif tiles serve --map MAP.osm.pbf --port 8081)`;
    return;
  }
  const [west, south, east, north] = info.bounds;
  const map = L.map('map', { minZoom: info.minzoom, maxZoom: info.maxzoom });
  map.fitBounds([[south, west], [north, east]]);
  const state = { map, loaded: 0, failed: 0, layers: {}, current: 'stylized' };
  window.motifMap = state;
  const options = { tileSize: info.tile_size, minZoom: info.minzoom, maxZoom: info.maxzoom, attribution: info.attribution };
  for (const [name, path] of [['stylized', '/{z}/{x}/{y}.png'], ['plain', '/plain/{z}/{x}/{y}.png']]) {
    const layer = L.tileLayer(base + path, options);
    layer.on('tileload', () => { state.loaded += 1; });
    layer.on('tileerror', () => { state.failed += 1; });
    state.layers[name] = layer;
  }
  state.layers.stylized.addTo(map);
  map.on('baselayerchange', (event) => { state.current = event.layer === state.layers.plain ? 'plain' : 'stylized'; });
  L.control.layers({ 'stylized (motif)': state.layers.stylized, 'plain segment map': state.layers.plain }).addTo(map);
  status.textContent = `tiles from ${base}`;
})();
