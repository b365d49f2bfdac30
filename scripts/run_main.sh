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
echo "  results.json               swelling strains, unbalanced-force history, force quantiles, breaks and tensile capacities per kind"
echo "  curves.csv, plot_data.txt  every per-step series, one row a step (units in the CSV's header; the second for yade.plot)"
echo "  contact_breaks.npz         the step at which each bonded contact broke (crack maps at any time)"
echo "  table.md, table.csv        the paper's Table 3.6 form at the last step, the paper's values beside ours"
echo "  swelling_strain.png        swelling strain against log time with the free swelling (the form of paper Figure 3.9, right)"
echo "  unbalanced.png             unbalanced-force ratio against cumulative iterations, iterations per step (form of Figure 3.9, left)"
echo "  force_quantiles.png        5 % / 95 % normal-force quantiles per kind with the tensile capacity, broken share (Figure 3.12, one row)"
echo "  crack_map.png              broken contacts over the mesostructure at the end (Figure 3.15)"
echo "  crack_map_100d.png, crack_map_200d.png   the same at tau_L and 2 tau_L"
echo "  assembly.npz               the mesostructure (swelldem.meso.load)"
echo "  vtk/                       particles (displacement, stress, damage) and contacts (forces, cracks) for ParaView"
