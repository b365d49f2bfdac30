# SPDX-License-Identifier: GPL-2.0-or-later
"""Tests of the 3D mesostructure as the generator delivers it (swelldem.meso.generate(dim=3)): the
assembly's geometry checked against quantities recomputed here from the spheres and the polyhedra
(not from the generator's own figures), the one kind rule, save/load, seeds, refusals, the pictures'
sections against closed forms, the ParaView file read back with VTK, and the script.

The specimen is a 12 mm cube holding 25 % of the fine sieve fraction only (2.4-4.75 mm; the default
grading's 10 mm aggregates need a larger box, and a box under 3 grain lengths places its grains for
a few seeds only): about 9 s to generate on one core.
"""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO  # and py/ on the path
from swelldem import meso
from swelldem.meso import plot3d

BOX = dict(dim=3, width_mm=12.0, height_mm=12.0, depth_mm=12.0, sieve_fractions_mm=((2.4, 4.75),),
           fraction_shares=(1.0,), aggregate_area_fraction=0.25)


@pytest.fixture(scope="module")
def box():
    return meso.generate(seed=1, **BOX)


def centres(a):
    return np.stack([a.x, a.y, a.z], axis=1)


# ---------------------------------------------------------------------------- geometry

def test_spheres_do_not_overlap_and_stay_inside(box):
    from scipy.spatial import cKDTree
    c, r = centres(box), box.r
    pairs = cKDTree(c).query_pairs(2 * r.max(), output_type="ndarray")
    gap = np.linalg.norm(c[pairs[:, 0]] - c[pairs[:, 1]], axis=1) - r[pairs[:, 0]] - r[pairs[:, 1]]
    rmax = box.parameters["rmax_mm"] * 1e-3
    assert gap.min() >= -1e-9 * rmax  # the packing's stated tolerance
    size = np.array(box.specimen_size_m)
    assert np.all(c - r[:, None] >= -1e-12) and np.all(c + r[:, None] <= size + 1e-12)


def test_cells_tile_the_box_and_facets_are_the_polygons_they_say(box):
    vol = np.prod(box.specimen_size_m)
    assert abs(box.cell_volume_m3.sum() - vol) <= 1e-9 * vol
    # each facet polygon's own area (fan of triangles from its first vertex) and normal
    area = np.empty(box.n_contacts)
    for k, p in enumerate(box.facet_polygons):
        cross = np.cross(p[1:-1] - p[0], p[2:] - p[0]).sum(axis=0)
        area[k] = 0.5 * np.linalg.norm(cross)
        assert abs(abs(cross @ box.facet_normal[k]) - np.linalg.norm(cross)) <= 1e-9 * np.linalg.norm(cross)
    assert np.allclose(area, box.facet_area_m2, rtol=1e-9, atol=0)
    c = centres(box)
    d = c[box.contacts[:, 1]] - c[box.contacts[:, 0]]
    assert np.allclose(np.linalg.norm(box.facet_normal, axis=1), 1.0, atol=1e-12)
    # the power plane is perpendicular to the line of centres, normal from i to j
    assert np.allclose((d / np.linalg.norm(d, axis=1)[:, None] * box.facet_normal).sum(1), 1.0, atol=1e-9)


def test_contacts_are_the_neighbours_within_the_gap_and_the_rest_are_kept(box):
    c = centres(box)
    tol = box.stats["contact_gap_tolerance_m"]
    n = box.neighbours
    gap = np.linalg.norm(c[n[:, 1]] - c[n[:, 0]], axis=1) - box.r[n[:, 0]] - box.r[n[:, 1]]
    expect = set(map(tuple, n[gap <= tol].tolist()))
    assert set(map(tuple, box.contacts.tolist())) == expect
    assert len(n) - len(expect) == box.stats["laguerre_pairs_not_in_contact"] > 0
    assert np.all(box.neighbour_facet_area_m2 > 0)
    assert np.allclose(box.distance_m, np.linalg.norm(c[box.contacts[:, 1]] - c[box.contacts[:, 0]], axis=1))
    # a bonded network with a normal and two shear springs a contact needs 6 / 3 x 2 = 4 contacts a
    # sphere to hold its 6 degrees of freedom; the packing gives about 6 (measured 5.9-6.1)
    assert box.mean_coordination > 5.0


def test_spheres_inside_an_aggregate_are_labelled_with_it_and_kinds_follow_the_rule(box):
    from scipy.spatial import Delaunay
    assert box.n_aggregates > 0
    c = centres(box)
    expect = np.full(box.n_particles, -1)
    for k, v in enumerate(box.polyhedra):
        expect[Delaunay(v).find_simplex(c) >= 0] = k
    assert np.array_equal(expect, box.aggregate_id)
    assert np.array_equal(box.material, (expect >= 0).astype(np.int8))
    a, b = expect[box.contacts[:, 0]], expect[box.contacts[:, 1]]
    rule = np.where((a < 0) & (b < 0), meso.MORTAR, np.where(a == b, meso.AGG, meso.ITZ))
    assert np.array_equal(box.kind, rule)
    assert all((box.kind == k).any() for k in (meso.MORTAR, meso.ITZ, meso.AGG))
    assert box.stats["empty_aggregates"] == 0


def test_aggregate_volume_fraction_is_the_polyhedra_volume(box):
    from scipy.spatial import ConvexHull
    vol = sum(ConvexHull(v).volume for v in box.polyhedra) / np.prod(box.specimen_size_m)
    assert vol == pytest.approx(box.stats["aggregate_volume_fraction"], rel=1e-12)
    # the grading stops at the polyhedron that brings the total closest to its target: within half
    # the largest one's volume (4.75 mm wide, up to 1.8 times as long: 0.1 of this box at most)
    assert abs(vol - BOX["aggregate_area_fraction"]) < 0.05


# ---------------------------------------------------------------------- seeds, save/load, without

def test_a_seed_gives_the_same_box_and_another_seed_another(box):
    assert box.equals(meso.generate(seed=1, **BOX))
    small = dict(BOX, width_mm=5.0, height_mm=5.0, depth_mm=5.0, aggregate_area_fraction=0.0)
    assert not meso.generate(seed=1, **small).equals(meso.generate(seed=2, **small))


def test_save_and_load_keep_everything(box, tmp_path):
    path = box.save(tmp_path / "a3")
    b = meso.load(path)
    assert b.equals(box) and b.dim == 3 and b.depth_m == box.depth_m
    assert b.summary()["facet_area_m2"] == box.summary()["facet_area_m2"]
    with np.load(path) as z:
        assert json.loads(str(z["meta_json"]))["format_version"] == 2
    two = meso.generate(seed=1, width_mm=6, height_mm=6, aggregate_area_fraction=0)
    with np.load(two.save(tmp_path / "a2")) as z:
        assert json.loads(str(z["meta_json"]))["format_version"] == 1  # a 2D file reads with any version


def test_without_drops_spheres_with_their_contacts_and_facets(box):
    drop = np.arange(0, box.n_particles, 7)
    b = box.without(drop)
    assert b.n_particles == box.n_particles - len(drop) and b.dim == 3
    keep = np.setdiff1d(np.arange(box.n_particles), drop)
    assert np.array_equal(b.z, box.z[keep]) and np.array_equal(b.cell_volume_m3, box.cell_volume_m3[keep])
    gone = np.isin(box.contacts, drop).any(axis=1)
    assert b.n_contacts == int((~gone).sum()) == len(b.facet_polygons)
    assert np.array_equal(b.facet_area_m2, box.facet_area_m2[~gone])
    assert all(np.array_equal(p, q) for p, q in zip(b.facet_polygons, [box.facet_polygons[k] for k in np.flatnonzero(~gone)]))


# ---------------------------------------------------------------------------- refusals

@pytest.mark.parametrize("change, name", [
    (dict(dim=4), "dim"), (dict(dim=True), "dim"), (dict(depth_mm=-1.0), "depth_mm"), (dict(depth_mm=float("nan")), "depth_mm"),
    (dict(depth_mm=0.5), "rmax_mm"), (dict(width_mm=80.0, height_mm=80.0, depth_mm=80.0), "rmax_mm"),
    (dict(depth_mm=5.0), "sieve_fractions_mm"), (dict(aggregate_area_fraction=0.7), "aggregate_area_fraction"),
])
def test_bad_3d_parameters_are_refused_naming_them(change, name):
    with pytest.raises(meso.MesoParameterError) as ei:
        meso.generate(seed=1, **dict(BOX, **change))
    assert str(ei.value).startswith(f"swelldem: {name} = ") and "allowed:" in str(ei.value)


def test_order_hilbert_is_refused_in_3d():
    with pytest.raises(meso.MesoParameterError, match="order = 'hilbert'"):
        meso.generate(seed=1, order="hilbert", **dict(BOX, aggregate_area_fraction=0))


# ---------------------------------------------------------------------------- pictures, files

def test_sections_of_a_cube_and_an_octahedron_are_their_closed_forms():
    cube = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], dtype=float)
    t = 0.4
    rot = np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
    sq = plot3d.section_polygon(cube @ rot.T, 2, 0.3)
    area = lambda p: 0.5 * abs(np.cross(p[1:-1] - p[0], p[2:] - p[0]).sum(0)[2])  # noqa: E731
    assert len(sq) == 4 and area(sq) == pytest.approx(1.0, rel=1e-12)
    octa = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    for h in (0.0, 0.25, 0.7):
        assert area(plot3d.section_polygon(octa, 2, h)) == pytest.approx(2 * (1 - h) ** 2, rel=1e-12)
    assert plot3d.section_polygon(octa, 2, 1.2) is None


def test_the_paraview_file_reads_back_with_vtk(box, tmp_path):
    vtk = pytest.importorskip("vtk")
    from vtk.util.numpy_support import vtk_to_numpy
    from swelldem.meso import paraview
    path = paraview.write_vtm(box, tmp_path / "m.vtm")
    rd = vtk.vtkXMLMultiBlockDataReader()
    rd.SetFileName(path)
    rd.Update()
    mb = rd.GetOutput()
    spheres, facets, aggs = (mb.GetBlock(k) for k in range(3))
    assert spheres.GetNumberOfPoints() == box.n_particles
    assert np.allclose(vtk_to_numpy(spheres.GetPointData().GetArray("radius")), box.r * 1e3)
    assert facets.GetNumberOfCells() == box.n_contacts
    assert np.array_equal(vtk_to_numpy(facets.GetCellData().GetArray("kind")), box.kind)
    # the facets' areas as VTK measures its polygons
    q = vtk.vtkCellSizeFilter()
    q.SetInputData(facets)
    q.Update()
    assert np.allclose(vtk_to_numpy(q.GetOutput().GetCellData().GetArray("Area")), box.facet_area_m2 * 1e6, rtol=1e-9)
    assert set(vtk_to_numpy(aggs.GetCellData().GetArray("aggregate_id"))) == set(range(box.n_aggregates))


def test_script_writes_the_3d_outputs_and_refuses_a_wrong_size(tmp_path):
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    script = os.path.join(REPO, "scripts", "make_mesostructure.py")
    out = tmp_path / "o"
    proc = subprocess.run([sys.executable, script, "--dim", "3", "--size-mm", "6", "7", "8", "--aggregate-fraction", "0",
                           "--seed", "2", "--out", str(out)], capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 0, proc.stderr
    s = json.load(open(out / "mesostructure.json"))
    assert s["dim"] == 3 and s["depth_m"] == pytest.approx(8e-3)
    assert set(s["facet_size_mm"]) >= {"3d", "2d_section"} and s["facet_size_mm"]["3d"]["all"]["n"] == s["n_contacts"]
    for f in ("mesostructure.png", "facets.png", "mesostructure.vtm", "mesostructure.md", "assembly.npz"):
        assert os.path.getsize(out / f) > 200, f
    assert meso.load(out / "assembly.npz").equals(meso.generate(seed=2, dim=3, width_mm=6, height_mm=7, depth_mm=8,
                                                               aggregate_area_fraction=0))
    bad = subprocess.run([sys.executable, script, "--dim", "3", "--size-mm", "6", "7", "--out", str(tmp_path / "b")],
                         capture_output=True, text=True, timeout=60, env=env)
    assert bad.returncode == 2 and bad.stderr.strip() == ("make_mesostructure.py: swelldem: size_mm = 6 7 is out of range; "
                                                          "allowed: 3 lengths in mm for --dim 3 (W H D)")
    assert not (tmp_path / "b").exists()
