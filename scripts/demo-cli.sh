#!/usr/bin/env bash
# Builds the command-line tool and runs it on the project's generated demo: a human body walking,
# whose true motion is known, its 39 markers (a Plug-in Gait style set) recorded as a C3D take
# (10 mm off the skin, with gaps), and its correspondence file. The take is solved into an OBJ
# sequence, then the truth is reconstructed from 39 vertices by Boneless and by ARAP and the errors
# printed side by side.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
"$root/scripts/build.sh" --target boneless-cli
export OPENBLAS_NUM_THREADS=1
cli="$build/bin/boneless-cli"
demo="$build/demo"
"$cli" demo --out "$demo"
"$cli" solve --mesh "$demo/walker.obj" --c3d "$demo/walker.c3d" \
  --map "$demo/walker.map.json" --out "$demo/solved"
echo "OBJ sequence and its sidecar: $demo/solved/"
"$cli" eval --sequence "$demo/truth" --markers 39 --method both --quiet
