# SPDX-License-Identifier: GPL-2.0-or-later
"""Who owns the run (docs/architecture.md, "Run-time ownership"): a ContactKind holds parameters
only; what a run does with it (the step begun, the law built for that step, the breaks) belongs to
the scene's law functor. So one set of kinds serves two scenes run one after the other in one
process, each getting the result it gets alone, and ContactKind(**kind.dict()) is a full copy."""

RUNS = r"""
from swelldem import scenario
import yade
W = yade.wrapper

def test(out, t_end):
    # damage on and viscoelastic: breaks and Kelvin chains; the second scene's span (t_end) gives
    # its chains other lags, which a kind carrying the first run's law would have to give up
    return scenario.SwellingTest(scenario="isr", behaviour="viscoelastic", size_mm=(12, 12), seed=3,
                                 aggregate_area_fraction=0.2, steps_per_decade=5, t_end_days=t_end, out=out)

KEYS = ("times_days", "swelling_strain_x", "swelling_strain_y", "unbalanced_ratio", "per_kind")
def kept(res):
    return {k: res[k] for k in KEYS}

def run(t, kinds=None):
    _, solver = scenario.prepare(t)
    res = scenario.run(t, prepared=(kinds, solver) if kinds else None)
    return kept(res), [I.phys.Fn for I in yade.Omega().interactions if I.isReal]

b_alone = run(test("b_alone", 100.0))
a_alone = run(test("a_alone", 3650.0))
kinds, _ = scenario.prepare(test("a", 3650.0))
a_shared = run(test("a", 3650.0), kinds)
b_shared = run(test("b", 100.0), kinds)
copies = {n: W.ContactKind(**k.dict()).dict() == k.dict() for n, k in kinds.items()}
dump({"a": [a_alone, a_shared], "b": [b_alone, b_shared], "copies": copies,
      "names": sorted(W.ContactKind().dict())})
"""


def test_one_set_of_kinds_serves_two_scenes_one_after_the_other(yade_run):
    """The same three kinds for a 3650-day run and then a 100-day run of another span: each
    gives, bit for bit, what it gives with kinds of its own (strains, unbalanced ratios, per-kind
    force quantiles and broken counts, every contact force); a copy by dict() equals the kind."""
    r = yade_run(RUNS, timeout=900)
    assert r["a"][0] == r["a"][1]
    assert r["b"][0] == r["b"][1]
    assert r["b"][0][0]["times_days"][-1] == 100.0 and r["a"][0][0]["times_days"][-1] == 3650.0
    assert all(r["copies"].values()), r["copies"]
    # settings only: no run state left on a kind for a copy to drag along
    for name in ("stepSerial", "breakEvents", "shortestLag", "longestLag", "breaksAtEquilibrium", "shearFromStepStart"):
        assert name not in r["names"]
