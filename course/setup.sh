#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image
# (Ubuntu 22.04 unless the assignment picks another), with the autograder's
# zip unpacked in /autograder/source and Glint's source tree in
# /autograder/source/glint. It installs Rust if there is none, lavapipe
# (Mesa's software Vulkan) with Glint's own .ci/setup, then builds glint and
# installs it in /usr/local/bin. What is there already is left as it is, so a
# second run installs nothing.
#
# GLINT_AUTOGRADER (default /autograder) is the autograder's folder and
# GLINT_SETUP_ROOT (default /) where the machine's files are read, as
# .ci/setup reads them: crates/glint-cli/tests/course_kit.rs runs this script
# on temporary folders with stub commands.
set -euo pipefail
autograder="${GLINT_AUTOGRADER:-/autograder}"
glint_source="$autograder/source/glint"
root="${GLINT_SETUP_ROOT:-}"
root="${root%/}"

say() { echo "setup.sh: $*" >&2; }
have() { command -v "$1" >/dev/null 2>&1; }

cargo_home="${CARGO_HOME:-${HOME:-/root}/.cargo}"
export PATH="$cargo_home/bin:$PATH"
if ! have cargo; then
  have curl || { apt-get update -qq && apt-get install -y -qq curl; }
  say "installing Rust with rustup"
  curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal
fi

# Ubuntu's own Mesa is older than 25, whose lavapipe may end long shader
# loops early (docs/golden-ci.md, "Installing lavapipe"); kisak's PPA has a
# newer one, which .ci/setup then installs.
os_id=$( (. "$root/etc/os-release" 2>/dev/null && echo "${ID:-}") || true)
if [ "$os_id" = ubuntu ] && ! grep -rqs kisak-mesa "$root/etc/apt/sources.list.d"; then
  have add-apt-repository || { apt-get update -qq && apt-get install -y -qq software-properties-common; }
  say "adding ppa:kisak/kisak-mesa for Mesa 25 or newer"
  add-apt-repository -y ppa:kisak/kisak-mesa
fi
bash "$glint_source/.ci/setup"

version=$(sed -n 's/^version = "\(.*\)"$/\1/p' "$glint_source/Cargo.toml" | head -n1)
if [ "$(glint --version 2>/dev/null)" = "glint $version" ]; then
  say "glint $version is installed"
else
  cargo install --locked --path "$glint_source/crates/glint-cli" --root /usr/local
fi
# The adapter the autograder will render on: lavapipe, or the build fails here.
glint info
