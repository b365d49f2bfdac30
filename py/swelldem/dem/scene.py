# SPDX-License-Identifier: GPL-2.0-or-later
"""Building blocks of swelldem scenes in YADE: contact kinds from the paper's data, 2D discs, the
engine list, the quasi-static solver chosen by name, and the one scene builder.

Import inside YADE with the plugin (scripts/yade-swelldem); in plain Python every function that
needs YADE raises swelldem.plugin.YadeUnavailableError.
"""
import time

import numpy as np

from .. import paper
from ..plugin import require

BEHAVIOURS = ("elastic", "aging-elastic", "viscoelastic")

#: Quasi-static solvers by name: the plugin class of each. All share the settings tStart, tEnd
#: [day], stepsPerDecade, extraTimes, tolerance, verbose and stepHook, and the results physTime,
#: step, times, stepIterations, totalIterations, unbalanced, stepUnbalanced, finished.
SOLVERS = {"adr": "AdrLogTimeIntegrator", "implicit": "ImplicitLogTimeSolver"}


def _yade(user="swelldem.dem.scene"):
    return require(user)


def _plain(value):
    """A numpy scalar (or 0-d array) as the Python number it holds: boost.python's converters for
    the plugin's double, int and bool attributes take Python numbers only."""
    if isinstance(value, np.generic) or (isinstance(value, np.ndarray) and value.ndim == 0):
        return value.item()
    return value


def contact_kind(name, behaviour="elastic", young=30e9, b3="mortar", shear_ratio=0.3, swell_disp_inf=0.0, kinetics="isr",
                 damage=False, tensile_strength=4e6, **extra):
    """A ContactKind named `name` (kindId from swelldem.paper.KIND_IDS or STRUCTURE_KIND_IDS, 6 for other names) with the
    paper's B3 q's of `b3` (a paper.B3_Q key) and the kinetics of `kinetics` (a paper.KINETICS key).
    Units: young [Pa], swell_disp_inf [m], tensile_strength [Pa]. `extra` are further ContactKind
    attributes by their plugin names (e.g. residualFrictionAngle, swelling, tensileStrength); they
    override the values above. The ContactKind constructor validates every value and raises
    ValueError naming it; an unknown name is a ValueError listing the known ones. Numbers may be
    numpy scalars (numpy.float64, numpy.int64, ...)."""
    if behaviour not in BEHAVIOURS:
        raise ValueError(f"swelldem: behaviour = {behaviour!r} is out of range; allowed: {', '.join(BEHAVIOURS)}")
    if b3 not in paper.B3_Q:
        raise ValueError(f"swelldem: b3 = {b3!r} is out of range; allowed: {', '.join(paper.B3_Q)}")
    if kinetics not in paper.KINETICS:
        raise ValueError(f"swelldem: kinetics = {kinetics!r} is out of range; allowed: {', '.join(paper.KINETICS)}")
    _, W = _yade()
    check_kind_attributes(extra, f"ContactKind {name}")
    young, shear_ratio, swell_disp_inf, damage, tensile_strength = (
        _plain(v) for v in (young, shear_ratio, swell_disp_inf, damage, tensile_strength))
    extra = {k: _plain(v) for k, v in extra.items()}
    q1, q2, q3, q4 = (q * 1e-12 for q in paper.B3_Q[b3])
    tau_c, tau_l, _ = paper.KINETICS[kinetics]
    swelling = bool(extra.pop("swelling", False)) or swell_disp_inf > 0  # a kind may swell through per-contact overrides only
    kw = dict(name=name, kindId={**paper.KIND_IDS, **paper.STRUCTURE_KIND_IDS}.get(name, 6), behaviour=behaviour, young=young, shearRatio=shear_ratio,
              q1=q1, q2=q2, q3=q3, q4=q4, swelling=swelling, swellDispInf=swell_disp_inf, tauC=tau_c, tauL=tau_l,
              damage=damage, tensileStrength=tensile_strength)
    kw.update(extra)  # named attributes have the last word (the per-kind overrides of a scenario)
    return W.ContactKind(**kw)


def scene_law():
    """The running scene's Law2_ScGeom_SwellPhys_AgingSwelling: the owner of what the run does with
    its kinds (stepSerial, the step begun, chainSize(kind), nBreaks)."""
    yade, W = _yade()
    found = [f for e in yade.Omega().engines if hasattr(e, "lawDispatcher") for f in e.lawDispatcher.functors
             if isinstance(f, W.Law2_ScGeom_SwellPhys_AgingSwelling)]
    if len(found) != 1:
        raise ValueError(f"swelldem: the scene holds {len(found)} Law2_ScGeom_SwellPhys_AgingSwelling functors; allowed: exactly one")
    return found[0]


def concrete_ip2(kinds, **attrs):
    """An Ip2_ConcreteMat_ConcreteMat_SwellPhys with each ContactKind of `kinds` (a dict keyed by the kind
    names of swelldem.paper, KIND_NAMES and STRUCTURE_KIND_IDS) in its slot of that kind (the name in
    lower case: MORTAR -> mortar), and the further Ip2 attributes `attrs`; a kind not given stays None."""
    _, W = _yade()
    known = (*paper.KIND_NAMES, *paper.STRUCTURE_KIND_IDS)
    unknown = sorted(set(kinds) - set(known))
    if unknown:
        raise ValueError(f"swelldem: kind names {unknown} are out of range; allowed: {', '.join(known)}")
    return W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(**{name.lower(): kind for name, kind in kinds.items()}, **attrs)


def check_kind_attributes(attrs, where):
    """ValueError naming the first of `attrs` (names) that ContactKind does not have."""
    if not attrs:
        return
    known = kind_setting_names()
    for a in attrs:
        if a not in known:
            raise ValueError(f"swelldem: {where} attribute = {a!r} is out of range; allowed: {', '.join(known)}")


def _solver_class(name):
    """The plugin class of solver `name` (a SOLVERS key); ValueError when the name is unknown or its
    class is not in the loaded plugin."""
    if name not in SOLVERS:
        raise ValueError(f"swelldem: solver = {name!r} is out of range; allowed: {', '.join(SOLVERS)}")
    _, W = _yade()
    cls = getattr(W, SOLVERS[name], None)
    if cls is None:
        have = ", ".join(n for n, c in SOLVERS.items() if hasattr(W, c))
        raise ValueError(f"swelldem: solver = {name!r} is out of range; allowed: {have} "
                         f"(this build of the plugin has no {SOLVERS[name]})")
    return cls


def _setting_names(cls, yade_base):
    """The attributes that cls and its bases below the YADE class `yade_base` flag
    swelldem_attr::Setting: those that Python may write and that the object's dict() shows
    (results are read-only, internals not shown; the attributes of YADE's own classes, such as an
    engine's label, are not swelldem's settings). Sorted."""
    own = set()
    for c in cls.__mro__:
        if c is yade_base:
            break
        own |= {k for k, v in vars(c).items() if isinstance(v, property) and v.fset is not None}
    return sorted(own & set(cls().dict()))


def _as_run(obj, names):
    """{name: value} of obj's attributes `names` as JSON takes them (lists for the plugin's vectors)."""
    return {k: (list(v) if not isinstance(v, (str, bytes)) and hasattr(v, "__len__") else v)
            for k, v in ((k, getattr(obj, k)) for k in names)}


def solver_setting_names(name):
    """The settings of solver `name` (a SOLVERS key): the attributes its plugin class and
    LogTimeSolver flag swelldem_attr::Setting (see _setting_names). Sorted."""
    _, W = _yade()
    return _setting_names(_solver_class(name), W.GlobalEngine)


def solver_defaults(name):
    """{setting: default} of solver `name`, read from a fresh object of its plugin class: the one
    place the defaults are stated is the C++ class (e.g. tolerance 1e-4 for adr, 1e-10 for implicit)."""
    return solver_settings(_solver_class(name)())


def solver_settings(solver):
    """{setting: value} of a solver object, as it runs (lists for the plugin's vectors): what
    results.json records as solver_settings."""
    name = next(n for n, c in SOLVERS.items() if type(solver).__name__ == c)
    return _as_run(solver, solver_setting_names(name))


def kind_setting_names():
    """The settings of ContactKind: name, kindId, behaviour and every per-kind parameter (the
    attributes its plugin class flags swelldem_attr::Setting, see _setting_names). Sorted."""
    _, W = _yade()
    return _setting_names(W.ContactKind, W.Serializable)


def kind_settings(kind):
    """{setting: value} of a ContactKind as it runs (every setting of the class, lists for the
    plugin's vectors): what results.json records per kind under 'kinds'."""
    return _as_run(kind, kind_setting_names())


def functor_kinds(functor):
    """{kind name: ContactKind} of the ContactKinds a functor holds (the Ip2's kinds: those its
    attributes hold, alone or in a list), in kindId order; the kinds of a scene, whatever set them
    (the scenario's three, the bars', the platens')."""
    _, W = _yade()
    found = []
    for v in functor.dict().values():
        for k in (v if isinstance(v, (list, tuple)) else [v]):
            if isinstance(k, W.ContactKind):
                found.append(k)
    return {k.name: k for k in sorted(found, key=lambda k: k.kindId)}


def check_solver_settings(name, attrs, where="solver_params"):
    """ValueError in the one message form naming the first of `attrs` (names) that is not a setting
    of solver `name` (unknown, a result, or a setting of the other solver only), with the allowed
    names."""
    if not attrs:
        return
    known = solver_setting_names(name)
    for a in attrs:
        if a not in known:
            raise ValueError(f"swelldem: {where} name = {a!r} is not a setting of the {name} solver ({SOLVERS[name]}); "
                             f"allowed: {', '.join(known)}")


def make_solver(name, **settings):
    """The quasi-static engine `name` (a SOLVERS key) with `settings` by their plugin names
    (tStart, tEnd [day], stepsPerDecade, tolerance, verbose, ... and YADE's label); its constructor
    validates their values. ValueError before anything is built when the name is unknown, its class
    is not in the loaded plugin, or a setting is not one of its settings (check_solver_settings)."""
    cls = _solver_class(name)
    check_solver_settings(name, [k for k in settings if k != "label"], where="solver setting")
    return cls(**{k: _plain(v) for k, v in settings.items()})


def disc(center_xy, radius, material, fixed=False):
    """A 2D disc: a YADE sphere in the plane z = 0 with z translation and x, y rotations blocked
    (all blocked when fixed). center_xy, radius [m]."""
    yade, _ = _yade()
    b = yade.utils.sphere((center_xy[0], center_xy[1], 0.0), radius, material=material)
    b.state.blockedDOFs = "xyzXYZ" if fixed else "zXY"
    return b


def sphere(center_xyz, radius, material, fixed=False):
    """A sphere of a 3D scene, free in every direction (all blocked when fixed). center_xyz, radius [m]."""
    yade, _ = _yade()
    b = yade.utils.sphere(tuple(float(c) for c in center_xyz), radius, material=material)
    b.state.blockedDOFs = "xyzXYZ" if fixed else ""
    return b


def engines(ip2, law2, integrator, ig2=None, detection_factor=1.0, collider=True, extra_engines=()):
    """ForceResetter, the collider (when `collider`), InteractionLoop (label 'iloop'), extra_engines,
    then the integrator. detection_factor [-] is the sphere geometry functor's
    interactionDetectionFactor and the bounding boxes' aabbEnlargeFactor (ig2, if given, is used as is)."""
    _, W = _yade()
    ig2 = ig2 if ig2 is not None else W.Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=detection_factor)
    out = [W.ForceResetter()]
    if collider:
        out.append(W.InsertionSortCollider([W.Bo1_Sphere_Aabb(aabbEnlargeFactor=detection_factor)], verletDist=0, label="collider"))
    out.append(W.InteractionLoop([ig2], [ip2], [law2], label="iloop"))
    return out + list(extra_engines) + ([integrator] if integrator is not None else [])


def reset_keeping_tags():
    """O.reset() that keeps O.tags (a yade-batch job's id, description and params live there)."""
    yade, _ = _yade()
    O = yade.Omega()
    tags = dict(O.tags)
    O.reset()
    for k, v in tags.items():
        O.tags[k] = v


def build_scene(x, y, r, materials, ip2, law2, integrator, material_of=None, contacts=None, fixed=(), ig2=None,
                detection_factor=1.0, collider=True, extra_engines=(), reset=True, z=None):
    """Fills ``yade.Omega()`` with 2D discs (or 3D spheres, given z), their engines and bonded
    contacts; every swelldem scene (scenario, benchmarks, cohesive comparison, two particles) is built here.

    x, y, r [m]: disc centres and radii (body id = index); z [m]: the centres' third coordinate,
    which makes the bodies spheres free in every direction (a 3D scene); materials: YADE materials, appended to
    O.materials in order; material_of: per disc, an index into `materials` (default all 0);
    ip2, law2: the physics and law functors; integrator: the last engine (or None);
    contacts: (m, 2) disc indices whose interactions are created now (bonded, whatever their gap),
    or None to let the collider find them; fixed: indices of discs held in every direction;
    ig2, detection_factor, collider, extra_engines: see :func:`engines`.
    reset: O.reset() first, keeping O.tags; otherwise O must hold no bodies yet.
    Returns (body ids as an int array, list of the created interactions in `contacts` order)."""
    yade, _ = _yade()
    O = yade.Omega()
    n = len(r)
    if reset:
        reset_keeping_tags()
    elif len(O.bodies) > 0:
        raise ValueError(f"swelldem: O holds {len(O.bodies)} bodies; allowed: none (reset=True, or an empty scene: "
                         "body id = disc index is required)")
    fixed_set = {int(i) for i in np.atleast_1d(np.asarray(fixed, dtype=np.int64))}
    bad = [i for i in fixed_set if not 0 <= i < n]
    if bad:
        raise ValueError(f"swelldem: fixed disc indices {bad[:5]} are out of range; allowed: 0..{n - 1}")
    for m in materials:
        O.materials.append(m)
    which = np.zeros(n, dtype=int) if material_of is None else np.asarray(material_of, dtype=int)
    if z is None:
        bodies = [disc((float(x[i]), float(y[i])), float(r[i]), materials[which[i]], fixed=i in fixed_set) for i in range(n)]
    else:
        bodies = [sphere((x[i], y[i], z[i]), float(r[i]), materials[which[i]], fixed=i in fixed_set) for i in range(n)]
    ids = np.asarray(O.bodies.append(bodies), dtype=np.int64)
    if not np.array_equal(ids, np.arange(n)):
        raise RuntimeError("swelldem: YADE gave body ids different from the disc indices")
    O.engines = engines(ip2, law2, integrator, ig2=ig2, detection_factor=detection_factor, collider=collider,
                        extra_engines=extra_engines)
    # utils.createInteraction asks the geometry functor with force=True: a contact with a gap is
    # created whatever the detection factor; once real, the geometry functor keeps it.
    inters = []
    for c, (i, j) in enumerate(np.asarray(contacts if contacts is not None else [], dtype=np.int64).reshape(-1, 2)):
        I = yade.utils.createInteraction(int(i), int(j))
        if I is None or not I.isReal:
            raise RuntimeError(f"swelldem: contact {c} ({i}, {j}) did not become a real interaction")
        inters.append(I)
    return ids, inters


def run_to_end(solver, chunk=2000, seconds=None):
    """Runs until the solver has converged its last physical step (errors propagate), in calls of
    O.run of at most `chunk` iterations. With `seconds`, a call lasts about that long: the chunk
    follows the measured time of an iteration, down to one. Python runs a signal handler only
    between two calls, and an implicit iteration of a large damage run (a factorization) takes
    seconds, so a fixed chunk would hold a stop signal for minutes. The iterations, and so the
    results, do not depend on how they are chunked."""
    yade, _ = _yade()
    O = yade.Omega()
    n = int(chunk) if seconds is None else 1
    while not solver.finished:
        t = time.perf_counter()
        O.run(n, True)
        if seconds is not None:
            per_iteration = (time.perf_counter() - t) / n
            n = max(1, min(int(chunk), int(seconds / per_iteration) if per_iteration > 0 else int(chunk)))


def run_chunk_quietly(solver, chunk=2000):
    """Runs at most `chunk` iterations of O (fewer when the solver or a step hook stops O): by
    O.run while the solver cannot reach its maxIterations within them, else by O.step, one
    iteration at a time. A step that finds no equilibrium then raises its RuntimeError in Python
    just the same, but without YADE's 'FATAL ERROR ... ThreadRunner' and 'pyOmega::wait()' lines:
    YADE prints those for an exception in the thread that O.run iterates in, while O.step iterates
    in the caller's thread and hands the exception over unprinted. For an ending that is expected,
    such as a virtual test driven past its peak (swelldem.residual). The iterations are the same
    either way: the results do not change. The count a step may take before it fails starts again
    after breaks (the solver's message says 'since the last breaks'), so it is at least the
    iterations of the step: chunks shorter than maxIterations - iterInStep cannot fail."""
    yade, _ = _yade()
    O = yade.Omega()
    safe = int(solver.maxIterations) - int(solver.iterInStep) - 1
    if safe >= 1:
        O.run(min(int(chunk), safe), True)
    else:
        O.step()
