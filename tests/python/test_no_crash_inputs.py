# SPDX-License-Identifier: GPL-2.0-or-later
"""No Python-settable value crashes the process: a contact's kind set to None or to an object of
another type is refused when set with the plugin's error form and the run goes on (a kind new to the
scene is taken, from the next physical step); an Ip2 without a kind for a pair of the scene's
materials is refused before the first step of either log-time solver, and under YADE's stock
NewtonIntegrator the contact carries no force instead of YADE aborting on its assertion I->phys.
Each case runs in its own yade process: an abort or a segmentation fault is exit 134 or 139 there."""
import pytest

SOLVERS = ("AdrLogTimeIntegrator", "ImplicitLogTimeSolver")

# Two discs of materials MAT_A, MAT_B (ConcreteMat keyword dicts) bonded, one kind for every slot
# but those in NONE; `solver` is a class name or "Newton". Names: W, R, kind, ip2, solver.
SCENE = r"""
from yade import utils
from swelldem import dem
W = yade.wrapper
R = 0.5e-3

def scene(solver, mat_a={}, mat_b={}, none=(), contacts=[(0, 1)], extra_wall=False, third=False):
    kind = W.ContactKind(name="MORTAR", behaviour="elastic", young=30e9, swelling=True, swellDispInf=1e-6, tauC=50.0, tauL=100.0)
    slots = {s: (None if s in none else kind) for s in ("mortar", "itz", "agg", "platen", "steel", "bond")}
    ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(**{s: k for s, k in slots.items() if k is not None})
    integ = (W.NewtonIntegrator(damping=0.5) if solver == "Newton"
             else getattr(W, solver)(tStart=1.0, tEnd=1e4, stepsPerDecade=20, verbose=False, colliderPeriod=1))
    mats = [W.ConcreteMat(young=30e9, poisson=0.2, density=2400, **mat_a), W.ConcreteMat(young=30e9, poisson=0.2, density=2400, **mat_b)]
    x = [0, 2 * R] + ([10 * R] if third else [])
    dem.build_scene(x, [0] * len(x), [R] * len(x), mats, ip2, W.Law2_ScGeom_SwellPhys_AgingSwelling(), integ,
                    material_of=[0, 1] + ([1] if third else []), contacts=contacts, fixed=[0])
    if extra_wall:
        O.bodies.append(utils.wall((0, -5 * R, 0), 1, material=W.ConcreteMat(young=30e9, poisson=0.2, density=2400, platen=True)))
    if solver == "Newton":
        O.dt = 1e-9
    return kind, ip2, integ

def attempt(f):
    try:
        f()
        return "accepted"
    except Exception as e:
        return f"{type(e).__name__}: {e}"
"""


def _run(yade_run, script, *args):
    res = yade_run(SCENE + script, *args, threads=1, check=False)
    p = yade_run.proc
    assert p.returncode not in (134, 139, -6, -11), f"yade crashed ({p.returncode}):\n{p.stderr[-3000:]}"
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-3000:]
    return res, p


def test_kind_none_on_a_live_contact_is_refused_and_the_run_goes_on(yade_run):
    """phys.kind = None (assignment and updateAttrs) between two O.run calls: ValueError naming the
    attribute, its value and what is allowed; the old kind kept; both solvers then finish."""
    res, _ = _run(yade_run, r"""
out = {}
for solver in SOLVERS:
    kind, ip2, integ = scene(solver)
    O.run(3, True)
    ph = O.interactions[0, 1].phys
    out[solver] = {"set": attempt(lambda: setattr(ph, "kind", None)),
                   "updateAttrs": attempt(lambda: ph.updateAttrs({"kind": None})),
                   "kept": ph.kind is kind}
    while not integ.finished:
        O.run(500, True)
    out[solver]["finished"] = integ.finished
dump(out)
""".replace("SOLVERS", repr(SOLVERS)))
    for solver in SOLVERS:
        r = res[solver]
        for how in ("set", "updateAttrs"):
            assert r[how].startswith("ValueError: SwellPhys.kind = None refused"), (solver, how, r[how])
            assert "allowed: a ContactKind" in r[how], r[how]
        assert r["kept"] and r["finished"], r


def test_a_kind_of_another_type_is_refused_and_a_new_kind_applies_from_the_next_step(yade_run):
    """A ConcreteMat given as a kind (contact and Ip2 slot) and a number to the Ip2's constructor: each
    a ValueError in the plugin's form. A ContactKind new to the scene, set on a contact during a run,
    is taken and applies from the next physical step: the contact's step stiffness kn = E A / L then
    stands to the old one as the two kinds' moduli (1e9 / 30e9), and the run finishes."""
    res, _ = _run(yade_run, r"""
out = {}
for solver in SOLVERS:
    kind, ip2, integ = scene(solver)
    ph = O.interactions[0, 1].phys
    mat = O.materials[0]
    out[solver] = {"phys_wrong_type": attempt(lambda: setattr(ph, "kind", mat)),
                   "ip2_wrong_type": attempt(lambda: setattr(ip2, "itz", mat)),
                   "ip2_ctor_number": attempt(lambda: W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=3))}
    O.run(3, True)
    kn_before, step = ph.kn, integ.step
    out[solver]["new_kind"] = attempt(lambda: setattr(ph, "kind", W.ContactKind(name="OTHER", behaviour="elastic", young=1e9)))
    while integ.step == step and not integ.finished:
        O.run(1, True)
    O.run(1, True)  # the contact's first iteration of the next step sets it up
    out[solver]["kn_ratio"] = ph.kn / kn_before
    out[solver]["kind_name"] = ph.kindName
    while not integ.finished:
        O.run(500, True)
    out[solver]["finished"] = integ.finished
dump(out)
""".replace("SOLVERS", repr(SOLVERS)))
    for solver in SOLVERS:
        r = res[solver]
        assert r["phys_wrong_type"].startswith("ValueError: swelldem: SwellPhys.kind = <ConcreteMat instance"), r
        assert r["ip2_wrong_type"].startswith("ValueError: swelldem: Ip2_ConcreteMat_ConcreteMat_SwellPhys.itz = <ConcreteMat"), r
        assert r["ip2_ctor_number"] == ("ValueError: swelldem: Ip2_ConcreteMat_ConcreteMat_SwellPhys.mortar = 3 is out of range; "
                                        "allowed: a ContactKind object"), r
        for key in ("phys_wrong_type", "ip2_wrong_type"):
            assert "is out of range; allowed: a ContactKind object" in r[key], r[key]
        assert r["new_kind"] == "accepted" and r["kind_name"] == "OTHER" and r["finished"], r
        assert abs(r["kn_ratio"] - 1e9 / 30e9) < 1e-12, r


# (slot, the two materials' ConcreteMat keywords): each slot of the Ip2 as a pair of the scene needs it
SLOTS = [("mortar", {}, {}),
         ("itz", {}, {"aggregateId": 0}),
         ("agg", {"aggregateId": 1}, {"aggregateId": 1}),
         ("steel", {"steel": True}, {"steel": True}),
         ("bond", {}, {"steel": True})]


@pytest.mark.parametrize("slot,mat_a,mat_b", SLOTS, ids=[s[0] for s in SLOTS])
def test_an_ip2_without_the_kind_of_a_pair_is_refused_before_the_first_step(yade_run, slot, mat_a, mat_b):
    """The bonded contact is made with the slot None (no abort on YADE's assertion I->phys); both
    solvers refuse to start naming the slot, in their first iteration, which does not complete; under
    NewtonIntegrator the contact carries no force and stderr says why; once the slot is set the
    contact is made again and the solver runs."""
    res, p = _run(yade_run, rf"""
out = {{}}
for solver in {SOLVERS!r} + ("Newton",):
    kind, ip2, integ = scene(solver, {mat_a!r}, {mat_b!r}, none=({slot!r},))
    r = out[solver] = {{"made": O.interactions[0, 1].isReal, "kindless": O.interactions[0, 1].phys.kind is None}}
    r["run"] = attempt(lambda: O.run(5, True))
    r["iter"] = O.iter
    r["force"] = O.forces.f(1).norm()
    if solver != "Newton":
        r["step"] = integ.step
        setattr(ip2, {slot!r}, kind)
        r["rerun"] = attempt(lambda: O.run(5, True))
        r["kind_now"] = O.interactions[0, 1].phys.kindName
dump(out)
""")
    for solver in SOLVERS:
        r = res[solver]
        assert r["made"] and r["kindless"], r
        assert r["run"].startswith(f"RuntimeError: swelldem: {solver} cannot start: Ip2_ConcreteMat_ConcreteMat_SwellPhys.{slot} = None "
                                   "is out of range; allowed: a ContactKind (the scene's bodies 0 and 1"), r["run"]
        assert r["iter"] == 0 and r["step"] == 0, r  # the first iteration did not complete
        assert r["rerun"] == "accepted" and r["kind_now"] == "MORTAR", r
    newton = res["Newton"]
    assert newton["run"] == "accepted" and newton["iter"] == 5 and newton["force"] == 0.0, newton
    assert f"swelldem: Ip2_ConcreteMat_ConcreteMat_SwellPhys.{slot} = None is out of range (contact of bodies 0 and 1)" in p.stderr


def test_a_platen_without_its_kind_is_refused_before_the_first_step(yade_run):
    """A platen (a Wall of a ConcreteMat with platen set) and discs need the platen slot, whether or
    not a contact with it exists yet."""
    res, _ = _run(yade_run, r"""
kind, ip2, integ = scene("ImplicitLogTimeSolver", none=("platen",), extra_wall=True)
dump({"run": attempt(lambda: O.run(5, True))})
""")
    assert res["run"].startswith("RuntimeError: swelldem: ImplicitLogTimeSolver cannot start: "
                                 "Ip2_ConcreteMat_ConcreteMat_SwellPhys.platen = None is out of range"), res


@pytest.mark.parametrize("solver", SOLVERS)
def test_a_slot_set_to_none_during_a_run_stops_it_when_a_contact_needs_it(yade_run, solver):
    """A disc brought into contact after the slot it needs was set to None: the contact carries no
    force and the solver stops with the slot's name at the next iteration (no segmentation fault)."""
    res, _ = _run(yade_run, rf"""
kind, ip2, integ = scene({solver!r}, third=True)
O.run(3, True)
ip2.mortar = None
O.bodies[2].state.pos = (3.9 * R, 0, 0)
dump({{"run": attempt(lambda: O.run(50, True)), "finished": integ.finished}})
""")
    assert res["run"].startswith(f"RuntimeError: swelldem: {solver} stopped at physical step"), res
    assert "Ip2_ConcreteMat_ConcreteMat_SwellPhys.mortar = None is out of range (contact of bodies 1 and 2)" in res["run"], res
    assert not res["finished"]
