#!/usr/bin/env bash
# Builds the command-line tool and runs it on the project's generated demo: a creature whose true motion is
# known, its markers recorded as a C3D take (10 mm off the skin, with gaps), and its
# correspondence file. The take is solved into an OBJ sequence, then the truth is reconstructed
# from 30 vertices by Boneless and by ARAP and the errors printed side by side.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BONELESS_BUILD_DIR:-$root/build}
"$root/scripts/build.sh" --target boneless-cli
export OPENBLAS_NUM_THREADS=1
cli="$build/bin/boneless-cli"
demo="$build/demo"
"$cli" demo --out "$demo"
"$cli" solve --mesh "$demo/creature.obj" --c3d "$demo/creature.c3d" \
  --map "$demo/creature.map.json" --out "$demo/solved"
echo "OBJ sequence and its sidecar: $demo/solved/"
"$cli" eval --sequence "$demo/truth" --markers 30 --method both --quiet
