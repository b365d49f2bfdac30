# SPDX-License-Identifier: GPL-2.0-or-later
"""The ParaView time series of a swelling test (swelldem.dem.vtk_series): one particles and one
contacts .vtp file per exported step, .pvd collections with the physical times [day], and every
field equal to what the live scene's Python API gave at that step. python3-vtk is not a
dependency: the files are read back with the standard library's XML parser."""
import json
import math
import os
import xml.etree.ElementTree as ET

import pytest

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


def _values(el, cast=float):
    return [cast(v) for v in (el.text or "").split()]


def read_vtp(path):
    """(field data, piece attributes, {array name: values}, {array name: components}) of an ASCII .vtp."""
    root = ET.parse(path).getroot()
    assert root.get("type") == "PolyData"
    field = {a.get("Name"): _values(a) for a in root.find("PolyData/FieldData")}
    piece = root.find("PolyData/Piece")
    arrays, comps = {}, {}
    for a in piece.iter("DataArray"):
        cast = float if a.get("type").startswith("Float") else int
        arrays[a.get("Name")] = _values(a, cast)
        comps[a.get("Name")] = int(a.get("NumberOfComponents", "1"))
    return field, {k: int(v) for k, v in piece.attrib.items()}, arrays, comps


def read_pvd(path):
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection"
    return [(float(d.get("timestep")), d.get("file")) for d in root.find("Collection")]


@pytest.mark.parametrize("every", [1, 3])
def test_vtk_series_matches_the_live_scene(yade_run, tmp_path, every):
    live = yade_run(SCRIPT, every, threads=1, timeout=300)
    out = tmp_path / "out"
    res = json.loads((out / "results.json").read_text())
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
    cracks = 0
    for s in expected_steps:
        scene = live[s]
        # particles: one 16-gon per disc, vertices on the live disc's circle
        field, piece, arr, comps = read_vtp(vtk / f"particles_{s:05d}.vtp")
        assert field["TimeValue"] == [times[s]] and field["step"] == [s]
        assert (field["kindId_MORTAR"], field["kindId_ITZ"], field["kindId_AGG"]) == ([0], [1], [2])
        nb = len(scene["bodies"])
        assert piece["NumberOfPolys"] == nb and piece["NumberOfPoints"] == 16 * nb and piece["NumberOfVerts"] == 0
        assert arr["offsets"] == [16 * (k + 1) for k in range(nb)] and arr["connectivity"] == list(range(16 * nb))
        assert comps["displacement"] == 3 and comps["Points"] == 3
        for k, b in enumerate(scene["bodies"]):
            assert arr["id"][k] == b["id"] and arr["radius"][k] == b["r"] and arr["aggregateId"][k] == b["agg"]
            assert arr["displacement"][3 * k:3 * k + 3] == b["displ"]
            for v in range(16 * k, 16 * k + 16):
                x, y, z = arr["Points"][3 * v:3 * v + 3]
                assert z == 0 and math.hypot(x - b["x"], y - b["y"]) == pytest.approx(b["r"], rel=1e-12)
        # contacts: one line per real interaction between the live centres
        field, piece, arr, comps = read_vtp(vtk / f"contacts_{s:05d}.vtp")
        assert field["TimeValue"] == [times[s]]
        nc = len(scene["contacts"])
        assert piece["NumberOfLines"] == nc and piece["NumberOfPolys"] == 0 and piece["NumberOfPoints"] == nb
        for key in ("kindId", "Fn", "Fs", "area", "strength", "FnOverStrength", "broken", "failureMode", "bonded",
                    "crackOpening"):
            assert len(arr[key]) == nc, key
        for c in range(nc):
            i, j = arr["id"][arr["connectivity"][2 * c]], arr["id"][arr["connectivity"][2 * c + 1]]
            p = scene["contacts"][f"{i}-{j}"]
            assert arr["Points"][3 * arr["connectivity"][2 * c]] == scene["bodies"][i]["x"]
            assert (arr["kindId"][c], arr["Fn"][c], arr["Fs"][c], arr["area"][c]) == (p["kindId"], p["Fn"], p["Fs"], p["area"])
            assert (arr["broken"][c], arr["failureMode"][c]) == (int(p["broken"]), p["failureMode"])
            finite = math.isfinite(p["fnMax"]) and p["fnMax"] > 0
            assert arr["strength"][c] == (p["fnMax"] if finite else 0.0)
            assert arr["FnOverStrength"][c] == (p["Fn"] / p["fnMax"] if finite else 0.0)
            opening = max(p["FnHat"], 0.0) / p["kn"] if p["broken"] else 0.0
            assert arr["crackOpening"][c] == pytest.approx(opening, rel=1e-15, abs=0)
            cracks += arr["crackOpening"][c] > 0
        # bonded: the contacts at the start of the run (the mesostructure's), same count as results.json
        assert sum(arr["bonded"]) <= sum(res["n_contacts_by_kind"].values())
    last = read_vtp(vtk / f"contacts_{n - 1:05d}.vtp")[2]
    broken_bonded = sum(1 for b, d in zip(last["broken"], last["bonded"]) if b and d)
    assert broken_bonded == sum(res["per_kind"][k]["broken"][-1] for k in ("MORTAR", "ITZ", "AGG")) > 0
    assert cracks > 0  # the run cracks: openings are exported, not only zeros
