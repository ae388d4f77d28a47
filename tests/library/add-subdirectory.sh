#!/usr/bin/env bash
# Another project adds a clone of Boneless with add_subdirectory, as docs/library.md says, and its
# configure step succeeds and offers boneless_core (until 30 November 2026 it failed: the clone
# looked for its CMake modules and LICENSE in the other project's folder).
# Usage: add-subdirectory.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source=$1 build=$2
work=$(mktemp -d "$build/library-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
if ! cmake -S "$source/tests/library/consumer" -B "$work" -G Ninja -DBONELESS_DIR="$source" \
     >"$work/configure.log" 2>&1; then
  cat "$work/configure.log" >&2
  echo "add-subdirectory: configuring a project that adds Boneless failed" >&2
  exit 1
fi
# Only the core and the CLI: none of Boneless's own tests or package rules.
grep -q "my-method" "$work/build.ninja" || { echo "add-subdirectory: no my-method target" >&2; exit 1; }
if grep -q "boneless_tests\|CPackConfig" "$work/build.ninja"; then
  echo "add-subdirectory: Boneless's own tests or package come along" >&2
  exit 1
fi
[ ! -e "$work/CPackConfig.cmake" ] || { echo "add-subdirectory: CPack configured in the other project" >&2; exit 1; }
echo "add-subdirectory: ok"
