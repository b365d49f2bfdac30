/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * swelldem_geom: C API of the YADE-free geometry library of swelldem.
 *
 * Lengths are in any consistent unit (the Python side passes millimetres);
 * areas are in that unit squared. Every function returns a negative value on
 * error and then swd_geom_last_error() gives a message (per thread).
 */
#ifndef SWELLDEM_GEOM_H
#define SWELLDEM_GEOM_H

#ifdef __cplusplus
extern "C" {
#endif

#define SWD_API __attribute__((visibility("default")))

/* Version string of the library, e.g. "0.1.0". */
SWD_API const char* swd_geom_version(void);

/* Message of the last error raised in this thread ("" if none). */
SWD_API const char* swd_geom_last_error(void);

/*
 * Compact random packing of non-overlapping discs in the rectangle [0,W]x[0,H],
 * radii drawn uniformly in [rmin, rmax] from a generator seeded with `seed`.
 * Constructive advancing-front algorithm: every disc is tangent to two objects
 * already placed (discs or walls). Writes at most `capacity` discs to x, y, r.
 * stats (may be NULL) receives 8 doubles:
 *   [0] packing density (disc area / W H), [1] number of discs,
 *   [2] placements abandoned on the front, [3] discs added by the top-fill pass,
 *   [4] number of front collapses, [5] max overlap found by the final check
 *   (relative to rmax; <= 0 means none), [6] discs whose radius had to be
 *   enlarged to bridge a front gap, [7] reserved (0).
 * Returns the number of discs (>= 0) or -1 (bad argument, capacity too small).
 * A safe capacity is floor(W H / (pi rmin^2)) + 16.
 */
SWD_API long swd_pack_rectangle(double width, double height, double rmin, double rmax,
                                unsigned long long seed, long capacity,
                                double* x, double* y, double* r, double* stats);

/*
 * Random packing of non-overlapping spheres in the box [0,W]x[0,H]x[0,D]
 * (W = width, H = height, D = depth), radii drawn uniformly in [rmin, rmax] from a
 * generator seeded with `seed`, every sphere inside the box. Collective rearrangement:
 * radii filling 0.60 of the box at random centres, then overlapping pairs of slightly
 * inflated spheres pushed apart until none overlaps at the true radii (see
 * pkg/meso/packing3d.cpp). Spheres are numbered
 * in Morton (Z-curve) order of the cubic cells of side rmin that hold their centres (one
 * centre a cell at most). Writes at most `capacity` spheres to x, y, z, r.
 * stats (may be NULL) receives 8 doubles:
 *   [0] packing density (sphere volume / W H D), [1] number of spheres,
 *   [2] density of the radii drawn (before spheres were dropped), [3] overlap-removal
 *   sweeps, [4] pair pushes in them, [5] max overlap found by the final check (relative
 *   to rmax; <= 0 means none), [6] spheres dropped to unjam the relaxation,
 *   [7] pairs with a gap below 0.025 rmax (near-contacts), per sphere.
 * Returns the number of spheres (>= 0) or -1 (bad argument, capacity too small).
 * A safe capacity is floor(W H D / (4/3 pi rmin^3)) + 16.
 */
SWD_API long swd_pack_box(double width, double height, double depth, double rmin, double rmax,
                          unsigned long long seed, long capacity,
                          double* x, double* y, double* z, double* r, double* stats);

/*
 * Laguerre (power) diagram of n discs (weights r^2) with CGAL's 2D regular
 * triangulation, each cell clipped to the rectangle [0,W]x[0,H].
 * Outputs:
 *   cell_area[n]      area of every clipped cell;
 *   facets (at most `capacity` of them; 3 n is always enough): for every pair
 *   i < j whose clipped cells share an edge of positive length:
 *   fi[k], fj[k]      the two disc indices,
 *   flen[k]           edge length (mean of the lengths seen from both cells),
 *   fseg[4k..4k+3]    edge end points x1, y1, x2, y2.
 * stats (may be NULL) receives 8 doubles:
 *   [0] sum of cell areas, [1] max |length seen from i - length seen from j|
 *   over all facets, [2] number of hidden discs (empty cells; 0 for
 *   non-overlapping discs), [3] triangulation dimension,
 *   [4] number of neighbour pairs of the triangulation, [5] number of those whose
 *   clipped edge had zero length, [6] length threshold used for "zero",
 *   [7] reserved (0).
 * Returns the number of facets (>= 0) or -1.
 */
SWD_API long swd_laguerre_rectangle(long n, const double* x, const double* y, const double* r,
                                    double width, double height, long capacity,
                                    int* fi, int* fj, double* flen, double* fseg,
                                    double* cell_area, double* stats);

/*
 * Laguerre (power) diagram of n spheres (weights r^2) with CGAL's 3D regular
 * triangulation, each cell clipped to the box [0,W]x[0,H]x[0,D] (W = width,
 * H = height, D = depth). Radii must be > 0 and the centres inside the box.
 * Outputs:
 *   cell_volume[n]     volume of every clipped cell;
 *   box_area[6n]       per sphere, its cell's area on the box sides x = 0, x = W,
 *                      y = 0, y = H, z = 0, z = D (outward normals -x, +x, -y, +y, -z, +z);
 *   facets (at most `capacity`), one for every pair i < j whose clipped cells share
 *   a face of area above the threshold stats[7], sorted by (i, j):
 *   fi[k], fj[k]       the two sphere indices,
 *   farea[k]           facet area (mean of the areas seen from both cells),
 *   fnormal[3k..3k+2]  unit normal from centre i towards centre j,
 *   fcentroid[3k..]    centroid of the facet polygon;
 *   polygons, only if fverts is not NULL (then fvoff is required): the vertices of
 *   facet k are fverts[3 fvoff[k] .. 3 fvoff[k+1] - 1] (x, y, z each), counter-clockwise
 *   about fnormal[k]; fvoff needs room for capacity + 1 entries (m + 1 are written),
 *   fverts for `vcapacity` vertices. fvoff alone (fverts NULL) still receives the offsets.
 * needed (may be NULL) receives 2 longs, the number of facets and of polygon
 * vertices, as soon as the diagram is made, so that a caller whose capacity was too
 * small can call again with enough.
 * stats (may be NULL) receives 12 doubles:
 *   [0] sum of cell volumes, [1] max |area seen from i - area seen from j| over
 *   all neighbour pairs, [2] spheres hidden in the triangulation (no cell; 0 for
 *   non-overlapping spheres), [3] cells of zero volume (the hidden ones included),
 *   [4] triangulation dimension, [5] neighbour pairs of the triangulation,
 *   [6] of those, pairs without a facet (zero area, as lattices have), [7] area
 *   threshold used for "zero", [8] clips whose new face was ordered by angle instead
 *   of by its edges (a sign of near-degenerate input; 0 expected), [9..11] reserved (0).
 * Returns the number of facets (>= 0) or -1.
 */
SWD_API long swd_laguerre_box(long n, const double* x, const double* y, const double* z, const double* r,
                              double width, double height, double depth, long capacity, long vcapacity,
                              int* fi, int* fj, double* farea, double* fnormal, double* fcentroid,
                              long* fvoff, double* fverts, double* cell_volume, double* box_area,
                              long* needed, double* stats);

/*
 * Contact kind of m pairs of concrete particles from their aggregate ids (-1 mortar, >= 0 one
 * coarse aggregate): kind[k] = 0 MORTAR, 1 ITZ or 2 AGG for the pair (aggregate1[k], aggregate2[k]),
 * by the rule the plugin's Ip2 applies to the particles' materials (pkg/core/PairKind.hpp).
 * Returns m or -1.
 */
SWD_API long swd_pair_kinds(long m, const int* aggregate1, const int* aggregate2, int* kind);

#ifdef __cplusplus
}
#endif
#endif
