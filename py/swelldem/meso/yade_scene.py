# SPDX-License-Identifier: GPL-2.0-or-later
"""An :class:`~swelldem.meso.Assembly` as a YADE scene of the swelldem plugin.

Use inside YADE with the plugin loaded (``scripts/yade-swelldem``)::

    from swelldem import meso, scene
    a = meso.generate(seed=1, width_mm=30, height_mm=30)
    kinds = {"MORTAR": scene.contact_kind("MORTAR", ...), "ITZ": ..., "AGG": ...}
    solver = yade.wrapper.AdrLogTimeIntegrator(tStart=0.01, tEnd=3650, stepsPerDecade=10)
    ys = meso.to_yade(a, kinds, solver)          # O is reset and filled
    meso.set_gel_pockets(ys, a, fraction=0.1, d_inf_m=0.794e-6, seed=3)   # ASR-coarse, optional
    scene.run_to_end(solver)

This module imports nothing from YADE at import time, so ``swelldem.meso`` stays usable in plain
Python; the functions raise :class:`YadeUnavailableError` there.
"""
import time
from dataclasses import dataclass, field
from typing import Dict, List

import numpy as np

from .assembly import AGG, AGGREGATE_MATERIAL, KIND_NAMES, MORTAR_MATERIAL

__all__ = ["YadeScene", "YadeUnavailableError", "to_yade", "set_contact_swelling", "set_gel_pockets",
           "choose_contacts", "MAX_GAP_RATIO"]

#: Largest initial gap of an assembly contact accepted by :func:`to_yade`, as a fraction of the
#: largest radius. The generator's contacts have gaps up to contact_gap_ratio (0.05) x Rmax.
MAX_GAP_RATIO = 0.25

PLUGIN_CLASSES = ("ConcreteMat", "ContactKind", "SwellPhys", "Ip2_ConcreteMat_ConcreteMat_SwellPhys",
                  "Law2_ScGeom_SwellPhys_AgingSwelling", "AdrLogTimeIntegrator")


class YadeUnavailableError(RuntimeError):
    """Raised when the YADE scene functions run outside YADE or without the swelldem plugin."""


def _yade():
    """yade module and its wrapper, with a clear error outside YADE or without the plugin."""
    try:
        import yade
        from yade import wrapper
    except ImportError as e:
        raise YadeUnavailableError(
            "swelldem.meso.to_yade needs YADE with the swelldem plugin: run the script with "
            "scripts/yade-swelldem (e.g. scripts/yade-swelldem -n -x script.py), not with plain python "
            f"({e})") from None
    missing = [c for c in PLUGIN_CLASSES if not hasattr(wrapper, c)]
    if missing:
        raise YadeUnavailableError(
            "swelldem.meso.to_yade: YADE runs but the swelldem plugin is not loaded (missing "
            + ", ".join(missing) + "); start YADE through scripts/yade-swelldem, which points YADE_PREFIX "
            "at the build's overlay prefix")
    return yade, wrapper


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
        """Current (n, 2) centre positions of the particles [m]."""
        yade, _ = _yade()
        O = yade.Omega()
        return np.array([[O.bodies[int(i)].state.pos[0], O.bodies[int(i)].state.pos[1]] for i in self.ids])


def _check_kinds(assembly, kinds):
    from ..scene import KIND_IDS
    if not isinstance(kinds, dict):
        raise TypeError("swelldem.meso.to_yade: kinds must be a dict {'MORTAR': ContactKind, 'ITZ': ..., 'AGG': ...}")
    unknown = set(kinds) - set(KIND_NAMES)
    if unknown:
        raise ValueError(f"swelldem.meso.to_yade: unknown kind names {sorted(unknown)}; allowed: {', '.join(KIND_NAMES)}")
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
                raise ValueError(f"swelldem.meso.to_yade: kinds['{name}'] is missing; the assembly "
                                 f"can have {name} contacts (give a ContactKind, e.g. swelldem.scene.contact_kind('{name}', ...))")
            continue
        if kind.kindId != KIND_IDS[name]:
            raise ValueError(f"swelldem.meso.to_yade: kinds['{name}'].kindId = {kind.kindId}; allowed: {KIND_IDS[name]} "
                             f"(0 MORTAR, 1 ITZ, 2 AGG: the id is compared with the assembly's kind of each contact)")


def to_yade(assembly, kinds, solver, reset=True, density=2400.0, young=30e9, poisson=0.2,
            detection_factor=1.0, fixed=None, check_geometry=True):
    """Fill ``yade.Omega()`` with the assembly and return a :class:`YadeScene`.

    Args:
        assembly: a :class:`swelldem.meso.Assembly` (SI metres).
        kinds: dict of ContactKind for 'MORTAR', 'ITZ', 'AGG' (kindId 0, 1, 2); a kind may be
            left out only if the assembly cannot make such a contact (no aggregate: ITZ and AGG).
        solver: the quasi-static engine (an AdrLogTimeIntegrator), put last in O.engines.
        reset: O.reset() first (default); otherwise O must have no bodies yet.
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
    yade, W = _yade()
    from .. import scene as sc
    _check_kinds(assembly, kinds)
    n, m = assembly.n_particles, assembly.n_contacts
    if n == 0:
        raise ValueError("swelldem.meso.to_yade: the assembly has no particles")
    rmax = float(assembly.r.max())
    if m and float(assembly.gap_m.max()) > MAX_GAP_RATIO * rmax:
        c = int(np.argmax(assembly.gap_m))
        raise ValueError(f"swelldem.meso.to_yade: contact {c} {tuple(assembly.contacts[c])} has a gap of "
                         f"{assembly.gap_m[c]:.3g} m; allowed: <= {MAX_GAP_RATIO} x Rmax = {MAX_GAP_RATIO * rmax:.3g} m")
    O = yade.Omega()
    if reset:
        O.reset()
    elif len(O.bodies) > 0:
        raise ValueError(f"swelldem.meso.to_yade: O already holds {len(O.bodies)} bodies; use reset=True "
                         "(particle index = body id is required)")

    # Materials: mortar, then one per aggregate polygon (the Ip2 tells AGG from ITZ by aggregateId).
    mortar = W.ConcreteMat(young=young, poisson=poisson, density=density, aggregateId=-1, label="mortar")
    O.materials.append(mortar)
    aggs = []
    for k in range(assembly.n_aggregates):
        mat = W.ConcreteMat(young=young, poisson=poisson, density=density, aggregateId=k, label=f"aggregate{k}")
        O.materials.append(mat)
        aggs.append(mat)
    fixed_set = set() if fixed is None else {int(i) for i in np.atleast_1d(fixed)}
    bad = [i for i in fixed_set if not 0 <= i < n]
    if bad:
        raise ValueError(f"swelldem.meso.to_yade: fixed particle indices {bad[:5]} are out of range; allowed: 0..{n - 1}")
    bodies = []
    for i in range(n):
        a = int(assembly.aggregate_id[i])
        mat = mortar if a < 0 else aggs[a]
        bodies.append(sc.disc((float(assembly.x[i]), float(assembly.y[i])), float(assembly.r[i]), mat, fixed=i in fixed_set))
    ids = np.asarray(O.bodies.append(bodies), dtype=np.int64)
    if not np.array_equal(ids, np.arange(n)):
        raise RuntimeError("swelldem.meso.to_yade: YADE gave body ids different from the particle indices")

    ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kinds.get("MORTAR"), itz=kinds.get("ITZ"), agg=kinds.get("AGG"),
                                                  thickness=float(assembly.thickness_m), cohesive=True)
    O.engines = sc.engines(ip2, solver, detection_factor=detection_factor)

    # The assembly's contacts: bonded, stress-free at their initial distance, facet area from Laguerre.
    # utils.createInteraction asks the geometry functor with force=True, so a contact with a gap is
    # created whatever interactionDetectionFactor is; once real, Ig2_Sphere_Sphere_ScGeom keeps it.
    create = yade.utils.createInteraction
    contacts = np.asarray(assembly.contacts, dtype=np.int64).reshape(-1, 2)
    per_kind = {name: 0 for name in KIND_NAMES}
    worst_dist = 0.0
    try:
        for c in range(m):
            i, j = int(contacts[c, 0]), int(contacts[c, 1])
            I = create(i, j)
            if I is None or not I.isReal:
                raise RuntimeError(f"swelldem.meso.to_yade: contact {c} ({i}, {j}) did not become a real interaction")
            p = I.phys
            want = int(assembly.kind[c])
            if p.kindId != want:
                raise ValueError(
                    f"swelldem.meso.to_yade: contact {c} between particles {i} and {j} is {KIND_NAMES[want]} in the "
                    f"assembly (aggregate ids {int(assembly.aggregate_id[i])}, {int(assembly.aggregate_id[j])}) but the "
                    f"Ip2 made it {p.kindName!r} (kindId {p.kindId}); check the kinds dict and the materials' aggregateId")
            p.area = float(assembly.facet_area_m2[c])
            if check_geometry:
                worst_dist = max(worst_dist, abs(p.length - float(assembly.distance_m[c])))
            per_kind[KIND_NAMES[want]] += 1
    finally:
        ip2.cohesive = False  # contacts made from now on are cohesionless
    if check_geometry and worst_dist > 1e-9 * rmax:
        raise RuntimeError(f"swelldem.meso.to_yade: an interaction's stress-free length differs from the assembly's "
                           f"centre distance by {worst_dist:.3g} m (> 1e-9 Rmax)")
    counts = {"n_particles": n, "n_contacts": m, "contacts_by_kind": per_kind, "n_aggregate_materials": len(aggs),
              "n_materials": 1 + len(aggs), "n_fixed": len(fixed_set), "max_initial_gap_m": float(assembly.gap_m.max()) if m else 0.0,
              "max_length_mismatch_m": worst_dist, "thickness_m": float(assembly.thickness_m),
              "detection_factor": float(detection_factor), "wall_s": time.time() - t0}
    return YadeScene(ids=ids, mortar_material=mortar, aggregate_materials=aggs,
                     kinds={name: kinds.get(name) for name in KIND_NAMES}, ip2=ip2, solver=solver,
                     contacts=contacts, counts=counts)


def choose_contacts(assembly, kind, fraction, seed):
    """A seeded random choice of round(fraction x count) contacts of one kind (indices, sorted).

    kind: 0/1/2 or 'MORTAR'/'ITZ'/'AGG'; fraction in [0, 1]; seed: int (numpy SeedSequence).
    """
    if not 0.0 <= float(fraction) <= 1.0:
        raise ValueError(f"swelldem.meso.choose_contacts: fraction = {fraction} is out of range; allowed: [0, 1]")
    idx = assembly.contacts_of_kind(kind)
    k = int(round(float(fraction) * len(idx)))
    rng = np.random.default_rng(np.random.SeedSequence(int(seed)))
    return np.sort(rng.choice(idx, size=k, replace=False)) if k else np.zeros(0, dtype=np.int64)


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
        raise ValueError("swelldem.meso.set_contact_swelling: d_inf_m is out of range; allowed: finite values")
    for c, dc in zip(idx, d):
        i, j = yscene.contacts[int(c)]
        p = O.interactions[int(i), int(j)].phys
        if dc > 0 and not p.kind.swelling:
            raise ValueError(f"swelldem.meso.set_contact_swelling: contact {int(c)} is of kind {p.kindName}, whose "
                             "ContactKind.swelling is False; switch it on (with swellDispInf 0 for the others)")
        p.swellDispInf = float(dc)
    return int(idx.size)


def set_gel_pockets(yscene, assembly, fraction, d_inf_m, seed, kind=AGG):
    """The paper's ASR with reactive coarse aggregate: a seeded random `fraction` of the contacts of
    `kind` (default AGG) swell with d_inf_m [m], all other contacts of that kind get d_inf = 0.
    The kind needs ContactKind.swelling = True (its swellDispInf is then irrelevant for the
    assembly's contacts; contacts made later use it). Returns the chosen contact indices."""
    chosen = choose_contacts(assembly, kind, fraction, seed)
    all_of_kind = assembly.contacts_of_kind(kind)
    set_contact_swelling(yscene, np.setdiff1d(all_of_kind, chosen), 0.0)
    set_contact_swelling(yscene, chosen, d_inf_m)
    return chosen
