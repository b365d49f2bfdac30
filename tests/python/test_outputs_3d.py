# SPDX-License-Identifier: GPL-2.0-or-later
"""The outputs of a 3D box's swelling test: the crack maps as mid-plane sections and in 3D, their
per-kind counts against counts made here from contact_breaks.npz and the assembly's own arrays,
the aggregates' sections against a half-plane intersection, a facet's trace against closed forms,
and the volume change in swelling_strain.png."""
import csv
import json
import os
import subprocess

import numpy as np
import pytest

from conftest import LAUNCHER, REPO, build_dir


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """One 12 mm ISR box with aggregates and damage, one step a decade (implicit: 38 s against 52 s
    for the ADR on this machine); the folder it wrote."""
    out = tmp_path_factory.mktemp("box") / "run"
    p = subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"), "--dim", "3",
                        "--size-mm", "12", "12", "12", "--aggregate-area-fraction", "0.2", "--steps-per-decade", "1",
                        "--solver", "implicit", "--out", str(out)],
                       capture_output=True, text=True, timeout=900, env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir()})
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    return out


def _rows(out):
    with open(out / "crack_sections.csv") as f:
        return list(csv.DictReader(f))


def test_a_box_writes_its_section_maps_at_the_characteristic_days_and_a_3d_view(run):
    res = json.load(open(run / "results.json"))
    assert res["dim"] == 3 and res["status"] == "finished"
    tau_l = res["kinds"]["MORTAR"]["tauL"]       # ISR: the maps at tau_L and 2 tau_L, as a 2D run's
    names = ["crack_map.png", f"crack_map_{tau_l:g}d.png", f"crack_map_{2 * tau_l:g}d.png"]
    for name in names + ["crack_map_3d_view.png"]:
        assert (run / name).stat().st_size > 10_000, name
    assert sorted({r["map"] for r in _rows(run)}) == sorted(names)
    from test_guide import documented_names, undocumented
    assert undocumented(run, documented_names(2, 3)) == []  # every file the box wrote, named in the guide


def _broken_by(breaks, times, day):
    """Indices into breaks of the contacts broken by the last step at or before `day`."""
    step = int(np.flatnonzero(times <= day * (1 + 1e-9))[-1])
    return np.flatnonzero((breaks["break_step"] >= 0) & (breaks["break_step"] <= step)), float(times[step])


def test_the_section_counts_are_the_broken_facets_within_a_mean_radius_of_each_mid_plane(run):
    res = json.load(open(run / "results.json"))
    times = np.asarray(res["times_days"])
    with np.load(run / "contact_breaks.npz") as z:
        breaks = {k: z[k] for k in z.files}
    with np.load(run / "assembly.npz", allow_pickle=False) as z:
        contacts, centroid, r = z["contacts"], z["facet_centroid_m"], z["r"]
    at = {(int(i), int(j)): c for c, (i, j) in enumerate(contacts)}
    half = np.asarray(res["config"]["size_mm"], dtype=float) / 2e3
    slab = r.mean()
    rows = _rows(run)
    checked = 0
    for name in sorted({row["map"] for row in rows}):
        day = times[-1] if name == "crack_map.png" else float(name[len("crack_map_"):-len("d.png")])
        sel, t = _broken_by(breaks, times, day)
        for row in (row for row in rows if row["map"] == name):
            axis = "xyz".index(row["section"][0])
            kind = {"MORTAR": 0, "ITZ": 1, "AGG": 2}[row["kind"]]
            mine = [k for k in sel if breaks["kind"][k] == kind]
            near = sum(abs(centroid[at[tuple(breaks["pairs"][k])], axis] - half[axis]) <= slab for k in mine)
            assert float(row["t_days"]) == t
            assert float(row["slab_half_width_mm"]) == pytest.approx(slab * 1e3, rel=1e-12)
            assert (int(row["broken_in_box"]), int(row["broken_in_slab"])) == (len(mine), near), row
            checked += near
    # every kind shown in every section, and cracks in the slabs to count
    assert len(rows) == 3 * 3 * 3 and checked > 100
    final = {row["kind"]: int(row["broken_in_box"]) for row in rows if row["map"] == "crack_map.png"}
    assert final == {k: res["per_kind"][k]["broken"][-1] for k in ("MORTAR", "ITZ", "AGG")}


def _area(poly):
    x, y = np.asarray(poly).T
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _cut_by_half_planes(vertices, axis, level):
    """The area [m^2] of the plane coordinate[axis] = level's cut of the convex hull of `vertices`,
    as the intersection of the hull's faces' half-planes in that plane (each face n . x + c <= 0
    restricted to it), from an interior point found by linear programming: no edge is cut."""
    from scipy.optimize import linprog
    from scipy.spatial import ConvexHull, HalfspaceIntersection
    eq = ConvexHull(vertices).equations
    u, w = [k for k in range(3) if k != axis]
    hs = np.column_stack([eq[:, u], eq[:, w], eq[:, 3] + eq[:, axis] * level])
    # the centre of the largest disc inside: maximise s with n . p + |n| s + c <= 0
    norm = np.linalg.norm(hs[:, :2], axis=1)
    lp = linprog([0, 0, -1], A_ub=np.column_stack([hs[:, :2], norm]), b_ub=-hs[:, 2], bounds=[(None, None)] * 2 + [(0, None)])
    assert lp.success and lp.x[2] > 0
    pts = HalfspaceIntersection(hs, lp.x[:2]).intersections
    return ConvexHull(pts).volume


def test_each_aggregate_section_has_the_area_of_the_hull_faces_half_planes(run):
    from swelldem import meso, report
    a = meso.load(str(run / "assembly.npz"))
    assert a.n_aggregates >= 1
    sections = report.crack_sections(a, [], ["MORTAR", "ITZ", "AGG"])
    size = np.asarray(a.specimen_size_m)
    n = 0
    for sec in sections:
        k = sec["normal"]
        assert sec["level_m"] == size[k] / 2
        spanning = [v for v in a.polyhedra if v[:, k].min() < size[k] / 2 < v[:, k].max()]
        want = sorted(_cut_by_half_planes(v, k, size[k] / 2) for v in spanning)
        got = sorted(_area(p) * 1e-6 for p in sec["aggregates"])  # drawn in mm
        assert len(got) == len(want) and np.allclose(got, want, rtol=1e-9, atol=0)
        n += len(got)
    assert n >= 3


def test_a_facets_trace_is_its_chord_at_the_level():
    from swelldem.report import facet_trace
    t = 0.7  # a unit square tilted about x: its chord at any height within it is a side's length, along x
    sq = np.array([[0, 0, 0], [1, 0, 0], [1, np.cos(t), np.sin(t)], [0, np.cos(t), np.sin(t)]])
    chord = facet_trace(sq, 2, 0.3)
    assert chord.shape == (2, 3) and np.allclose(sorted(chord[:, 0]), [0, 1], atol=1e-15)
    assert np.allclose(chord[:, 2], 0.3) and np.allclose(chord[:, 1], 0.3 / np.tan(t))
    tri = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0]], dtype=float)
    assert np.linalg.norm(np.subtract(*facet_trace(tri, 1, 0.5))) == pytest.approx(1.5, rel=1e-14)
    assert np.allclose(sorted(facet_trace(tri, 1, 0.0)[:, 0]), [0, 2])     # an edge on the plane
    assert facet_trace(tri, 1, 2.0) is None and facet_trace(tri, 1, 2.5) is None  # a vertex, then nothing
    flat = facet_trace(tri, 2, 0.0)                                         # a facet in the plane: its outline
    assert len(flat) == 4 and np.array_equal(flat[0], flat[-1])


def _drawn(monkeypatch):
    from swelldem import report
    figs = []
    monkeypatch.setattr(report, "_save", lambda fig, path, dpi=120: figs.append(fig))
    return figs


def test_the_strain_plot_of_a_box_draws_z_and_the_volume_change_and_of_a_section_neither(monkeypatch):
    from swelldem import report
    t = [10.0, 100.0, 1000.0]
    section = {"scenario": "isr", "behaviour": "elastic", "damage": False, "times_days": t,
               "swelling_strain_x": [1e-5, 4e-4, 9e-4], "swelling_strain_y": [1e-5, 4e-4, 8e-4]}
    box = dict(section, swelling_strain_z=[1e-5, 3e-4, 7e-4], swelling_strain_volume=[3e-5, 1.1e-3, 2.4e-3], dim=3)
    figs = _drawn(monkeypatch)
    report.plot_strain("unused.png", section)
    report.plot_strain("unused.png", box)
    ys = lambda ax: [list(np.round(line.get_ydata(), 9)) for line in ax.get_lines()]  # noqa: E731
    assert len(figs[0].axes) == 1 and len(ys(figs[0].axes[0])) == 3   # x, y and the free swelling
    strains, volume = figs[1].axes[0], figs[1].axes[1]
    assert [10.0, 300.0, 700.0] in ys(strains)
    assert [30.0, 1100.0, 2400.0] in ys(volume)
    free = [y for y in ys(volume) if len(y) > 3]  # the free swelling's (1 + eps)^3 - 1 against its eps
    eps = [y for y in ys(strains) if len(y) > 3]
    assert free and np.allclose(free[0], ((1 + np.asarray(eps[0]) * 1e-6) ** 3 - 1) * 1e6, rtol=1e-6)
