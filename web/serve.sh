#!/usr/bin/env bash
# Builds Glint's page (web/build.sh) and serves it on 127.0.0.1:${PORT:-8080}.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/target/web"
port="${PORT:-8080}"
bash "$root/web/build.sh" "$out"
echo "Glint is at http://127.0.0.1:$port/ (Ctrl-C stops the server)"
exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$out"
