# SPDX-License-Identifier: GPL-2.0-or-later
"""With creep and swelling off and the same kn, ks, the plugin's law reproduces
Law2_ScGeom_FrictPhys_CundallStrack (friction angle next to 90 degrees, i.e. no slip) on a small 2D
assembly, to round-off. Contacts that open are CundallStrack's no-tension contacts (neverErase);
ours reach the same state through damage at a vanishing tensile strength, which also checks the
broken path: no tension, Coulomb friction in compression, an opened contact carries nothing."""

SCRIPT = r"""
import random, math, sys
from yade import utils
law = sys.argv[1]
rng = random.Random(7)  # utils.sphere draws colours from the global generator
O.reset()
if law == 'stock':
    mat = FrictMat(young=1e8, poisson=0.3, frictionAngle=math.pi / 2 - 1e-9, density=2600)
else:
    mat = ConcreteMat(young=1e8, poisson=0.3, density=2600, aggregateId=-1)
O.materials.append(mat)
# 7 columns of 6 discs standing on fixed discs, each disc slightly off its column's axis so the
# contacts are inclined (shear), radii slightly above half the vertical spacing so each disc rests
# on the one below; gravity keeps every contact in compression.
for i in range(7):
    for j in range(6):
        r = 0.05 * (1 + 0.05 * rng.random())
        fixed = j == 0
        b = utils.sphere((i * 0.115 + 0.006 * (rng.random() - 0.5), j * 0.1, 0), r, material=mat, fixed=fixed)
        b.state.blockedDOFs = 'xyzXYZ' if fixed else 'zXY'
        O.bodies.append(b)
if law == 'stock':
    ip2, law2 = Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack(neverErase=True)
else:
    kind = ContactKind(name='MORTAR', behaviour='elastic', young=1.0, shearRatio=0.3, damage=True, tensileStrength=1e-30,
                       residualFrictionAngle=math.pi / 2 - 1e-9)
    ip2, law2 = Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kind, itz=kind, agg=kind), Law2_ScGeom_SwellPhys_AgingSwelling()
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [ip2], [law2]),
             NewtonIntegrator(damping=0.8, gravity=(0, -20000.0, 0))]
O.dt = 1e-5
for b1 in O.bodies:
    for b2 in O.bodies:
        if b1.id < b2.id and (b1.state.pos - b2.state.pos).norm() < b1.shape.radius + b2.shape.radius:
            i = utils.createInteraction(b1.id, b2.id)
            if law != 'stock':
                # the stock Ip2's stiffness, kn = 2 E r1 r2 / (r1 + r2) = E_c A / L with E_c = 1 Pa, and
                # CundallStrack's stress-free state at zero overlap
                r1, r2 = i.geom.refR1, i.geom.refR2
                i.phys.area = 2 * 1e8 * r1 * r2 / (r1 + r2) * i.phys.length
                i.phys.uRef = 0.0
if law != 'stock':
    ip2.cohesive = False  # contacts made from now on are cohesionless, like CundallStrack's
n_real = []
for k in range(int(sys.argv[2]) if len(sys.argv) > 2 else 400):  # longer runs amplify round-off chaotically
    O.step()
    n_real.append(len([i for i in O.interactions if i.isReal]))
dump({'pos': [list(b.state.pos) for b in O.bodies], 'force': [list(O.forces.f(b.id)) for b in O.bodies], 'n_real': n_real,
      'fn': [i.phys.normalForce.norm() for i in O.interactions if i.isReal],
      'fs': [i.phys.shearForce.norm() for i in O.interactions if i.isReal],
      'min_pen': min(i.geom.penetrationDepth for i in O.interactions if i.isReal)})
"""


def test_elastic_law_reproduces_cundall_strack(yade_run):
    stock = yade_run(SCRIPT, "stock", threads=1)
    ours = yade_run(SCRIPT, "ours", threads=1)
    assert stock["n_real"] == ours["n_real"]
    assert min(stock["n_real"]) >= 35, "the columns stay in contact"
    assert max(stock["fs"]) > 1e-3 * max(stock["fn"]), "shear is exercised"
    scale = max(max(abs(x) for x in p) for p in stock["pos"])
    dp = max(abs(a - b) for pa, pb in zip(stock["pos"], ours["pos"]) for a, b in zip(pa, pb))
    assert dp <= 1e-13 * scale
    fscale = max(stock["fn"])
    df = max(abs(a - b) for fa, fb in zip(stock["force"], ours["force"]) for a, b in zip(fa, fb))
    assert df <= 1e-9 * fscale
