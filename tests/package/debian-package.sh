#!/usr/bin/env bash
# Builds the .deb with CPack and checks what it holds and what it depends on.
# Usage: debian-package.sh BUILD_DIR VERSION
set -euo pipefail
build=$1 version=$2
out=$(mktemp -d "$build/deb-test.XXXXXX")
trap 'rm -rf "$out"' EXIT
cpack --config "$build/CPackConfig.cmake" -G DEB -B "$out" >/dev/null
deb=$(ls "$out"/boneless_"$version"_*.deb)

fail() { echo "debian-package: $*" >&2; exit 1; }
contents=$(dpkg-deb -c "$deb")
for f in ./usr/bin/boneless ./usr/bin/boneless-cli \
         ./usr/share/applications/org.boneless.Boneless.desktop \
         ./usr/share/metainfo/org.boneless.Boneless.metainfo.xml \
         ./usr/share/icons/hicolor/256x256/apps/org.boneless.Boneless.png \
         ./usr/share/doc/boneless/LICENSE; do
  grep -q " $f\$" <<<"$contents" || fail "$(basename "$deb") has no $f"
done
# Nothing of the build tree (static libraries, headers, tests) is shipped.
if grep -E '\.a$|/include/|boneless_tests|bench' <<<"$contents"; then fail "ships build files"; fi
depends=$(dpkg-deb -f "$deb" Depends)
for lib in libqt6widgets6 libvtk9.1 libcholmod3 libopenmesh; do
  grep -q "$lib" <<<"$depends" || fail "Depends lacks $lib: $depends"
done
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "wrong version"
echo "debian-package: $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB), Depends: $depends"
