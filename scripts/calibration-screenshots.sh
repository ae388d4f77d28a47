#!/usr/bin/env bash
# The before/after pictures of docs/calibration.md: CMU 85_02 frame 577 on the MakeHuman `body`,
# solved with --calibrate none and with shape, drawn by the app's own screenshot path
# (`boneless --project P --frame N --screenshot OUT`, under Xvfb): whole body and right hand.
#
#   scripts/calibration-screenshots.sh [BUILD_DIR]    # writes docs/images/calibration-*.png
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
DATA="$ROOT/../shared/data"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT

# name calibrate focal_x focal_y focal_z distance
shot() {
    python3 - "$WORK/$1.boneless" "$2" "$3" "$4" "$5" "$6" "$DATA" "$ROOT" <<'PY'
import json, sys
out, calibrate, x, y, z, distance, data, root = sys.argv[1:]
mapPath = root + "/tests/data/cmu-85_02-makehuman-body.map.json"
focal = [float(x), float(y), float(z)]
json.dump({"format": "boneless-project", "version": 1,
           "mesh": {"file": data + "/meshes/makehuman/makehuman_base.obj", "group": "body"},
           "take": {"file": data + "/c3d/cmu/85_02.c3d"},
           "correspondence": {"file": mapPath, "modified": False, "map": json.load(open(mapPath))},
           "alignment": None, "settings": {"calibrate": calibrate},
           "view": {"camera": {"position": [focal[0], focal[1], focal[2] + float(distance)],
                               "focal_point": focal, "view_up": [0, 1, 0], "view_angle": 30}}},
          open(out, "w"))
PY
    XDG_CONFIG_HOME="$WORK/config" XDG_DATA_HOME="$WORK/data" XDG_CACHE_HOME="$WORK/cache" \
        OPENBLAS_NUM_THREADS=1 "$ROOT/tests/gui/run-with-display.sh" "$BUILD/bin/boneless" \
        --project "$WORK/$1.boneless" --frame 577 --screenshot "$WORK/$1.png" --size 480x360
}

mkdir -p "$ROOT/docs/images"
for calibrate in none shape; do
    shot "body-$calibrate" "$calibrate" -4.13 -1.52 8.55 34
    shot "hand-$calibrate" "$calibrate" 1.6 -7.0 8.7 9
    for part in body hand; do
        cp "$WORK/$part-$calibrate.png" \
            "$ROOT/docs/images/calibration-cmu-85_02-frame577-$part-$calibrate.png"
    done
done
