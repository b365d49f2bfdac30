# SPDX-License-Identifier: GPL-2.0-or-later
"""The ParaView time series of a swelling test (swelldem.dem.vtk_series): one particles and one
contacts .vtp file per exported step, binary with compressed appended data, .pvd collections with
the physical times [day], and every field equal to what the live scene's Python API gave at that
step; the discs' displacement as point data, their Love-Weber stress (against a closed form) and
damage, the kind names. Read with VTK's own reader (python3-vtk9, conftest.read_vtp)."""
import json
import math
import os
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import read_vtp

SCRIPT = r"""
import sys
from yade import O
from swelldem import scenario
live = []
def snapshot():
    bodies = [dict(id=b.id, x=b.state.pos[0], y=b.state.pos[1], r=b.shape.radius, agg=b.material.aggregateId,
                   displ=list(b.state.displ())) for b in O.bodies]
    contacts = {f"{i.id1}-{i.id2}": dict(kindId=i.phys.kindId, Fn=i.phys.Fn, Fs=i.phys.Fs, area=i.phys.area,
                                         fnMax=i.phys.fnMax, broken=i.phys.broken, FnHat=i.phys.FnHat, kn=i.phys.kn,
                                         failureMode=i.phys.failureMode)
                for i in O.interactions if i.isReal}
    live.append(dict(bodies=bodies, contacts=contacts))
test = scenario.SwellingTest(scenario="isr", behaviour="elastic", size_mm=(12, 12), steps_per_decade=2,
                             vtk_every=int(sys.argv[1]), out="out")
scenario.run(test, after_step=snapshot)
dump(live)
"""

KINDS = ["MORTAR", "ITZ", "AGG", "PLATEN", "STEEL", "BOND"]


def read_pvd(path):
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection"
    return [(float(d.get("timestep")), d.get("file")) for d in root.find("Collection")]


def assert_binary_compressed(path):
    """The XML head of a .vtp: every array appended as raw zlib-compressed bytes, none in ASCII."""
    data = open(path, "rb").read()
    head = data[:data.index(b"<AppendedData")].decode()
    assert 'compressor="vtkZLibDataCompressor"' in head, head[:300]
    assert 'format="ascii"' not in head and 'format="binary"' not in head
    assert head.count('format="appended"') >= 10
    assert b'<AppendedData encoding="raw">' in data


@pytest.mark.parametrize("every", [1, 3])
def test_vtk_series_matches_the_live_scene(yade_run, tmp_path, every):
    from swelldem import meso
    live = yade_run(SCRIPT, every, threads=1, timeout=300)
    out = tmp_path / "out"
    res = json.loads((out / "results.json").read_text())
    assembly = meso.load(str(out / "assembly.npz"))
    volume = assembly.cell_area_m2 * assembly.thickness_m
    times = res["times_days"]
    assert len(live) == len(times) >= 6
    n = len(times)
    expected_steps = sorted({s for s in range(n) if (s + 1) % every == 0} | {n - 1})
    vtk = out / "vtk"
    names = sorted(os.listdir(vtk))
    assert names == sorted(["particles.pvd", "contacts.pvd"] + [f"{w}_{s:05d}.vtp" for s in expected_steps
                                                                 for w in ("particles", "contacts")])
    for what in ("particles", "contacts"):
        entries = read_pvd(vtk / f"{what}.pvd")
        assert [f for _, f in entries] == [f"{what}_{s:05d}.vtp" for s in expected_steps]
        assert [t for t, _ in entries] == [times[s] for s in expected_steps]  # [day], exactly the run's
        assert all(a < b for (a, _), (b, _) in zip(entries, entries[1:]))
    cracks = damaged = peak = 0
    from vtk.util.numpy_support import vtk_to_numpy
    for s in expected_steps:
        scene = live[s]
        nb = len(scene["bodies"])
        # particles: one 16-gon per disc, vertices on the live disc's circle (single precision)
        assert_binary_compressed(vtk / f"particles_{s:05d}.vtp")
        poly, cells, points, field = read_vtp(vtk / f"particles_{s:05d}.vtp")
        assert list(field["TimeValue"]) == [times[s]] and list(field["step"]) == [s]
        assert field["kindNames"] == KINDS
        assert [int(field[f"kindId_{k}"][0]) for k in KINDS] == list(range(6))
        assert poly.GetNumberOfPolys() == nb and poly.GetNumberOfPoints() == 16 * nb and poly.GetNumberOfVerts() == 0
        assert (vtk_to_numpy(poly.GetPolys().GetOffsetsArray()) == 16 * np.arange(nb + 1)).all()
        assert (vtk_to_numpy(poly.GetPolys().GetConnectivityArray()) == np.arange(16 * nb)).all()
        pts = vtk_to_numpy(poly.GetPoints().GetData()).astype(float).reshape(nb, 16, 3)
        displ = points["displacement"].reshape(nb, 16, 3)
        for k, b in enumerate(scene["bodies"]):
            assert (cells["id"][k], cells["radius"][k], cells["aggregateId"][k]) == (b["id"], b["r"], b["agg"])
            assert (displ[k] == b["displ"]).all()  # point data: every vertex of the disc's polygon, exactly
            assert (pts[k, :, 2] == 0).all()
            assert np.hypot(pts[k, :, 0] - b["x"], pts[k, :, 1] - b["y"]) == pytest.approx(np.full(16, b["r"]), rel=2e-5)
        # contacts: one line per real interaction between the live centres
        assert_binary_compressed(vtk / f"contacts_{s:05d}.vtp")
        poly, arr, cpoints, field = read_vtp(vtk / f"contacts_{s:05d}.vtp")
        assert list(field["TimeValue"]) == [times[s]] and field["kindNames"] == KINDS
        nc = len(scene["contacts"])
        assert poly.GetNumberOfLines() == nc and poly.GetNumberOfPolys() == 0 and poly.GetNumberOfPoints() == nb
        centres = vtk_to_numpy(poly.GetPoints().GetData())
        conn = vtk_to_numpy(poly.GetLines().GetConnectivityArray()).reshape(-1, 2)
        for k, b in enumerate(scene["bodies"]):
            assert cpoints["id"][k] == b["id"] and (centres[k, 0], centres[k, 1]) == (b["x"], b["y"])
            assert list(cpoints["displacement"][k]) == b["displ"]
        for key in ("kindId", "kind", "Fn", "Fs", "area", "strength", "FnOverStrength", "broken", "failureMode", "bonded",
                    "crackOpening"):
            assert len(arr[key]) == nc, key
        assert arr["kind"] == [KINDS[k] for k in arr["kindId"]]
        for c in range(nc):
            i, j = cpoints["id"][conn[c, 0]], cpoints["id"][conn[c, 1]]
            p = scene["contacts"][f"{i}-{j}"]
            assert (arr["kindId"][c], arr["Fn"][c], arr["Fs"][c], arr["area"][c]) == (p["kindId"], p["Fn"], p["Fs"], p["area"])
            assert (arr["broken"][c], arr["failureMode"][c]) == (int(p["broken"]), p["failureMode"])
            finite = math.isfinite(p["fnMax"]) and p["fnMax"] > 0
            assert arr["strength"][c] == (p["fnMax"] if finite else 0.0)
            assert arr["FnOverStrength"][c] == (p["Fn"] / p["fnMax"] if finite else 0.0)
            opening = max(p["FnHat"], 0.0) / p["kn"] if p["broken"] else 0.0
            assert arr["crackOpening"][c] == pytest.approx(opening, rel=1e-15, abs=0)
            cracks += arr["crackOpening"][c] > 0
        # bonded: the contacts at the start of the run (the mesostructure's), same count as results.json
        bonded = arr["bonded"] == 1
        assert bonded.sum() <= sum(res["n_contacts_by_kind"].values())
        # damage: per disc, the share of its bonded contacts broken, here from the contacts' file
        assert cells["bondedContacts"].sum() == 2 * sum(res["n_contacts_by_kind"].values())
        ends = conn[bonded].ravel()
        intact = np.bincount(conn[bonded & (arr["broken"] == 0)].ravel(), minlength=nb)
        assert (np.bincount(ends, minlength=nb) <= cells["bondedContacts"]).all()
        total = cells["bondedContacts"]
        assert cells["damage"] == pytest.approx(np.where(total > 0, (total - intact) / np.maximum(total, 1), 0.0), abs=1e-15)
        damaged += (cells["damage"] > 0).sum()
        # stress [Pa]: symmetric, plane; a free specimen in equilibrium: the sum of V sigma over the discs is
        # the sum over the discs of their contact forces' resultant (x) centre, 0 up to the unbalanced forces
        sig = cells["stress"].reshape(nb, 3, 3)
        assert (sig[:, 0, 1] == sig[:, 1, 0]).all() and (sig[:, 2, :] == 0).all() and (sig[:, :, 2] == 0).all()
        assert (cells["meanStress"] == 0.5 * (sig[:, 0, 0] + sig[:, 1, 1])).all()
        total_vs = (sig[:, :2, :2] * volume[:, None, None]).sum(axis=0)
        scale = np.abs(sig[:, :2, :2] * volume[:, None, None]).sum(axis=0)
        # measured: 4 to 60 times the step's unbalanced-force ratio (lever arms up to the specimen's size)
        assert (np.abs(total_vs) < (100 * res["unbalanced_ratio"][s] + 1e-9) * scale).all(), (total_vs / scale, res["unbalanced_ratio"][s])
        peak = max(peak, np.abs(sig).max())
    last = read_vtp(vtk / f"contacts_{n - 1:05d}.vtp")[1]
    broken_bonded = sum(1 for b, d in zip(last["broken"], last["bonded"]) if b and d)
    assert broken_bonded == sum(res["per_kind"][k]["broken"][-1] for k in ("MORTAR", "ITZ", "AGG")) > 0
    assert cracks > 0 and damaged > 0  # the run cracks: openings and damage are exported, not only zeros
    assert peak > 1e6  # the swelling stresses the discs [Pa] (MPa range)


# Two discs of radius R, the first held, the second pulled along the line of centres (angle THETA)
# by a constant force F; at equilibrium the contact carries F in tension. Love-Weber's mean stress
# of either disc, sigma = (1/V) sum_c f_c (x) l_c, with its single contact: the force on it is
# F n towards the other disc, its branch vector half the centre distance along n, so
# sigma = F (d / 2) n (x) n / (A t), for the cell area A and thickness t given to the series.
PAIR = r"""
import math
from yade import utils
from swelldem import dem
from swelldem.dem.vtk_series import VtkSeries
W = yade.wrapper
R, E, F, THETA, A, T = 0.5e-3, 30e9, 200.0, 0.4, 1.3e-6, 0.5
mat = W.ConcreteMat(young=E, poisson=0.2, density=2400, aggregateId=-1)
O.materials.append(mat)
kind = W.ContactKind(name="MORTAR", behaviour="elastic", young=E, shearRatio=0.3)
n = (math.cos(THETA), math.sin(THETA))
a = O.bodies.append(dem.disc((0, 0), R, mat, fixed=True))
b = O.bodies.append(dem.disc((2 * R * n[0], 2 * R * n[1]), R, mat))
solver = W.ImplicitLogTimeSolver(tStart=1.0, tEnd=10.0, stepsPerDecade=2, verbose=False)
ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kind, itz=kind, agg=kind)
O.engines = dem.engines(ip2, W.Law2_ScGeom_SwellPhys_AgingSwelling(), solver, detection_factor=1.05)
utils.createInteraction(a, b)
ip2.cohesive = False
O.forces.setPermF(b, Vector3(F * n[0], F * n[1], 0))
dem.run_to_end(solver)
i = O.interactions[a, b]
d = (O.bodies[b].state.pos - O.bodies[a].state.pos).norm()
VtkSeries("vtk", cell_area=[A, A], thickness=T).export(0, solver.physTime)
dump({"Fn": i.phys.Fn, "Fs": i.phys.Fs, "d": d, "n": n, "F": F, "A": A, "T": T, "unbalanced": solver.unbalanced})
"""


def test_love_weber_stress_of_a_pulled_pair_is_the_closed_form(yade_run, tmp_path):
    r = yade_run(PAIR, threads=1)
    assert r["Fn"] == pytest.approx(r["F"], rel=1e-9) and abs(r["Fs"]) < 1e-9 * r["F"]  # tension positive
    _, cells, _, _ = read_vtp(tmp_path / "vtk" / "particles_00000.vtp")
    n = np.array(r["n"])
    expected = r["F"] * (r["d"] / 2) * np.outer(n, n) / (r["A"] * r["T"])  # [Pa]
    for k in range(2):
        sig = cells["stress"][k].reshape(3, 3)
        assert sig[:2, :2] == pytest.approx(expected, rel=1e-8, abs=1e-8 * np.abs(expected).max())
        assert cells["meanStress"][k] == pytest.approx(0.5 * np.trace(expected), rel=1e-8)
        assert cells["damage"][k] == 0 and cells["bondedContacts"][k] == 1
