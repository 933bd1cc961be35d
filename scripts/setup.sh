#!/bin/sh
# Installs the Debian packages casteljau needs (only those missing), then configures and builds.
#   CJ_BUILD_DIR  build folder (default: build)
#   CJ_CMAKE_ARGS extra arguments for the configure step (e.g. -DCJ_SANITIZE=ON)
set -eu
cd "$(dirname "$0")/.."
PKGS="build-essential cmake pkg-config libcmocka-dev libmpfr-dev libgmp-dev libcjson-dev \
liblapacke-dev libfreetype-dev fonts-dejavu-core libopenimageio-dev libvtk9-dev \
xvfb xauth libgl1-mesa-dri libcairo2-dev clang libclang-rt-14-dev libgif-dev libembree-dev \
libglfw3-dev xdotool valgrind"
PKGS="$PKGS libpng-dev libfontconfig-dev"
PKGS="$PKGS python3-cffi python3-numpy python3-pytest"
PKGS="$PKGS libimagequant-dev libavformat-dev libavcodec-dev libswscale-dev poppler-utils libexpat1-dev"
PKGS="$PKGS libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev"
PKGS="$PKGS cargo librust-kurbo-dev"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    echo "setup: installing$missing"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
fi
BUILD_DIR="${CJ_BUILD_DIR:-build}"
# shellcheck disable=SC2086
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${CJ_CMAKE_ARGS:-} >/dev/null
cmake --build "$BUILD_DIR" -j "$(nproc)"
