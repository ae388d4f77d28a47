#!/usr/bin/env bash
# Builds Boneless and runs every test (unit, CLI, real data when ../shared/data is present, the
# C3D reader under AddressSanitizer/UBSan, and a short fuzzing run). Installs what it needs first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
"$root/scripts/install-deps.sh"
# CHOLMOD's OpenMP and OpenBLAS's threads would otherwise fight over the two cores.
export OPENBLAS_NUM_THREADS=1
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$(nproc)"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
