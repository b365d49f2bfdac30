#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# Sets up (Debian packages + build) and runs the main job into out/main/.
set -eu
REPO=$(cd "$(dirname "$0")/.." && pwd)
OUT=${1:-$REPO/out/main}
sh "$REPO/scripts/setup.sh"
Y="$REPO/scripts/yade-swelldem"
for c in isr asr; do
	"$Y" -n -x "$REPO/scripts/two_particles.py" --case $c --steps-per-decade 10 --out "$OUT/two_particles_$c"
done
"$Y" -n -x "$REPO/scripts/two_particles.py" --case isr --restrained --steps-per-decade 10 --out "$OUT/two_particles_isr_restrained"
"$Y" -n -x "$REPO/scripts/make_mesostructure.py" --size-mm 30 30 --seed 1 --out "$OUT/meso"
echo "main job done: results and plots in $OUT"
ls "$OUT"/*/*.png
