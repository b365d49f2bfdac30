# SPDX-License-Identifier: GPL-2.0-or-later
"""The generated mesostructure: particles, labels, contacts and Laguerre facets, in SI units.

One form for both dimensions (``dim`` 2 or 3): a 2D section of discs (the paper's model) or a 3D
box of spheres. Everything stored in an :class:`Assembly` is in SI metres (areas in m^2, volumes
in m^3); the generation parameters keep the units of their names (mostly mm).
"""
import json
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

# Contact kinds (mortar-mortar; aggregate-mortar or two different aggregates; same aggregate).
from ..paper import AGG, ITZ, KIND_NAMES, MORTAR  # noqa: F401  (re-exported by swelldem.meso)

#: Particle materials.
MORTAR_MATERIAL = 0
AGGREGATE_MATERIAL = 1
MATERIAL_NAMES = ("MORTAR", "AGGREGATE")


FORMAT = "swelldem.meso.assembly"
#: Version 2 added 3D assemblies; a 2D assembly is still written as version 1, which every reader reads.
FORMAT_VERSION = 2

# The arrays of each dimension, by what they are indexed with (particles, contacts, neighbours).
_PER_PARTICLE = {2: ("x", "y", "r", "material", "aggregate_id", "cell_area_m2"),
                 3: ("x", "y", "z", "r", "material", "aggregate_id", "cell_volume_m3")}
_PER_CONTACT = {2: ("kind", "facet_length_m", "facet_area_m2", "distance_m", "gap_m", "facet_segment_m"),
                3: ("kind", "facet_area_m2", "distance_m", "gap_m", "facet_normal", "facet_centroid_m")}
_PER_NEIGHBOUR = {2: ("neighbour_facet_length_m",), 3: ("neighbour_facet_area_m2",)}
_PER_AGGREGATE = ("aggregate_sieve_size_m", "aggregate_fraction", "aggregate_aspect_ratio")
_ARRAYS = {d: _PER_PARTICLE[d] + ("contacts",) + _PER_CONTACT[d] + _PER_AGGREGATE + ("neighbours",) + _PER_NEIGHBOUR[d]
           for d in (2, 3)}
# the attributes that belong to one dimension only: None in an assembly of the other
_ONLY = {d: sorted(set(_ARRAYS[d]) - set(_ARRAYS[5 - d])) for d in (2, 3)}


def _ragged_pack(pieces, width):
    """(offsets, stacked rows) of a list of (k, width) arrays."""
    nv = np.array([len(p) for p in pieces], dtype=np.int64)
    off = np.concatenate([[0], np.cumsum(nv)]).astype(np.int64)
    rows = np.concatenate(pieces, axis=0) if pieces else np.zeros((0, width))
    return off, rows


def _ragged_unpack(off, rows):
    return [rows[off[k]:off[k + 1]].copy() for k in range(len(off) - 1)]


@dataclass
class Assembly:
    """A concrete mesostructure: a 2D section of discs (``dim`` 2) or a 3D box of spheres (``dim`` 3),
    all lengths in metres.

    Particles (n of them):
        x, y [m] (and z in 3D): centres, in [0, width_m] x [0, height_m] (x [0, depth_m]) (float64, n);
        r [m]: radii (float64, n);
        material: 0 mortar, 1 aggregate (int8, n);
        aggregate_id: index of the aggregate (``polygons`` in 2D, ``polyhedra`` in 3D) a particle
            belongs to, -1 for mortar (int32, n);
        cell_area_m2 [m^2] (2D): in-plane area of the disc's Laguerre cell clipped to the specimen;
        cell_volume_m3 [m^3] (3D): volume of the sphere's Laguerre cell clipped to the specimen.
    Contacts (m of them, pairs sharing a Laguerre facet whose gap is within the tolerance):
        contacts: (m, 2) int32 particle indices i < j;
        kind: 0 MORTAR, 1 ITZ, 2 AGG (int8, m);
        facet_area_m2 [m^2]: the contact area A_c: in 2D the facet length x thickness_m, in 3D the
            area of the facet (a convex polygon shared by the two Laguerre cells);
        distance_m [m]: centre distance d; gap_m [m]: d - ri - rj (<= 0 touching);
        2D: facet_length_m [m], facet_segment_m: (m, 4) facet end points x1, y1, x2, y2 [m];
        3D: facet_normal: (m, 3) unit normal from i to j [-]; facet_centroid_m: (m, 3) [m];
            facet_polygons: list of (k, 3) vertex arrays [m] (loop order), one a contact.
    Laguerre neighbours (every pair sharing a facet of positive size, in contact or not; for
    contacts created later, e.g. by compression):
        neighbours: (p, 2) int32 i < j; neighbour_facet_length_m [m] (2D) or
        neighbour_facet_area_m2 [m^2] (3D) (p).
    Aggregates (k of them):
        polygons (2D): list of (n_v, 2) CCW vertex arrays [m];
        polyhedra (3D): list of (n_v, 3) vertex arrays [m], each the vertices of a convex hull;
        aggregate_sieve_size_m [m] (smallest width), aggregate_fraction (index of the sieve
        fraction), aggregate_aspect_ratio [-].
    Specimen and provenance:
        width_m, height_m [m]; thickness_m [m] (2D: out-of-plane thickness; 3D: unused);
        depth_m [m] (3D: third side; 2D: 0); seed; parameters (dict, units as named, see
        MesoParameters); stats (dict of measured figures, see generate()).
    The attributes of the other dimension are None (``polygons``/``polyhedra`` empty lists).
    """

    x: np.ndarray
    y: np.ndarray
    r: np.ndarray
    material: np.ndarray
    aggregate_id: np.ndarray
    cell_area_m2: Optional[np.ndarray]
    contacts: np.ndarray
    kind: np.ndarray
    facet_length_m: Optional[np.ndarray]
    facet_area_m2: np.ndarray
    distance_m: np.ndarray
    gap_m: np.ndarray
    facet_segment_m: Optional[np.ndarray]
    polygons: List[np.ndarray]
    aggregate_sieve_size_m: np.ndarray
    aggregate_fraction: np.ndarray
    aggregate_aspect_ratio: np.ndarray
    neighbours: np.ndarray
    neighbour_facet_length_m: Optional[np.ndarray]
    width_m: float
    height_m: float
    thickness_m: float
    seed: int
    parameters: Dict = field(default_factory=dict)
    stats: Dict = field(default_factory=dict)
    dim: int = 2
    depth_m: float = 0.0
    z: Optional[np.ndarray] = None
    cell_volume_m3: Optional[np.ndarray] = None
    facet_normal: Optional[np.ndarray] = None
    facet_centroid_m: Optional[np.ndarray] = None
    facet_polygons: Optional[List[np.ndarray]] = None
    polyhedra: List[np.ndarray] = field(default_factory=list)
    neighbour_facet_area_m2: Optional[np.ndarray] = None

    # ------------------------------------------------------------- properties
    @property
    def n_particles(self):
        return int(len(self.r))

    @property
    def n_contacts(self):
        return int(len(self.kind))

    @property
    def n_aggregates(self):
        return len(self.polyhedra) if self.dim == 3 else len(self.polygons)

    @property
    def mean_coordination(self):
        """2 x contacts / particles."""
        return 2.0 * self.n_contacts / max(self.n_particles, 1)

    @property
    def specimen_size_m(self):
        """(W, H) of a 2D section, (W, H, D) of a 3D box [m]."""
        return (self.width_m, self.height_m) if self.dim == 2 else (self.width_m, self.height_m, self.depth_m)

    @property
    def packing_density(self):
        """Disc area / specimen area (2D), sphere volume / box volume (3D)."""
        if self.dim == 3:
            return float(4.0 / 3.0 * np.pi * np.sum(self.r ** 3) / (self.width_m * self.height_m * self.depth_m))
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
        reinforcing bar (swelldem.dem.rebar). Aggregate shapes are kept as they are."""
        d = self.dim
        drop = np.zeros(self.n_particles, dtype=bool)
        drop[np.asarray(particles, dtype=np.int64)] = True
        keep = np.flatnonzero(~drop)
        new_index = np.full(self.n_particles, -1, dtype=np.int64)
        new_index[keep] = np.arange(keep.size)
        per_particle = {k: getattr(self, k)[keep] for k in _PER_PARTICLE[d]}
        c_keep = ~(drop[self.contacts[:, 0]] | drop[self.contacts[:, 1]]) if self.n_contacts else np.zeros(0, dtype=bool)
        per_contact = {k: getattr(self, k)[c_keep] for k in _PER_CONTACT[d]}
        contacts = new_index[self.contacts[c_keep]].astype(self.contacts.dtype)
        n_keep = ~(drop[self.neighbours[:, 0]] | drop[self.neighbours[:, 1]]) if len(self.neighbours) else np.zeros(0, dtype=bool)
        neighbours = new_index[self.neighbours[n_keep]].astype(self.neighbours.dtype)
        per_neighbour = {k: getattr(self, k)[n_keep] for k in _PER_NEIGHBOUR[d]}
        others = {k: None for k in _ONLY[5 - d]}
        if d == 3:
            others["facet_polygons"] = [q for q, k in zip(self.facet_polygons, c_keep) if k]
        return Assembly(contacts=contacts, neighbours=neighbours,
                        polygons=list(self.polygons), polyhedra=list(self.polyhedra),
                        aggregate_sieve_size_m=self.aggregate_sieve_size_m,
                        aggregate_fraction=self.aggregate_fraction, aggregate_aspect_ratio=self.aggregate_aspect_ratio,
                        width_m=self.width_m, height_m=self.height_m, thickness_m=self.thickness_m,
                        depth_m=self.depth_m, dim=d, seed=self.seed,
                        parameters=dict(self.parameters), stats=dict(self.stats, removed_particles=int(drop.sum())),
                        **per_particle, **per_contact, **per_neighbour, **others)

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
            "dim": int(self.dim),
            "n_particles": self.n_particles,
            "n_aggregate_particles": int((self.material == AGGREGATE_MATERIAL).sum()),
            "n_mortar_particles": int((self.material == MORTAR_MATERIAL).sum()),
            "n_aggregates": self.n_aggregates,
            "n_contacts": self.n_contacts,
            "width_m": self.width_m,
            "height_m": self.height_m,
        }
        s.update({"thickness_m": self.thickness_m} if self.dim == 2 else {"depth_m": self.depth_m})
        s.update({
            "seed": int(self.seed),
            "mean_radius_m": float(self.r.mean()) if self.n_particles else None,
            "packing_density": self.packing_density,
            "mean_coordination": self.mean_coordination,
            "contacts_by_kind": by_kind,
            "facet_area_m2": facet,
        })
        for k in ("aggregate_area_fraction", "aggregate_area_fraction_target",
                  "aggregate_area_fraction_cells", "aggregate_area_by_fraction",
                  "aggregate_volume_fraction", "aggregate_volume_fraction_target",
                  "aggregate_volume_fraction_cells", "aggregate_volume_by_fraction",
                  "aggregates_by_fraction", "empty_aggregates", "max_overlap_m", "max_outside_m",
                  "cell_area_sum_rel_error", "cell_volume_sum_rel_error", "facet_asymmetry_max_m",
                  "contact_gap_tolerance_m", "laguerre_pairs", "laguerre_pairs_not_in_contact",
                  "spheres_without_contact", "timings_s",
                  "wall_s", "packing_stats"):
            if k in self.stats:
                s[k] = self.stats[k]
        return s

    # -------------------------------------------------------------- save/load
    def save(self, path):
        """Write the assembly to one compressed ``.npz`` file (arrays + JSON metadata); returns the path."""
        path = str(path)
        if not path.endswith(".npz"):
            path += ".npz"
        arrays = {k: np.asarray(getattr(self, k)) for k in _ARRAYS[self.dim]}
        if self.dim == 2:
            arrays["polygon_offsets"], arrays["polygon_vertices"] = _ragged_pack(self.polygons, 2)
        else:
            arrays["polyhedron_offsets"], arrays["polyhedron_vertices"] = _ragged_pack(self.polyhedra, 3)
            arrays["facet_polygon_offsets"], arrays["facet_polygon_vertices"] = _ragged_pack(self.facet_polygons, 3)
        meta = {"format": FORMAT, "format_version": 1 if self.dim == 2 else FORMAT_VERSION,
                "width_m": self.width_m, "height_m": self.height_m, "thickness_m": self.thickness_m,
                "seed": int(self.seed), "parameters": self.parameters, "stats": self.stats,
                "units": "SI (m, m^2); parameters as named (mm)",
                "kind_names": list(KIND_NAMES), "material_names": list(MATERIAL_NAMES)}
        if self.dim == 3:
            meta.update(dim=3, depth_m=self.depth_m, units="SI (m, m^2, m^3); parameters as named (mm)")
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
            d = int(meta.get("dim", 2))
            arrays = {k: z[k].copy() for k in _ARRAYS[d]}
            arrays.update({k: None for k in _ONLY[5 - d]})
            if d == 2:
                arrays["polygons"] = _ragged_unpack(z["polygon_offsets"], z["polygon_vertices"])
            else:
                arrays["polygons"] = []
                arrays["polyhedra"] = _ragged_unpack(z["polyhedron_offsets"], z["polyhedron_vertices"])
                arrays["facet_polygons"] = _ragged_unpack(z["facet_polygon_offsets"], z["facet_polygon_vertices"])
        return cls(width_m=float(meta["width_m"]), height_m=float(meta["height_m"]),
                   thickness_m=float(meta["thickness_m"]), depth_m=float(meta.get("depth_m", 0.0)), dim=d,
                   seed=int(meta["seed"]), parameters=meta["parameters"], stats=meta["stats"], **arrays)

    def equals(self, other):
        """True when both assemblies have identical arrays, aggregate shapes, facets and parameters (stats ignored)."""
        if not isinstance(other, Assembly) or self.dim != other.dim:
            return False
        for k in _ARRAYS[self.dim]:
            a, b = getattr(self, k), getattr(other, k)
            if a.shape != b.shape or a.dtype != b.dtype or not np.array_equal(a, b):
                return False
        lists = ("polygons",) if self.dim == 2 else ("polyhedra", "facet_polygons")
        for name in lists:
            p, q = getattr(self, name), getattr(other, name)
            if len(p) != len(q) or not all(np.array_equal(u, v) for u, v in zip(p, q)):
                return False
        return (self.width_m, self.height_m, self.thickness_m, self.depth_m, self.seed, self.parameters) == \
            (other.width_m, other.height_m, other.thickness_m, other.depth_m, other.seed, other.parameters)


def load(path):
    """Read an assembly file written by :meth:`Assembly.save`."""
    return Assembly.load(path)
