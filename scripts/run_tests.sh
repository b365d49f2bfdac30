#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# Sets up (packages + build) and runs the whole test suite: C++ unit tests with ctest, then the
# Python tests with pytest, which drive real YADE with the real plugin.
set -eu
REPO=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${SWELLDEM_BUILD_DIR:-$REPO/build}
sh "$REPO/scripts/setup.sh"
echo "== ctest"
(cd "$BUILD" && ctest --output-on-failure -j2)
echo "== pytest"
cd "$REPO"
# two workers, each test file on one of them (a file's module-scoped runs are made once): the
# tests are YADE processes of one thread each, two at a time on a 2-core machine
SWELLDEM_BUILD_DIR=$BUILD PYTHONPATH=$REPO/py /usr/bin/python3 -m pytest -p no:cacheprovider -n 2 --dist loadfile tests/python "$@"
