#!/usr/bin/env bash
# Builds Boneless and runs it on the project's generated demo: a creature whose true motion is
# known, reconstructed from 30 of its vertices by Boneless and by ARAP, side by side.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
"$root/scripts/build.sh" --target boneless-cli
export OPENBLAS_NUM_THREADS=1
"$build/bin/boneless-cli" demo --out "$build/demo"
"$build/bin/boneless-cli" eval --sequence "$build/demo" --markers 30 --method both
