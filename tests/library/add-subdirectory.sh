#!/usr/bin/env bash
# Another project adds a clone of Boneless with add_subdirectory, as docs/library.md says, and its
# configure step succeeds and offers boneless_core (until 30 November 2026 it failed: the clone
# looked for its CMake modules and LICENSE in the other project's folder).
# Its install brings none of Boneless's files unless asked (until 1 December 2026 it installed
# boneless-cli).
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
# The other project's `cmake --install` installs its own files, not boneless-cli or Boneless's
# docs, unless it asks with BONELESS_INSTALL=ON (the consumer has no install rule of its own).
installs() { grep -rhoE 'file\(INSTALL DESTINATION [^ ]+ TYPE [A-Z]+ FILES "[^"]*"' \
               --include=cmake_install.cmake "$work"; }
if rules=$(installs); then
  echo "add-subdirectory: the other project's install brings Boneless's files:" >&2
  echo "$rules" >&2
  exit 1
fi
cmake -S "$source/tests/library/consumer" -B "$work" -DBONELESS_INSTALL=ON >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log" >&2; exit 1; }
installs | grep -q 'boneless-cli"' ||
  { echo "add-subdirectory: BONELESS_INSTALL=ON does not install boneless-cli" >&2; exit 1; }
echo "add-subdirectory: ok"
