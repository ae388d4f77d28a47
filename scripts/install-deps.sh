#!/usr/bin/env bash
# Installs every Debian bookworm package Boneless needs to build, test and run (as root).
set -euo pipefail
packages=(
  # toolchain
  g++ cmake ninja-build pkg-config git xz-utils
  # core
  libeigen3-dev libopenmesh-dev libsuitesparse-dev libopenblas-dev libtinygltf-dev
  # CLI
  nlohmann-json3-dev libcli11-dev
  # application: Qt6 and VTK 9.1 (never libvtk9-qt-dev: Debian builds it for Qt5)
  qt6-base-dev libqt6opengl6-dev libvtk9-dev fonts-dejavu-core
  # desktop integration: the icon's PNG sizes, and the checks of the .desktop, metainfo, MIME types
  # (opened as a file manager opens them) and .deb
  librsvg2-bin desktop-file-utils appstream dpkg-dev shared-mime-info libglib2.0-bin
  # GUI tests: a virtual X server with Mesa's software OpenGL
  xvfb xauth x11-utils libgl1-mesa-dri mesa-utils
  # tests, benchmarks, fuzzing (clang's libFuzzer and sanitizer runtimes)
  libgtest-dev libbenchmark-dev clang libclang-rt-14-dev
  # a real client reading the exports back: headless Blender (its glTF importer needs numpy)
  blender python3-numpy
)
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: run as root (it calls apt-get)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends "${packages[@]}"
