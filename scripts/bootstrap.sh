#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# Installs every Debian package swelldem needs. Idempotent: when all are present it only checks.
set -eu
PACKAGES="yade cmake make g++ binutils pkg-config libeigen3-dev petsc-dev libboost-python-dev libboost-serialization-dev
libcgal-dev libsuitesparse-dev libgmp-dev libmpfr-dev libgtest-dev libpython3.11-dev python3-numpy python3-scipy python3-matplotlib python3-pytest python3-pytest-xdist python3-vtk9 python3-distributed"
missing=""
for p in $PACKAGES; do
	status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
	case "$status" in *"install ok installed"*) ;; *) missing="$missing $p" ;; esac
done
if [ -z "$missing" ]; then
	echo "bootstrap: all Debian packages present"
	exit 0
fi
echo "bootstrap: installing$missing"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
# shellcheck disable=SC2086
$SUDO apt-get install -y -q --no-install-recommends $missing
