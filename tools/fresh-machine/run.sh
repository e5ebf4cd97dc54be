#!/usr/bin/env bash
# Runs the README's two quick-start commands as a new user would, in a clean
# Debian 12 root made by debootstrap: Rust (the host's toolchain, bind-mounted,
# with an empty cargo home), gcc, and Node.js 20 from NodeSource
# when the host has it (repacked from the host's package: the machine on which
# the README's first command once failed). Prints each command's time.
#
#   sudo bash tools/fresh-machine/run.sh DIR [render|tests|both]
#
# DIR is made if missing and reused if it already holds a root; the clone of
# this repository in it is made anew each time. Needs debootstrap (and
# dpkg-repack for NodeSource's nodejs): apt-get install debootstrap dpkg-repack.
set -euo pipefail
dir=$(realpath -m "$1")
what=${2:-both}
repo=$(cd "$(dirname "$0")/../.." && pwd)

if [ ! -x "$dir/bin/bash" ]; then
  mirror=$(awk '/^URIs:/ {print $2; exit}' /etc/apt/sources.list.d/debian.sources 2>/dev/null || true)
  debootstrap --include=ca-certificates,gcc,libc6-dev,git bookworm "$dir" "${mirror:-http://deb.debian.org/debian}"
  cp /etc/apt/sources.list.d/debian.sources "$dir/etc/apt/sources.list.d/" 2>/dev/null || true
fi
if dpkg-query -W -f='${Version}' nodejs 2>/dev/null | grep -q nodesource \
    && ! chroot "$dir" dpkg-query -W nodejs >/dev/null 2>&1; then
  (cd "$dir/tmp" && dpkg-repack nodejs >/dev/null)
  chroot "$dir" sh -c 'dpkg -i /tmp/nodejs_*.deb && rm /tmp/nodejs_*.deb'
fi

mounted=()
bind() { mkdir -p "$dir$2"; mount --bind "$1" "$dir$2"; mounted=("$dir$2" "${mounted[@]}"); }
cleanup() { for m in "${mounted[@]}"; do umount -l "$m" || true; done; }
trap cleanup EXIT
bind /proc /proc
bind /sys /sys
bind /dev /dev
bind /dev/pts /dev/pts
bind "$HOME/.rustup" /root/.rustup
cp /etc/resolv.conf "$dir/etc/resolv.conf"
mkdir -p "$dir/root/.cargo/bin"
cp -a "$HOME/.cargo/bin/." "$dir/root/.cargo/bin/"

rm -rf "$dir/work/glint"
mkdir -p "$dir/work"
git clone -q "$repo" "$dir/work/glint"

in_root() {
  chroot "$dir" /usr/bin/env -i HOME=/root TERM=dumb PATH=/root/.cargo/bin:/usr/local/bin:/usr/bin:/bin \
    RUSTUP_HOME=/root/.rustup CARGO_HOME=/root/.cargo bash -c "cd /work/glint && $1"
}
timed() {
  local start=$SECONDS
  echo "fresh-machine: $1" >&2
  if in_root "$1"; then
    echo "fresh-machine: ok in $((SECONDS - start)) s: $1" >&2
  else
    echo "fresh-machine: FAILED after $((SECONDS - start)) s: $1" >&2
    return 1
  fi
}
case "$what" in
  render|both) timed "bash .ci/setup && cargo run --release -- render scenes/showcase.toml -o showcase.png" ;;
esac
case "$what" in
  tests|both) timed "bash .ci/setup --tests && cargo test --release --workspace" ;;
esac
