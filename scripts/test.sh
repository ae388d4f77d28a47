#!/usr/bin/env bash
# Builds Boneless and runs every test (unit, CLI, real data when ../shared/data is present).
# Installs what it needs first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
build=${build%/}  # build-asan beside it, not build/-asan inside it
"$root/scripts/build.sh"
# CHOLMOD's OpenMP threads and OpenBLAS's would otherwise compete for the same cores.
export OPENBLAS_NUM_THREADS=1
ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
# The C3D reader reads untrusted files: its tests again under ASan/UBSan, then a short fuzzing run.
ASAN_BUILD="$build-asan" FUZZ_BUILD="$build-fuzz" "$root/scripts/ci-c3d.sh"
