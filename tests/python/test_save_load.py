# SPDX-License-Identifier: GPL-2.0-or-later
"""O.save / O.load round trips (xml, binary, bz2, memory) of a scene holding every plugin class,
each with every one of its own attributes set away from its default; the reloaded scene must hold
the same values and continue to the same state as the uninterrupted run."""
import pytest

from conftest import plugin_classes

SCRIPT = r"""
import sys
from yade import utils
classes = sys.argv[1].split(',')
fname = sys.argv[2]

def changed(v, i):
    if isinstance(v, bool): return not v
    if isinstance(v, int): return v + 3 + i
    if isinstance(v, float): return v * 1.5 + 0.25 + i
    if isinstance(v, str): return v + '_x%d' % i
    if isinstance(v, (list, tuple)) and all(isinstance(x, float) for x in v): return [x + 1.0 + i for x in v] or [1.0 + i]
    return v

def own_attrs(obj):
    base = obj.__class__.__mro__[1]()
    return [k for k in obj.dict() if k not in base.dict()]

def build():
    O.reset()
    mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.4, density=2600))
    O.bodies.append([utils.sphere((0, 0, 0), 0.5, material=mat, fixed=True), utils.sphere((0.1, 0.05, 0.95), 0.5, material=mat)])
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81))]
    O.dt = 2e-5
    O.run(100, True)
    placed = {}
    for i, name in enumerate(classes):
        obj = eval(name)()
        for k in own_attrs(obj):
            setattr(obj, k, changed(getattr(obj, k), i))
        if isinstance(obj, GlobalEngine): O.engines = O.engines[:-1] + [obj] + O.engines[-1:]
        elif isinstance(obj, IPhysFunctor): O.engines[2].physDispatcher.functors = O.engines[2].physDispatcher.functors + [obj]
        elif isinstance(obj, LawFunctor): O.engines[2].lawDispatcher.functors = O.engines[2].lawDispatcher.functors + [obj]
        elif isinstance(obj, Material): O.materials.append(obj)
        elif isinstance(obj, IPhys): pass  # placed on the interaction below
        else: raise RuntimeError('no place in the test scene for ' + name)
        placed[name] = obj
    return placed

def find_all():
    found = {}
    objs = list(O.engines) + list(O.engines[2].physDispatcher.functors) + list(O.engines[2].lawDispatcher.functors) + list(O.materials)
    objs += [i.phys for i in O.interactions]
    for o in objs:
        if type(o).__name__ in classes: found[type(o).__name__] = o
    return found

placed = build()
before = {n: {k: getattr(o, k) for k in own_attrs(o)} for n, o in placed.items()}
O.save(fname)
O.run(200, True)
ref = list(O.bodies[1].state.pos)
O.reset()
O.load(fname)
found = find_all()
after = {n: {k: getattr(o, k) for k in own_attrs(o)} for n, o in found.items()}
O.run(200, True)
dump({'before': before, 'after': after, 'pos_ref': ref, 'pos_loaded': list(O.bodies[1].state.pos), 'iter': O.iter})
"""


@pytest.mark.parametrize("fname", ["scene.xml", "scene.yade", "scene.xml.bz2", ":memory:swelldem"])
def test_round_trip_keeps_every_attribute_and_continues_identically(yade_run, fname):
    classes = plugin_classes()
    res = yade_run(SCRIPT, ",".join(classes), fname, threads=1)
    assert sorted(res["before"]) == classes, "every plugin class must be in the saved scene"
    assert res["after"] == res["before"]
    assert all(v for v in res["before"].values()), "every class has attributes set away from defaults"
    assert res["pos_loaded"] == res["pos_ref"]
    assert res["iter"] == 300
