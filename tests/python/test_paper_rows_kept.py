# SPDX-License-Identifier: GPL-2.0-or-later
"""The ISR and ASR-fine rows of the paper's tables that swelldem reproduces stay as they were made
before the ASR-coarse readings existed: the eight runs at 20 x 20 mm against the values stored in
tests/python/data/paper_rows_20mm.json (made at commit bc105d4, by the code before this test's
subject). The readings change only ASR-coarse's gel pockets; these runs share none of it."""
import json
import os

import pytest

from conftest import REPO

STORED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "paper_rows_20mm.json")

SCRIPT = r"""
import sys
sys.path.insert(0, sys.argv[1])
from swelldem import scenario
out = {}
for name in sys.argv[3:]:
    sc, b, d = name.rsplit('-', 2)
    r = scenario.run(scenario.SwellingTest(scenario=sc, behaviour=b, damage=d == 'dmg', size_mm=(20, 20), seed=1,
                                           steps_per_decade=5, out=sys.argv[2] + '/' + name))
    out[name] = {'strain_x': r['swelling_strain_x'][-1], 'strain_y': r['swelling_strain_y'][-1],
                 'per_kind': {k: {'fn_p05_kN': v['fn_p05_kN'][-1], 'fn_p95_kN': v['fn_p95_kN'][-1], 'broken': v['broken'][-1]}
                              for k, v in r['per_kind'].items()}}
dump(out)
"""


def test_isr_and_asr_fine_rows_are_kept(yade_run, tmp_path):
    with open(STORED) as f:
        stored = json.load(f)["runs"]
    res = yade_run(SCRIPT, os.path.join(REPO, "py"), tmp_path, *sorted(stored), threads=1, timeout=900)
    for name, want in stored.items():
        got = res[name]
        # One thread runs the same code to the same numbers on one machine (bc105d4 and this code
        # agree bit for bit here), but the BLAS kernels under CHOLMOD differ by CPU: the stored
        # values, made on another machine, differ from this one's by up to 3.5e-6 relative in a
        # strain of a damage run (ASR-fine elastic, where the broken contacts leave soft modes),
        # 4e-9 in a force quantile and 1.6e-12 kN in a quantile that is zero. The tolerances are
        # about 30 times those; a changed reading moves these values by percents.
        assert got["strain_x"] == pytest.approx(want["strain_x"], rel=1e-4), name
        assert got["strain_y"] == pytest.approx(want["strain_y"], rel=1e-4), name
        for kind, w in want["per_kind"].items():
            g = got["per_kind"][kind]
            assert g["broken"] == w["broken"], (name, kind)
            assert g["fn_p05_kN"] == pytest.approx(w["fn_p05_kN"], rel=1e-7, abs=5e-11), (name, kind)
            assert g["fn_p95_kN"] == pytest.approx(w["fn_p95_kN"], rel=1e-7, abs=5e-11), (name, kind)
