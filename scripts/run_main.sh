#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# Sets up (Debian packages + build) and runs the main job: the paper's ISR swelling test on a small
# default specimen (30 x 30 mm, aging viscoelastic contacts, damage on), into out/main/ (or $1).
set -eu
REPO=$(cd "$(dirname "$0")/.." && pwd)
OUT=${1:-$REPO/out/main}
sh "$REPO/scripts/setup.sh"
"$REPO/scripts/yade-swelldem" -n -x "$REPO/scripts/swelling_test.py" --scenario isr --behaviour viscoelastic \
	--size-mm 30 30 --seed 1 --steps-per-decade 10 --out "$OUT"
echo
echo "main job done. In $OUT:"
echo "  results.json               swelling strains, unbalanced force, force quantiles and breaks per kind over time"
echo "  table.md, table.csv        the paper's Table 3.6 form at the last step"
echo "  swelling_strain.png        swelling strain against log time"
echo "  unbalanced.png             unbalanced-force ratio and ADR iterations per physical step"
echo "  force_quantiles.png        5 % / 95 % normal-force quantiles and broken contacts per kind over time"
echo "  crack_map.png              broken contacts over the mesostructure"
echo "  vtk/                       particles and contacts for ParaView"
