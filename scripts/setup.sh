#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# Installs the Debian packages and builds swelldem (plugin, core, geometry, overlay prefix) in
# $SWELLDEM_BUILD_DIR (default: build/ at the top of the repository).
set -eu
REPO=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${SWELLDEM_BUILD_DIR:-$REPO/build}
sh "$REPO/scripts/bootstrap.sh"
mkdir -p "$BUILD"
cmake -S "$REPO" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$BUILD/configure.log" 2>&1 || { cat "$BUILD/configure.log"; exit 1; }
cmake --build "$BUILD" -j"$(nproc)"
echo "setup: built in $BUILD; launcher: $REPO/scripts/yade-swelldem"
