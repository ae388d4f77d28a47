#!/usr/bin/env bash
# Builds the .deb with CPack and checks what it holds and what it depends on.
# Usage: debian-package.sh BUILD_DIR VERSION [SOURCE_DIR]
set -euo pipefail
build=$1 version=$2 source=${3:-}
out=$(mktemp -d "$build/deb-test.XXXXXX")
trap 'rm -rf "$out"' EXIT
fail() { echo "debian-package: $*" >&2; exit 1; }

# Built from a git checkout, the package's version names the commit, later commits sorting
# higher: with the bare project version, a package of a newer commit left the older installed
# ("boneless is already the newest version (0.1.0)" from apt-get install ./boneless.deb).
if [ -n "$source" ] && git -C "$source" rev-parse HEAD >/dev/null 2>&1; then
  stamp=$(TZ=UTC git -C "$source" log -1 --format=%cd.%h --abbrev=7 \
          --date=format-local:%Y%m%d.%H%M%S)
  dpkg --compare-versions "$version+git$stamp" gt "$version" || fail "$stamp sorts below $version"
  version="$version+git$stamp"
fi
cpack --config "$build/CPackConfig.cmake" -G DEB -B "$out" >/dev/null
deb=$(ls "$out"/boneless_*.deb)
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] ||
  fail "version $(dpkg-deb -f "$deb" Version), expected $version"
contents=$(dpkg-deb -c "$deb")
for f in ./usr/bin/boneless ./usr/bin/boneless-cli \
         ./usr/share/applications/org.boneless.Boneless.desktop \
         ./usr/share/metainfo/org.boneless.Boneless.metainfo.xml \
         ./usr/share/mime/packages/org.boneless.Boneless.xml \
         ./usr/share/icons/hicolor/256x256/apps/org.boneless.Boneless.png \
         ./usr/share/doc/boneless/LICENSE; do
  grep -q " $f\$" <<<"$contents" || fail "$(basename "$deb") has no $f"
done
# What lintian holds a package to: a copyright file, stripped binaries, a description of lines
# under 80 columns (the description's lines began with the ";" of a CMake list until 1 December
# 2026).
grep -q " ./usr/share/doc/boneless/copyright\$" <<<"$contents" || fail "no copyright file"
description=$(dpkg-deb -f "$deb" Description)
if grep -nE '^ ;|.{81}' <<<"$description"; then fail "the description is mangled: $description"; fi
unpacked="$out/unpacked"
dpkg-deb -x "$deb" "$unpacked"
for program in boneless boneless-cli; do
  if readelf -S "$unpacked/usr/bin/$program" | grep -q '\.symtab'; then
    fail "$program is not stripped"
  fi
done
# A user's report quotes --version: it names the package's version, commit and all (until
# 1 December 2026 the binaries printed 0.1.0 whichever commit they were built from).
printed=$("$unpacked/usr/bin/boneless-cli" --version)
[ "$printed" = "boneless-cli $version" ] || fail "boneless-cli --version printed '$printed'"
# Each program's manual page, and in boneless-cli's a section for every command its --help lists
# (there were no pages until 1 December 2026).
for program in boneless boneless-cli; do
  page="$unpacked/usr/share/man/man1/$program.1.gz"
  [ -s "$page" ] || fail "no manual page for $program"
  text=$(zcat "$page")
  grep -q "^\.TH \"${program^^}\" 1 \"\" \"[^\"]* $version\"" <<<"$text" ||
    fail "$program's manual page does not name version $version"
done
commands=$("$unpacked/usr/bin/boneless-cli" --help | sed -n '/^Subcommands:/,/^$/p' |
           awk 'NR > 1 && NF { print $1 }')
[ -n "$commands" ] || fail "boneless-cli --help lists no commands"
text=$(zcat "$unpacked/usr/share/man/man1/boneless-cli.1.gz")
for command in $commands; do
  grep -q "^\.SS \"boneless-cli $command\"" <<<"$text" || fail "man boneless-cli has no $command"
done
# Nothing of the build tree (static libraries, headers, tests) is shipped.
if grep -E '\.a$|/include/|boneless_tests|boneless-bench' <<<"$contents"; then
  fail "ships build files"
fi
depends=$(dpkg-deb -f "$deb" Depends)
for lib in libqt6widgets6 libvtk9.1 libcholmod3 libopenmesh; do
  grep -q "$lib" <<<"$depends" || fail "Depends lacks $lib: $depends"
done
echo "debian-package: $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB), Depends: $depends"
