# SPDX-License-Identifier: GPL-2.0-or-later
"""The generated mesostructure: discs, labels, contacts and Laguerre facets, in SI units.

Everything stored in an :class:`Assembly` is in SI metres (areas in m^2); the
generation parameters keep the units of their names (mostly mm).
"""
import json
from dataclasses import dataclass, field
from typing import Dict, List

import numpy as np

# Contact kinds (mortar-mortar; aggregate-mortar or two different aggregates; same aggregate).
from ..paper import AGG, ITZ, KIND_NAMES, MORTAR  # noqa: F401  (re-exported by swelldem.meso)

#: Particle materials.
MORTAR_MATERIAL = 0
AGGREGATE_MATERIAL = 1
MATERIAL_NAMES = ("MORTAR", "AGGREGATE")


FORMAT = "swelldem.meso.assembly"
FORMAT_VERSION = 1

_ARRAYS = ("x", "y", "r", "material", "aggregate_id", "cell_area_m2",
           "contacts", "kind", "facet_length_m", "facet_area_m2", "distance_m", "gap_m",
           "facet_segment_m", "aggregate_sieve_size_m", "aggregate_fraction",
           "aggregate_aspect_ratio", "neighbours", "neighbour_facet_length_m")


@dataclass
class Assembly:
    """A 2D concrete mesostructure discretised by discs (all lengths in metres).

    Particles (n of them):
        x, y [m]: centres, in [0, width_m] x [0, height_m] (float64, n);
        r [m]: radii (float64, n);
        material: 0 mortar, 1 aggregate (int8, n);
        aggregate_id: index into ``polygons`` of the aggregate a disc belongs to, -1 for mortar (int32, n);
        cell_area_m2 [m^2]: in-plane area of the disc's Laguerre cell clipped to the specimen (float64, n).
    Contacts (m of them, pairs sharing a Laguerre facet whose gap is within the tolerance):
        contacts: (m, 2) int32 particle indices i < j;
        kind: 0 MORTAR, 1 ITZ, 2 AGG (int8, m);
        facet_length_m [m]: length of the shared Laguerre facet;
        facet_area_m2 [m^2]: facet length x thickness_m (the contact area A_c);
        distance_m [m]: centre distance d; gap_m [m]: d - ri - rj (<= 0 touching);
        facet_segment_m: (m, 4) facet end points x1, y1, x2, y2 [m].
    Laguerre neighbours (every pair sharing a facet of positive length, in contact or not;
    for contacts created later, e.g. by compression):
        neighbours: (p, 2) int32 i < j; neighbour_facet_length_m [m] (p).
    Aggregates (k of them):
        polygons: list of (n_v, 2) CCW vertex arrays [m];
        aggregate_sieve_size_m [m] (smallest width), aggregate_fraction (index of the sieve
        fraction), aggregate_aspect_ratio [-].
    Specimen and provenance:
        width_m, height_m, thickness_m [m]; seed; parameters (dict, units as named,
        see MesoParameters); stats (dict of measured figures, see generate()).
    """

    x: np.ndarray
    y: np.ndarray
    r: np.ndarray
    material: np.ndarray
    aggregate_id: np.ndarray
    cell_area_m2: np.ndarray
    contacts: np.ndarray
    kind: np.ndarray
    facet_length_m: np.ndarray
    facet_area_m2: np.ndarray
    distance_m: np.ndarray
    gap_m: np.ndarray
    facet_segment_m: np.ndarray
    polygons: List[np.ndarray]
    aggregate_sieve_size_m: np.ndarray
    aggregate_fraction: np.ndarray
    aggregate_aspect_ratio: np.ndarray
    neighbours: np.ndarray
    neighbour_facet_length_m: np.ndarray
    width_m: float
    height_m: float
    thickness_m: float
    seed: int
    parameters: Dict = field(default_factory=dict)
    stats: Dict = field(default_factory=dict)

    # ------------------------------------------------------------- properties
    @property
    def n_particles(self):
        return int(len(self.r))

    @property
    def n_contacts(self):
        return int(len(self.kind))

    @property
    def n_aggregates(self):
        return len(self.polygons)

    @property
    def mean_coordination(self):
        """2 x contacts / particles."""
        return 2.0 * self.n_contacts / max(self.n_particles, 1)

    @property
    def packing_density(self):
        """Disc area / specimen area."""
        return float(np.pi * np.sum(self.r ** 2) / (self.width_m * self.height_m))

    def contacts_of_kind(self, kind):
        """Indices of the contacts of a kind (0/1/2 or "MORTAR"/"ITZ"/"AGG")."""
        if isinstance(kind, str):
            kind = KIND_NAMES.index(kind.upper())
        return np.nonzero(self.kind == kind)[0]

    def coordination(self):
        """Number of contacts of every particle (int, n)."""
        return np.bincount(self.contacts.ravel(), minlength=self.n_particles)

    def without(self, particles):
        """A copy without the given particle indices (and their contacts and neighbours), the others
        renumbered in order: room for an inclusion the generator does not place, e.g. a
        reinforcing bar (swelldem.dem.rebar). Aggregate polygons are kept as they are."""
        drop = np.zeros(self.n_particles, dtype=bool)
        drop[np.asarray(particles, dtype=np.int64)] = True
        keep = np.flatnonzero(~drop)
        new_index = np.full(self.n_particles, -1, dtype=np.int64)
        new_index[keep] = np.arange(keep.size)
        per_particle = {k: getattr(self, k)[keep] for k in ("x", "y", "r", "material", "aggregate_id", "cell_area_m2")}
        c_keep = ~(drop[self.contacts[:, 0]] | drop[self.contacts[:, 1]]) if self.n_contacts else np.zeros(0, dtype=bool)
        per_contact = {k: getattr(self, k)[c_keep] for k in ("kind", "facet_length_m", "facet_area_m2", "distance_m", "gap_m",
                                                            "facet_segment_m")}
        contacts = new_index[self.contacts[c_keep]].astype(self.contacts.dtype)
        n_keep = ~(drop[self.neighbours[:, 0]] | drop[self.neighbours[:, 1]]) if len(self.neighbours) else np.zeros(0, dtype=bool)
        neighbours = new_index[self.neighbours[n_keep]].astype(self.neighbours.dtype)
        return Assembly(contacts=contacts, neighbours=neighbours, neighbour_facet_length_m=self.neighbour_facet_length_m[n_keep],
                        polygons=list(self.polygons), aggregate_sieve_size_m=self.aggregate_sieve_size_m,
                        aggregate_fraction=self.aggregate_fraction, aggregate_aspect_ratio=self.aggregate_aspect_ratio,
                        width_m=self.width_m, height_m=self.height_m, thickness_m=self.thickness_m, seed=self.seed,
                        parameters=dict(self.parameters), stats=dict(self.stats, removed_particles=int(drop.sum())),
                        **per_particle, **per_contact)

    # ---------------------------------------------------------------- summary
    def summary(self):
        """Plain-JSON dictionary of the measured figures (see docs/mesostructure.md)."""
        by_kind = {}
        facet = {}
        for k, name in enumerate(KIND_NAMES):
            sel = self.kind == k
            by_kind[name] = int(sel.sum())
            a = self.facet_area_m2[sel]
            facet[name] = ({"min": float(a.min()), "mean": float(a.mean()), "max": float(a.max())}
                           if a.size else {"min": None, "mean": None, "max": None})
        s = {
            "n_particles": self.n_particles,
            "n_aggregate_particles": int((self.material == AGGREGATE_MATERIAL).sum()),
            "n_mortar_particles": int((self.material == MORTAR_MATERIAL).sum()),
            "n_aggregates": self.n_aggregates,
            "n_contacts": self.n_contacts,
            "width_m": self.width_m,
            "height_m": self.height_m,
            "thickness_m": self.thickness_m,
            "seed": int(self.seed),
            "mean_radius_m": float(self.r.mean()) if self.n_particles else None,
            "packing_density": self.packing_density,
            "mean_coordination": self.mean_coordination,
            "contacts_by_kind": by_kind,
            "facet_area_m2": facet,
        }
        for k in ("aggregate_area_fraction", "aggregate_area_fraction_target",
                  "aggregate_area_fraction_cells", "aggregate_area_by_fraction",
                  "aggregates_by_fraction", "empty_aggregates", "max_overlap_m", "max_outside_m",
                  "cell_area_sum_rel_error", "facet_asymmetry_max_m", "contact_gap_tolerance_m",
                  "laguerre_pairs", "laguerre_pairs_not_in_contact", "timings_s", "wall_s",
                  "packing_stats"):
            if k in self.stats:
                s[k] = self.stats[k]
        return s

    # -------------------------------------------------------------- save/load
    def save(self, path):
        """Write the assembly to one compressed ``.npz`` file (arrays + JSON metadata); returns the path."""
        path = str(path)
        if not path.endswith(".npz"):
            path += ".npz"
        arrays = {k: np.asarray(getattr(self, k)) for k in _ARRAYS}
        nv = np.array([len(p) for p in self.polygons], dtype=np.int64)
        arrays["polygon_offsets"] = np.concatenate([[0], np.cumsum(nv)]).astype(np.int64)
        arrays["polygon_vertices"] = (np.concatenate(self.polygons, axis=0) if self.polygons
                                      else np.zeros((0, 2)))
        meta = {"format": FORMAT, "format_version": FORMAT_VERSION,
                "width_m": self.width_m, "height_m": self.height_m, "thickness_m": self.thickness_m,
                "seed": int(self.seed), "parameters": self.parameters, "stats": self.stats,
                "units": "SI (m, m^2); parameters as named (mm)",
                "kind_names": list(KIND_NAMES), "material_names": list(MATERIAL_NAMES)}
        arrays["meta_json"] = np.array(json.dumps(meta))
        with open(path, "wb") as f:
            np.savez_compressed(f, **arrays)
        return path

    @classmethod
    def load(cls, path):
        """Read an assembly written by :meth:`save`."""
        with np.load(str(path), allow_pickle=False) as z:
            meta = json.loads(str(z["meta_json"]))
            if meta.get("format") != FORMAT:
                raise ValueError(f"{path}: not a swelldem mesostructure assembly file")
            if int(meta.get("format_version", 0)) > FORMAT_VERSION:
                raise ValueError(f"{path}: format version {meta.get('format_version')} is newer than "
                                 f"this swelldem supports ({FORMAT_VERSION})")
            arrays = {k: z[k].copy() for k in _ARRAYS}
            off = z["polygon_offsets"]
            verts = z["polygon_vertices"]
            polygons = [verts[off[k]:off[k + 1]].copy() for k in range(len(off) - 1)]
        return cls(polygons=polygons, width_m=float(meta["width_m"]), height_m=float(meta["height_m"]),
                   thickness_m=float(meta["thickness_m"]), seed=int(meta["seed"]),
                   parameters=meta["parameters"], stats=meta["stats"], **arrays)

    def equals(self, other):
        """True when both assemblies have identical arrays, polygons and parameters (stats ignored)."""
        if not isinstance(other, Assembly):
            return False
        for k in _ARRAYS:
            a, b = getattr(self, k), getattr(other, k)
            if a.shape != b.shape or a.dtype != b.dtype or not np.array_equal(a, b):
                return False
        if len(self.polygons) != len(other.polygons):
            return False
        if not all(np.array_equal(p, q) for p, q in zip(self.polygons, other.polygons)):
            return False
        return (self.width_m, self.height_m, self.thickness_m, self.seed, self.parameters) == \
            (other.width_m, other.height_m, other.thickness_m, other.seed, other.parameters)


def load(path):
    """Read an assembly file written by :meth:`Assembly.save`."""
    return Assembly.load(path)
