# SPDX-License-Identifier: GPL-2.0-or-later
"""A time series of the scene for ParaView: per exported step one XML PolyData (.vtp) file of the
particles and one of the contacts, and one .pvd collection of each that lists every file with its
physical time [day] (ParaView's time).

Written with plain Python (ASCII .vtp): YADE's VTKExporter writes discs as vertices without cells
and has no field data, so ParaView would show nothing before a Glyph filter and would have no time.

particles_<step>.vtp: one polygon cell per disc (a regular N-gon inscribed in the disc, in the
plane z = 0); cell data:
  id [-] body id, radius [m], aggregateId [-] (-1 mortar, else the aggregate polygon's index),
  steel [-] 1 for the discs of a reinforcing bar (swelldem.dem.rebar), else 0,
  displacement [m] (3 components, YADE's state.displ()).
contacts_<step>.vtp: one line cell per real interaction, between the two disc centres (points: the
centres of all bodies, point data id); cell data:
  kindId [-] (lookup in the field data, below), Fn [N] normal force, tension positive; Fs [N]
  shear force; area [m2] facet area; strength [N] tensile strength fnMax (0 where the contact has
  none: damage off, or a contact born broken); FnOverStrength [-] Fn / fnMax (0 where no strength);
  broken [-] 0/1; failureMode [-] 0 intact, 1 tension, 2 shear; bonded [-] 1 for a contact bonded at
  the start of the run, 0 for one made during it; crackOpening [m] of a broken contact, FnHat / kn
  (the normal opening beyond its stress-free state; 0 when closed or intact).
Platens (swelldem.dem.platens) and their contacts are left out; their stress is in results.json.
Field data of both: TimeValue [day], step [-] (index into results.json's times_days) and the kind
name table kindId_MORTAR = 0, kindId_ITZ = 1, kindId_AGG = 2, kindId_PLATEN = 3, kindId_STEEL = 4, kindId_BOND = 5 (VTK's ASCII XML has no portable
string array, and ParaView colours by integer arrays, e.g. with "Interpret Values As Categories").
"""
import glob
import math
import os

from ..paper import KIND_IDS, STRUCTURE_KIND_IDS
from ..plugin import require

#: Sides of the polygon drawn for each disc.
DISC_SIDES = 16


def _yade():
    return require("swelldem.dem.vtk_series")


def _numbers(values):
    # repr of a Python float round-trips exactly: the files hold the scene's values, not rounded ones
    return " ".join(repr(v) for v in values)


def _data_array(name, vtk_type, values, components=1):
    return (f'<DataArray type="{vtk_type}" Name="{name}" NumberOfComponents="{components}" format="ascii">'
            f"{_numbers(values)}</DataArray>")


def _field_data(time_days, step):
    arrays = [f'<Array type="Float64" Name="TimeValue" NumberOfTuples="1" format="ascii">{float(time_days)!r}</Array>',
              f'<Array type="Int32" Name="step" NumberOfTuples="1" format="ascii">{int(step)}</Array>']
    arrays += [f'<Array type="Int32" Name="kindId_{name}" NumberOfTuples="1" format="ascii">{k}</Array>'
               for name, k in {**KIND_IDS, **STRUCTURE_KIND_IDS}.items()]
    return "<FieldData>" + "".join(arrays) + "</FieldData>"


def write_polydata(path, points, cell_type, connectivity, offsets, cell_data, point_data=(), time_days=0.0, step=0):
    """One ASCII VTK XML PolyData file.

    points: (x, y, z) tuples [m]; cell_type: 'Polys' or 'Lines'; connectivity, offsets: VTK's
    cell arrays (point indices, and the end of each cell in connectivity); cell_data, point_data:
    (name, VTK type e.g. 'Float64' or 'Int32', flat values, components) tuples; time_days [day] and
    step [-] go into the field data (TimeValue, step) with the kind name table. Written to a
    temporary file, then renamed: a reader never sees half a file."""
    n_cells = len(offsets)
    counts = {k: (n_cells if k == cell_type else 0) for k in ("Verts", "Lines", "Strips", "Polys")}
    parts = ['<?xml version="1.0"?>',
             '<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">', "<PolyData>",
             _field_data(time_days, step),
             f'<Piece NumberOfPoints="{len(points)}" NumberOfVerts="{counts["Verts"]}" NumberOfLines="{counts["Lines"]}" '
             f'NumberOfStrips="{counts["Strips"]}" NumberOfPolys="{counts["Polys"]}">',
             "<PointData>" + "".join(_data_array(*a) for a in point_data) + "</PointData>",
             "<CellData>" + "".join(_data_array(*a) for a in cell_data) + "</CellData>",
             "<Points>" + _data_array("Points", "Float64", [c for p in points for c in p], 3) + "</Points>",
             f"<{cell_type}>" + _data_array("connectivity", "Int64", connectivity) + _data_array("offsets", "Int64", offsets)
             + f"</{cell_type}>",
             "</Piece>", "</PolyData>", "</VTKFile>", ""]
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(parts))
    os.replace(path + ".tmp", path)


def write_pvd(path, entries):
    """A ParaView collection: entries are (time [day], file name relative to the .pvd)."""
    lines = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">', "<Collection>"]
    lines += [f'<DataSet timestep="{float(t)!r}" group="" part="0" file="{name}"/>' for t, name in entries]
    lines += ["</Collection>", "</VTKFile>", ""]
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(path + ".tmp", path)


def particle_cells(sides=DISC_SIDES):
    """Points, connectivity, offsets and cell data of the discs of O as polygons of `sides` sides."""
    yade, _ = _yade()
    O = yade.Omega()
    ring = [(math.cos(2 * math.pi * k / sides), math.sin(2 * math.pi * k / sides)) for k in range(sides)]
    points, ids, radius, agg, steel, displ = [], [], [], [], [], []
    for b in O.bodies:
        if b is None or not _is_disc(b):
            continue
        x, y, r = float(b.state.pos[0]), float(b.state.pos[1]), float(b.shape.radius)
        points += [(x + r * c, y + r * s, 0.0) for c, s in ring]
        ids.append(b.id)
        radius.append(r)
        agg.append(int(getattr(b.material, "aggregateId", -1)))
        steel.append(int(bool(getattr(b.material, "steel", False))))
        displ += [float(v) for v in b.state.displ()]
    n = len(ids)
    connectivity = range(n * sides)
    offsets = [sides * (k + 1) for k in range(n)]
    cells = [("id", "Int32", ids, 1), ("radius", "Float64", radius, 1), ("aggregateId", "Int32", agg, 1), ("steel", "Int32", steel, 1),
             ("displacement", "Float64", displ, 3)]
    return points, connectivity, offsets, cells


def _is_disc(body):
    """Discs only: platens (Wall bodies, swelldem.dem.platens) have no radius and no place in these files."""
    return hasattr(body.shape, "radius")


def contact_cells(bonded=None):
    """Points (all disc centres), connectivity, offsets, cell data and point data of the real
    interactions of O as lines; bonded: the (id1, id2) pairs (id1 < id2) bonded at the start
    (recorder.bonded_pairs(); None: all)."""
    yade, _ = _yade()
    O = yade.Omega()
    index, points, pid = {}, [], []
    for b in O.bodies:
        if b is None or not _is_disc(b):
            continue
        index[b.id] = len(points)
        points.append((float(b.state.pos[0]), float(b.state.pos[1]), 0.0))
        pid.append(b.id)
    conn, cols = [], {k: [] for k in ("kindId", "Fn", "Fs", "area", "strength", "FnOverStrength", "broken", "failureMode",
                                      "bonded", "crackOpening")}
    for i in O.interactions:
        if not i.isReal or i.id1 not in index or i.id2 not in index:  # platen contacts: results.json has their stress
            continue
        p = i.phys
        conn += [index[i.id1], index[i.id2]]
        fn, fn_max = float(p.Fn), float(p.fnMax)
        has_strength = math.isfinite(fn_max) and fn_max > 0
        cols["kindId"].append(int(p.kindId))
        cols["Fn"].append(fn)
        cols["Fs"].append(float(p.Fs))
        cols["area"].append(float(p.area))
        cols["strength"].append(fn_max if has_strength else 0.0)
        cols["FnOverStrength"].append(fn / fn_max if has_strength else 0.0)
        cols["broken"].append(int(bool(p.broken)))
        cols["failureMode"].append(int(p.failureMode))
        pair = (i.id1, i.id2) if i.id1 < i.id2 else (i.id2, i.id1)
        cols["bonded"].append(int(bonded is None or pair in bonded))
        cols["crackOpening"].append(max(float(p.FnHat), 0.0) / float(p.kn) if p.broken and p.kn > 0 else 0.0)
    ints = {"kindId", "broken", "failureMode", "bonded"}
    cells = [(k, "Int32" if k in ints else "Float64", v, 1) for k, v in cols.items()]
    offsets = [2 * (c + 1) for c in range(len(conn) // 2)]
    return points, conn, offsets, cells, [("id", "Int32", pid, 1)]


class VtkSeries:
    """The ParaView time series of a run in folder `vtk_dir`: export(step, time_days) writes
    particles_<step>.vtp and contacts_<step>.vtp and rewrites particles.pvd and contacts.pvd with
    every file exported so far. Files of an earlier run in the folder are removed when the series
    is made, so the collections list only this run's. bonded: see contact_cells; sides: of each
    disc's polygon."""

    def __init__(self, vtk_dir, bonded=None, sides=DISC_SIDES):
        self.dir, self.bonded, self.sides = vtk_dir, bonded, sides
        self.entries = []  # (step, time [day])
        os.makedirs(vtk_dir, exist_ok=True)
        for pattern in ("particles_*.vtp", "contacts_*.vtp", "particles.pvd", "contacts.pvd", "swelling-*.vtk"):
            for f in glob.glob(os.path.join(vtk_dir, pattern)):
                os.remove(f)

    def exported(self, step):
        """Whether step (index into times_days) has been written."""
        return any(s == step for s, _ in self.entries)

    def export(self, step, time_days):
        """Writes the scene of O now as step `step` at physical time time_days [day]."""
        name = f"{step:05d}.vtp"
        pts, conn, offs, cells = particle_cells(self.sides)
        write_polydata(os.path.join(self.dir, "particles_" + name), pts, "Polys", conn, offs, cells,
                       time_days=time_days, step=step)
        pts, conn, offs, cells, pdata = contact_cells(self.bonded)
        write_polydata(os.path.join(self.dir, "contacts_" + name), pts, "Lines", conn, offs, cells, pdata,
                       time_days=time_days, step=step)
        self.entries.append((step, float(time_days)))
        for what in ("particles", "contacts"):
            write_pvd(os.path.join(self.dir, what + ".pvd"), [(t, f"{what}_{s:05d}.vtp") for s, t in self.entries])
