# SPDX-License-Identifier: GPL-2.0-or-later
"""An :class:`~swelldem.meso.Assembly` as a YADE scene of the swelldem plugin.

Use inside YADE with the plugin loaded (``scripts/yade-swelldem``)::

    from swelldem import meso, dem
    a = meso.generate(seed=1, width_mm=30, height_mm=30)
    kinds = {"MORTAR": dem.contact_kind("MORTAR", ...), "ITZ": ..., "AGG": ...}
    solver = dem.make_solver("adr", tStart=0.01, tEnd=3650, stepsPerDecade=10)
    ys = dem.to_yade(a, kinds, solver)          # O is reset (O.tags kept) and filled
    dem.set_gel_pockets(ys, a, fraction=0.1, d_inf_m=0.794e-6, seed=3)   # ASR-coarse, optional
    dem.run_to_end(solver)
"""
import time
from dataclasses import dataclass, field
from typing import Dict, List

import numpy as np

from ..meso.assembly import AGGREGATE_MATERIAL, KIND_NAMES, MORTAR_MATERIAL
from ..meso import gel_pockets
from ..paper import KIND_IDS
from . import scene as sc

__all__ = ["YadeScene", "to_yade", "set_contact_swelling", "set_gel_pockets", "MAX_GAP_RATIO"]

#: Largest initial gap of an assembly contact accepted by :func:`to_yade`, as a fraction of the
#: largest radius. The generator's contacts have gaps up to contact_gap_ratio (0.05) x Rmax.
MAX_GAP_RATIO = 0.25


def _yade():
    return sc.require("swelldem.dem.to_yade")


@dataclass
class YadeScene:
    """What :func:`to_yade` made (the YADE objects live in ``yade.Omega()``).

    ids: body id of every assembly particle (equal to the particle index);
    mortar_material: the ConcreteMat of mortar discs (aggregateId -1);
    aggregate_materials: one ConcreteMat per aggregate polygon (aggregateId = polygon index);
    kinds: the ContactKind given for each of MORTAR, ITZ, AGG (None if absent);
    ip2: the Ip2 functor (cohesive is False after the set-up); solver: the given solver;
    contacts: (m, 2) body ids of the created interactions (the assembly's contacts, same order);
    counts: figures of the set-up (particles, contacts, per kind, materials, fixed, wall_s, ...).
    """
    ids: np.ndarray
    mortar_material: object
    aggregate_materials: List[object]
    kinds: Dict[str, object]
    ip2: object
    solver: object
    contacts: np.ndarray
    counts: Dict[str, object] = field(default_factory=dict)

    def interaction(self, c):
        """The YADE interaction of assembly contact c."""
        yade, _ = _yade()
        i, j = self.contacts[c]
        return yade.Omega().interactions[int(i), int(j)]

    def positions(self):
        """Current centre positions of the particles [m]: (n, 2) of a 2D scene, (n, 3) of a 3D one."""
        yade, _ = _yade()
        O = yade.Omega()
        if self.counts.get("dim", 2) == 3:
            return np.array([list(O.bodies[int(i)].state.pos) for i in self.ids])
        return np.array([[O.bodies[int(i)].state.pos[0], O.bodies[int(i)].state.pos[1]] for i in self.ids])


def _check_kinds(assembly, kinds):
    if not isinstance(kinds, dict):
        raise TypeError("swelldem.dem.to_yade: kinds must be a dict {'MORTAR': ContactKind, 'ITZ': ..., 'AGG': ...}")
    unknown = set(kinds) - set(KIND_NAMES)
    if unknown:
        raise ValueError(f"swelldem.dem.to_yade: unknown kind names {sorted(unknown)}; allowed: {', '.join(KIND_NAMES)}")
    has_mortar = bool(np.any(assembly.material == MORTAR_MATERIAL))
    has_agg = bool(np.any(assembly.material == AGGREGATE_MATERIAL))
    needed = {"MORTAR": has_mortar, "ITZ": has_agg, "AGG": has_agg}
    for k in range(len(KIND_NAMES)):  # any kind with contacts is needed as well
        if np.any(assembly.kind == k):
            needed[KIND_NAMES[k]] = True
    for name, need in needed.items():
        kind = kinds.get(name)
        if kind is None:
            if need:
                raise ValueError(f"swelldem.dem.to_yade: kinds['{name}'] is missing; the assembly "
                                 f"can have {name} contacts (give a ContactKind, e.g. swelldem.dem.contact_kind('{name}', ...))")
            continue
        if kind.kindId != KIND_IDS[name]:
            raise ValueError(f"swelldem.dem.to_yade: kinds['{name}'].kindId = {kind.kindId}; allowed: {KIND_IDS[name]} "
                             f"(0 MORTAR, 1 ITZ, 2 AGG: the id is compared with the assembly's kind of each contact)")


def to_yade(assembly, kinds, solver, reset=True, density=2400.0, young=30e9, poisson=0.2,
            detection_factor=1.0, fixed=None, check_geometry=True):
    """Fill ``yade.Omega()`` with the assembly (discs of a 2D section, or spheres free in every
    direction for a 3D assembly) and return a :class:`YadeScene`.

    Args:
        assembly: a :class:`swelldem.meso.Assembly` (SI metres).
        kinds: dict of ContactKind for 'MORTAR', 'ITZ', 'AGG' (kindId 0, 1, 2); a kind may be
            left out only if the assembly cannot make such a contact (no aggregate: ITZ and AGG).
        solver: the last engine: a quasi-static solver (swelldem.dem.make_solver) or a YADE integrator.
        reset: O.reset() first, keeping O.tags (default); otherwise O must have no bodies yet.
        density [kg/m3], young [Pa], poisson [-]: of the ConcreteMat instances. The contact law
            takes its stiffness from the kinds; these matter only to YADE's own tools.
        detection_factor [-]: interactionDetectionFactor of the sphere geometry functor and
            aabbEnlargeFactor during the run. Contacts made later by the collider (cohesionless,
            stress-free when the discs touch) appear when discs come closer than
            detection_factor x (r1 + r2). The assembly's contacts, created explicitly, stay real
            whatever their gap.
        fixed: optional indices of particles to hold (all translations and rotations blocked).
        check_geometry: compare every interaction's centre distance with the assembly's.
    Raises:
        YadeUnavailableError outside YADE or without the plugin; ValueError for missing or
        mislabelled kinds, non-empty O (reset=False), gaps beyond MAX_GAP_RATIO x Rmax, or an
        interaction whose kind (as assigned by the Ip2 from the materials) differs from the
        assembly's kind.
    """
    t0 = time.time()
    dim = getattr(assembly, "dim", 2)
    yade, W = _yade()
    _check_kinds(assembly, kinds)
    n, m = assembly.n_particles, assembly.n_contacts
    if n == 0:
        raise ValueError("swelldem.dem.to_yade: the assembly has no particles")
    rmax = float(assembly.r.max())
    if m and float(assembly.gap_m.max()) > MAX_GAP_RATIO * rmax:
        c = int(np.argmax(assembly.gap_m))
        raise ValueError(f"swelldem.dem.to_yade: contact {c} {tuple(assembly.contacts[c])} has a gap of "
                         f"{assembly.gap_m[c]:.3g} m; allowed: <= {MAX_GAP_RATIO} x Rmax = {MAX_GAP_RATIO * rmax:.3g} m")
    # Materials: mortar, then one per aggregate polygon (the Ip2 tells AGG from ITZ by aggregateId).
    mortar = W.ConcreteMat(young=young, poisson=poisson, density=density, aggregateId=-1, label="mortar")
    aggs = [W.ConcreteMat(young=young, poisson=poisson, density=density, aggregateId=k, label=f"aggregate{k}")
            for k in range(assembly.n_aggregates)]
    fixed = () if fixed is None else fixed
    # In 3D the Ip2's thickness is unused: a contact's area is the assembly's facet area, or the smaller
    # sphere's cross-section for one made during the run (and a platen's).
    ip2 = sc.concrete_ip2(kinds, thickness=float(assembly.thickness_m) if dim == 2 else 1.0, cohesive=True)
    # The assembly's contacts: bonded, stress-free at their initial distance, facet area from Laguerre.
    contacts = np.asarray(assembly.contacts, dtype=np.int64).reshape(-1, 2)
    try:
        ids, inters = sc.build_scene(assembly.x, assembly.y, assembly.r, [mortar] + aggs, ip2, W.Law2_ScGeom_SwellPhys_AgingSwelling(),
                                     solver, material_of=np.asarray(assembly.aggregate_id) + 1, contacts=contacts, fixed=fixed,
                                     detection_factor=detection_factor, reset=reset,
                                     z=assembly.z if dim == 3 else None)
    finally:
        ip2.cohesive = False  # contacts made from now on are cohesionless
    per_kind = {name: 0 for name in KIND_NAMES}
    worst_dist = 0.0
    for c, I in enumerate(inters):
        p = I.phys
        want = int(assembly.kind[c])
        if p.kindId != want:
            i, j = int(contacts[c, 0]), int(contacts[c, 1])
            raise ValueError(
                f"swelldem.dem.to_yade: contact {c} between particles {i} and {j} is {KIND_NAMES[want]} in the "
                f"assembly (aggregate ids {int(assembly.aggregate_id[i])}, {int(assembly.aggregate_id[j])}) but the "
                f"Ip2 made it {p.kindName!r} (kindId {p.kindId}); check the kinds dict and the materials' aggregateId")
        p.area = float(assembly.facet_area_m2[c])
        if check_geometry:
            worst_dist = max(worst_dist, abs(p.length - float(assembly.distance_m[c])))
        per_kind[KIND_NAMES[want]] += 1
    if check_geometry and worst_dist > 1e-9 * rmax:
        raise RuntimeError(f"swelldem.dem.to_yade: an interaction's stress-free length differs from the assembly's "
                           f"centre distance by {worst_dist:.3g} m (> 1e-9 Rmax)")
    counts = {"n_particles": n, "n_contacts": m, "contacts_by_kind": per_kind, "n_aggregate_materials": len(aggs),
              "n_materials": 1 + len(aggs), "n_fixed": len(set(np.atleast_1d(fixed).tolist())), "max_initial_gap_m": float(assembly.gap_m.max()) if m else 0.0,
              "max_length_mismatch_m": worst_dist, "thickness_m": float(assembly.thickness_m) if dim == 2 else None, "dim": dim,
              "detection_factor": float(detection_factor), "wall_s": time.time() - t0}
    return YadeScene(ids=ids, mortar_material=mortar, aggregate_materials=aggs,
                     kinds={name: kinds.get(name) for name in KIND_NAMES}, ip2=ip2, solver=solver,
                     contacts=contacts, counts=counts)


def set_contact_swelling(yscene, contact_indices, d_inf_m):
    """Per-contact ultimate swelling displacement d_inf [m] (SwellPhys.swellDispInf) of the given
    assembly contacts: one value for all, or one per contact; a value < 0 restores the kind's.
    The contacts' kind must have swelling on (ContactKind.swelling), otherwise a positive
    override would be silently ignored by the law. Returns the number of contacts set."""
    yade, _ = _yade()
    O = yade.Omega()
    idx = np.atleast_1d(np.asarray(contact_indices, dtype=np.int64))
    d = np.broadcast_to(np.asarray(d_inf_m, dtype=float), idx.shape)
    if not np.all(np.isfinite(d)):
        raise ValueError("swelldem.dem.set_contact_swelling: d_inf_m is out of range; allowed: finite values")
    for c, dc in zip(idx, d):
        i, j = yscene.contacts[int(c)]
        p = O.interactions[int(i), int(j)].phys
        if dc > 0 and not p.kind.swelling:
            raise ValueError(f"swelldem.dem.set_contact_swelling: contact {int(c)} is of kind {p.kindName}, whose "
                             "ContactKind.swelling is False; switch it on (with swellDispInf 0 for the others)")
        p.swellDispInf = float(dc)
    return int(idx.size)


def set_gel_pockets(yscene, assembly, fraction, d_inf_m, seed, reading="single", radius_m=1e-3):
    """The paper's ASR with reactive coarse aggregate: the gel pockets of one reading
    (swelldem.meso.gel_pockets.choose: 'single', 'clustered', 'rim', 'with-itz') swell with d_inf_m
    [m]; every other contact of the kinds the pockets are drawn from (AGG, and ITZ for 'with-itz')
    gets d_inf = 0. Those kinds need ContactKind.swelling = True (their swellDispInf is then
    irrelevant for the assembly's contacts; contacts made later use it). Returns the chosen
    contact indices."""
    chosen = gel_pockets.choose(assembly, reading, fraction, seed, radius_m)
    set_contact_swelling(yscene, np.setdiff1d(gel_pockets.pool(assembly, reading), chosen), 0.0)
    set_contact_swelling(yscene, chosen, d_inf_m)
    return chosen
