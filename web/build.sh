#!/usr/bin/env bash
# Builds Glint's page into a static folder (web/ in cargo's target folder by
# default, or $1):
# the viewer compiled to WebAssembly, bound by wasm-bindgen, and index.html.
# Any static web server (or GitHub Pages) can host the folder.
# Installs the wasm32 target and wasm-bindgen-cli when missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
# Where cargo puts what it builds: CARGO_TARGET_DIR when set (relative to here).
target="${CARGO_TARGET_DIR:-target}"
out="${1:-$target/web}"

bash web/install-tools.sh
cargo build --release --target wasm32-unknown-unknown -p glint-web
mkdir -p "$out"
# Without the names of functions (1.4 MB of 11.5), which only a debugger reads.
wasm-bindgen --target web --no-typescript --remove-name-section --remove-producers-section \
    --out-dir "$out" "$target/wasm32-unknown-unknown/release/glint_web.wasm"
cp web/index.html "$out/index.html"
echo "built $out"
