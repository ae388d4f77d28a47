#!/usr/bin/env bash
# Installs the build into a temporary root and runs the installed binaries from there: the
# version, and the application rendering its demo to a PNG (under Xvfb when there is no display).
# Usage: installed-tree.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$1 source=$2 version=$3
root=$(mktemp -d "$build/install-test.XXXXXX")
trap 'rm -rf "$root"' EXIT
cmake --install "$build" --prefix "$root/usr" >/dev/null

fail() { echo "installed-tree: $*" >&2; exit 1; }
for f in bin/boneless bin/boneless-cli share/applications/org.boneless.Boneless.desktop \
         share/metainfo/org.boneless.Boneless.metainfo.xml \
         share/icons/hicolor/scalable/apps/org.boneless.Boneless.svg \
         share/icons/hicolor/48x48/apps/org.boneless.Boneless.png share/doc/boneless/LICENSE; do
  [ -e "$root/usr/$f" ] || fail "the install has no $f"
done
# The README is installed as the manual (Help → Getting Started says so): every page it links to
# is installed beside it.
doc="$root/usr/share/doc/boneless"
for link in $(grep -oE '\]\(docs/[^)#]+' "$doc/README.md" | cut -c3- | sort -u); do
  [ -e "$doc/$link" ] || fail "the installed README links to $link, which is not installed"
done
desktop-file-validate "$root/usr/share/applications/org.boneless.Boneless.desktop"
appstreamcli validate --no-net "$root/usr/share/metainfo/org.boneless.Boneless.metainfo.xml" \
  >/dev/null || fail "the AppStream metainfo does not validate"

# Double-clicking a project or a take opens Boneless: the desktop's own look-ups (GIO's, as a
# file manager makes them) find the file's type by its extension and Boneless as its application.
# Until 1 December 2026 a .boneless was plain text to them, opened by a text editor.
share="$root/usr/share"
[ -e "$share/mime/packages/org.boneless.Boneless.xml" ] || fail "the install has no MIME types"
update-mime-database "$share/mime"
XDG_DATA_DIRS="$share" update-desktop-database "$share/applications"
opens_with() {  # FILE: the content type and the default application the desktop gives it
  ( export XDG_DATA_DIRS="$share:/usr/share" XDG_DATA_HOME="$root/none" XDG_CONFIG_HOME="$root/none"
    export PATH="$root/usr/bin:$PATH"
    type=$(gio info -a standard::content-type "$1" | sed -n 's/.*content-type: //p')
    echo "$type $(gio mime "$type" | sed -n 's/^Default application for .*: //p')" )
}
mkdir "$root/files"
echo '{"format": "boneless-project", "version": 1}' >"$root/files/walk.boneless"
printf '\x02\x50' >"$root/files/walk.c3d"
printf 'ply\nformat ascii 1.0\n' >"$root/files/body.ply"
printf 'OFF\n3 1 0\n' >"$root/files/body.off"
for f in walk.boneless walk.c3d body.ply body.off; do
  got=$(opens_with "$root/files/$f")
  [[ "$got" == *" org.boneless.Boneless.desktop" ]] || fail "$f opens as '$got', not in Boneless"
done
[[ "$(opens_with "$root/files/walk.boneless")" == "application/x-boneless-project "* ]] ||
  fail "a .boneless is not a Boneless project to the desktop"

# From a git checkout the version names the commit (cmake/GitVersion.cmake).
if git -C "$source" rev-parse HEAD >/dev/null 2>&1; then
  version="$version+git$(TZ=UTC git -C "$source" log -1 --format=%cd.%h --abbrev=7 \
                         --date=format-local:%Y%m%d.%H%M%S)"
fi
printed=$("$root/usr/bin/boneless-cli" --version)
[ "$printed" = "boneless-cli $version" ] || fail "boneless-cli --version printed '$printed'"
printed=$(QT_QPA_PLATFORM=offscreen "$root/usr/bin/boneless" --version)
[[ "$printed" == *"$version"* ]] || fail "boneless --version printed '$printed'"

# The demo is written into the per-user data folder: a fresh one, so the test writes its own.
export XDG_DATA_HOME="$root/data" XDG_CONFIG_HOME="$root/config"
"$source/tests/gui/run-with-display.sh" "$root/usr/bin/boneless" --size 160x120 \
  --screenshot "$root/shot.png"
[ -s "$root/shot.png" ] || fail "the installed boneless wrote no screenshot"
# A dock matches the running window to its menu entry, on X11 by the window's class, the entry's
# StartupWMClass (until 1 December 2026 the entry had none, and a dock showed the window as an
# application apart from its launcher).
entry="$share/applications/org.boneless.Boneless.desktop"
class=$("$source/tests/gui/run-with-display.sh" "$source/tests/package/window-identity.sh" \
        "$root/usr") || fail "could not read the window's class"
wmclass=$(sed -n 's/^StartupWMClass=//p' "$entry")
[ "$class" = "$wmclass" ] || fail "the window's class is '$class', its entry's '$wmclass'"
echo "installed-tree: $root/usr runs boneless-cli $version and renders the demo"
