#!/usr/bin/env bash
# CI for the C3D reader: its unit tests under AddressSanitizer + UndefinedBehaviorSanitizer, then
# a short libFuzzer run seeded with the real files in ../shared/data/c3d (when present).
#
#   scripts/ci-c3d.sh                 # 60 s of fuzzing
#   FUZZ_SECONDS=600 scripts/ci-c3d.sh
#   STEPS=fuzz scripts/ci-c3d.sh      # one step only ("asan", "fuzz")
#
# Exits non-zero on a test failure, a sanitizer report or a fuzzer crash (the crashing input is
# left in $FUZZ_BUILD/fuzz-ci/ for reproduction: boneless-fuzz-c3d <file>).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ASAN_BUILD="${ASAN_BUILD:-$ROOT/build-c3d-asan}"
FUZZ_BUILD="${FUZZ_BUILD:-$ROOT/build-fuzz}"
FUZZ_SECONDS="${FUZZ_SECONDS:-60}"
JOBS="${JOBS:-2}"
STEPS="${STEPS:-asan fuzz}"

if [[ " $STEPS " == *" asan "* ]]; then
echo "== C3D and mesh reader unit tests, ASan + UBSan ($ASAN_BUILD)"
cmake -S "$ROOT" -B "$ASAN_BUILD" -G Ninja -DBONELESS_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build "$ASAN_BUILD" --target boneless_reader_tests -j"$JOBS"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$ASAN_BUILD/bin/boneless_reader_tests" --gtest_brief=1
fi

if [[ " $STEPS " == *" fuzz "* ]]; then
echo "== C3D reader fuzzing, ${FUZZ_SECONDS} s ($FUZZ_BUILD)"
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$FUZZ_BUILD" -G Ninja -DBONELESS_FUZZ=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$FUZZ_BUILD" --target boneless-fuzz-c3d -j"$JOBS"
work="$FUZZ_BUILD/fuzz-ci"
mkdir -p "$work/corpus" "$work/seeds"
shared="$ROOT/../shared/data/c3d"
if [ -d "$shared" ]; then
    find "$shared" -name '*.c3d' -size +0 -exec cp -f {} "$work/seeds/" \;
fi
set +e
"$FUZZ_BUILD/bin/boneless-fuzz-c3d" -max_total_time="$FUZZ_SECONDS" -max_len=4096 \
    -dict="$ROOT/tests/fuzz/c3d.dict" -artifact_prefix="$work/" -print_final_stats=1 \
    "$work/corpus" "$work/seeds" 2>&1 | grep -E '^(stat::|Done)|ERROR|SUMMARY|crash'
status=${PIPESTATUS[0]}  # libFuzzer's, not grep's
set -e
if [ "$status" -ne 0 ]; then
    echo "fuzzer failed (status $status); inputs in $work" >&2
    exit "$status"
fi

# The other loaders, each seeded by the project's own writers (--write-seeds): the OBJ reader,
# PLY/OFF/STL through OpenMesh, the correspondence loader and the app's project loader (whose
# seeds are whole saved projects, larger than the other inputs).
LOADER_SECONDS="${LOADER_SECONDS:-20}"
for name in obj mesh correspondence project; do
    max_len=4096
    [ "$name" = project ] && max_len=65536
    echo "== $name loader fuzzing, ${LOADER_SECONDS} s"
    cmake --build "$FUZZ_BUILD" --target "boneless-fuzz-$name" -j"$JOBS"
    dir="$FUZZ_BUILD/fuzz-ci-$name"
    mkdir -p "$dir/corpus"
    "$FUZZ_BUILD/bin/boneless-fuzz-$name" --write-seeds="$dir/seeds" >/dev/null 2>&1 || true
    set +e
    "$FUZZ_BUILD/bin/boneless-fuzz-$name" -max_total_time="$LOADER_SECONDS" -max_len="$max_len" \
        -dict="$ROOT/tests/fuzz/$name.dict" -artifact_prefix="$dir/" -print_final_stats=1 \
        "$dir/corpus" "$dir/seeds" 2>&1 | grep -E '^(stat::number_of_executed|Done)|ERROR|SUMMARY|crash'
    status=${PIPESTATUS[0]}
    set -e
    if [ "$status" -ne 0 ]; then
        echo "fuzzer $name failed (status $status); inputs in $dir" >&2
        exit "$status"
    fi
done
fi
echo "== C3D CI passed ($STEPS)"
