#!/usr/bin/env bash
# Runs a GUI test on the current X display, or on a private Xvfb (Mesa, software GL) when there is
# none, as on CI.
set -euo pipefail
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d /tmp/boneless-xdg.XXXXXX)}
chmod 700 "$XDG_RUNTIME_DIR"
# Software GL behaves the same everywhere, so screenshot baselines compare.
export LIBGL_ALWAYS_SOFTWARE=1
unset QT_QPA_PLATFORM
if [ -n "${DISPLAY:-}" ] && xdpyinfo >/dev/null 2>&1; then
  exec "$@"
fi
exec xvfb-run -a -s "-screen 0 1280x800x24" "$@"
