#!/usr/bin/env bash
# Builds the playground into web/dist: the WebAssembly module (release, wasm32-unknown-unknown),
# its JavaScript glue (wasm-bindgen-cli of the exact version in the workspace's Cargo.lock, installed from
# the crate registry into web/.tools when missing), the page and the real exemplars it offers.
# Serve with: python3 -m http.server --bind 127.0.0.1 -d web/dist 8000   (then open http://127.0.0.1:8000)
set -euo pipefail
cd "$(dirname "$0")"
rustup target list --installed 2> /dev/null | grep -q wasm32-unknown-unknown || rustup target add wasm32-unknown-unknown
# The workspace's `wasm` profile (LTO, one codegen unit), into the workspace's target folder.
cargo build --profile wasm --locked --target wasm32-unknown-unknown -p motif-web
wasm="${CARGO_TARGET_DIR:-../target}/wasm32-unknown-unknown/wasm/motif_web.wasm"
version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/"/, "", $3); print $3; exit }' ../Cargo.lock)
bindgen=.tools/bin/wasm-bindgen
if ! [ -x "$bindgen" ] || [ "$("$bindgen" --version | awk '{print $2}')" != "$version" ]; then
  echo "installing wasm-bindgen-cli $version into web/.tools"
  # --locked pins the CLI's own dependencies; a registry mirror missing one of those versions
  # falls back to the newest compatible ones. The first attempt's messages are kept back unless
  # both fail, so that a build that succeeds prints no error line.
  locked_log=$(mktemp)
  if ! cargo install --locked --quiet --root .tools wasm-bindgen-cli --version "$version" 2> "$locked_log"; then
    echo "some of wasm-bindgen-cli's locked dependencies are not in this registry; using the newest compatible ones"
    if ! cargo install --quiet --root .tools wasm-bindgen-cli --version "$version"; then
      echo "the locked install failed first with:" >&2
      cat "$locked_log" >&2
      rm -f "$locked_log"
      exit 1
    fi
  fi
  rm -f "$locked_log"
fi
rm -rf dist.tmp
mkdir -p dist.tmp/pkg dist.tmp/exemplars
"$bindgen" --target web --no-typescript --out-dir dist.tmp/pkg "$wasm"
cp index.html main.js worker.js style.css dist.tmp/
cp ../data/real/curve/chain_small.png ../data/real/curve/rope.png ../data/real/curve/vine.png dist.tmp/exemplars/
rm -rf dist
mv dist.tmp dist
echo "built web/dist ($(du -sh dist/pkg/motif_web_bg.wasm | cut -f1) of WebAssembly)"
