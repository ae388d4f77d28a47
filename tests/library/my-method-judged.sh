#!/usr/bin/env bash
# docs/library.md's example program, built against the core, writes its answers for the demo's
# true motion; `eval --reconstruction` judges them, and since the example asks Boneless's own
# solver with eval's markers, it finds what `eval --markers` finds.
# Usage: my-method-judged.sh MY_METHOD BONELESS_CLI BUILD_DIR
set -euo pipefail
method=$1 cli=$2 build=$3
work=$(mktemp -d "$build/library-judged.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$cli" demo --out "$work/demo" --frame-count 5 >/dev/null
"$method" "$work/demo/truth" 20 "$work/mine"
"$cli" eval --sequence "$work/demo/truth" --reconstruction "$work/mine" --json >"$work/judged.json"
"$cli" eval --sequence "$work/demo/truth" --markers 20 --json >"$work/eval.json"
/usr/bin/python3 - "$work/judged.json" "$work/eval.json" <<'PY'
import json, sys
judged, own = (json.load(open(p)) for p in sys.argv[1:3])
assert judged["method"] == "reconstruction", judged["method"]
assert judged["frame_count"] == own["frame_count"] == 4, (judged["frame_count"], own["frame_count"])
for key in ("rms_pct_mean", "max_pct_worst_frame"):
    assert abs(judged[key] - own[key]) < 1e-6 * max(1.0, own[key]), (key, judged[key], own[key])
print("my-method-judged: ok", judged["rms_pct_mean"])
PY
