# SPDX-License-Identifier: GPL-2.0-or-later
"""Layout probes: values set through YADE's own Python API, read back through swelldem's
declarations of YADE's classes (SwelldemAbiProbe). A wrong offset reads another field or garbage."""
import math

import pytest

SCENE = r"""
from yade import utils
O.reset()
O.tags['swelldem-probe'] = 'yes'
mat = FrictMat(young=3.1e9, poisson=0.27, frictionAngle=0.43, density=2417., label='probeMat')
O.materials.append(mat)
O.bodies.append([utils.sphere((0, 0, 0), 0.5, material=mat), utils.sphere((0.93, 0.11, 0.0), 0.45, material=mat)])
b0, b1 = O.bodies[0], O.bodies[1]
b1.state.blockedDOFs = 'zXY'
b0.mask = 5
b0.state.vel = (0.1, -0.2, 0.3); b0.state.angVel = (0.01, 0.02, 0.03); b0.state.refPos = (1, 2, 3)
b1.state.isDamped = False; b1.state.densityScaling = 3.5
O.engines = [ForceResetter(label='fr'), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             SwelldemAbiProbe(label='probe', dead=False), NewtonIntegrator(damping=0.2, label='newton')]
O.dt = 1.25e-5
O.timingEnabled = True
O.run(7, True)
probe.ompThreads = 1
i = O.interactions[0, 1]
i.phys.shearForce = (0.5, 0.25, 0.125)
i.phys.tangensOfFrictionAngle = 0.625
checks = []
def chk(name, mine, theirs):
    checks.append((name, mine if not hasattr(mine, '__len__') or isinstance(mine, str) else list(mine),
                   theirs if not hasattr(theirs, '__len__') or isinstance(theirs, str) else list(theirs)))
s = probe.readScene()
for k, v in (('dt', O.dt), ('iter', O.iter), ('time', O.time), ('isPeriodic', O.periodic), ('trackEnergy', O.trackEnergy),
             ('nEngines', len(O.engines)), ('nBodies', len(O.bodies)), ('nBodiesExported', len(O.bodies)),
             ('nMaterials', len(O.materials)), ('nInteractions', len(O.interactions)), ('nLinIntrs', len(O.interactions)),
             ('forcesSyncCount', O.forces.syncCount)):
    chk('Scene.' + k, s[k], v)
chk('Scene.tags has probe tag', 'swelldem-probe=yes' in s['tags'], True)
O.trackEnergy = True; O.periodic = True
s = probe.readScene(); chk('Scene.trackEnergy(set)', s['trackEnergy'], True); chk('Scene.isPeriodic(set)', s['isPeriodic'], True)
O.trackEnergy = False; O.periodic = False
for b in O.bodies:
    d = probe.readBody(b); st = b.state; n = 'Body%d.' % b.id
    chk(n + 'id', d['id'], b.id); chk(n + 'groupMask', d['groupMask'], b.mask); chk(n + 'clumpId', d['clumpId'], b.clumpId)
    chk(n + 'iterBorn', d['iterBorn'], b.iterBorn); chk(n + 'timeBorn', d['timeBorn'], b.timeBorn); chk(n + 'materialId', d['materialId'], b.material.id)
    chk(n + 'pos', d['pos'], st.pos); chk(n + 'posRefOk', d['posRefOk'], True); chk(n + 'ori', d['ori'], (st.ori[0], st.ori[1], st.ori[2], st.ori[3]))
    chk(n + 'vel', d['vel'], st.vel); chk(n + 'mass', d['mass'], st.mass); chk(n + 'angVel', d['angVel'], st.angVel)
    chk(n + 'angMom', d['angMom'], st.angMom); chk(n + 'inertia', d['inertia'], st.inertia); chk(n + 'refPos', d['refPos'], st.refPos)
    chk(n + 'isDamped', d['isDamped'], st.isDamped); chk(n + 'densityScaling', d['densityScaling'], st.densityScaling)
    bits = sum(v for c, v in zip('xyzXYZ', (1, 2, 4, 8, 16, 32)) if c in st.blockedDOFs)
    chk(n + 'blockedDOFs', d['blockedDOFs'], bits)
chk('intrs maps hold each interaction twice', sum(probe.readBody(b)['nIntrs'] for b in O.bodies), 2 * len(O.interactions))
for m in O.materials:
    d = probe.readMaterial(m)
    for k, v in (('id', m.id), ('label', m.label), ('density', m.density), ('young', m.young), ('poisson', m.poisson), ('frictionAngle', m.frictionAngle)):
        chk('FrictMat.' + k, d[k], v)
d = probe.readInteraction(i); g = i.geom; p = i.phys
for k, v in (('id1', i.id1), ('id2', i.id2), ('iterMadeReal', i.iterMadeReal), ('iterBorn', i.iterBorn), ('isReal', i.isReal),
             ('isActive', i.isActive), ('cellDist', i.cellDist), ('lawFunctor', 'Law2_ScGeom_FrictPhys_CundallStrack'),
             ('penetrationDepth', g.penetrationDepth), ('normal', g.normal), ('contactPoint', g.contactPoint), ('refR1', g.refR1),
             ('refR2', g.refR2), ('radius1', g.refR1), ('radius2', g.refR2), ('shearInc', g.shearInc), ('kn', p.kn), ('ks', p.ks),
             ('normalForce', p.normalForce), ('shearForce', p.shearForce), ('tangensOfFrictionAngle', p.tangensOfFrictionAngle)):
    chk('Interaction.' + k, d[k], v)
for e in O.engines:
    d = probe.readEngine(e)
    for k, v in (('dead', e.dead), ('ompThreads', e.ompThreads), ('label', e.label), ('execCount', e.execCount), ('execTime', e.execTime)):
        chk(type(e).__name__ + '.' + k, d[k], v)
    chk(type(e).__name__ + '.hasScene', d['hasScene'], True)
il = O.engines[2]
for f in il.geomDispatcher.functors + il.physDispatcher.functors + il.lawDispatcher.functors:
    d = probe.readFunctor(f)
    chk(type(f).__name__ + '.bases', d['types'], f.bases)
f = il.lawDispatcher.functors[0]; f.label = 'lawLabel'
chk('Functor.label', probe.readFunctor(f)['label'], 'lawLabel')
chk('probe.nCalls == execCount', probe.nCalls, probe.execCount)
chk('probe.lastIter', probe.lastIter, O.iter - 1)
chk('probe.totalMass', probe.totalMass, sum(b.state.mass for b in O.bodies))
dump({'checks': checks, 'layout': probe.declaredLayout()})
"""


def _close(a, b):
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return math.isclose(a, b, rel_tol=0, abs_tol=0) or a == b
    return a == b


@pytest.fixture(scope="module")
def probed(tmp_path_factory):
    from conftest import YadeRun
    return YadeRun(tmp_path_factory.mktemp("abi"))(SCENE, threads=1)


def test_every_probed_field_matches_yade(probed):
    checks = probed["checks"]
    assert len(checks) > 100
    bad = [(n, mine, theirs) for n, mine, theirs in checks if not _close(mine, theirs)]
    assert not bad, "fields read through swelldem's declarations differ from YADE's accessors:\n" + "\n".join(map(str, bad))


def test_declared_layout_is_debians(probed):
    # The byte offsets documented in pkg/yade/compat/README.md for Debian's yade-double 2023.02a-1,
    # established by the probes above; a change of a declaration shows up here by name.
    expected = {"sizeof FrictPhys": 104, "sizeof ScGeom": 192, "sizeof State": 320, "sizeof FrictMat": 104, "sizeof Body": 176,
                "sizeof Interaction": 168, "sizeof ForceContainer": 304, "sizeof Scene": 752, "sizeof Engine": 104,
                "sizeof Functor": 80, "NormPhys::kn": 32, "NormPhys::normalForce": 40, "NormShearPhys::ks": 64,
                "NormShearPhys::shearForce": 72, "FrictPhys::tangensOfFrictionAngle": 96, "ScGeom::penetrationDepth": 160,
                "ScGeom::shearInc": 168, "State::se3": 88, "State::vel": 144, "State::blockedDOFs": 304, "State::densityScaling": 312,
                "Body::material": 40, "Body::intrs": 104, "Body::timeBorn": 168, "Interaction::id1": 88, "Interaction::phys": 128,
                "InteractionContainer::currSize": 80, "Scene::dt": 440, "Scene::time": 464, "Scene::bodies": 600,
                "Scene::interactions": 616, "Scene::cell": 688, "Engine::label": 72, "Functor::label": 48}
    layout = probed["layout"]
    assert {k: layout[k] for k in expected} == expected
