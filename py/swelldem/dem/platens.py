# SPDX-License-Identifier: GPL-2.0-or-later
"""Rigid platens on the sides of a specimen: free, fixed (restrained), at a constant applied
stress, or held by a spring (partial restraint), per axis (x, y; and z for a 3D box).

Each loaded axis gets two YADE Wall bodies at the specimen's extreme disc edges. The low one
(left, bottom) is fixed; the high one (right, top) is fixed, loaded by a constant force (YADE's
ForceEngine) or held by a spring (the solver's springBodies), and moves along its axis only. A
fixed low platen and a loaded high one are what a press or a restraining frame does, and they
leave no rigid-body mode in the loaded direction.

A generated specimen's sides are rough (the top of a packing most: its outermost discs stand up
to a radius out). The discs that face a platen (facing_discs: within 1.5 Rmax of the outermost
edge and not hidden behind another disc) get a contact with it at the set-up, whatever their gap,
as a capping layer would bond them: intact contacts of the PLATEN kind (elastic, stress-free as
created, never breaking), made through the one contact path (Ip2_ConcreteMat_ConcreteMat_SwellPhys
with its `platen` kind, the same law). Their stiffness is kn = E_platen A / L with the Ip2's
fallback facet A = 2 r b and L = 2 r + gap, about E_platen b per contact; their shear ratio is
tiny (PLATEN_SHEAR_RATIO): lubricated platens, which restrain the specimen along their axis only
(a ratio of 1e-3 was measured to carry 10 % of a -5 MPa load on the other axis's platens). Discs that reach a
platen later get a cohesionless (compression-only) contact from the collider, like every contact
made during a run.

Platen stress [Pa] (compression negative) is the platens' contact force along their axis over the
specimen's nominal face (2D: height for the x platens, width for the y platens, times the
thickness; 3D: the product of the box's two other sides): the mean of the two platens' reactions.
Platen displacement [m] is the change of the distance between the two platens (elongation
positive).

In a 3D box the same holds face for face: the spheres that face a platen (none closer to it within
a radius across) get its contact, whose facet is the sphere's cross-section (the Ip2's 3D fallback);
a spring's K is per square metre of the face [N/m / m2], a 2D one's per metre of thickness.
A facing sphere bonded to the specimen by fewer than MIN_HELD_3D contacts is left out: one bonded
contact fixes only its contact point and two an axis, so the sphere can roll about them, and under
a platen load it rolls across the lubricated platen until a contact lines up with the load (a
mechanism of the packing's cut edges, not of concrete; the 12 x 12 x 24 mm prism of
scripts/loaded_expansion.py has three such spheres with one contact and 25 with two among 583 that
face its z platens). Such a sphere shares no collision-mask bit with the platens (YADE's
Body.groupMask: the platens get PLATEN_MASK, every other sphere keeps bit 1 and gains it), so the
platen never touches it later either; the overlap it could reach is the platen's travel.
"""
from dataclasses import dataclass

import numpy as np

from .. import options
from . import scene as sc

#: Name of the platens' contact kind (swelldem.paper.STRUCTURE_KIND_IDS).
PLATEN = "PLATEN"
#: Contact modulus of platen contacts [Pa]: steel.
PLATEN_YOUNG = 200e9
#: ks / kn of platen contacts [-]: lubricated platens (nearly frictionless, but not a mechanism).
PLATEN_SHEAR_RATIO = 1e-6
#: In 3D, the fewest bonded specimen contacts of a sphere the platen holds (see the module's doc).
MIN_HELD_3D = 3
#: Collision-mask bit of the platens in 3D; the spheres a platen leaves out lack it.
PLATEN_MASK = 2
BOUNDARY_TYPES = ("free", "fixed", "stress", "spring")
AXES = ("x", "y", "z")


@dataclass(frozen=True)
class Boundary:
    """The condition of one axis: type 'free', 'fixed', 'stress' (value: applied stress [Pa],
    compression negative) or 'spring' (value: stiffness [N/m per metre of thickness in 2D, per
    square metre of the face in 3D])."""
    type: str = "free"
    value: float = 0.0

    @classmethod
    def parse(cls, name, text):
        """'free', 'fixed', 'stress:S' or 'spring:K' -> Boundary; ValueError in the options'
        message form naming `name` otherwise."""
        allowed = ("free, fixed, stress:S (S in Pa, finite, compression negative) or spring:K (K in N/m per metre of thickness, "
                   "per square metre of the face in 3D, 0 < K < inf)")
        if not isinstance(text, str):
            options.bad(name, text, allowed)
        head, colon, tail = text.strip().partition(":")
        if head in ("free", "fixed") and not colon:
            return cls(head)
        if head not in ("stress", "spring") or not colon:
            options.bad(name, text, allowed)
        try:
            value = float(tail)
        except ValueError:
            options.bad(name, text, allowed)
        if not np.isfinite(value) or (head == "spring" and value <= 0):
            options.bad(name, text, allowed)
        return cls(head, value)

    def __str__(self):
        return self.type if self.type in ("free", "fixed") else f"{self.type}:{self.value:g}"


class Platens:
    """The platens of a scene (see the module's doc): body ids per axis, and their readings."""

    def __init__(self, boundaries, walls, area, left_out=()):
        self.boundaries, self.walls, self.area = boundaries, walls, area
        #: body ids of the facing spheres the platens leave out (3D, fewer than MIN_HELD_3D bonded contacts)
        self.left_out = sorted(left_out)
        self.start = {a: self._distance(a) for a in walls}

    def _distance(self, axis):
        """The platens' distance along axis 'x', 'y' or 'z' now [m]."""
        yade, _ = sc.require("swelldem.dem.platens")
        O = yade.Omega()
        k = AXES.index(axis)
        lo, hi = self.walls[axis]
        return float(O.bodies[hi].state.pos[k] - O.bodies[lo].state.pos[k])

    def force_on(self, body_id, axis):
        """Sum of the contact forces on one body along axis k (0 x, 1 y, 2 z) [N]."""
        yade, _ = sc.require("swelldem.dem.platens")
        O = yade.Omega()
        total = 0.0
        for I in O.interactions.withBody(body_id):
            if not I.isReal:
                continue
            f = -(I.phys.normalForce + I.phys.shearForce)  # the law's force on body id1
            total += float(f[axis]) if I.id1 == body_id else -float(f[axis])
        return total

    def stress(self, axis):
        """Platen stress along axis 'x', 'y' or 'z' [Pa], compression negative; 0 without platens."""
        if axis not in self.walls:
            return 0.0
        k = AXES.index(axis)
        lo, hi = self.walls[axis]
        return 0.5 * (self.force_on(lo, k) - self.force_on(hi, k)) / self.area[axis]

    def displacement(self, axis):
        """Change of the platens' distance along axis 'x', 'y' or 'z' [m] (elongation positive); 0 without platens."""
        return self._distance(axis) - self.start[axis] if axis in self.walls else 0.0


def facing_discs(depth, across, r, band):
    """Indices of the discs (spheres) that face a platen: within `band` [m] of the outermost edge
    along the platen's normal, and not hidden from it by another (none closer to the platen covers
    the line from the centre to it). depth: centres along the outward normal [m]; across: centres
    along the platen [m], (n,) for discs or (n, 2) for spheres; r: radii [m]."""
    edge = depth + r
    across = np.asarray(across, dtype=float)
    cand = np.flatnonzero(edge > edge.max() - band)
    out = []
    for i in cand:
        off = np.abs(across - across[i]) if across.ndim == 1 else np.linalg.norm(across - across[i], axis=1)
        hiding = (depth > depth[i]) & (off < r)
        hiding[i] = False
        if not hiding.any():
            out.append(int(i))
    return np.array(out, dtype=np.int64)


def add_platens(assembly, yscene, boundary_x=Boundary(), boundary_y=Boundary(), boundary_z=Boundary(), young=PLATEN_YOUNG,
                shear_ratio=PLATEN_SHEAR_RATIO, band=None):
    """Adds the platens of the non-free axes to the scene made by swelldem.dem.to_yade (before
    the run starts); returns a :class:`Platens`, or None when every axis is free.
    boundary_z: a 3D box's z sides (free for a 2D section).
    band [m]: the discs (spheres) facing a platen within this depth of the outermost edge get a
    contact with it (default 1.5 Rmax; facing_discs)."""
    dim = getattr(assembly, "dim", 2)
    boundaries = {"x": boundary_x, "y": boundary_y, "z": boundary_z}
    for a, b in boundaries.items():
        if not isinstance(b, Boundary) or b.type not in BOUNDARY_TYPES:
            options.bad(f"boundary_{a}", b, "a swelldem.dem.platens.Boundary")
    if dim == 2 and boundary_z.type != "free":
        options.bad("boundary_z", str(boundary_z), "free for a 2D section (no z sides)")
    if all(b.type == "free" for b in boundaries.values()):
        return None
    yade, W = sc.require("swelldem.dem.platens")
    O = yade.Omega()
    from .scene import contact_kind
    kind = contact_kind(PLATEN, behaviour="elastic", young=young, shear_ratio=shear_ratio, damage=False)
    ip2, solver = yscene.ip2, yscene.solver
    ip2.platen = kind
    # the platens' geometry and bounds: Wall-disc contacts next to the disc-disc ones
    for e in O.engines:
        if getattr(e, "label", "") == "iloop":
            e.geomDispatcher.functors = list(e.geomDispatcher.functors) + [W.Ig2_Wall_Sphere_ScGeom()]
        elif getattr(e, "label", "") == "collider":
            e.boundDispatcher.functors = list(e.boundDispatcher.functors) + [W.Bo1_Wall_Aabb()]
    band = 1.5 * float(assembly.r.max()) if band is None else band
    centre = {"x": assembly.x, "y": assembly.y}
    if dim == 3:
        centre["z"] = assembly.z
        size = {"x": assembly.width_m, "y": assembly.height_m, "z": assembly.depth_m}
        # the face's area: the product of the box's two other sides
        face = {a: float(np.prod([size[o] for o in AXES if o != a])) for a in AXES}
        per = face  # a spring's K is per square metre of the face
    else:
        thickness = float(assembly.thickness_m)
        face = {"x": assembly.height_m * thickness, "y": assembly.width_m * thickness}
        per = {"x": thickness, "y": thickness}  # a spring's K is per metre of thickness
    axes = AXES[:dim]
    walls, area, forces = {}, {}, []
    specimen = {int(i) for i in yscene.ids}
    left_out = set()
    if dim == 3:
        for i in specimen:
            O.bodies[i].groupMask = O.bodies[i].groupMask | PLATEN_MASK
    ip2.cohesive = True
    try:
        for k, a in enumerate(axes):
            b = boundaries[a]
            if b.type == "free":
                continue
            c = centre[a]
            lo_edge, hi_edge = float(np.min(c - assembly.r)), float(np.max(c + assembly.r))
            ids = []
            for pos, sense, moves in ((lo_edge, 1, False), (hi_edge, -1, b.type != "fixed")):
                mat = W.ConcreteMat(platen=True, label=f"platen_{a}_{'high' if moves or sense < 0 else 'low'}")
                O.materials.append(mat)
                where = [0.0, 0.0, 0.0]
                where[k] = pos
                body = yade.utils.wall(tuple(where), axis=k, sense=sense, material=mat)
                if dim == 3:
                    body.groupMask = PLATEN_MASK
                body.state.blockedDOFs = "".join(d for d in "xyz" if d != a) + "XYZ" if moves else "xyzXYZ"
                wid = O.bodies.append(body)
                ids.append(wid)
                others = [centre[o] for o in axes if o != a]
                near = facing_discs(c if sense < 0 else -c, others[0] if dim == 2 else np.c_[others[0], others[1]], assembly.r, band)
                for i in near:
                    if dim == 3:
                        bid = int(yscene.ids[i])
                        held = sum(1 for J in O.interactions.withBody(bid) if J.isReal and {J.id1, J.id2} <= specimen)
                        if held < MIN_HELD_3D:
                            left_out.add(bid)
                            continue
                    I = yade.utils.createInteraction(wid, int(yscene.ids[i]))
                    if I is None or not I.isReal:
                        raise RuntimeError(f"swelldem: the platen contact of disc {int(i)} did not become a real interaction")
            walls[a] = tuple(ids)
            area[a] = face[a]
            hi = ids[1]
            if b.type == "stress":
                f = [0.0, 0.0, 0.0]
                f[k] = b.value * area[a]  # compression (value < 0) pushes the high platen towards the specimen
                forces.append(W.ForceEngine(ids=[hi], force=tuple(f), label=f"platen_{a}_load"))
            elif b.type == "spring":
                solver.springBodies = list(solver.springBodies) + [hi]
                solver.springAxes = list(solver.springAxes) + [k]
                solver.springStiffness = list(solver.springStiffness) + [b.value * per[a]]
        for i in left_out:
            O.bodies[i].groupMask = O.bodies[i].groupMask & ~PLATEN_MASK
    finally:
        ip2.cohesive = False
    if forces:  # before the solver, the last engine
        O.engines = O.engines[:-1] + forces + [O.engines[-1]]
    if left_out:
        print(f"swelldem: set-up: {len(left_out)} spheres facing a platen are bonded to the specimen by fewer than {MIN_HELD_3D} "
              "contacts and left out of the platens' contacts (they could roll under the load)", flush=True)
    return Platens(boundaries, walls, area, left_out)
