#!/usr/bin/env bash
# Installs the packages and builds Boneless into $BONELESS_BUILD_DIR (default: build/).
# Extra arguments are passed to `cmake --build` (for example `--target boneless-cli`).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$(nproc)" "$@"
