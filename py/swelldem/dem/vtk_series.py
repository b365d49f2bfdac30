# SPDX-License-Identifier: GPL-2.0-or-later
"""A time series of the scene for ParaView: per exported step one XML PolyData (.vtp) file of the
particles and one of the contacts, and one .pvd collection of each that lists every file with its
physical time [day] (ParaView's time).

Written with VTK's own writer (python3-vtk9): binary, zlib-compressed appended data. YADE's VTKExporter writes discs as vertices without cells and has
no field data, so ParaView would show nothing before a Glyph filter and would have no time.

particles_<step>.vtp: one polygon cell per disc (a regular N-gon inscribed in the disc, in the
plane z = 0; its vertices in single precision, a drawing).
  point data: displacement [m] (3 components, YADE's state.displ() of the disc, the same at its
    polygon's every vertex: Warp By Vector moves the discs as they moved).
  cell data: id [-] body id, radius [m], aggregateId [-] (-1 mortar, else the aggregate polygon's
    index), steel [-] 1 for the discs of a reinforcing bar (swelldem.dem.rebar), else 0;
    stress [Pa] the disc's Love-Weber mean stress tensor (9 components, tension positive; see
    disc_state), meanStress [Pa] its in-plane mean (sigma_xx + sigma_yy) / 2;
    damage [-] the share of the disc's bonded contacts (those bonded at the start) broken since,
    bondedContacts [-] their number (damage is 0 for a disc without any); h [-] the disc's relative
    humidity, in a run with a moisture model (swelldem.dem.humidity).
contacts_<step>.vtp: one line cell per real interaction, between the two disc centres.
  point data (the centres of all discs): id, displacement [m] (as in the particles' file).
  cell data: kindId [-] and kind (its name, a string), Fn [N] normal force, tension positive; Fs [N]
  shear force; area [m2] facet area; strength [N] tensile strength fnMax (0 where the contact has
  none: damage off, or a contact born broken); FnOverStrength [-] Fn / fnMax (0 where no strength);
  broken [-] 0/1; failureMode [-] 0 intact, 1 tension, 2 shear; bonded [-] 1 for a contact bonded at
  the start of the run, 0 for one made during it; crackOpening [m] of a broken contact, FnHat / kn
  (the normal opening beyond its stress-free state; 0 when closed or intact).
A 3D box (VtkSeries with cell_volume): particles_<step>.vtp holds one vertex a sphere at its
centre (double precision) and every array as point data, the ones above (stress in 3D, V the
sphere's power cell volume; meanStress the trace / 3) and radius [m] for ParaView's Glyph filter
(a sphere scaled by radius); contacts_<step>.vtp holds the same arrays as a section's, the centres
in 3D, and Fs2 [N], the shear along the contact's second tangent.
Platens (swelldem.dem.platens) and their contacts are left out of the drawing (their stress is in
results.json); their forces on the discs count in the discs' stress.
Field data of both: TimeValue [day], step [-] (index into results.json's times_days), kindNames
(string array: the name of kindId k at index k, '' where no kind has the id) and the same table
as integers kindId_MORTAR = 0, kindId_ITZ = 1, kindId_AGG = 2, kindId_PLATEN = 3, kindId_STEEL = 4,
kindId_BOND = 5.
"""
import glob
import math
import os

import numpy as np

from ..meso.paraview import cell_array, vtk_array
from ..paper import KIND_IDS, STRUCTURE_KIND_IDS
from ..plugin import require

#: Sides of the polygon drawn for each disc.
DISC_SIDES = 16
#: kindId -> name, every kind of the scenes (MORTAR, ITZ, AGG and the structures').
KIND_BY_ID = {k: name for name, k in {**KIND_IDS, **STRUCTURE_KIND_IDS}.items()}


def _yade():
    return require("swelldem.dem.vtk_series")


def _vtk():
    import vtk  # python3-vtk9 (scripts/bootstrap.sh)
    return vtk


def _string_array(vtk, name, values):
    arr = vtk.vtkStringArray()
    arr.SetName(name)
    arr.SetNumberOfValues(len(values))
    for k, v in enumerate(values):
        arr.SetValue(k, v)
    return arr


def _field_data(vtk, data, time_days, step):
    field = data.GetFieldData()
    field.AddArray(vtk_array(vtk, "TimeValue", [float(time_days)], np.float64))
    field.AddArray(vtk_array(vtk, "step", [int(step)], np.int32))
    field.AddArray(_string_array(vtk, "kindNames", [KIND_BY_ID.get(k, "") for k in range(max(KIND_BY_ID) + 1)]))
    for k, name in sorted(KIND_BY_ID.items()):
        field.AddArray(vtk_array(vtk, f"kindId_{name}", [k], np.int32))


def write_polydata(path, points, cell_type, offsets, connectivity, cell_data=(), point_data=(), time_days=0.0, step=0,
                   point_type=np.float64):
    """One VTK XML PolyData file, binary with zlib-compressed appended data.

    points: (n, 3) [m], stored as point_type; cell_type: 'Polys', 'Lines' or 'Verts'; offsets (cells + 1, from 0), connectivity:
    VTK's cell arrays; cell_data, point_data: (name, numpy dtype, values (n,) or (n, k)) tuples, or
    (name, str, list of strings) for a string array; time_days [day] and step [-] go into the field
    data with the kind name table. Written to a temporary file, then renamed: a reader never sees
    half a file."""
    vtk = _vtk()
    poly = vtk.vtkPolyData()
    pts = vtk.vtkPoints()
    pts.SetData(vtk_array(vtk, "Points", np.asarray(points, dtype=np.float64).reshape(-1, 3), point_type))
    poly.SetPoints(pts)
    cells = cell_array(vtk, offsets, connectivity)
    if cell_type == "Polys":
        poly.SetPolys(cells)
    elif cell_type == "Verts":
        poly.SetVerts(cells)
    else:
        poly.SetLines(cells)
    for target, arrays in ((poly.GetCellData(), cell_data), (poly.GetPointData(), point_data)):
        for name, kind, values in arrays:
            target.AddArray(_string_array(vtk, name, values) if kind is str else vtk_array(vtk, name, values, kind))
    _field_data(vtk, poly, time_days, step)
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(path + ".tmp")
    w.SetInputData(poly)
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()  # raw bytes: base64 would add a third
    w.SetCompressorTypeToZLib()
    if not w.Write():
        raise OSError(f"swelldem: VTK could not write {path}")
    os.replace(path + ".tmp", path)


def write_pvd(path, entries):
    """A ParaView collection: entries are (time [day], file name relative to the .pvd)."""
    lines = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">', "<Collection>"]
    lines += [f'<DataSet timestep="{float(t)!r}" group="" part="0" file="{name}"/>' for t, name in entries]
    lines += ["</Collection>", "</VTKFile>", ""]
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(path + ".tmp", path)


def _is_disc(body):
    """Discs only: platens (Wall bodies, swelldem.dem.platens) have no radius and no place in these files."""
    return hasattr(body.shape, "radius")


def _pair(i):
    return (i.id1, i.id2) if i.id1 < i.id2 else (i.id2, i.id1)


def disc_state(discs, cell_area=None, thickness=1.0, bonded=None, cell_volume=None):
    """Per disc of `discs` (YADE bodies): (stress (n, 3, 3) [Pa], damage (n,) [-], bonded contacts (n,)).
    With cell_volume [m3] by body id (a 3D box's assembly.cell_volume_m3) the particles are spheres:
    the sums run in three dimensions and V is the sphere's power cell volume ((2 r)^3 beyond it).

    stress: Love-Weber's mean stress of the disc, sigma = (1/V) sum_c f_c (x) l_c (sigma_ij = (1/V)
    sum_c f_i l_j) over its real interactions, f_c the contact's force on the disc (normal and
    shear, YADE's phys.normalForce + shearForce, tension positive), l_c the branch vector from the
    disc's centre to the contact point (geom.contactPoint); V = A t, A the disc's Laguerre cell area
    (cell_area[body id] [m2], the mesostructure's assembly.cell_area_m2; for a disc beyond it, a bar's,
    or without cell_area, (2 r)^2, the square of a disc in a row of touching discs) and t = thickness
    [m], the scene's (1 m by default). Returned symmetrised: a disc in equilibrium has a symmetric
    sum, and its antisymmetric part is the round-off of the moment balance. sigma_zz = 0.
    damage: the share of the disc's contacts to other discs bonded at the start (bonded: the
    (id1 < id2) pairs, recorder.bonded_pairs(); None: every real interaction of O counts as bonded)
    that are broken or gone; 0 for a disc with none."""
    yade, _ = _yade()
    O = yade.Omega()
    index = {b.id: k for k, b in enumerate(discs)}
    n = len(discs)
    d = 2 if cell_volume is None else 3
    pos = np.array([[float(b.state.pos[k]) for k in range(d)] for b in discs]).reshape(n, d)
    radius = np.array([float(b.shape.radius) for b in discs])
    ids = np.array([b.id for b in discs], dtype=int)
    if d == 3:
        volume = (2 * radius) ** 3
        have = ids < len(cell_volume)
        volume[have] = np.asarray(cell_volume, dtype=float)[ids[have]]
    else:
        area = (2 * radius) ** 2
        if cell_area is not None:
            have = ids < len(cell_area)
            area[have] = np.asarray(cell_area, dtype=float)[ids[have]]
        volume = area * thickness
    total = np.zeros(n, dtype=int)
    intact = np.zeros(n, dtype=int)
    whole = set()  # unbroken pairs of discs
    side, force, point = [], [], []  # per (contact, disc of it): the disc, the force on it, the contact point
    for i in O.interactions:
        if not i.isReal:
            continue
        f = i.phys.normalForce + i.phys.shearForce  # the law's force on id2; on id1 its opposite
        fc = [float(f[k]) for k in range(d)]
        cp = [float(i.geom.contactPoint[k]) for k in range(d)]
        for body, sign in ((i.id1, -1.0), (i.id2, 1.0)):
            k = index.get(body)
            if k is not None:
                side.append(k)
                force.append([sign * v for v in fc])
                point.append(cp)
        if i.id1 in index and i.id2 in index:
            if bonded is None:
                for body in (i.id1, i.id2):
                    total[index[body]] += 1
                    intact[index[body]] += not i.phys.broken
            elif not i.phys.broken:
                whole.add(_pair(i))
    for a, b in bonded or ():
        if a in index and b in index:
            for body in (a, b):
                total[index[body]] += 1
                intact[index[body]] += (a, b) in whole
    side = np.array(side, dtype=int)
    force, branch = np.array(force).reshape(-1, d), np.array(point).reshape(-1, d) - pos[side]
    moment = np.zeros((n, d, d))
    np.add.at(moment, side, force[:, :, None] * branch[:, None, :])
    sym = 0.5 * (moment + moment.transpose(0, 2, 1)) / volume[:, None, None]
    stress = np.zeros((n, 3, 3))
    stress[:, :d, :d] = sym
    damage = np.where(total > 0, (total - intact) / np.maximum(total, 1), 0.0)
    return stress, damage, total


def sphere_points(cell_volume, bonded=None):
    """Points, offsets, connectivity, cell data and point data of the spheres of a 3D box in O: one
    vertex a sphere at its centre, every array as point data (ParaView's Glyph, a sphere scaled by
    `radius`, draws them); cell_volume, bonded: see disc_state."""
    yade, _ = _yade()
    spheres = [b for b in yade.Omega().bodies if b is not None and _is_disc(b)]
    n = len(spheres)
    centre = np.array([[float(v) for v in b.state.pos] for b in spheres]).reshape(n, 3)
    displ = np.array([[float(v) for v in b.state.displ()] for b in spheres]).reshape(n, 3)
    stress, damage, total = disc_state(spheres, bonded=bonded, cell_volume=cell_volume)
    point_data = [("id", np.int32, [b.id for b in spheres]), ("radius", np.float64, [float(b.shape.radius) for b in spheres]),
                  ("aggregateId", np.int32, [int(getattr(b.material, "aggregateId", -1)) for b in spheres]),
                  ("displacement", np.float64, displ), ("stress", np.float64, stress.reshape(n, 9)),
                  ("meanStress", np.float64, np.trace(stress, axis1=1, axis2=2) / 3),
                  ("damage", np.float64, damage), ("bondedContacts", np.int32, total)]
    return centre, np.arange(n + 1), np.arange(n), [], point_data


def particle_cells(sides=DISC_SIDES, cell_area=None, thickness=1.0, bonded=None):
    """Points, offsets, connectivity, cell data and point data of the discs of O as polygons of
    `sides` sides; cell_area, thickness, bonded: see disc_state."""
    yade, _ = _yade()
    discs = [b for b in yade.Omega().bodies if b is not None and _is_disc(b)]
    n = len(discs)
    centre = np.array([[float(b.state.pos[0]), float(b.state.pos[1])] for b in discs]).reshape(n, 2)
    radius = np.array([float(b.shape.radius) for b in discs])
    angle = 2 * math.pi * np.arange(sides) / sides
    ring = np.stack([np.cos(angle), np.sin(angle)], axis=1)
    points = np.zeros((n, sides, 3))
    points[:, :, :2] = centre[:, None, :] + radius[:, None, None] * ring[None, :, :]
    displ = np.array([[float(v) for v in b.state.displ()] for b in discs]).reshape(n, 3)
    stress, damage, total = disc_state(discs, cell_area, thickness, bonded)
    cells = [("id", np.int32, [b.id for b in discs]), ("radius", np.float64, radius),
             ("aggregateId", np.int32, [int(getattr(b.material, "aggregateId", -1)) for b in discs]),
             ("steel", np.int32, [int(bool(getattr(b.material, "steel", False))) for b in discs]),
             ("stress", np.float64, stress.reshape(n, 9)), ("meanStress", np.float64, 0.5 * (stress[:, 0, 0] + stress[:, 1, 1])),
             ("damage", np.float64, damage), ("bondedContacts", np.int32, total)]
    point_data = [("displacement", np.float64, np.repeat(displ, sides, axis=0))]
    offsets = sides * np.arange(n + 1)
    return points.reshape(-1, 3), offsets, np.arange(n * sides), cells, point_data


def contact_cells(bonded=None, dim=2):
    """Points (all disc centres), offsets, connectivity, cell data and point data of the real
    interactions of O as lines; bonded: the (id1, id2) pairs (id1 < id2) bonded at the start
    (recorder.bonded_pairs(); None: all). dim 3: the centres in 3D and the shear's second
    component Fs2 [N] beside Fs."""
    yade, _ = _yade()
    O = yade.Omega()
    index, points, pid, displ = {}, [], [], []
    for b in O.bodies:
        if b is None or not _is_disc(b):
            continue
        index[b.id] = len(points)
        points.append((float(b.state.pos[0]), float(b.state.pos[1]), float(b.state.pos[2]) if dim == 3 else 0.0))
        pid.append(b.id)
        displ.append([float(v) for v in b.state.displ()])
    names = ("kindId", "kind", "Fn", "Fs") + (("Fs2",) if dim == 3 else ()) + (
        "area", "strength", "FnOverStrength", "broken", "failureMode", "bonded", "crackOpening")
    conn, cols = [], {k: [] for k in names}
    for i in O.interactions:
        if not i.isReal or i.id1 not in index or i.id2 not in index:  # platen contacts: results.json has their stress
            continue
        p = i.phys
        conn += [index[i.id1], index[i.id2]]
        fn, fn_max = float(p.Fn), float(p.fnMax)
        has_strength = math.isfinite(fn_max) and fn_max > 0
        cols["kindId"].append(int(p.kindId))
        cols["kind"].append(KIND_BY_ID.get(int(p.kindId), str(p.kindId)))
        cols["Fn"].append(fn)
        cols["Fs"].append(float(p.Fs))
        if dim == 3:
            cols["Fs2"].append(float(p.Fs2))
        cols["area"].append(float(p.area))
        cols["strength"].append(fn_max if has_strength else 0.0)
        cols["FnOverStrength"].append(fn / fn_max if has_strength else 0.0)
        cols["broken"].append(int(bool(p.broken)))
        cols["failureMode"].append(int(p.failureMode))
        cols["bonded"].append(int(bonded is None or _pair(i) in bonded))
        cols["crackOpening"].append(max(float(p.FnHat), 0.0) / float(p.kn) if p.broken and p.kn > 0 else 0.0)
    ints = {"kindId", "broken", "failureMode", "bonded"}
    cells = [(k, str if k == "kind" else np.int32 if k in ints else np.float64, v) for k, v in cols.items()]
    offsets = 2 * np.arange(len(conn) // 2 + 1)
    point_data = [("id", np.int32, pid), ("displacement", np.float64, np.array(displ).reshape(-1, 3))]
    return np.array(points).reshape(-1, 3), offsets, conn, cells, point_data


class VtkSeries:
    """The ParaView time series of a run in folder `vtk_dir`: export(step, time_days) writes
    particles_<step>.vtp and contacts_<step>.vtp and rewrites particles.pvd and contacts.pvd with
    every file exported so far. Files of an earlier run in the folder are removed when the series
    is made, but for those of the steps before `keep_before` listed in its particles.pvd, with which
    the series goes on (a resumed run). bonded: see contact_cells; sides: of each disc's polygon; cell_area [m2] by body id and
    thickness [m]: the discs' volumes for their stress (disc_state; a run passes its assembly's)."""

    def __init__(self, vtk_dir, bonded=None, sides=DISC_SIDES, cell_area=None, thickness=1.0, keep_before=0, cell_volume=None):
        self.dir, self.bonded, self.sides = vtk_dir, bonded, sides
        self.cell_area, self.thickness, self.cell_volume = cell_area, thickness, cell_volume
        self.entries = []  # (step, time [day])
        os.makedirs(vtk_dir, exist_ok=True)
        if keep_before:
            self.entries = [(s, t) for s, t in _pvd_entries(os.path.join(vtk_dir, "particles.pvd")) if s < keep_before]
        kept = {f"{w}_{s:05d}.vtp" for s, _ in self.entries for w in ("particles", "contacts")}
        for pattern in ("particles_*.vtp", "contacts_*.vtp", "particles.pvd", "contacts.pvd", "swelling-*.vtk"):
            for f in glob.glob(os.path.join(vtk_dir, pattern)):
                if os.path.basename(f) not in kept:
                    os.remove(f)
        if self.entries:
            self._write_collections()

    def exported(self, step):
        """Whether step (index into times_days) has been written."""
        return any(s == step for s, _ in self.entries)

    def export(self, step, time_days, particle_fields=None):
        """Writes the scene of O now as step `step` at physical time time_days [day].
        particle_fields: a callable of the particles' body ids giving further per-particle arrays,
        [(name, numpy dtype, values)] (a moisture run's h)."""
        name = f"{step:05d}.vtp"
        if self.cell_volume is not None:  # a 3D box: spheres as points
            pts, offs, conn, cells, pdata = sphere_points(self.cell_volume, self.bonded)
            if particle_fields is not None:
                pdata += particle_fields(np.asarray(pdata[0][2], dtype=np.int64))
            write_polydata(os.path.join(self.dir, "particles_" + name), pts, "Verts", offs, conn, cells, pdata,
                           time_days=time_days, step=step)
        else:
            pts, offs, conn, cells, pdata = particle_cells(self.sides, self.cell_area, self.thickness, self.bonded)
            if particle_fields is not None:
                cells += particle_fields(np.asarray(cells[0][2], dtype=np.int64))
            # the polygons are a drawing: single precision (a third of the file less; the centres are
            # exact in the contacts' file, the displacements in both)
            write_polydata(os.path.join(self.dir, "particles_" + name), pts, "Polys", offs, conn, cells, pdata,
                           time_days=time_days, step=step, point_type=np.float32)
        pts, offs, conn, cells, pdata = contact_cells(self.bonded, 3 if self.cell_volume is not None else 2)
        write_polydata(os.path.join(self.dir, "contacts_" + name), pts, "Lines", offs, conn, cells, pdata,
                       time_days=time_days, step=step)
        self.entries.append((step, float(time_days)))
        self._write_collections()

    def _write_collections(self):
        for what in ("particles", "contacts"):
            write_pvd(os.path.join(self.dir, what + ".pvd"), [(t, f"{what}_{s:05d}.vtp") for s, t in self.entries])


def _pvd_entries(path):
    """(step, time [day]) of the files a collection written by write_pvd lists ([] without one)."""
    import xml.etree.ElementTree as ET
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError):
        return []
    return [(int(d.get("file").rsplit("_", 1)[1].split(".")[0]), float(d.get("timestep"))) for d in root.iter("DataSet")]
