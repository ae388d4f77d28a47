#!/usr/bin/env bash
# Installs what Boneless needs, builds it and opens the application on the project's generated
# demo: a human body walking, its 39 markers (a Plug-in Gait style set) recorded as a C3D take
# (10 mm off the skin, with gaps), with its correspondence already authored. Press Space to play.
# (scripts/demo-cli.sh runs the same demo through the command line instead.)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
"$root/scripts/build.sh" --target boneless
# CHOLMOD's OpenMP threads and OpenBLAS's would otherwise compete for the same cores.
export OPENBLAS_NUM_THREADS=1
exec "$build/bin/boneless" "$@"
