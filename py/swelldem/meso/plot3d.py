# SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of a 3D mesostructure (matplotlib, Agg backend): three orthogonal sections and a 3D view of
the aggregates; the facet sizes of a 3D box against those of a 2D section.

A section through the box is what a person compares with a sawn and polished concrete face (and with
a 2D specimen of the paper's model): the spheres the plane cuts are drawn as the discs they cut, in
the colour of their aggregate, and each aggregate cut by the plane as the convex polygon it cuts.
"""
import numpy as np

from .assembly import AGG, ITZ, MORTAR

AXES = ("x", "y", "z")
#: The three sections: (normal axis, in-plane horizontal axis, in-plane vertical axis).
SECTIONS = ((2, 0, 1), (1, 0, 2), (0, 1, 2))


def _pyplot():
    import matplotlib
    if matplotlib.get_backend().lower() != "agg":
        try:
            matplotlib.use("Agg", force=True)
        except Exception:  # pragma: no cover - a backend already in use
            pass
    import matplotlib.pyplot as plt
    return plt


def hull_edges(vertices):
    """Unique vertex pairs (k, 2) of the edges of the triangulated convex hull of (n, 3) vertices
    (diagonals of a non-triangular face included: a section through them still lies in the hull)."""
    from scipy.spatial import ConvexHull
    tri = ConvexHull(vertices).simplices
    e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    return np.unique(np.sort(e, axis=1), axis=0)


def section_polygon(vertices, axis, level, edges=None):
    """The convex polygon that the plane ``coordinate[axis] = level`` cuts from the convex hull of
    ``vertices`` (n, 3), as (k, 3) points in counter-clockwise order in the plane's other two
    coordinates (in increasing order); None when the plane misses the hull (or only touches it)."""
    v = np.asarray(vertices, dtype=float)
    e = hull_edges(v) if edges is None else edges
    a, b = v[e[:, 0]], v[e[:, 1]]
    da, db = a[:, axis] - level, b[:, axis] - level
    cut = (da * db < 0) | ((da == 0) & (db != 0))
    if cut.sum() < 3:
        return None
    t = (da[cut] / (da[cut] - db[cut]))[:, None]
    p = a[cut] + t * (b[cut] - a[cut])
    u, w = [k for k in range(3) if k != axis]
    from scipy.spatial import ConvexHull, QhullError
    try:
        # the 2D hull drops the points that face diagonals add along the section's sides
        h = ConvexHull(p[:, [u, w]])
    except QhullError:
        return None  # the plane only touches the hull along an edge
    return p[h.vertices]


def _aggregate_palette(plt):
    cmap = plt.get_cmap("tab20")
    return np.array([cmap(k / 19.0) for k in range(20) if k not in (14, 15)])


def _draw_section(ax, a, normal, hor, ver, level, palette, edges):
    from matplotlib.collections import EllipseCollection
    from matplotlib.patches import Polygon
    s = 1e3
    c = np.stack([a.x, a.y, a.z], axis=1)
    d = c[:, normal] - level
    cut = np.abs(d) < a.r
    rc = np.sqrt(a.r[cut] ** 2 - d[cut] ** 2)
    colours = np.empty((int(cut.sum()), 4))
    colours[:] = (0.82, 0.82, 0.80, 1.0)
    agg = a.aggregate_id[cut]
    colours[agg >= 0] = palette[(agg[agg >= 0] * 7) % len(palette)]
    diam = 2 * rc * s
    ax.add_collection(EllipseCollection(diam, diam, np.zeros_like(diam), units="xy",
                                        offsets=np.stack([c[cut, hor], c[cut, ver]], 1) * s,
                                        offset_transform=ax.transData, facecolors=colours,
                                        edgecolors=(0.3, 0.3, 0.3, 1.0), linewidths=0.1))
    n_cut = 0
    for k, v in enumerate(a.polyhedra):
        if not (v[:, normal].min() < level < v[:, normal].max()):
            continue
        poly = section_polygon(v, normal, level, edges[k])
        if poly is not None:
            n_cut += 1
            ax.add_patch(Polygon(poly[:, [hor, ver]] * s, closed=True, fill=False, edgecolor="k", linewidth=0.7))
    size = np.array(a.specimen_size_m) * s
    ax.plot([0, size[hor], size[hor], 0, 0], [0, 0, size[ver], size[ver], 0], "k-", lw=0.8)
    ax.set_xlim(-0.01 * size[hor], 1.01 * size[hor])
    ax.set_ylim(-0.01 * size[ver], 1.01 * size[ver])
    ax.set_aspect("equal")
    ax.set_xlabel(f"{AXES[hor]} [mm]")
    ax.set_ylabel(f"{AXES[ver]} [mm]")
    share = float((agg >= 0).mean()) if len(agg) else 0.0
    ax.set_title(f"section {AXES[normal]} = {level * s:.1f} mm: {int(cut.sum())} spheres cut, "
                 f"{n_cut} aggregates, {100 * share:.0f} % of the cut spheres aggregate", fontsize=8)


def _draw_3d(ax, a):
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection
    from scipy.spatial import ConvexHull
    s = 1e3
    colours = ((0.85, 0.55, 0.25, 0.85), (0.35, 0.45, 0.75, 0.85), (0.4, 0.7, 0.4, 0.85))
    light = np.array([0.4, -0.5, 0.77])
    light /= np.linalg.norm(light)
    tris, fc = [], []
    for k, v in enumerate(a.polyhedra):
        h = ConvexHull(v * s)
        base = np.array(colours[int(a.aggregate_fraction[k]) % len(colours)])
        shade = 0.55 + 0.45 * np.clip(h.equations[:, :3] @ light, 0.0, 1.0)
        for t, f in zip(h.simplices, shade):
            tris.append(h.points[t])
            fc.append(np.concatenate([base[:3] * f, base[3:]]))
    if tris:
        ax.add_collection3d(Poly3DCollection(tris, facecolors=fc, edgecolors="none"))
    W, H, D = np.array(a.specimen_size_m) * s
    corners = np.array([[i * W, j * H, k * D] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    edges = [(p, q) for p in range(8) for q in range(p + 1, 8) if bin(p ^ q).count("1") == 1]
    ax.add_collection3d(Line3DCollection([corners[[p, q]] for p, q in edges], colors="k", linewidths=0.8))
    ax.set_xlim(0, W)
    ax.set_ylim(0, H)
    ax.set_zlim(0, D)
    ax.set_box_aspect((W, H, D))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    ax.view_init(elev=22, azim=-58)
    fr = a.parameters.get("sieve_fractions_mm", [])
    names = ", ".join(f"{lo:g}-{hi:g} mm {('orange', 'blue', 'green')[k % 3]}" for k, (lo, hi) in enumerate(fr))
    ax.set_title(f"{a.n_aggregates} aggregates ({names})", fontsize=8)


def plot_mesostructure_3d(assembly, path, levels=None, dpi=130, title=None):
    """Three orthogonal sections through the middle of the box (or at ``levels`` = (x, y, z) [m])
    and a 3D view of the aggregates, saved as one PNG; returns the path."""
    a = assembly
    if a.dim != 3:
        raise ValueError(f"plot_mesostructure_3d: the assembly is {a.dim}D; plot_mesostructure draws a 2D one")
    plt = _pyplot()
    palette = _aggregate_palette(plt)
    size = np.array(a.specimen_size_m)
    lv = size / 2 if levels is None else np.asarray(levels, dtype=float)
    edges = [hull_edges(v) for v in a.polyhedra]
    fig = plt.figure(figsize=(12, 11))
    for pos, (normal, hor, ver) in zip((1, 2, 3), SECTIONS):
        _draw_section(fig.add_subplot(2, 2, pos), a, normal, hor, ver, lv[normal], palette, edges)
    _draw_3d(fig.add_subplot(2, 2, 4, projection="3d"), a)
    if title is None:
        st = a.stats
        frac = st.get("aggregate_volume_fraction")
        title = (f"3D mesostructure {' x '.join(f'{v * 1e3:g}' for v in size)} mm, seed {a.seed}: "
                 f"{a.n_particles} spheres ({int((a.aggregate_id >= 0).sum())} aggregate), "
                 f"packing density {a.packing_density:.3f},\naggregate volume fraction "
                 f"{'-' if frac is None else f'{frac:.3f}'}, {a.n_contacts} contacts "
                 f"(MORTAR {int((a.kind == MORTAR).sum())}, ITZ {int((a.kind == ITZ).sum())}, "
                 f"AGG {int((a.kind == AGG).sum())})")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(str(path), dpi=dpi)
    plt.close(fig)
    return str(path)


def facet_sizes_mm(assembly):
    """The facet size of every contact [mm]: in 2D the facet length, in 3D the diameter of the disc of
    the facet's area, 2 sqrt(A / pi); one length so that a section's facets and a box's compare."""
    if assembly.dim == 2:
        return assembly.facet_length_m * 1e3
    return 2.0 * np.sqrt(assembly.facet_area_m2 / np.pi) * 1e3


def facet_size_table(assembly):
    """Per kind and for all contacts: count, mean and 5/50/95 % quantiles of the facet size [mm]."""
    size = facet_sizes_mm(assembly)
    out = {}
    for name, sel in (("all", np.ones(len(size), dtype=bool)), ("MORTAR", assembly.kind == MORTAR),
                      ("ITZ", assembly.kind == ITZ), ("AGG", assembly.kind == AGG)):
        v = size[sel]
        out[name] = ({"n": int(v.size), "mean": float(v.mean()), "q05": float(np.quantile(v, 0.05)),
                      "q50": float(np.quantile(v, 0.5)), "q95": float(np.quantile(v, 0.95))}
                     if v.size else {"n": 0, "mean": None, "q05": None, "q50": None, "q95": None})
    return out


def plot_facet_sizes(box, section, path, dpi=130):
    """Histograms of the facet sizes of a 3D box against those of a 2D section (facet_sizes_mm), both in
    units of the mean radius; returns the path."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    for a, label, colour in ((section, "2D section: facet length", "tab:blue"),
                             (box, "3D box: 2 sqrt(facet area / pi)", "tab:red")):
        v = facet_sizes_mm(a) / (a.r.mean() * 1e3)
        ax.hist(v, bins=60, range=(0.8, 2.6), density=True, histtype="step", lw=1.6, color=colour,
                label=f"{label} ({len(v)} contacts, mean {v.mean():.2f}, coordination {a.mean_coordination:.2f})")
    ax.set_xlabel("facet size / mean particle radius [-]")
    ax.set_ylabel("probability density [-]")
    ax.set_title(f"Laguerre facet sizes, {' x '.join(f'{v * 1e3:g}' for v in box.specimen_size_m)} mm box "
                 f"against a {' x '.join(f'{v * 1e3:g}' for v in section.specimen_size_m)} mm section, "
                 f"seed {box.seed}", fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(str(path), dpi=dpi)
    plt.close(fig)
    return str(path)
