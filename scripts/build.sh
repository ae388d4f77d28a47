#!/usr/bin/env bash
# Installs the packages and builds Boneless into $BONELESS_BUILD_DIR (default: build/).
# Extra arguments are passed to `cmake --build` (for example `--target boneless-cli`).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
build=${build%/}
# apt-get needs root; a user builds with what root installed (cmake names anything missing).
if [ "$(id -u)" -eq 0 ]; then
  "$root/scripts/install-deps.sh"
else
  echo "build.sh: not root, so no packages are installed (scripts/install-deps.sh as root does it)" >&2
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$(nproc)" "$@"
