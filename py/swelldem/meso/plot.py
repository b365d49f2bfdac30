# SPDX-License-Identifier: GPL-2.0-or-later
"""PNG picture of a mesostructure (matplotlib, Agg backend)."""
import numpy as np

from .assembly import ITZ


def plot_mesostructure(assembly, path, color_by="aggregate", show_itz=True, show_polygons=True,
                       dpi=150, size_in=8.0, title=None):
    """Draw the assembly and save it as a PNG; returns the path.

    Mortar discs are light grey; aggregate discs are coloured per aggregate
    (color_by="aggregate") or uniformly (color_by="uniform"); aggregate polygons are
    outlined in black; ITZ contacts are drawn in red between the disc centres.
    Axes are in mm. A 3D assembly is drawn as three orthogonal sections and a 3D view
    (:func:`swelldem.meso.plot3d.plot_mesostructure_3d`).
    """
    if assembly.dim == 3:
        from .plot3d import plot_mesostructure_3d
        return plot_mesostructure_3d(assembly, path, dpi=min(dpi, 130), title=title)
    import matplotlib
    if matplotlib.get_backend().lower() != "agg":
        try:
            matplotlib.use("Agg", force=True)
        except Exception:  # pragma: no cover - a backend already in use
            pass
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection, LineCollection
    from matplotlib.patches import Polygon

    if color_by not in ("aggregate", "uniform"):
        raise ValueError(f"color_by = {color_by!r} must be 'aggregate' or 'uniform'")
    a = assembly
    s = 1e3  # m -> mm
    W, H = a.width_m * s, a.height_m * s
    fig, ax = plt.subplots(figsize=(size_in, size_in * H / W + 0.6))
    colours = np.empty((a.n_particles, 4))
    colours[:] = (0.82, 0.82, 0.80, 1.0)
    agg = a.aggregate_id >= 0
    if agg.any():
        if color_by == "aggregate":
            cmap = plt.get_cmap("tab20")
            palette = np.array([cmap(k / 19.0) for k in range(20) if k not in (14, 15)])
            colours[agg] = palette[(a.aggregate_id[agg] * 7) % len(palette)]
        else:
            colours[agg] = (0.55, 0.45, 0.30, 1.0)
    d = 2 * a.r * s
    ec = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=np.stack([a.x, a.y], 1) * s,
                           offset_transform=ax.transData, facecolors=colours,
                           edgecolors=(0.3, 0.3, 0.3, 1.0), linewidths=0.15)
    ax.add_collection(ec)
    if show_polygons:
        for v in a.polygons:
            ax.add_patch(Polygon(v * s, closed=True, fill=False, edgecolor="k", linewidth=0.8))
    if show_itz:
        sel = a.kind == ITZ
        if sel.any():
            c = a.contacts[sel]
            seg = np.stack([np.stack([a.x[c[:, 0]], a.y[c[:, 0]]], 1),
                            np.stack([a.x[c[:, 1]], a.y[c[:, 1]]], 1)], 1) * s
            ax.add_collection(LineCollection(seg, colors="red", linewidths=0.5))
    ax.plot([0, W, W, 0, 0], [0, 0, H, H, 0], "k-", lw=1.0)
    ax.set_xlim(-0.01 * W, 1.01 * W)
    ax.set_ylim(-0.01 * H, 1.01 * H)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    if title is None:
        n_agg = int(agg.sum())
        title = (f"{a.n_particles} discs ({n_agg} aggregate), {a.n_aggregates} aggregates, "
                 f"{int((a.kind == ITZ).sum())} ITZ contacts (red), seed {a.seed}")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(str(path), dpi=dpi)
    plt.close(fig)
    return str(path)
