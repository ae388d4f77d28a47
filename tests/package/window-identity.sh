#!/usr/bin/env bash
# Run on a display (run-with-display.sh): starts the installed boneless and prints what an X11
# desktop matches its window to its menu entry by: its class, WM_CLASS's second string.
# Usage: window-identity.sh INSTALL_PREFIX
set -euo pipefail
errors=$(mktemp)
"$1/bin/boneless" >/dev/null 2>"$errors" &
app=$!
trap 'kill $app 2>/dev/null; wait $app 2>/dev/null || true; rm -f "$errors"' EXIT
for _ in $(seq 600); do
  # xwininfo's tree: 0x1234 "title": ("instance" "class")  WxH+X+Y ...
  id=$(xwininfo -root -tree | grep -E '"[^"]*Boneless": \("' | grep -v 'Qt Selection Owner' |
       awk '{print $1; exit}') || true
  [ -n "$id" ] && break
  if ! kill -0 $app 2>/dev/null; then
    echo "window-identity: boneless exited:" >&2; cat "$errors" >&2; exit 1
  fi
  sleep 0.1
done
[ -n "$id" ] || { echo "window-identity: no Boneless window after 60 s" >&2; exit 1; }
class=$(xprop -id "$id" WM_CLASS | sed -n 's/.*= "[^"]*", "\([^"]*\)"/\1/p')
echo "$class"
