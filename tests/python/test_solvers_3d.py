# SPDX-License-Identifier: GPL-2.0-or-later
"""Both solvers on 3D scenes (spheres, three translations and three rotations a body) against
closed forms evaluated here: a face-centred cubic lattice with every contact swelling, free (no
forces, the affine strain d_inf dxi / (2 r) in x, y and z) and held on its outer layer (every
interior contact at -kn d_inf dxi); a 3D mesostructure under both solvers; what the 3D path
refuses."""
import math

import numpy as np
import pytest

# An FCC lattice of equal spheres (nearest neighbours 2R apart: centres at (i, j, k) x sqrt(2) R with
# i + j + k even), its 12-neighbour contacts created bonded, one elastic swelling kind.
FCC = r"""
import math
from yade import utils
W = yade.wrapper
N, R, E, D_INF = {n}, 0.5e-3, 30e9, 1e-6
A = (2 * R) ** 2 / (2 * math.sqrt(2))    # a face of the rhombic dodecahedron (the FCC Voronoi cell)
O.reset()
mat = W.ConcreteMat(young=E, poisson=0.2, density=2400, aggregateId=-1)
O.materials.append(mat)
kind = W.ContactKind(name="MORTAR", behaviour="elastic", young=E, shearRatio=0.3, swelling=True, swellDispInf=D_INF,
                     tauC=50.0, tauL=100.0)
h = math.sqrt(2) * R
ids, outer = {{}}, set()
for i in range(N):
    for j in range(N):
        for k in range(N):
            if (i + j + k) % 2:
                continue
            b = utils.sphere((h * i, h * j, h * k), R, material=mat)
            b.state.blockedDOFs = ""
            ids[i, j, k] = O.bodies.append(b)
            if {{i, j, k}} & {{0, N - 1}}:
                outer.add(ids[i, j, k])
solver = W.{solver}(tStart=1.0, tEnd=3650.0, stepsPerDecade=5, tolerance={tol}, verbose=False)
ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kind, itz=kind, agg=kind)
O.engines = [W.ForceResetter(), W.InsertionSortCollider([W.Bo1_Sphere_Aabb(aabbEnlargeFactor=1.05)], verletDist=0, label="collider"),
             W.InteractionLoop([W.Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=1.05)], [ip2], [W.Law2_ScGeom_SwellPhys_AgingSwelling()]),
             solver]
pairs = []
for (i, j, k), a in ids.items():
    for d in ((1, 1, 0), (1, -1, 0), (1, 0, 1), (1, 0, -1), (0, 1, 1), (0, 1, -1)):
        b = ids.get((i + d[0], j + d[1], k + d[2]))
        if b is not None:
            I = utils.createInteraction(a, b)
            I.phys.area = A
            pairs.append((a, b))
ip2.cohesive = False
"""

RUN = r"""
{hold}
while not solver.finished:
    O.run(2000, True)
real = [i for i in O.interactions if i.isReal]
dump({{"fn": [O.interactions[a, b].phys.Fn for a, b in pairs],
      "interior": [a not in outer and b not in outer for a, b in pairs],
      "gap": [(O.bodies[b].state.pos - O.bodies[a].state.pos).norm() - 2 * R for a, b in pairs],
      "span": [max(b.state.pos[d] for b in O.bodies) - min(b.state.pos[d] for b in O.bodies) for d in range(3)],
      "span0": (N - 1) * h, "dims": sorted({{i.phys.dim for i in real}}), "nDim": solver.nDim,
      "n": len(O.bodies), "contacts": len(pairs), "iters": solver.totalIterations}})
"""


def larive(t):
    return (1 - math.exp(-t / 50.0)) / (1 + math.exp(-(t - 100.0) / 50.0))


D_INF, E, R = 1e-6, 30e9, 0.5e-3
KN = E * (2 * R) ** 2 / (2 * math.sqrt(2)) / (2 * R)   # kn = E A / L


# measured: ADR at tolerance 1e-7, 3.1e-5 (openings, forces) and 1.3e-5 (strains) in 1,333 iterations;
# implicit, 1.0e-12, 7.9e-13 and 3.1e-13 in 34 iterations. Bounds 1e-4 (3x) and 1e-9 (the issue's;
# 1000x). Holding two more bodies across the specimen in place of the centre body's rotations (the
# 2D way of removing the rigid modes) turns the lattice by 1.8e-3 rad and leaves 7e-5 (pins
# in ImplicitLogTimeSolver::choosePins).
@pytest.mark.parametrize("solver, tol, bound", [("AdrLogTimeIntegrator", 1e-7, 1e-4), ("ImplicitLogTimeSolver", 1e-10, 1e-9)])
def test_free_fcc_lattice_swells_affinely_without_forces(yade_run, solver, tol, bound):
    res = yade_run(FCC.format(n=7, tol=tol, solver=solver) + RUN.format(hold=""), threads=1)
    assert res["nDim"] == 3 and res["dims"] == [3] and res["contacts"] > 3 * res["n"]
    dxi = larive(3650.0) - larive(1.0)
    opening = D_INF * dxi
    strain = opening / (2 * R)                   # closed form: the lattice scales by 1 + d_inf dxi / (2 R)
    gap_err = max(abs(g - opening) for g in res["gap"]) / opening
    force = max(abs(f) for f in res["fn"]) / (KN * opening)
    strain_err = max(abs((s - res["span0"]) / res["span0"] - strain) for s in res["span"]) / strain
    print(f"measured: openings {gap_err:.2e}, forces {force:.2e}, strains {strain_err:.2e} of the closed form; "
          f"{res['iters']} iterations")
    assert gap_err < bound and force < bound and strain_err < bound


@pytest.mark.parametrize("solver, tol", [("AdrLogTimeIntegrator", 1e-7), ("ImplicitLogTimeSolver", 1e-10)])
def test_fcc_lattice_held_on_its_outer_layer_carries_the_contact_stiffness_force(yade_run, solver, tol):
    res = yade_run(FCC.format(n=7, tol=tol, solver=solver) + RUN.format(hold="""
for bid in outer:
    O.bodies[bid].state.blockedDOFs = "xyzXYZ"
"""), threads=1)
    dxi = larive(3650.0) - larive(1.0)
    want = -KN * D_INF * dxi                     # every contact restrained: Fn = -kn d_inf dxi
    inner = [f for f, i in zip(res["fn"], res["interior"]) if i]
    assert len(inner) > 100
    err = max(abs(f / want - 1) for f in inner)
    print(f"measured: interior contact forces {err:.2e} from -kn d_inf dxi")
    # measured 0 (every interior sphere is balanced by symmetry, nothing moves); bound 1e-9
    assert err < 1e-9


MESO = r"""
import sys
from swelldem import scenario, meso, dem
name = sys.argv[1]
test = scenario.SwellingTest(scenario="isr", behaviour="viscoelastic", damage=True, size_mm=[8.0, 8.0], seed=1, steps_per_decade=2)
assembly = meso.generate(dim=3, seed=1, width_mm=8.0, height_mm=8.0, depth_mm=8.0, aggregate_area_fraction=0.0)
kinds = scenario.make_kinds(test)
scenario.set_swelling(test, kinds, test.eps_inf * 2 * float(assembly.r.mean()))
settings = {"tolerance": float(sys.argv[2])} if len(sys.argv) > 2 else {}
solver = dem.make_solver(name, tStart=1.0, tEnd=3650.0, stepsPerDecade=2, verbose=False, **settings)
dem.to_yade(assembly, kinds, solver)
import numpy as np
p0 = np.array([list(b.state.pos) for b in O.bodies])
bonded = [(i.id1, i.id2) for i in O.interactions if i.isReal and not i.phys.broken]
while not solver.finished:
    O.run(5000, True)
xs = [b.state.pos for b in O.bodies]
# the affine fit of the displacements (least squares over every sphere): its diagonal
fit = np.linalg.lstsq(np.c_[p0, np.ones(len(p0))], np.array([list(p) for p in xs]) - p0, rcond=None)[0]
span = [max(p[d] for p in xs) - min(p[d] for p in xs) for d in range(3)]
broken = sum(1 for a, b in bonded if O.interactions[a, b] is None or not O.interactions[a, b].isReal or O.interactions[a, b].phys.broken)
dump({"n": len(O.bodies), "dims": sorted({i.phys.dim for i in O.interactions if i.isReal}), "nDim": solver.nDim,
      "span": span, "span0": [float(assembly.x.max() - assembly.x.min()), float(assembly.y.max() - assembly.y.min()),
                              float(assembly.z.max() - assembly.z.min())],
      "finished": solver.finished, "eps_inf": test.eps_inf, "broken": broken, "bonded": len(bonded),
      "iters": solver.totalIterations, "affine": [float(fit[d, d]) for d in range(3)]})
"""


def test_a_3d_mesostructure_swells_alike_under_both_solvers(yade_run):
    adr = yade_run(MESO, "adr", threads=1, timeout=900)
    imp = yade_run(MESO, "implicit", threads=1, timeout=900)
    strains = {}
    for name, res in (("adr", adr), ("implicit", imp)):
        assert res["finished"] and res["dims"] == [3] and res["nDim"] == 3
        strains[name] = [(s - s0) / s0 for s, s0 in zip(res["span"], res["span0"])]
    print("measured: strains", strains, "eps_inf", adr["eps_inf"], "spheres", adr["n"], "broken", adr["broken"], imp["broken"],
          "of", adr["bonded"], "iterations", adr["iters"], imp["iters"])
    # Plain mortar swelling freely: the same expansion in x, y and z, of the order of eps_inf
    # (ADR: measured 0.986, 0.992 and 0.999 eps_inf, 1,065 spheres; the 3D micro-macro factor is
    # table_3_2.py --dim 3's, not tested here, only that the specimen expands as a whole and alike
    # in each direction).
    for e in strains.values():
        assert all(0.5 * adr["eps_inf"] < x < 2 * adr["eps_inf"] for x in e)
        assert max(e) - min(e) < 0.1 * max(e)
    # The two solvers on one specimen, by the affine fit of the spheres' displacements (the spans
    # above hang on a few surface spheres): measured 1.3e-3, 1e-5 and 3e-4 apart with the ADR at
    # its default tolerance 1e-4 (at 1e-6: 4.7e-4, 2.5e-5, 3e-4); bound 5e-3, 4x.
    gap = max(abs(a / b - 1) for a, b in zip(imp["affine"], adr["affine"]))
    print("measured: affine strains", imp["affine"], adr["affine"], "apart", gap)
    assert gap < 5e-3


# ---------------------------------------------------------------- swelling_test.py --dim 3

def _swelling_test(tmp_path, *args):
    import os
    import subprocess
    from conftest import LAUNCHER, REPO, build_dir
    env = {**os.environ, "SWELLDEM_BUILD_DIR": build_dir()}
    return subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"), *args,
                           "--out", str(tmp_path / "run")], capture_output=True, text=True, timeout=900, env=env)


def test_the_swelling_test_of_a_3d_box_records_x_y_z_and_the_volume(tmp_path):
    import csv
    import glob
    import json
    p = _swelling_test(tmp_path, "--dim", "3", "--size-mm", "10", "10", "10", "--solver", "adr", "--aggregate-area-fraction", "0",
                       "--behaviour", "elastic", "--no-damage", "--steps-per-decade", "1")
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    res = json.load(open(tmp_path / "run" / "results.json"))
    assert res["dim"] == 3 and res["status"] == "finished" and "swelling_strain_area" not in res
    ex, ey, ez, ev = (res[f"swelling_strain_{k}"][-1] for k in ("x", "y", "z", "volume"))
    print("measured strains", ex, ey, ez, ev, "eps_inf", res["config"]["eps_inf"])
    # plain mortar, elastic, free: an isotropic expansion of the order of eps_inf (the 2D micro-macro
    # rule d_inf = eps_inf 2 R_mean; measured 0.97-0.99 eps_inf), the volume change the product's
    assert all(0.8 * 1e-3 < e < 1.2 * 1e-3 for e in (ex, ey, ez))
    assert ev == pytest.approx((1 + ex) * (1 + ey) * (1 + ez) - 1, rel=0.02)
    with open(tmp_path / "run" / "curves.csv") as f:
        header = next(csv.reader(f))
    assert "swelling_strain_z [-]" in header and "swelling_strain_volume [-]" in header
    # without damage: the section maps and the 3D view drawn with nothing broken, no intermediate maps
    assert (tmp_path / "run" / "crack_map.png").exists() and (tmp_path / "run" / "crack_map_3d_view.png").exists()
    assert not glob.glob(str(tmp_path / "run" / "crack_map_*d.png"))
    with open(tmp_path / "run" / "crack_sections.csv") as f:
        counts = [(r["section"], r["broken_in_slab"], r["broken_in_box"]) for r in csv.DictReader(f)]
    assert sorted({c[0] for c in counts}) == ["x = 5 mm", "y = 5 mm", "z = 5 mm"] and {c[1:] for c in counts} == {("0", "0")}
    assert "z " in p.stdout and "3D" in open(tmp_path / "run" / "table.md").read()
    # ParaView: the spheres as points with their arrays as point data, the contacts with both shears
    from conftest import read_vtp
    last = sorted(glob.glob(str(tmp_path / "run" / "vtk" / "particles_*.vtp")))[-1]
    poly, _, pts, field = read_vtp(last)
    assert poly.GetNumberOfPoints() == res["n_particles"] == poly.GetNumberOfVerts()
    for name, comps in (("displacement", 3), ("radius", 1), ("stress", 9), ("meanStress", 1), ("damage", 1)):
        assert name in pts and (pts[name].shape[1] if pts[name].ndim == 2 else 1) == comps, name
    centre = np.array([poly.GetPoint(k) for k in range(poly.GetNumberOfPoints())])
    assert np.ptp(centre[:, 2]) > 0.9e-2                           # the box's depth, not a plane
    # the displacement field is the swelling: z displacement across the depth ~ the z strain
    slope = np.polyfit(centre[:, 2], pts["displacement"][:, 2], 1)[0]
    assert slope == pytest.approx(ez, rel=0.05)
    _, cells, _, _ = read_vtp(last.replace("particles_", "contacts_"))
    assert "Fs2" in cells and len(cells["Fs2"]) == sum(res["n_contacts_by_kind"].values())


def test_free_mortar_swells_alike_in_a_box_and_in_a_section(tmp_path):
    """The same physics in both dimensions: plain mortar, elastic, free, the micro-macro rule
    d_inf = eps_inf 2 R_mean. Each specimen's strain is set against the affine estimate of its own
    assembly, d_inf / L_A (L_A the facet-area-weighted mean contact length: the equilibrium of an
    affine expansion, docs/mesostructure.md), and the box's x, y and z strains against the
    section's."""
    import json
    import os
    strains, affine = {}, {}
    for dim, size in ((2, ("10", "10")), (3, ("10", "10", "10"))):
        run = tmp_path / f"d{dim}"
        os.makedirs(run)
        p = _swelling_test(run, "--dim", str(dim), "--size-mm", *size, "--aggregate-area-fraction", "0", "--behaviour", "elastic",
                           "--no-damage", "--steps-per-decade", "1")
        assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
        res = json.load(open(run / "run" / "results.json"))
        a = np.load(run / "run" / "assembly.npz", allow_pickle=True)
        d_inf = res["config"]["eps_inf"] * 2 * a["r"].mean()
        L_A = (a["facet_area_m2"] * a["distance_m"]).sum() / a["facet_area_m2"].sum()
        axes = "xyz"[:dim]
        strains[dim] = [res[f"swelling_strain_{k}"][-1] for k in axes]
        affine[dim] = d_inf / L_A
        print("measured", dim, [e / affine[dim] - 1 for e in strains[dim]])
    # measured (10 mm, seed 1): the section's x, y +0.28 % and -0.59 % off its affine estimate, the
    # box's x, y, z -0.52, -0.36 and -0.67 % (a disordered network relaxes about an affine
    # expansion, docs/mesostructure.md: 0-0.8 %); bound 2 %, 3x the largest
    for dim in (2, 3):
        assert all(abs(e / affine[dim] - 1) < 0.02 for e in strains[dim]), (dim, strains[dim], affine[dim])
    # the box against the section, per direction: their contacts differ in mean length (a sphere's
    # facet-weighted contacts are longer than 2 R_mean by 2.7 %, a disc's by 1.3 %), which is the
    # two dimensions' micro-macro factors (0.974 and 0.985); measured 0.982-0.985 of the section's
    # mean strain; bound 3 %, 1.7x the largest difference
    section = np.mean(strains[2])
    print("measured box / section", [e / section for e in strains[3]])
    assert all(abs(e / section - 1) < 0.03 for e in strains[3])


@pytest.mark.parametrize("args, message", [
    (("--dim", "3", "--size-mm", "30", "30", "--solver", "adr"), "size_mm = "),
    (("--size-mm", "30", "30", "30"), "size_mm = "),
    (("--dim", "3", "--size-mm", "30", "30", "30", "--rebar-ratio", "0.01"),
     "rebar_ratio = 0.01 is out of range; allowed: 0 when dim is 3"),
    (("--dim", "4",), "dim = 4 is out of range"),
    # a box that cannot hold the smallest sieve fraction's aggregate
    (("--dim", "3", "--size-mm", "4", "4", "4"), "fraction 0 = 2.4-4.75 mm does not fit the 4 x 4 x 4 mm specimen"),
    (("--dim", "3", "--size-mm", "12", "12", "12", "--boundary-w", "fixed"), "unrecognized arguments: --boundary-w"),
])
def test_what_a_3d_box_does_not_take_is_refused_before_any_work(tmp_path, args, message):
    p = _swelling_test(tmp_path, *args)
    assert p.returncode == 2 and message in p.stderr, p.stderr[-2000:]
    assert not (tmp_path / "run").exists()
