# SPDX-License-Identifier: GPL-2.0-or-later
"""Macroscopic strain of a particle specimen, 2D or 3D, from the particles' displacements (plain numpy).

Two measures, both small-strain (the strains of interest are ~1e-3):

* :func:`affine_strain`: least-squares fit of an affine displacement field
  u(X) = c + G (X - X_mean) to the displacements of all particles (optionally weighted, or
  robust: iteratively reweighted with Huber weights so that a few loose particles do not pull
  the fit). The strain is the symmetric part of the gradient G, the rotation its skew part;
  rigid motions therefore give zero strain.
* :func:`side_strain`: the specimen's change of length between its sides, the way a gauge on a
  specimen would read it: mean displacement of the particles next to the right (top) side minus
  that of the particles next to the left (bottom) side, divided by the distance between the mean
  reference positions of those two groups.

Positions and displacements in any one length unit (metres in swelldem); strains are
dimensionless, eps_xy is the tensor component (half the engineering shear strain).
"""
import numpy as np

__all__ = ["affine_strain", "side_strain", "displacements"]


def _as_xy(a, name, dims=(2,)):
    a = np.asarray(a, dtype=float)
    if a.ndim != 2 or a.shape[1] not in dims:
        allowed = " or ".join(f"(n, {d})" for d in dims)
        raise ValueError(f"swelldem.measure: {name} has shape {a.shape}; allowed: {allowed}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"swelldem.measure: {name} holds non-finite values")
    return a


def displacements(ref_xy, cur_xy):
    """cur - ref as an (n, 2) or (n, 3) array, with shape and finiteness checks."""
    ref = _as_xy(ref_xy, "ref_xy", (2, 3))
    cur = _as_xy(cur_xy, "cur_xy", (2, 3))
    if ref.shape != cur.shape:
        raise ValueError(f"swelldem.measure: ref_xy {ref.shape} and cur_xy {cur.shape} differ in shape")
    return cur - ref


def _weighted_fit(X, U, w):
    """Weighted least squares of U = c + G (X - Xm); returns c, G (d x d), Xm."""
    sw = w.sum()
    Xm = (w[:, None] * X).sum(0) / sw
    Um = (w[:, None] * U).sum(0) / sw
    dX = X - Xm
    dU = U - Um
    M = (w[:, None, None] * dX[:, :, None] * dX[:, None, :]).sum(0)   # sum w dX dX^T
    B = (w[:, None, None] * dU[:, :, None] * dX[:, None, :]).sum(0)   # sum w dU dX^T
    if np.linalg.cond(M) > 1e12:
        raise ValueError("swelldem.measure: the reference positions are (nearly) collinear or coplanar; "
                         "an affine field needs particles spread in every direction")
    G = np.linalg.solve(M.T, B.T).T                                    # G M = B
    return Um, G, Xm


def affine_strain(ref_xy, cur_xy, weights=None, robust=False, huber_k=1.345, max_iter=50):
    """Least-squares affine fit of the displacements cur - ref against the reference positions.

    Args:
        ref_xy, cur_xy: (n, 2) or (n, 3) reference and current positions (n >= 3 not collinear in
            2D; n >= 4 not coplanar in 3D).
        weights: optional non-negative weights per particle (e.g. disc areas); default all 1.
        robust: Huber iteratively reweighted least squares (scale from the median absolute
            residual); a plain fit when False.
        huber_k: Huber's threshold in units of the robust residual scale.
    Returns a dict: eps_xx, eps_yy, eps_xy (tensor shear), eps_mean ((xx + yy)/2),
    eps_vol (xx + yy), rotation (rad, counter-clockwise), translation (2, at the weighted centre),
    gradient (2x2 list, du_i/dX_j), residual_rms (rms of the residual displacement, length unit),
    n (particles used), iterations (robust fit). In 3D also eps_zz, eps_xz, eps_yz; eps_mean and
    eps_vol are then (xx + yy + zz)/3 and xx + yy + zz, rotation the rotation vector (3), and
    translation and gradient 3 and 3x3.
    """
    U = displacements(ref_xy, cur_xy)
    X = np.asarray(ref_xy, dtype=float)
    n, d = X.shape
    if n < d + 1:
        raise ValueError(f"swelldem.measure: {n} particles; an affine fit in {d}D needs at least {d + 1}")
    w0 = np.ones(n) if weights is None else np.asarray(weights, dtype=float)
    if w0.shape != (n,) or np.any(~np.isfinite(w0)) or np.any(w0 < 0) or w0.sum() <= 0:
        raise ValueError("swelldem.measure: weights must be n finite non-negative values with a positive sum")
    # Work relative to the reference centroid and size: conditioning independent of units.
    scale = max(*(float(np.ptp(X[:, k])) for k in range(d)), 1e-300)
    Xs = (X - X.mean(0)) / scale
    w = w0.copy()
    c, Gs, Xm = _weighted_fit(Xs, U, w)
    iterations = 0
    if robust:
        for iterations in range(1, max_iter + 1):
            res = np.linalg.norm(U - c - (Xs - Xm) @ Gs.T, axis=1)
            s = 1.4826 * np.median(res)
            if s <= 1e-15 * max(np.abs(U).max(), 1e-300):
                break
            hw = np.minimum(1.0, huber_k * s / np.maximum(res, 1e-300))
            c_new, G_new, Xm = _weighted_fit(Xs, U, w0 * hw)
            done = np.abs(G_new - Gs).max() <= 1e-10 * max(np.abs(G_new).max(), 1e-300)
            c, Gs, w = c_new, G_new, w0 * hw
            if done:
                break
    G = Gs / scale
    r = U - c - (Xs - Xm) @ Gs.T
    exx, eyy, exy = G[0, 0], G[1, 1], 0.5 * (G[0, 1] + G[1, 0])
    rms = float(np.sqrt(np.mean(np.sum(r * r, axis=1))))
    if d == 3:
        ezz = G[2, 2]
        return {"eps_xx": float(exx), "eps_yy": float(eyy), "eps_zz": float(ezz), "eps_xy": float(exy),
                "eps_xz": float(0.5 * (G[0, 2] + G[2, 0])), "eps_yz": float(0.5 * (G[1, 2] + G[2, 1])),
                "eps_mean": float((exx + eyy + ezz) / 3), "eps_vol": float(exx + eyy + ezz),
                "rotation": [float(0.5 * (G[2, 1] - G[1, 2])), float(0.5 * (G[0, 2] - G[2, 0])), float(0.5 * (G[1, 0] - G[0, 1]))],
                "translation": [float(v) for v in c], "gradient": G.tolist(), "residual_rms": rms, "n": int(n),
                "iterations": int(iterations)}
    return {"eps_xx": float(exx), "eps_yy": float(eyy), "eps_xy": float(exy),
            "eps_mean": float(0.5 * (exx + eyy)), "eps_vol": float(exx + eyy),
            "rotation": float(0.5 * (G[1, 0] - G[0, 1])),
            "translation": [float(c[0]), float(c[1])], "gradient": G.tolist(),
            "residual_rms": rms, "n": int(n), "iterations": int(iterations)}


def side_strain(ref_xy, cur_xy, radius, band=None):
    """Change of length between opposite sides, per direction.

    The particles "at" a side are those whose reference centre lies within `band` of the extreme
    reference coordinate on that side (default: the largest radius, i.e. the discs touching the
    side in a packing that fills the rectangle). Returns eps_x, eps_y, eps_mean and the group sizes.
    A rigid rotation gives a second-order (~theta^2/2) apparent strain, negligible for small rotations.
    """
    U = displacements(ref_xy, cur_xy)
    X = np.asarray(ref_xy, dtype=float)
    r = np.broadcast_to(np.asarray(radius, dtype=float), (len(X),))
    band = float(r.max()) if band is None else float(band)
    if band <= 0:
        raise ValueError(f"swelldem.measure: band = {band} is out of range; allowed: > 0")
    out = {}
    for d, name in ((0, "x"), (1, "y")):
        lo = X[:, d] <= X[:, d].min() + band
        hi = X[:, d] >= X[:, d].max() - band
        if not lo.any() or not hi.any() or np.any(lo & hi):
            raise ValueError(f"swelldem.measure: the side bands in {name} are empty or overlap (band = {band})")
        length = X[hi, d].mean() - X[lo, d].mean()
        out[f"eps_{name}"] = float((U[hi, d].mean() - U[lo, d].mean()) / length)
        out[f"n_side_{name}"] = [int(lo.sum()), int(hi.sum())]
    out["eps_mean"] = 0.5 * (out["eps_x"] + out["eps_y"])
    return out
