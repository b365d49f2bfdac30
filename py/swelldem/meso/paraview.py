# SPDX-License-Identifier: GPL-2.0-or-later
"""A 3D mesostructure as a ParaView file (VTK XML multiblock, written with python3-vtk9).

Written with VTK's own writers, as the runs' fields are (swelldem.dem.vtk_series, which shares
vtk_array and cell_array). One ``.vtm`` file with three blocks,
in mm (the unit of the generator's parameters):

- ``spheres``: a vertex per sphere with point data ``radius`` [mm], ``aggregate_id`` (-1 mortar),
  ``material`` (0 mortar, 1 aggregate), ``cell_volume`` [mm^3] (in ParaView: Glyph, sphere, scale by
  ``radius``, scale factor 2: the glyph source has radius 0.5);
- ``facets``: the Laguerre facet of every contact as a polygon with cell data ``kind`` (0 MORTAR,
  1 ITZ, 2 AGG), ``area`` [mm^2], ``gap`` [mm], ``contact`` (index in the assembly);
- ``aggregates``: each polyhedron's hull triangles with cell data ``aggregate_id`` and ``fraction``.
"""
import os

import numpy as np

MM = 1e3  # millimetres per metre


def vtk_array(vtk, name, values, kind):
    """A named VTK data array holding a copy of `values` as numpy dtype `kind` (an (n, k) array: k
    components)."""
    from vtk.util.numpy_support import numpy_to_vtk
    arr = numpy_to_vtk(np.ascontiguousarray(values, dtype=kind), deep=True)
    arr.SetName(name)
    return arr


def cell_array(vtk, offsets, connectivity):
    """A vtkCellArray of VTK's offsets (n + 1, from 0) and connectivity (point indices) arrays."""
    from vtk.util.numpy_support import numpy_to_vtkIdTypeArray
    cells = vtk.vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.ascontiguousarray(offsets, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.ascontiguousarray(connectivity, dtype=np.int64), deep=True))
    return cells


def _polydata(vtk, points, polygons):
    """vtkPolyData of (k, 3) points and a list of index arrays, one polygon each (None: one vertex a point)."""
    from vtk.util.numpy_support import numpy_to_vtk
    pd = vtk.vtkPolyData()
    pts = vtk.vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    pd.SetPoints(pts)
    if polygons is None:
        n = len(points)
        conn = np.arange(n, dtype=np.int64)
        offs = np.arange(n + 1, dtype=np.int64)
    else:
        conn = np.concatenate(polygons).astype(np.int64) if polygons else np.zeros(0, np.int64)
        offs = np.concatenate([[0], np.cumsum([len(p) for p in polygons])]).astype(np.int64)
    cells = cell_array(vtk, offs, conn)
    if polygons is None:
        pd.SetVerts(cells)
    else:
        pd.SetPolys(cells)
    return pd


def write_vtm(assembly, path):
    """Write the 3D assembly as ``path`` (.vtm, with its pieces in a folder of the same name); returns the path."""
    import vtk
    from scipy.spatial import ConvexHull
    a = assembly
    if a.dim != 3:
        raise ValueError(f"write_vtm: the assembly is {a.dim}D; a 2D scene goes to ParaView through its YADE run")
    path = str(path)
    if not path.endswith(".vtm"):
        path += ".vtm"

    spheres = _polydata(vtk, np.stack([a.x, a.y, a.z], axis=1) * MM, None)
    pdata = spheres.GetPointData()
    pdata.AddArray(vtk_array(vtk, "radius", a.r * MM, np.float64))
    pdata.AddArray(vtk_array(vtk, "aggregate_id", a.aggregate_id, np.int32))
    pdata.AddArray(vtk_array(vtk, "material", a.material, np.int32))
    pdata.AddArray(vtk_array(vtk, "cell_volume", a.cell_volume_m3 * MM ** 3, np.float64))

    counts = np.array([len(q) for q in a.facet_polygons], dtype=np.int64)
    start = np.concatenate([[0], np.cumsum(counts)])
    fverts = np.concatenate(a.facet_polygons) * MM if len(counts) else np.zeros((0, 3))
    facets = _polydata(vtk, fverts, [np.arange(start[k], start[k + 1]) for k in range(len(counts))])
    cdata = facets.GetCellData()
    cdata.AddArray(vtk_array(vtk, "kind", a.kind, np.int32))
    cdata.AddArray(vtk_array(vtk, "area", a.facet_area_m2 * MM ** 2, np.float64))
    cdata.AddArray(vtk_array(vtk, "gap", a.gap_m * MM, np.float64))
    cdata.AddArray(vtk_array(vtk, "contact", np.arange(a.n_contacts), np.int64))

    pts, tris, agg_of, frac_of = [], [], [], []
    base = 0
    for k, v in enumerate(a.polyhedra):
        h = ConvexHull(v * MM)
        pts.append(h.points)
        tris.extend(list(h.simplices + base))
        agg_of.append(np.full(len(h.simplices), k))
        frac_of.append(np.full(len(h.simplices), int(a.aggregate_fraction[k])))
        base += len(h.points)
    aggregates = _polydata(vtk, np.concatenate(pts) if pts else np.zeros((0, 3)), tris)
    adata = aggregates.GetCellData()
    adata.AddArray(vtk_array(vtk, "aggregate_id", np.concatenate(agg_of) if agg_of else np.zeros(0), np.int32))
    adata.AddArray(vtk_array(vtk, "fraction", np.concatenate(frac_of) if frac_of else np.zeros(0), np.int32))

    mb = vtk.vtkMultiBlockDataSet()
    for k, (name, block) in enumerate((("spheres", spheres), ("facets", facets), ("aggregates", aggregates))):
        mb.SetBlock(k, block)
        mb.GetMetaData(k).Set(vtk.vtkCompositeDataSet.NAME(), name)
    w = vtk.vtkXMLMultiBlockDataWriter()
    w.SetFileName(path)
    w.SetInputData(mb)
    w.SetDataModeToBinary()
    w.SetCompressorTypeToZLib()
    if not w.Write():
        raise OSError(f"write_vtm: VTK could not write {path}")
    return os.path.abspath(path)
