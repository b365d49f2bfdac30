# SPDX-License-Identifier: GPL-2.0-or-later
"""swelldem.meso: concrete mesostructures discretised by discs (2D sections) or spheres (3D boxes).

Typical use::

    from swelldem import meso
    a = meso.generate(seed=1, width_mm=30, height_mm=30)   # parameters in mm
    a.x, a.y, a.r, a.material, a.aggregate_id               # discs (SI metres)
    a.contacts, a.kind, a.facet_area_m2                     # contacts (MORTAR/ITZ/AGG)
    a.save("assembly.npz"); b = meso.load("assembly.npz")
    meso.plot_mesostructure(a, "mesostructure.png")
    b = meso.generate(seed=1, dim=3, width_mm=20, height_mm=20, depth_mm=20)  # spheres, polyhedra
    b.z, b.cell_volume_m3, b.facet_normal, b.facet_polygons, b.polyhedra   # the 3D attributes

The heavy geometry (disc and sphere packings, Laguerre facets with CGAL) is in the compiled
library ``libswelldem_geom.so`` of the build folder (see :mod:`swelldem.paths`). The package is
pure geometry (numpy and that library): it imports no YADE code, and runs in plain Python. Its
YADE scene is made by :func:`swelldem.dem.to_yade`.
"""
from .aggregates import AggregatePlacementError
from .assembly import (AGG, AGGREGATE_MATERIAL, ITZ, KIND_NAMES, MATERIAL_NAMES, MORTAR,
                       MORTAR_MATERIAL, Assembly, load)
from .generator import choose_contacts, contact_kinds, generate, label_discs
from .params import (DEFAULT_AGGREGATE_AREA_FRACTION, FULLER_SHARES, PAPER_FRACTIONS_MM,
                     MesoParameterError, MesoParameters)
from .plot import plot_mesostructure

__all__ = ["AGG", "AGGREGATE_MATERIAL", "ITZ", "KIND_NAMES", "MATERIAL_NAMES", "MORTAR",
           "MORTAR_MATERIAL", "Assembly", "AggregatePlacementError", "DEFAULT_AGGREGATE_AREA_FRACTION",
           "FULLER_SHARES", "MesoParameterError", "MesoParameters", "PAPER_FRACTIONS_MM",
           "contact_kinds", "generate", "label_discs", "load", "plot_mesostructure",
           "choose_contacts"]
