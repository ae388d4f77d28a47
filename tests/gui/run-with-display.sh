#!/usr/bin/env bash
# Runs a GUI test on the current X display, or on a private Xvfb (Mesa, software GL) when there is
# none, as on CI.
set -euo pipefail
# A runtime folder made here is removed after the test (every GUI test run used to leave one).
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  XDG_RUNTIME_DIR=$(mktemp -d /tmp/boneless-xdg.XXXXXX)
  trap 'rm -rf "$XDG_RUNTIME_DIR"' EXIT
fi
export XDG_RUNTIME_DIR
chmod 700 "$XDG_RUNTIME_DIR"
# Software GL behaves the same everywhere, so screenshot baselines compare.
export LIBGL_ALWAYS_SOFTWARE=1
unset QT_QPA_PLATFORM
if [ -n "${DISPLAY:-}" ] && xdpyinfo >/dev/null 2>&1; then
  "$@"
  exit
fi
xvfb-run -a -s "-screen 0 1280x800x24" "$@"
