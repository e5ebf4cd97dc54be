#!/usr/bin/env bash
# Installs what building Glint's page needs, when missing: the wasm32 target
# and wasm-bindgen-cli at the version of the wasm-bindgen crate in Cargo.lock
# (the two must match). Used by web/build.sh and .ci/setup.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi
version="$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' "$root/Cargo.lock")"
if [ "$(wasm-bindgen --version 2>/dev/null | cut -d' ' -f2)" != "$version" ]; then
    # --locked as released; a registry that lacks one of its locked
    # dependencies' versions gets the newest compatible ones instead.
    cargo install wasm-bindgen-cli --version "$version" --locked \
        || cargo install wasm-bindgen-cli --version "$version"
fi
