# SPDX-License-Identifier: GPL-2.0-or-later
"""Virtual uniaxial tests of a specimen in YADE: displacement-controlled tension or compression
between two bands of discs, for any contact law.

The discs whose left (right) edge lies within ``band`` of the left (right) side are held in x and
moved apart (tension) or together (compression) at a constant strain increment per step; y and
rotations stay free (one left disc held in y against drift), the lateral faces are free. The scene
(built with :func:`swelldem.dem.build_scene` or :func:`swelldem.dem.to_yade`) runs with YADE's
NewtonIntegrator and local damping, dt from the contact stiffness (:func:`stable_dt`).
Stress = mean band reaction / (H b) [Pa]; strain = band displacement / W [-].

Run inside YADE with the plugin (scripts/yade-swelldem).
"""
import time

import numpy as np

from ..paper import KIND_NAMES
from ..plugin import require


def _yade():
    return require("swelldem.dem.uniaxial")


def bands(assembly, band=None):
    """(left, right) disc indices of the loading bands: discs whose edge lies within `band` [m]
    (default 1.5 Rmax) of the left or right side of the specimen."""
    band = 1.5 * float(assembly.r.max()) if band is None else band
    left = np.flatnonzero(assembly.x - assembly.r < band)
    right = np.flatnonzero(assembly.x + assembly.r > assembly.width_m - band)
    return left, right


def stable_dt(safety=0.3):
    """dt [s] = safety x 2 min_i sqrt(m_i / K_i), K_i = sum over the body's contacts of kn + ks
    (an upper bound of its translational stiffness; rotations are softer: I = 0.4 m r^2 against
    ks r^2)."""
    yade, _ = _yade()
    O = yade.Omega()
    K = np.zeros(len(O.bodies))
    for I in O.interactions:
        if not I.isReal:
            continue
        k = abs(I.phys.kn) + abs(I.phys.ks)
        K[I.id1] += k
        K[I.id2] += k
    m = np.array([b.state.mass for b in O.bodies])
    sel = K > 0
    return float(safety * 2 * np.min(np.sqrt(m[sel] / K[sel])))


def broken_contacts(contacts, is_broken=lambda phys: bool(phys.broken)):
    """Per contact (pairs of body ids): bond broken according to is_broken(phys) (default:
    swelldem's SwellPhys.broken); an erased interaction counts as broken."""
    yade, _ = _yade()
    O = yade.Omega()
    out = np.zeros(len(contacts), dtype=bool)
    for c, (i, j) in enumerate(contacts):
        I = O.interactions[int(i), int(j)] if O.interactions.has(int(i), int(j)) else None
        out[c] = True if I is None or not I.isReal else is_broken(I.phys)
    return out


def count_per_kind(mask, kind):
    """{kind name: number of True in `mask` among contacts of that kind, 'total': all}."""
    d = {name: int(np.sum(mask & (kind == k))) for k, name in enumerate(KIND_NAMES)}
    d["total"] = int(mask.sum())
    return d


def fit_modulus(strain, stress, eps_peak, eps_first_break=None, window=(0.3, 0.9)):
    """Macroscopic modulus [Pa]: slope of an affine least-squares fit of stress against strain over
    the elastic range, strains within `window` x the elastic limit (the strain of the first break,
    or 0.5 x the strain at peak when nothing broke before it). The lower bound skips the start-up
    transient (the bands start moving at once; the interior follows a few wave transits later)."""
    lim = 0.5 * eps_peak
    if eps_first_break is not None and 0 < eps_first_break < eps_peak:
        lim = eps_first_break
    sel = (strain >= window[0] * lim) & (strain <= window[1] * lim)
    if sel.sum() < 3:
        return float("nan")
    return float(np.polyfit(strain[sel], stress[sel], 1)[0])


def run_uniaxial(assembly, contacts, mode="tension", deps_per_step=2e-8, chunk=50, max_strain=None, drop=0.5,
                 safety=0.3, min_strain=0.0, broken=broken_contacts, damaged=None):
    """Strain-controlled uniaxial test of the scene in O, whose body ids are the assembly's indices.

    contacts: (m, 2) body ids of the contacts followed (the assembly's); mode 'tension' or
    'compression'; deps_per_step: strain increment per step [-]; every `chunk` steps the stress,
    strain and broken contacts are recorded. Stops when the stress has fallen below `drop` x peak
    after the peak (and beyond min_strain), or at max_strain [-] (default 1e-3 tension, 5e-3
    compression). broken(contacts) -> bool array: the law's broken bonds (default swelldem's);
    damaged(contacts) -> int, optional: contacts with any damage (a law that damages before it
    breaks; the first damage ends the elastic range of the modulus fit). Returns a dict (SI)."""
    yade, _ = _yade()
    O = yade.Omega()
    t0 = time.time()
    sign = 1.0 if mode == "tension" else -1.0
    if max_strain is None:
        max_strain = 1e-3 if mode == "tension" else 5e-3
    # one step at rest with a tiny dt: stock laws set some contact values at the first step (Cpm's kn)
    O.dt = 1e-20
    O.step()
    dt = stable_dt(safety)
    O.dt = dt
    left, right = bands(assembly)
    v = 0.5 * deps_per_step * assembly.width_m / dt
    for i in left:
        b = O.bodies[int(i)]
        b.state.blockedDOFs = "xzXY"
        b.state.vel = yade.Vector3(-sign * v, 0, 0)
    hold = int(left[np.argmin(assembly.y[left])])
    O.bodies[hold].state.blockedDOFs = "xyzXY"
    for i in right:
        b = O.bodies[int(i)]
        b.state.blockedDOFs = "xzXY"
        b.state.vel = yade.Vector3(sign * v, 0, 0)
    x0l = np.array([O.bodies[int(i)].state.pos[0] for i in left])
    x0r = np.array([O.bodies[int(i)].state.pos[0] for i in right])
    area = assembly.height_m * assembly.thickness_m
    kind = np.asarray(assembly.kind)
    strain, stress, nbroken = [0.0], [0.0], [0]
    peak, peak_at, peak_broken = 0.0, 0, np.zeros(len(contacts), dtype=bool)
    first_break = None
    first_damage = None
    steps = 0
    status = "max_strain"
    while True:
        O.run(chunk, True)
        steps += chunk
        dl = np.mean([O.bodies[int(i)].state.pos[0] for i in left]) - x0l.mean()
        dr = np.mean([O.bodies[int(i)].state.pos[0] for i in right]) - x0r.mean()
        eps = sign * (dr - dl) / assembly.width_m
        fr = -sum(O.forces.f(int(i))[0] for i in right)
        fl = sum(O.forces.f(int(i))[0] for i in left)
        sig = sign * 0.5 * (fr + fl) / area
        br = broken(contacts)
        strain.append(eps)
        stress.append(sig)
        nbroken.append(int(br.sum()))
        if damaged is not None and first_damage is None and damaged(contacts) > 0:
            first_damage = eps
        if first_break is None and br.any():
            first_break = {"strain": eps, "stress": sig, "contacts": np.flatnonzero(br).tolist(), "step": steps}
        if sig > peak:
            peak, peak_at, peak_broken = sig, len(stress) - 1, br
        if eps > min_strain and peak > 0 and sig < drop * peak and len(stress) - 1 > peak_at:
            status = "post_peak"
            break
        if eps >= max_strain:
            break
        if not np.isfinite(sig):
            status = "diverged"
            break
    strain, stress = np.array(strain), np.array(stress)
    eps_peak = float(strain[peak_at])
    limit = first_damage if first_damage is not None else (first_break["strain"] if first_break else None)
    return {"mode": mode, "modulus_Pa": fit_modulus(strain, stress, eps_peak, limit), "peak_stress_Pa": float(peak),
            "strain_at_peak": eps_peak, "broken_at_peak": count_per_kind(peak_broken, kind), "broken_end": count_per_kind(br, kind),
            "damaged_end": damaged(contacts) if damaged is not None else None, "first_break": first_break,
            "first_damage_strain": first_damage, "n_contacts": int(len(contacts)), "n_particles": int(assembly.n_particles),
            "dt_s": dt, "steps": steps, "deps_per_step": deps_per_step, "status": status, "wall_s": time.time() - t0,
            "strain": strain.tolist(), "stress_Pa": stress.tolist(), "n_broken": nbroken,
            "broken_contacts_end": np.flatnonzero(br).tolist()}
