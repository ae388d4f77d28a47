#!/bin/sh
# boneless-bench-take on folders it cannot measure: it aborted with an uncaught exception
# ("body.pc2: cannot open", or nlohmann's parse_error naming no file). Each must be one line
# naming the file and what is wrong, and exit 1.
# Usage: bench-take-says-which-file-is-wrong.sh BENCH CLI WORKDIR
bench=$1 cli=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 2
"$cli" demo --out "$work/demo" >/dev/null 2>&1 || exit 2
mesh="--mesh $work/demo/walker.obj --map $work/demo/walker.map.json"
fail=0
expect() {  # expect NAME TEXT COMMAND...: exit 1 and TEXT in what it prints
    name=$1 text=$2
    shift 2
    out=$("$@" 2>&1)
    code=$?
    if [ $code -ne 1 ] || ! printf '%s' "$out" | grep -qF -- "$text"; then
        echo "FAIL $name: exit $code, wanted 1 and \"$text\" in:"
        echo "$out"
        fail=1
    fi
}
"$cli" solve $mesh --c3d "$work/demo/walker.c3d" --out "$work/obj" --format obj --frames 0:3 \
    --quiet >/dev/null 2>&1 || exit 2
expect "solved to OBJ" "$work/obj/walker.pc2: cannot open" "$bench" $mesh --solved "$work/obj"
expect "no folder" "$work/missing/walker.json: cannot open" "$bench" $mesh --solved "$work/missing"
"$cli" solve $mesh --c3d "$work/demo/walker.c3d" --out "$work/calibrated" --format pc2 \
    --frames 0:3 --quiet >/dev/null 2>&1 || exit 2
expect "no calibrated rest" "solve again with --write-calibrated-rest" "$bench" $mesh \
    --solved "$work/calibrated"
exit $fail
