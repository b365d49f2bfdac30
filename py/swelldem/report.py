# SPDX-License-Identifier: GPL-2.0-or-later
"""Tables (Markdown, CSV) and plots (PNG) of swelling tests, in the form of the paper's tables
and figures. Plain Python: it reads results.json dictionaries (and, for the crack map, the list
of broken contacts with the assembly's facet segments)."""
import csv
import json
import math
import os
import time

import numpy as np

from .paper import (BEHAVIOUR_KEYS, BEHAVIOUR_WORDS, EPS_INF, KIND_NAME_OF_ID, KIND_NAMES, KINETICS, LARIVE_T0, LARIVE_UC, LARIVE_UL,
                    SCENARIOS, SPECIMEN_SIZE_MM, STRUCTURE_KIND_IDS, larive_xi_under,
                    TABLE_FORCES, VARIATION)

LABEL = {"isr": "ISR", "asr-fine": "ASR-fine agg.", "asr-coarse": "ASR-coarse agg."}
#: Colour of each contact kind in the plots and crack maps; the structures' kinds each their own, so
#: that a bar or a broken bond is never taken for a mortar crack.
COLORS = {"MORTAR": "tab:blue", "ITZ": "tab:red", "AGG": "tab:green", "PLATEN": "tab:purple", "STEEL": "0.25", "BOND": "darkorange"}


def kinds_of(res):
    """The contact kinds of a run's per-kind results: the paper's three, then the structures' kinds
    (PLATEN, STEEL, BOND) that its scene has, in kindId order."""
    per_kind = res.get("per_kind") or {}
    return list(KIND_NAMES) + [name for name in STRUCTURE_KIND_IDS if name in per_kind]



class ResultsError(ValueError):
    """A results.json that is missing, malformed, truncated or not a swelling test's; the message
    names the file."""


#: What a swelling test's results.json must hold for the tables: key -> type.
RESULT_KEYS = {"scenario": str, "behaviour": str, "damage": bool, "status": str, "times_days": list,
               "n_contacts_by_kind": dict, "per_kind": dict}
SERIES = ("fn_p05_kN", "fn_p95_kN", "broken")

#: A 'running' results.json not rewritten for this long is taken for a dead run [s]: the recorder
#: rewrites it after every physical step, and steps of the paper-size runs take seconds to a few
#: minutes (docs/performance.md). Scaled up for slow runs: 10 x the run's mean step time.
STALE_AFTER_S = 600.0


#: results.json keys under the names that earlier versions of swelldem wrote: old name -> present name.
RENAMED_KEYS = {"adr_iterations": "iterations", "adr_iterations_per_step": "iterations_per_step"}


def current_form(res):
    """A results dict in today's form, whatever version of swelldem wrote it: the keys of
    RENAMED_KEYS under their present names, and without the flat copies '<series>_<KIND>' (e.g.
    broken_ITZ) of the per_kind series that earlier files held beside per_kind; a config without a
    field of scenario.VALUE_BEFORE_FIELD gets the value the run had. What a file does
    not hold (e.g. 'kinds' in files written before it was recorded) stays absent. Changes `res`
    and returns it."""
    for old, new in RENAMED_KEYS.items():
        if old in res and new not in res:
            res[new] = res.pop(old)
    if isinstance(res.get("config"), dict) and res["config"]:
        from .scenario import VALUE_BEFORE_FIELD  # a config written before a field existed: what the run did
        for name, value in VALUE_BEFORE_FIELD.items():
            res["config"].setdefault(name, value)
    for name, series in (res.get("per_kind") or {}).items():
        for key in series if isinstance(series, dict) else ():
            res.pop(f"{key}_{name}", None)
    return res


def load_results(path):
    """The results dict of a swelling test's results.json at `path`, in today's form whatever
    version wrote it (current_form); ResultsError naming the file when it is missing, is not JSON
    (truncated, malformed) or lacks what the tables read."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise ResultsError(f"{path}: cannot be read ({e.strerror}); run scripts/swelling_test.py --out {os.path.dirname(path) or '.'} first")
    try:
        res = json.loads(text)
    except ValueError as e:
        raise ResultsError(f"{path}: not a results.json of swelldem: truncated or malformed JSON ({e})") from None
    if not isinstance(res, dict):
        raise ResultsError(f"{path}: not a results.json of swelldem: a JSON {type(res).__name__}, not an object")
    missing = [k for k in RESULT_KEYS if k not in res]
    if missing:
        raise ResultsError(f"{path}: not a swelling test's results.json (scripts/swelling_test.py): no {', '.join(missing)}")
    wrong = [f"{k} is a {type(res[k]).__name__}" for k, t in RESULT_KEYS.items() if not isinstance(res[k], t)]
    if wrong:
        raise ResultsError(f"{path}: not a swelling test's results.json: {', '.join(wrong)}")
    n = len(res["times_days"])
    for name in KIND_NAMES:
        d = res["per_kind"].get(name)
        if not isinstance(d, dict) or any(not isinstance(d.get(k), list) or len(d[k]) != n for k in SERIES):
            raise ResultsError(f"{path}: not a swelling test's results.json: per_kind {name} lacks one of {', '.join(SERIES)} "
                               f"with one value per step ({n} steps)")
        if not isinstance(res["n_contacts_by_kind"].get(name, 0), int):
            raise ResultsError(f"{path}: not a swelling test's results.json: n_contacts_by_kind {name} is not an integer")
    return current_form(res)


def run_state(res, now=None):
    """How a run ended, for a table: 'finished', its 'failed: ...' or 'interrupted: ...' status, or,
    for a run still 'running', 'running (last update N s ago)' while it is recent and
    'unfinished (last update <UTC time>)' once older than the stale limit (STALE_AFTER_S, or
    10 x the run's mean step time): the process died without a word (SIGKILL, a crash)."""
    status = str(res.get("status", "?"))
    if status == "finished" or status.startswith(("failed", "interrupted")):
        return status
    if status != "running":
        return f"unknown status {status!r}"
    updated = res.get("updated")
    if not isinstance(updated, (int, float)) or isinstance(updated, bool):
        return "unfinished (no update time)"
    now = time.time() if now is None else now
    steps = len(res.get("times_days") or []) or 1
    limit = max(STALE_AFTER_S, 10.0 * float(res.get("wall_s") or 0.0) / steps)
    stamp = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime(updated))
    if now - updated > limit:
        return f"unfinished (last update {stamp})"
    return f"running (last update {stamp}, {now - updated:.0f} s ago)"


def _iteration_name(res):
    """What one iteration of the run's solver is (results.json 'solver')."""
    return "Newton and relaxation" if res.get("solver") == "implicit" else "ADR"


def iterations_text(res):
    """The run's iterations in words: 'ADR iterations N', or for the implicit solver 'iterations
    N (Newton n, dynamic relaxation m)' (the split left out for a file that does not record it)."""
    total = res.get("iterations", "?")
    if res.get("solver") != "implicit":
        return f"ADR iterations {total}"
    split = f" (Newton {res['newton_iterations']}, dynamic relaxation {res['relaxation_iterations']})" if "newton_iterations" in res else ""
    return f"iterations {total}{split}"

def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def final_rows(res, kinds=None):
    """Per kind at the last step: 5 % and 95 % normal-force quantiles [kN], broken contacts (of the
    n_contacts bonded at the start) and their share, and the contacts made during the run (born
    broken; None in a results.json written before they were counted apart, whose 'broken' then
    includes them). kinds: the kinds' names (default kinds_of(res): the structures' too)."""
    rows = []
    for name in kinds or kinds_of(res):
        d = res["per_kind"][name]
        n = res["n_contacts_by_kind"].get(name, 0)
        broken = d["broken"][-1] if d["broken"] else 0
        born = d.get("born_broken")
        rows.append({"kind": name, "n_contacts": n,
                     "fn_p05_kN": d["fn_p05_kN"][-1] if d["fn_p05_kN"] else float("nan"),
                     "fn_p95_kN": d["fn_p95_kN"][-1] if d["fn_p95_kN"] else float("nan"),
                     "broken": broken, "broken_pct": 100.0 * broken / n if n else float("nan"),
                     "born_broken": (born[-1] if born else 0) if born is not None else None})
    return rows


def paper_key(res):
    """(scenario, 'el'|'ve', 'nodmg'|'dmg') of a run of the paper's study, or None for a run the
    paper has no counterpart of (another behaviour or scenario)."""
    beh = {v: k for k, v in BEHAVIOUR_KEYS.items()}.get(res.get("behaviour"))
    key = (res.get("scenario"), beh, "dmg" if res.get("damage") else "nodmg")
    return key if key in TABLE_FORCES else None


def run_key(res):
    """'<scenario>-<el|ve>-<nodmg|dmg>' of a run of the paper's study, from its results.json's
    scenario, behaviour and damage (scripts/paper_study.py names its run folders so), or None for
    a run the paper has no counterpart of."""
    key = paper_key(res)
    return None if key is None else "-".join(key)


#: Settings of a swelling test that change the physics away from the paper's study when set away
#: from their default (the scenario's); the solver and the outputs are not conditions.
_PARAMETER_SETTINGS = ("eps_inf", "gel_fraction", "gel_pockets", "gel_pocket_radius_mm", "gel_displacement", "shear_ratio",
                       "aggregate_young", "strength_scale", "kelvin_units_per_decade", "parameters", "aggregate_area_fraction", "t_start_days", "t_end_days")


def run_conditions(res):
    """The run's conditions away from the paper's study (a free 2D section at the kinds' reference
    temperatures with the paper's parameters), as short texts in a fixed order: temperature,
    platens or applied stress per axis, bars, a 3D box, and every parameter or kind parameter set
    away from its default. [] for a run under the paper's conditions (or without a config)."""
    cfg = res.get("config") or {}
    if not cfg:
        return []
    from .scenario import SwellingTest  # plain Python, loaded with the package
    defaults = SwellingTest()
    out = []
    if cfg.get("temperature_c") is not None and cfg["temperature_c"] != 20.0:  # 20 C: the paper's
        out.append(f"{cfg['temperature_c']:g} C")
    elif cfg.get("temperature_csv"):
        out.append(f"temperature history {os.path.basename(str(cfg['temperature_csv']))}")
    for axis in ("x", "y", "z"):
        if cfg.get(f"boundary_{axis}", "free") != "free":
            out.append(f"{axis} sides {cfg[f'boundary_{axis}']}")
    if cfg.get("rebar_ratio"):
        out.append(f"bars {100 * cfg['rebar_ratio']:g} %")
    if cfg.get("dim") == 3:
        out.append("3D box")
    out += humidity_conditions(cfg)
    for name in _PARAMETER_SETTINGS:
        if name in cfg and json.dumps(cfg[name]) != json.dumps(getattr(defaults, name)):
            out.append(f"{name}={setting_text(res, name)}")
    if cfg.get("kind_params"):
        out.append(setting_text(res, "kind_params"))
    return out


def run_numerics(res):
    """How a run was solved, as short texts: the solver, the linear solver an implicit run used
    (when not CHOLMOD), the physical steps a decade, and the solver's settings given to the run
    (its config's tolerance and solver_params, without verbose). Numerics, not conditions: they do
    not take the paper's values away from a table (run_conditions does)."""
    cfg = res.get("config") or {}
    solver = res.get("solver") or cfg.get("solver")
    if not solver:
        return []
    out = ["ADR" if solver == "adr" else f"{solver} solver"]
    linear = (res.get("linear_solver") or {}).get("name")
    if solver == "implicit" and linear and linear != "cholmod":
        out.append(f"linear solver {linear}")
    spd = (res.get("solver_settings") or {}).get("stepsPerDecade", cfg.get("steps_per_decade"))
    if spd:
        out.append(f"{spd:g} steps a decade")
    if cfg.get("tolerance") is not None:
        out.append(f"tolerance {cfg['tolerance']:g}")
    given = {k: v for k, v in (cfg.get("solver_params") or {}).items() if k not in ("verbose", "linearSolver")}
    return out + _name_values(given)


def mean_expansion(res):
    """(times [day], the mean of the x and y swelling strains [-] at each): a run's expansion as
    the study scripts plot it."""
    return np.array(res["times_days"]), 0.5 * (np.array(res["swelling_strain_x"]) + np.array(res["swelling_strain_y"]))


def broken_share_pct(res):
    """The share [%] of a run's MORTAR, ITZ and AGG contacts broken at its end."""
    return 100 * sum(res["per_kind"][k]["broken"][-1] for k in KIND_NAMES) / max(1, sum(res["n_contacts_by_kind"].values()))


def humidity_conditions(cfg):
    """The moisture settings of a run's config as short texts ([] for a saturated run): the exposed
    faces with their ambient h (or history file), the initial h, and the coupling where set away
    from its default."""
    faces, h0 = cfg.get("humidity_faces") or {}, cfg.get("humidity_initial", 1.0)
    if not faces and h0 == 1.0:
        return []
    out = []
    by_value = {}
    for face, v in faces.items():
        by_value.setdefault(str(v) if not isinstance(v, (int, float)) else f"h {v:g}", []).append(face)
    for v, fs in by_value.items():
        out.append(f"{' '.join(fs)} exposed to {v if v.startswith('h ') else os.path.basename(v)}")
    if not faces:
        out.append("sealed")
    out.append(f"h initial {h0:g}")
    from .scenario import SwellingTest
    d = SwellingTest()
    if cfg.get("humidity_exponent", d.humidity_exponent) != d.humidity_exponent:
        out.append(f"f(h) = h^{cfg['humidity_exponent']:g}")
    if cfg.get("shrinkage"):
        out.append("k_sh " + " ".join(f"{k}={v:g}" for k, v in sorted(cfg["shrinkage"].items())))
    return out


def exposed_faces(res):
    """{face: label} of the faces a run exposed to an ambient humidity ({} for a sealed or
    saturated run)."""
    faces = (res.get("config") or {}).get("humidity_faces") or {}
    return {f: (f"h {v:g}" if isinstance(v, (int, float)) else os.path.basename(str(v))) for f, v in faces.items()}


def _mark_faces(ax, res, width_mm, height_mm):
    """The exposed faces of a section's map, a blue band along each (drying or wetting)."""
    ends = {"x-": ([0, 0], [0, height_mm]), "x+": ([width_mm] * 2, [0, height_mm]),
            "y-": ([0, width_mm], [0, 0]), "y+": ([0, width_mm], [height_mm] * 2)}
    for n, (face, label) in enumerate(sorted(exposed_faces(res).items())):
        if face in ends:
            ax.plot(*ends[face], "-", color="tab:blue", lw=5, alpha=0.7, solid_capstyle="butt", clip_on=False,
                    label=f"exposed faces ({', '.join(f'{f} {v}' for f, v in sorted(exposed_faces(res).items()))})"
                    if n == 0 else None)


def plot_humidity_maps(out, res, assembly, days=None, name="humidity_maps.png"):
    """h of every particle at up to four times (default: 10, 100 and 1000 days and the run's
    end, those within it) from the run's humidity.npz, the exposed faces marked; a 3D box's
    particles within a radius of its mid-depth plane. Returns the path, or None without the file."""
    path = os.path.join(out, "humidity.npz")
    if not os.path.exists(path):
        return None
    data = np.load(path)
    times, h = data["times_days"], data["h"].astype(float)
    if days is None:
        days = [d for d in (10.0, 100.0, 1000.0) if times[0] < d < times[-1]] + [float(times[-1])]
    plt = _plt()
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Circle
    x, y, r = np.asarray(assembly.x) * 1e3, np.asarray(assembly.y) * 1e3, np.asarray(assembly.r) * 1e3
    if getattr(assembly, "dim", 2) == 3:
        dz = np.asarray(assembly.z) * 1e3 - assembly.depth_m * 1e3 / 2
        keep = np.abs(dz) < r
        r = np.where(keep, np.sqrt(np.maximum(r ** 2 - dz ** 2, 0)), 0)
    else:
        keep = np.ones(len(x), dtype=bool)
    w, hh = assembly.width_m * 1e3, assembly.height_m * 1e3
    n = len(days)
    fig, axes = plt.subplots(1, n, figsize=(3.6 * n + 1.2, 3.6 * hh / w + 0.9), squeeze=False, layout="constrained")
    lo = float(min(h.min(), 0.999))
    for ax, d in zip(axes[0], days):
        k = int(np.argmin(np.abs(times - d)))
        pc = PatchCollection([Circle((x[i], y[i]), r[i]) for i in np.nonzero(keep)[0]], cmap="viridis_r", linewidths=0)
        pc.set_array(h[k][keep])
        pc.set_clim(lo, 1.0)
        ax.add_collection(pc)
        _mark_faces(ax, res, w, hh)
        _frame(ax, w, hh, "x [mm]", "y [mm]", f"t = {times[k]:.4g} d, mean h {h[k] @ _volumes(assembly) / _volumes(assembly).sum():.3f}")
    fig.colorbar(pc, ax=axes[0].tolist(), label="relative humidity h [-]", shrink=0.85)
    fig.suptitle(_title(res) + ("" if getattr(assembly, "dim", 2) == 2 else ", mid-depth section"), fontsize=10)
    target = os.path.join(out, name)
    fig.savefig(target, dpi=110)  # constrained layout: not _save's tight_layout, which ignores the colour bar
    plt.close(fig)
    return target


def _volumes(assembly):
    return np.asarray(assembly.cell_volume_m3 if getattr(assembly, "dim", 2) == 3 else assembly.cell_area_m2, dtype=float)


def size_note(res):
    """One sentence: the run's specimen size against the paper's (forces and broken counts depend
    on it: docs/scenarios.md compares 40 and 100 mm)."""
    size = (res.get("config") or {}).get("size_mm")
    pw, ph = SPECIMEN_SIZE_MM
    if not size:
        return f"Specimen size not recorded; the paper's is {pw:g} x {ph:g} mm."
    if len(size) == 3:
        w, h, d = (float(v) for v in size)
        return (f"Specimen a {w:g} x {h:g} x {d:g} mm box of spheres (3D); the paper's is a {pw:g} x {ph:g} mm section "
                "(2D), its forces those of a unit thickness: compare shares and strains, not forces.")
    w, h = size
    same = (float(w), float(h)) == (pw, ph)
    return (f"Specimen {float(w):g} x {float(h):g} mm" + (", as the paper's." if same else
            f"; the paper's is {pw:g} x {ph:g} mm ({pw * ph / (float(w) * float(h)):.3g} times the area; "
            "docs/scenarios.md compares 40 and 100 mm runs)."))


def _f(v, fmt="{:.2f}"):
    """A table cell: '-' for None or NaN."""
    return "-" if v is None or v != v else fmt.format(v)


def write_tables(out, res):
    """table.md and table.csv in the form of the paper's Tables 3.4 / 3.6, with the paper's values
    of the same run beside ours (when the paper has the run) and the specimen size against the paper's."""
    rows = final_rows(res)
    key = paper_key(res)
    cond = run_conditions(res)
    # the paper's values stand beside a run of its conditions only
    ref = TABLE_FORCES.get(key, {}) if not cond else {}
    for r in rows:
        p = ref.get(r["kind"], {})
        r.update(paper_fn_p05_kN=p.get("p05"), paper_fn_p95_kN=p.get("p95"), paper_broken_pct=p.get("broken_pct"))
    with open(os.path.join(out, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    t = res["times_days"][-1] if res["times_days"] else float("nan")
    lines = [f"# {LABEL.get(res['scenario'], res['scenario'])}, {res['behaviour']}, damage {'on' if res['damage'] else 'off'}: "
             f"normal contact forces at t = {t:g} days", "", (f"Conditions: {'; '.join(cond)}. " if cond else "") + size_note(res), "",
             "| contact | contacts | 5 % Fn (kN) | 5 % paper (kN) | 95 % Fn (kN) | 95 % paper (kN) | broken (%) | broken paper (%) | new contacts |",
             "|---|---|---|---|---|---|---|---|---|"]
    box = res.get("dim") == 3
    fn = "{:.3g}" if box else "{:.2f}"  # a sphere's facet carries forces three decades below a section's unit thickness
    for r in rows:
        lines.append(f"| {r['kind']} | {r['n_contacts']} | {fn.format(r['fn_p05_kN'])} | {_f(r['paper_fn_p05_kN'], '{:.1f}')} | {fn.format(r['fn_p95_kN'])} | "
                     f"{_f(r['paper_fn_p95_kN'], '{:.1f}')} | {r['broken']} ({r['broken_pct']:.1f}) | {_f(r['paper_broken_pct'], '{:.1f}')} | "
                     f"{'-' if r['born_broken'] is None else r['born_broken']} |")
    sx, sy = res["swelling_strain_x"], res["swelling_strain_y"]
    table = {"nodmg": "3.4", "dmg": "3.6"}[key[2]] if key else None
    paper_line = (f"Paper: Table {table}, its {LABEL[key[0]]} {BEHAVIOUR_WORDS[key[1]]} run. " if key and not cond else
                  f"Paper: its runs are free 2D sections at 20 C with its parameters; this run differs ({'; '.join(cond)}), so "
                  "the paper's values are not set beside it. " if cond else "Paper: no run of these settings. ")
    lines += ["", paper_line
              + "Broken: contacts bonded at the start that broke (share of the kind's contacts). New contacts: "
              "contacts made during the run by discs coming into touch, born broken (compression only), not counted as broken. "
              "Variations to a reference run (the paper's Table 3.7 form): scripts/compare_runs.py or scripts/paper_study.py."]
    structures = [k for k in kinds_of(res) if k in STRUCTURE_KIND_IDS]
    if structures:
        what = {"PLATEN": "PLATEN: platen-specimen contacts (elastic, never break)",
                "STEEL": "STEEL: contacts along a bar (elastic, never break)",
                "BOND": "BOND: bar-concrete contacts (the ITZ's law and strength unless --kind-param BOND.<attribute> sets them)"}
        lines += ["", "Structures' contacts: " + "; ".join(what[k] for k in structures) + "."]
    state = run_state(res)
    if state != "finished":
        lines += ["", f"Run not finished ({state}): the numbers are those of its last step done."]
    if sx:
        z = (f", z {res['swelling_strain_z'][-1] * 1e6:.0f}e-6, volume {res['swelling_strain_volume'][-1] * 1e6:.0f}e-6"
             if box and res.get("swelling_strain_z") else "")
        lines += ["", f"Final swelling strain: x {sx[-1] * 1e6:.0f}e-6, y {sy[-1] * 1e6:.0f}e-6{z}. "
                      f"{res['n_particles']} particles, {iterations_text(res)}, wall {res['wall_s']:.1f} s."]
    with open(os.path.join(out, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return rows


def _title(res):
    """The run: scenario, behaviour, damage, its numerics (run_numerics) and its conditions away from
    the paper's (run_conditions)."""
    cond, numerics = run_conditions(res), run_numerics(res)
    return (f"{LABEL.get(res['scenario'], res['scenario'])}, {res['behaviour']}, damage {'on' if res['damage'] else 'off'}"
            + (f"; {', '.join(numerics)}" if numerics else "") + (f"\n{', '.join(cond)}" if cond else ""))


def _save(fig, path, dpi=120):
    fig.tight_layout()
    fig.savefig(path, dpi=dpi, bbox_inches="tight")  # legends placed outside the axes stay in
    _plt().close(fig)


def _step_ends(res):
    """Cumulative iteration [-] at the end of each converged step."""
    return np.cumsum(np.asarray(res.get("iterations_per_step") or [], dtype=float))


def _history(res):
    """(cumulative iterations, unbalanced-force ratios) of the run's unbalanced-force history, or
    of its converged steps only when it has none (results.json of a solver without history)."""
    h = res.get("unbalanced_history") or {}
    if h.get("iteration"):
        return np.asarray(h["iteration"], dtype=float), np.asarray(h["ratio"], dtype=float), True
    return _step_ends(res), np.asarray(res.get("unbalanced_ratio") or [], dtype=float), False


def _tolerance(res):
    """The tolerance a run used (results.json 'tolerance', the solver's as run), or None if the
    file does not say (then no tolerance line is drawn)."""
    return res.get("tolerance") or (res.get("solver_settings") or {}).get("tolerance") or res.get("config", {}).get("tolerance")


def plot_unbalanced(path, res):
    """The paper's Figures 3.3-3.5 and 3.9-3.11 (left): the unbalanced-force ratio against the
    cumulative iterations, log scale, step ends marked and labelled with their physical time at
    each decade; below, the iterations each step took."""
    plt = _plt()
    from matplotlib.transforms import blended_transform_factory
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, gridspec_kw={"height_ratios": [3, 1.4]})
    it, ratio, full = _history(res)
    ends = _step_ends(res)
    every = (res.get("unbalanced_history") or {}).get("every")
    if full:
        ax.semilogy(it, ratio, "-", color="tab:blue", lw=0.8,
                    label=f"unbalanced-force ratio\n(every {every} iterations, each step's first and last)")
    at_end = np.asarray(res["unbalanced_ratio"], dtype=float)
    n = min(len(ends), len(at_end))
    ax.semilogy(ends[:n], at_end[:n], "o", ms=3, color="navy", label="at convergence (step end)")
    ro = np.array(res.get("step_at_round_off", [False] * n), dtype=bool)[:n]
    limit = np.asarray(res.get("round_off_ratio") or [], dtype=float)
    if len(limit) >= n and n and np.isfinite(limit[:n]).any():
        # the ratio below which the positions resolve no better equilibrium, at each step's end
        ax.semilogy(ends[:n], limit[:n], "_", ms=9, mew=1.5, color="tab:orange",
                    label="round-off limit of the positions\n(no equilibrium resolved below it)")
    if ro.any():  # steps that ended above the tolerance: at that limit, or settled by the implicit solver's relaxation
        above = ro & (at_end[:n] > limit[:n]) if len(limit) >= n else np.zeros(n, dtype=bool)
        at = ro & ~above
        if at.any():
            ax.semilogy(ends[:n][at], at_end[:n][at], "x", color="tab:red",
                        label=f"step ended at the round-off limit\n({int(at.sum())} of {n} steps)")
        if above.any():
            ax.semilogy(ends[:n][above], at_end[:n][above], "+", ms=8, color="tab:purple",
                        label=f"step settled by relaxation above the tolerance\n({int(above.sum())} of {n} steps)")
    if _tolerance(res):
        met = n - int(ro.sum())
        ax.axhline(_tolerance(res), color="k", lw=0.8, ls=":", label=f"tolerance {_tolerance(res):g}\n(met by {met} of {n} steps)")
    trans = blended_transform_factory(ax.transData, ax.transAxes)
    for k, x in enumerate(ends):
        ax.axvline(x, color="0.6", lw=0.4, zorder=0)
        t = res["times_days"][k] if k < len(res["times_days"]) else None
        if t is not None and abs(math.log10(t) - round(math.log10(t))) < 1e-6:
            ax.text(x, 0.98, f" {t:g} d", transform=trans, rotation=90, va="top", ha="right", fontsize=7, color="0.35")
    ax.plot([], [], color="0.6", lw=0.6, label="step ends\n(physical time at each decade)")
    ax.set(ylabel="unbalanced-force ratio [-]", title=f"{_title(res)}: convergence of every step")
    ax.grid(True, which="major", axis="y", lw=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    per_step = np.asarray(res.get("iterations_per_step") or [], dtype=float)
    ax2.plot(ends, per_step, "o-", ms=3, color="tab:green", lw=1, label="iterations of each step\n(at its end)")
    ax2.set(xlabel=f"cumulative {_iteration_name(res)} iterations [-]", ylabel="iterations per step [-]")
    ax2.grid(True, which="major", lw=0.3)
    ax2.set_ylim(bottom=0)
    ax2.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    _save(fig, path)


def run_kinetics(res):
    """The swelling kinetics the run's swelling phase followed: (tau_c [day], tau_L [day] at the
    reference temperature, days [day], temperatures [K] of its history (empty: the reference
    temperature throughout), reference temperature [K], Uc [K], UL [K]), from results.json's kinds
    and temperature record; the scenario's kinetics at 20 C for a record without them."""
    name = (swelling_kinds(res) or ["MORTAR"])[0]
    k = (res.get("kinds") or {}).get(name) or {}
    sc = SCENARIOS.get(res["scenario"])
    tau_c, tau_l, _ = KINETICS[sc["kinetics"] if sc else "isr"]  # an own scene's kinds record their own (kinds' tauC, tauL)
    temp = ((res.get("temperature") or {}).get("per_kind") or {}).get(name) or {}
    return (float(k.get("tauC", tau_c)), float(k.get("tauL", tau_l)), list(temp.get("days") or []),
            list(temp.get("temperatures_K") or []), float(k.get("referenceTemperature", LARIVE_T0)),
            float(k.get("Uc", LARIVE_UC)), float(k.get("UL", LARIVE_UL)))


def swelling_kinds(res):
    """The kinds whose contacts swell in the run: the scenario's (asr-coarse: AGG, its gel pockets);
    for a scene of one's own (a 'scenario' that is none of the paper's, swelldem.dem.standard_outputs)
    the kinds its results.json records with swelling on and swellDispInf > 0."""
    sc = SCENARIOS.get(res.get("scenario"))
    if sc is not None:
        return list(sc["swelling_kinds"] or ("AGG",))
    return [n for n, k in (res.get("kinds") or {}).items() if k.get("swelling") and (k.get("swellDispInf") or 0) > 0]


def run_eps_inf(res):
    """The free swelling strain at infinity of the run's swelling phase [-]: the scenario's eps_inf
    (config), or for a scene of one's own its swelling kind's swellDispInf over 2 R_mean (the
    paper's micro-macro rule read backwards)."""
    cfg = res.get("config") or {}
    if "eps_inf" in cfg or res.get("scenario") in SCENARIOS:
        return cfg.get("eps_inf", EPS_INF)
    names = swelling_kinds(res)
    r_mean = res.get("r_mean_m")
    return res["kinds"][names[0]]["swellDispInf"] / (2 * r_mean) if names and r_mean else 0.0


def run_free_swelling(res, t, t0):
    """The free swelling strain [-] of the run's swelling phase at times t [day] since t0 [day], under
    the run's own kinetics and temperature history: eps_inf (xi(t) - xi(t0)) (run_eps_inf)."""
    eps_inf = run_eps_inf(res)
    tau_c, tau_l, days, temps, T0, Uc, UL = run_kinetics(res)
    xi = larive_xi_under(np.append(np.asarray(t, dtype=float), t0), tau_c, tau_l, days, temps, T0, Uc, UL)
    return eps_inf * (xi[:-1] - xi[-1])


def _free_swelling_curve(ax, res, t_last, specimen_max):
    """The scenario's free swelling eps_inf (xi(t) - xi(t0)) as a black dashed line [1e-6], on a
    right-hand axis of its own when the specimen swells less than a fifth of it (ASR-coarse: only
    the gel pockets swell), so that the specimen's curves keep the height of the plot. Then the
    legend of both axes."""
    cfg = res.get("config") or {}
    if not swelling_kinds(res):  # a scene of one's own in which nothing swells
        ax.legend(fontsize=7, loc="upper left")
        return
    eps_inf = run_eps_inf(res)
    t0 = (res.get("solver_settings") or {}).get("tStart", cfg.get("t_start_days", 1.0))  # --solver-param tStart= has the last word
    tau_c, tau_l, days, temps, T0, Uc, UL = run_kinetics(res)
    tt = np.geomspace(t0, t_last, 200)
    free = run_free_swelling(res, tt, t0) * 1e6
    if len(days) == 1:  # one temperature: the kinetics' times at it
        f = lambda U: math.exp(U * (1 / temps[0] - 1 / T0))  # noqa: E731
        at = f"at {temps[0] - 273.15:g} C: $\\tau_c$ {tau_c * f(Uc):.3g} d, $\\tau_L$ {tau_l * f(UL):.3g} d"
    elif days:
        at = f"under the run's temperature history ($\\tau_c$ {tau_c:g} d, $\\tau_L$ {tau_l:g} d at {T0 - 273.15:g} C)"
    else:
        at = f"$\\tau_c$ {tau_c:g} d, $\\tau_L$ {tau_l:g} d"
    if res["scenario"] != "asr-coarse":
        phase = " and ".join(swelling_kinds(res)) + " contacts"
    elif cfg.get("gel_displacement", "rule") == "aggregate":  # the pockets' d set so that the aggregate swells by eps_inf
        phase = "reactive aggregate, gel pockets at 2 $R_{mean} \\varepsilon_\\infty$ / gel fraction"
    else:
        phase = "gel pockets"
    apart = specimen_max == specimen_max and specimen_max < 0.2 * free.max()
    fax = ax.twinx() if apart else ax
    fax.semilogx(tt, free, "--", color="k", lw=1,
                 label=f"free swelling of the swelling phase ({phase}){', right axis' if apart else ''}:\n"
                       f"$\\varepsilon_\\infty$ = {eps_inf * 1e6:g}e-6 x Larive $\\xi(t)$, {at}")
    if apart:
        fax.set_ylabel("free swelling [1e-6]")
    handles = ax.get_legend_handles_labels()[0] + (fax.get_legend_handles_labels()[0] if apart else [])
    ax.legend(handles=handles, fontsize=7, loc="upper left")


def _max(*series):
    values = [v for s in series for v in (s or []) if v == v]
    return max(values) * 1e6 if values else float("nan")


def plot_strain(path, res):
    """The paper's Figures 3.3-3.5 and 3.9-3.11 (right): swelling strain against log time, with
    the free swelling of the swelling phase; for a 3D box the z strain too, and below, the volume
    change with the free swelling's (1 + eps)^3 - 1."""
    plt = _plt()
    t = np.array(res["times_days"])
    box = "swelling_strain_volume" in res
    if box:
        fig, (ax, axv) = plt.subplots(2, 1, figsize=(7, 7.2), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    else:
        fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.semilogx(t, np.array(res["swelling_strain_x"]) * 1e6, "o-", ms=3, label="specimen, x")
    ax.semilogx(t, np.array(res["swelling_strain_y"]) * 1e6, "s-", ms=3, label="specimen, y")
    if "swelling_strain_z" in res:
        ax.semilogx(t, np.array(res["swelling_strain_z"]) * 1e6, "^-", ms=3, label="specimen, z")
    loaded = _structures(res)
    # under platens, an applied stress or bars the specimen's strain is the swelling's and the load's
    ylabel = "strain of the specimen (swelling and load) [1e-6]" if loaded else "swelling strain [1e-6]"
    ax.set(xlabel=None if box else "time [day]", ylabel=ylabel, title=_title(res))
    ax.grid(True, which="both", lw=0.3)
    along = _max(res["swelling_strain_x"], res["swelling_strain_y"], res.get("swelling_strain_z"))
    if len(t):
        _free_swelling_curve(ax, res, t[-1], along if box else _max(res["swelling_strain_x"], res["swelling_strain_y"]))
    if box:
        _volume_panel(axv, res, t, along)
    _save(fig, path)


def _volume_panel(ax, res, t, along):
    """A 3D box's volume change against log time [1e-6], with the free swelling's volume change
    (1 + eps)^3 - 1 where the free swelling shares the strains' axis (not under ASR-coarse's gel
    pockets, whose free swelling the specimen's is a fraction of: _free_swelling_curve)."""
    ax.semilogx(t, np.array(res["swelling_strain_volume"]) * 1e6, "D-", ms=3, color="tab:purple", label="specimen, volume change $\\Delta V / V$")
    if len(t) and swelling_kinds(res):
        cfg = res.get("config") or {}
        t0 = (res.get("solver_settings") or {}).get("tStart", cfg.get("t_start_days", 1.0))
        tt = np.geomspace(t0, t[-1], 200)
        free = run_free_swelling(res, tt, t0)
        if not along < 0.2 * free.max() * 1e6:
            ax.semilogx(tt, ((1 + free) ** 3 - 1) * 1e6, "--", color="k", lw=1,
                        label="free swelling of the swelling phase, its volume change $(1 + \\varepsilon)^3 - 1$")
    ax.set(xlabel="time [day]", ylabel="volume change [1e-6]")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7, loc="upper left")


def _structures(res):
    """The run's structures that load the specimen: platen axes (boundary other than free) and bars."""
    cfg = res.get("config") or {}
    axes = [a for a in ("x", "y", "z") if cfg.get(f"boundary_{a}", "free") != "free"]
    return axes + (["bars"] if res.get("rebar") else [])


def plot_structure_stress(path, res):
    """structure_stress.png of a run with platens or bars: the platens' mean normal stress on the
    specimen per axis and the bars' largest and mean axial stress against time [MPa], compression
    negative, in their kinds' colours (COLORS), with the bars' yield stress (named only, when the
    bars stay below a quarter of it)."""
    plt = _plt()
    t = np.array(res["times_days"])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    cfg = res.get("config") or {}
    for axis in ("x", "y", "z"):
        if cfg.get(f"boundary_{axis}", "free") != "free":
            ax.semilogx(t, np.array(res[f"platen_stress_{axis}_Pa"]) / 1e6, {"x": "o-", "y": "^-", "z": "s-"}[axis], ms=3,
                        color=COLORS["PLATEN"], label=f"platens on the {axis} sides ({cfg[f'boundary_{axis}']}): mean normal stress")
    if res.get("rebar"):
        bar = res["rebar"]
        ax.semilogx(t, np.array(res["rebar_stress_max_Pa"]) / 1e6, "s-", ms=3, color=COLORS["STEEL"],
                    label=f"bars ({100 * bar['ratio']:g} %, {bar['n_bars']}): largest axial stress")
        ax.semilogx(t, np.array(res["rebar_stress_mean_Pa"]) / 1e6, "s--", ms=3, mfc="none", color=COLORS["STEEL"],
                    label="bars: mean axial stress")
        fy = bar["yield_stress_Pa"] / 1e6
        if np.nanmax(np.abs(res["rebar_stress_max_Pa"] or [0.0])) / 1e6 >= 0.25 * fy:
            ax.axhline(fy, color="k", lw=0.8, ls=":", label=f"steel yield stress {fy:g} MPa")
        else:  # a line far above the stresses would flatten them to the axis
            ax.plot([], [], " ", label=f"steel yield stress {fy:g} MPa (above the plot)")
    ax.axhline(0, color="0.5", lw=0.5)
    ax.set(xlabel="time [day]", ylabel="stress [MPa] (tension > 0)", title=_title(res))
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    _save(fig, path)


def _capacity(ax, res, name):
    """The kind's tensile capacity f_t A: its median over the kind's contacts as a dashed line,
    its range (min-max) as a grey band [kN]."""
    cap = (res.get("tensile_capacity_kN") or {}).get(name)
    if not cap:
        return
    ax.axhspan(cap["min"], cap["max"], color="0.5", alpha=0.18, lw=0,
               label=f"tensile capacity $f_t A$, min-max ({cap['min']:.3g}-{cap['max']:.3g} kN)")
    ax.axhline(cap["median"], color="k", ls="--", lw=1,
               label=f"$f_t A$ median {cap['median']:.3g} kN ($f_t$ = {cap['f_t_Pa'] / 1e6:g} MPa)")


def _force_panel(ax, res, name, legend=True):
    t = np.array(res["times_days"])
    d = res["per_kind"][name]
    ax.fill_between(t, d["fn_p05_kN"], d["fn_p95_kN"], color=COLORS[name], alpha=0.15, lw=0)
    ax.semilogx(t, d["fn_p95_kN"], "-", color=COLORS[name], label="95 % quantile")
    ax.semilogx(t, d["fn_p05_kN"], "--", color=COLORS[name], label="5 % quantile")
    _capacity(ax, res, name)
    ax.axhline(0, color="0.3", lw=0.5)
    ax.grid(True, which="major", lw=0.3)
    if legend:
        ax.legend(fontsize=6.5, loc="best")


def plot_forces(path, res):
    """The paper's Figures 3.6-3.8 and 3.12-3.14 for one run: one panel per contact kind (the
    structures' kinds after the paper's three, kinds_of), the 5 % and 95 % normal-force quantiles
    against log time with the kind's tensile capacity; with damage a row below with the broken
    share of the kind's bonded contacts."""
    plt = _plt()
    rows = 2 if res["damage"] else 1
    kinds = kinds_of(res)
    fig, axes = plt.subplots(rows, len(kinds), figsize=(13 * len(kinds) / 3, 4.2 if rows == 1 else 6), sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": [3, 1.2][:rows]})
    t = np.array(res["times_days"])
    for c, name in enumerate(kinds):
        ax = axes[0, c]
        if res["n_contacts_by_kind"].get(name):
            _force_panel(ax, res, name)
        ax.set(title=f"{name} contacts", ylabel="normal contact force [kN] (tension > 0)" if c == 0 else None)
        if rows == 2:
            n = res["n_contacts_by_kind"].get(name) or 1
            axes[1, c].semilogx(t, 100.0 * np.array(res["per_kind"][name]["broken"]) / n, "-", color=COLORS[name])
            axes[1, c].set(ylabel="broken [%]" if c == 0 else None)
            axes[1, c].grid(True, which="major", lw=0.3)
        for a in axes[-1:, c]:
            a.set(xlabel="time [day]")
    fig.suptitle(_title(res), fontsize=11)
    _save(fig, path)


def plot_curves(out, res):
    """swelling_strain.png, unbalanced.png and force_quantiles.png of one run in `out`, and
    structure_stress.png when platens or bars load it."""
    plot_strain(os.path.join(out, "swelling_strain.png"), res)
    plot_unbalanced(os.path.join(out, "unbalanced.png"), res)
    plot_forces(os.path.join(out, "force_quantiles.png"), res)
    if _structures(res):
        plot_structure_stress(os.path.join(out, "structure_stress.png"), res)


def _fill_aggregates(ax, polygons_mm):
    """The aggregates of a crack map, (k, 2) polygons [mm] filled grey: a section's in 2D, the
    polyhedra's cuts by a section plane in 3D."""
    for p in polygons_mm:
        ax.fill(p[:, 0], p[:, 1], color="0.85", lw=0.5, ec="0.5")


def _add_cracks(ax, lines_by_kind, labels):
    """The broken contacts of a crack map: per kind name its lines ([(x, y) ...] in mm, each a
    facet's trace) in the kind's colour (COLORS), labelled labels[kind] in the legend."""
    from matplotlib.collections import LineCollection
    for kname, segs in lines_by_kind.items():
        if segs:
            # a structure's broken contact drawn thicker: one bond facet against hundreds of mortar ones
            ax.add_collection(LineCollection(segs, colors=COLORS[kname], linewidths=1.2 if kname in KIND_NAMES else 2.5,
                                             label=labels[kname]))


def _frame(ax, width_mm, height_mm, xlabel, ylabel, title):
    ax.set_xlim(0, width_mm)
    ax.set_ylim(0, height_mm)
    ax.set_aspect("equal")
    ax.set(xlabel=xlabel, ylabel=ylabel, title=title)


def _map_kinds(res):
    """The kinds a crack map draws, by name: the run's (kinds_of) or, for a results dict without
    per-kind series, the paper's three."""
    return kinds_of(res) if res.get("per_kind") else list(KIND_NAMES)


def _map_title(res, step):
    t = res["times_days"][step] if res["times_days"] else float("nan")
    return f"crack map: {LABEL.get(res['scenario'], res['scenario'])}, {res['behaviour']}, t = {t:.4g} d"


def plot_crack_map(out, res, assembly, broken_contacts, step=-1, name="crack_map.png", segments=None):
    """Broken contacts drawn as their Laguerre facets, coloured by kind (COLORS), over the
    mesostructure, with the bars and platens in their kinds' colours; `step`: the index into
    times_days of the time the map shows (-1: the last); segments: {(id1, id2): (x1, y1, x2, y2)
    [m]} of contacts that are not the assembly's (a broken BOND contact; load_breaks'
    'segment_m'), drawn across their normal. A 3D box's map is plot_crack_sections' (its rows
    returned; None for a 2D section)."""
    if getattr(assembly, "dim", 2) == 3:
        return plot_crack_sections(out, res, assembly, broken_contacts, step=step, name=name)
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 7 * assembly.height_m / assembly.width_m))
    _fill_aggregates(ax, [np.asarray(poly) * 1e3 for poly in assembly.polygons])
    index = {(int(i), int(j)): c for c, (i, j) in enumerate(assembly.contacts)}
    bar = res.get("rebar")
    if bar and res.get("rebar_stress_mean_Pa"):  # the bars (swelldem.dem.rebar), with their stress at that time
        # rounded first, so that a stress of -0.01 MPa prints as 0, not -0
        mean, big = (round(res[f"rebar_stress_{w}_Pa"][step] / 1e6) + 0 for w in ("mean", "max"))
        for n, y in enumerate(bar["y_m"]):
            ax.plot([0, assembly.width_m * 1e3], [y * 1e3] * 2, "-", color=COLORS["STEEL"], lw=3, alpha=0.6,
                    label=f"bar ({100 * bar['ratio']:g} %): stress mean {mean:.0f}, largest {big:.0f} MPa" if n == 0 else None)
    cfg = res.get("config") or {}
    for axis in ("x", "y"):  # the platens, at the specimen's sides
        if cfg.get(f"boundary_{axis}", "free") != "free":
            w, h = assembly.width_m * 1e3, assembly.height_m * 1e3
            for n, edge in enumerate((0.0, w if axis == "x" else h)):
                xy = ([edge, edge], [0, h]) if axis == "x" else ([0, w], [edge, edge])
                ax.plot(*xy, "-", color=COLORS["PLATEN"], lw=4, solid_capstyle="butt", clip_on=False,
                        label=f"platens on the {axis} sides ({cfg[f'boundary_{axis}']})" if n == 0 else None)
    lines = {}
    for kname in _map_kinds(res):
        k = {v: kk for kk, v in KIND_NAME_OF_ID.items()}[kname]
        segs = lines.setdefault(kname, [])
        for i, j, kind in broken_contacts:
            pair = (min(i, j), max(i, j))
            if kind != k:
                continue
            c = index.get(pair) if kind in (0, 1, 2) else None
            s = assembly.facet_segment_m[c] if c is not None else (segments or {}).get(pair)
            if s is not None and np.all(np.isfinite(s)):
                s = np.asarray(s) * 1e3
                segs.append([(s[0], s[1]), (s[2], s[3])])
    _add_cracks(ax, lines, {kname: f"{kname} ({len(segs)} broken)" for kname, segs in lines.items()})
    _mark_faces(ax, res, assembly.width_m * 1e3, assembly.height_m * 1e3)
    _frame(ax, assembly.width_m * 1e3, assembly.height_m * 1e3, "x [mm]", "y [mm]", _map_title(res, step))
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper right", fontsize=8)
    _save(fig, os.path.join(out, name), dpi=130)


#: The file of a 3D box's crack maps' counts, one row per map, section and kind (crack_section_rows).
CRACK_SECTIONS_FILE = "crack_sections.csv"
AXIS_NAMES = ("x", "y", "z")


def facet_trace(polygon, axis, level):
    """The chord that the plane coordinate[axis] = level cuts from a planar convex polygon ((k, 3)
    vertices in loop order) as two (3,) points; None when the plane misses it. A polygon lying in
    the plane (every vertex within 1e-9 of its own size of it) has no chord: its closed outline,
    k + 1 points, is returned instead."""
    v = np.asarray(polygon, dtype=float)
    d = v[:, axis] - level
    if np.all(np.abs(d) <= 1e-9 * max(float(np.ptp(v, axis=0).max()), 1e-300)):
        return np.vstack([v, v[:1]])
    pts = []
    for k in range(len(v)):
        a, b = k, (k + 1) % len(v)
        if d[a] == 0.0:
            pts.append(v[a])
        elif d[a] * d[b] < 0.0:
            pts.append(v[a] + d[a] / (d[a] - d[b]) * (v[b] - v[a]))
    if len(pts) < 2:
        return None
    pts = np.asarray(pts)
    # a vertex on the plane between two edges that cross it gives more than two points, all on one line
    far = np.linalg.norm(pts[:, None] - pts[None], axis=2)
    i, j = np.unravel_index(int(np.argmax(far)), far.shape)
    return np.array([pts[i], pts[j]])


def crack_sections(assembly, broken_contacts, kinds):
    """The three mid-plane sections of a 3D box's crack map (swelldem.meso.plot3d.SECTIONS' order:
    z = D/2, y = H/2, x = W/2), each a dict: 'axis' (its normal, 'x' | 'y' | 'z'), 'normal', 'hor',
    'ver' (axis indices), 'level_m', 'slab_m' (the mean sphere radius), 'aggregates': the
    polyhedra's cuts by the plane as (k, 2) polygons in (hor, ver) [mm], and per kind name of
    `kinds`: 'lines' (each broken contact of the slab as its facet's trace at its centroid's level,
    in (hor, ver) [mm]), 'in_slab' (the broken contacts whose facet centroid lies within slab_m of
    the plane) and 'in_box' (every broken contact of the kind). broken_contacts: (id1, id2, kindId)."""
    from .meso.plot3d import SECTIONS, section_polygon
    index = {(int(i), int(j)): c for c, (i, j) in enumerate(assembly.contacts)}
    ids = {name: kk for kk, name in KIND_NAME_OF_ID.items()}
    by_kind = {name: [] for name in kinds}
    in_box = {name: 0 for name in kinds}
    for i, j, kind in broken_contacts:
        name = KIND_NAME_OF_ID.get(int(kind))
        if name not in by_kind:
            continue
        in_box[name] += 1
        c = index.get((min(int(i), int(j)), max(int(i), int(j)))) if int(kind) == ids.get(name) else None
        if c is not None:
            by_kind[name].append(c)
    size = np.asarray(assembly.specimen_size_m, dtype=float)
    slab = float(np.mean(assembly.r))
    centroid = np.asarray(assembly.facet_centroid_m)
    sections = []
    for normal, hor, ver in SECTIONS:
        level = float(size[normal] / 2)
        sec = {"axis": AXIS_NAMES[normal], "normal": normal, "hor": hor, "ver": ver, "level_m": level, "slab_m": slab,
               "aggregates": [], "lines": {}, "in_slab": {}, "in_box": dict(in_box)}
        for v in assembly.polyhedra:
            v = np.asarray(v)
            if v[:, normal].min() < level < v[:, normal].max():
                poly = section_polygon(v, normal, level)
                if poly is not None:
                    sec["aggregates"].append(poly[:, [hor, ver]] * 1e3)
        for name, cs in by_kind.items():
            near = [c for c in cs if abs(centroid[c, normal] - level) <= slab]
            lines = []
            for c in near:
                trace = facet_trace(assembly.facet_polygons[c], normal, centroid[c, normal])
                if trace is not None:
                    lines.append(trace[:, [hor, ver]] * 1e3)
            sec["lines"][name], sec["in_slab"][name] = lines, len(near)
        sections.append(sec)
    return sections


def crack_section_rows(sections, name, t_days):
    """The rows of crack_sections.csv of one map (file `name`, time t_days [day]): per section and
    kind the broken contacts in the slab and in the whole box."""
    return [{"map": name, "t_days": t_days, "section": f"{s['axis']} = {s['level_m'] * 1e3:g} mm",
             "slab_half_width_mm": s["slab_m"] * 1e3, "kind": kind, "broken_in_slab": s["in_slab"][kind],
             "broken_in_box": s["in_box"][kind]} for s in sections for kind in s["in_slab"]]


def write_crack_section_rows(out, rows):
    """crack_sections.csv in `out` from crack_section_rows' rows (of every map drawn)."""
    with open(os.path.join(out, CRACK_SECTIONS_FILE), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["map", "t_days", "section", "slab_half_width_mm", "kind", "broken_in_slab", "broken_in_box"])
        w.writeheader()
        w.writerows(rows)


def plot_crack_sections(out, res, assembly, broken_contacts, step=-1, name="crack_map.png"):
    """A 3D box's crack map: its three mid-plane sections side by side (crack_sections), each with
    the aggregates' cuts grey and the broken contacts of its slab as their facets' traces, coloured
    by kind as a 2D crack map; the legends count each kind's broken contacts in the slab and in the
    box. Returns the map's crack_section_rows."""
    plt = _plt()
    from matplotlib.lines import Line2D
    sections = crack_sections(assembly, broken_contacts, _map_kinds(res))
    size = np.asarray(assembly.specimen_size_m) * 1e3
    widths = [size[s["hor"]] / size[s["ver"]] for s in sections]  # panels of one height, each its section's aspect
    fig, axes = plt.subplots(1, 3, figsize=(15, 6.2), gridspec_kw={"width_ratios": widths})
    for ax, sec in zip(axes, sections):
        _fill_aggregates(ax, sec["aggregates"])
        labels = {k: f"{k}: {sec['in_slab'][k]} in the slab, {sec['in_box'][k]} in the box" for k in sec["lines"]}
        _add_cracks(ax, sec["lines"], labels)
        h, v = AXIS_NAMES[sec["hor"]], AXIS_NAMES[sec["ver"]]
        _frame(ax, size[sec["hor"]], size[sec["ver"]], f"{h} [mm]", f"{v} [mm]",
               f"section {sec['axis']} = {sec['level_m'] * 1e3:g} mm\n(slab {sec['axis']} = "
               f"{(sec['level_m'] - sec['slab_m']) * 1e3:.2f}-{(sec['level_m'] + sec['slab_m']) * 1e3:.2f} mm, "
               f"{len(sec['aggregates'])} aggregate{'' if len(sec['aggregates']) == 1 else 's'} cut)")
        ax.title.set_fontsize(9)
        # every kind broken somewhere in the box, the kinds none of whose cracks reach this slab too
        handles = [Line2D([], [], color=COLORS[k], label=labels[k]) for k in sec["lines"] if sec["in_box"][k]]
        if handles:
            ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=7.5, title="broken contacts",
                      title_fontsize=7.5)
    t = res["times_days"][step] if res["times_days"] else float("nan")
    fig.suptitle(f"{_map_title(res, step)}; {' x '.join(f'{v:g}' for v in size)} mm box, mid-plane sections\n"
                 f"drawn: the broken contacts whose facet centroid lies within the mean sphere radius "
                 f"({sections[0]['slab_m'] * 1e3:.3g} mm) of the plane, each as its facet's trace at its centroid's level; "
                 "aggregates cut by the plane grey", fontsize=9)
    _save(fig, os.path.join(out, name), dpi=130)
    return crack_section_rows(sections, name, t)


def plot_crack_view_3d(out, res, assembly, broken_contacts, step=-1, name="crack_map_3d_view.png"):
    """A 3D box's broken contacts as points at their facet centroids in a 3D view, coloured by kind
    (COLORS), with the box's edges; the legend counts them per kind. Named so that no
    crack_map_<day>d.png (a map at day 3 is crack_map_3d.png) can take its name."""
    plt = _plt()
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    index = {(int(i), int(j)): c for c, (i, j) in enumerate(assembly.contacts)}
    centroid = np.asarray(assembly.facet_centroid_m) * 1e3
    fig = plt.figure(figsize=(8, 7.5))
    ax = fig.add_subplot(projection="3d")
    ids = {name: kk for kk, name in KIND_NAME_OF_ID.items()}
    for kname in _map_kinds(res):
        cs = [index.get((min(i, j), max(i, j))) for i, j, kind in broken_contacts if kind == ids[kname]]
        cs = [c for c in cs if c is not None]
        if cs:
            p = centroid[cs]
            ax.scatter(p[:, 0], p[:, 1], p[:, 2], s=4, color=COLORS[kname], depthshade=True, label=f"{kname} ({len(cs)} broken)")
    W, H, D = np.asarray(assembly.specimen_size_m) * 1e3
    corners = np.array([[i * W, j * H, k * D] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    edges = [(p, q) for p in range(8) for q in range(p + 1, 8) if bin(p ^ q).count("1") == 1]
    ax.add_collection3d(Line3DCollection([corners[[p, q]] for p, q in edges], colors="k", linewidths=0.8))
    ax.set(xlim=(0, W), ylim=(0, H), zlim=(0, D), xlabel="x [mm]", ylabel="y [mm]", zlabel="z [mm]")
    ax.set_box_aspect((W, H, D))
    ax.view_init(elev=22, azim=-58)
    ax.set_title(f"{_map_title(res, step)}\nbroken contacts at their facet centroids (paler: farther), {W:g} x {H:g} x {D:g} mm box", fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", fontsize=8, markerscale=3)
    _save(fig, os.path.join(out, name), dpi=130)


def load_breaks(out):
    """The recorder's contact_breaks.npz in `out` as a dict of arrays ('pairs', 'kind',
    'break_step', 'times_days'), or None when the run has none."""
    path = os.path.join(out, "contact_breaks.npz")
    if not os.path.exists(path):
        return None
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def break_segments(breaks):
    """{(id1, id2): (x1, y1, x2, y2) [m]} of the contacts of load_breaks' dict (its 'segment_m'; {}
    for a file without it): what plot_crack_map draws for a contact that is not the assembly's."""
    if breaks is None or "segment_m" not in breaks:
        return {}
    return {(int(i), int(j)): s for (i, j), s in zip(breaks["pairs"], breaks["segment_m"])}


def broken_at(breaks, step):
    """(id1, id2, kindId) of the bonded contacts broken at or before step index `step`."""
    sel = (breaks["break_step"] >= 0) & (breaks["break_step"] <= step)
    return [(int(i), int(j), int(k)) for (i, j), k in zip(breaks["pairs"][sel], breaks["kind"][sel])]


def crack_map_days(res):
    """The times [day] of the intermediate crack maps: the run's latency time tau_L and 2 tau_L at
    its temperature, when it has one; under a temperature history the times at which its free
    swelling has done what it does by tau_L and 2 tau_L at the reference temperature (43 % and
    86 % for the paper's kinetics); those before the run's last step."""
    tau_c, tau_l, days, temps, T0, Uc, UL = run_kinetics(res)
    t = res["times_days"]
    if len(days) <= 1:
        scale = math.exp(UL * (1 / temps[0] - 1 / T0)) if days else 1.0
        marks = [tau_l * scale, 2 * tau_l * scale]
    else:
        ref = larive_xi_under(np.array([tau_l, 2 * tau_l]), tau_c, tau_l)
        grid = np.geomspace(1e-3, max(t[-1] if t else 1.0, 1.0) * 10, 4000)
        xi = larive_xi_under(grid, tau_c, tau_l, days, temps, T0, Uc, UL)
        marks = [float(np.interp(x, xi, grid)) for x in ref if x <= xi[-1]]
    return [float(f"{d:.4g}") for d in marks if t and t[0] <= d < t[-1]]


def plot_crack_maps(out, res, assembly, breaks, days, rows=None):
    """crack_map_<day>d.png in `out` for each time in `days` [day]: the contacts broken by the last
    step at or before it (from load_breaks). Returns the file names; a 3D box's maps add their
    crack_section_rows to the list `rows` when given."""
    times = np.asarray(res["times_days"], dtype=float)
    segments = break_segments(breaks)
    names = []
    for day in days:
        step = int(np.searchsorted(times, day * (1 + 1e-9), side="right")) - 1
        if step < 0:
            continue
        names.append(f"crack_map_{day:g}d.png")
        drawn = plot_crack_map(out, res, assembly, broken_at(breaks, step), step=step, name=names[-1], segments=segments)
        if rows is not None and drawn:
            rows.extend(drawn)
    return names


def write_all(out, res, assembly, broken_contacts):
    """Tables, curves, the crack map at the end and, with the recorder's contact_breaks.npz, at
    crack_map_days(res); broken_contacts: (id1, id2, kindId) of the broken contacts at the end. A
    3D box's maps are mid-plane sections (plot_crack_sections), with crack_map_3d_view.png (the broken
    contacts in 3D) and crack_sections.csv (the sections' counts)."""
    write_tables(out, res)
    plot_curves(out, res)
    breaks = load_breaks(out)
    rows = plot_crack_map(out, res, assembly, broken_contacts, segments=break_segments(breaks))
    if breaks is not None and res["damage"]:
        plot_crack_maps(out, res, assembly, breaks, crack_map_days(res), rows=rows)
    if getattr(assembly, "dim", 2) == 3:
        plot_crack_view_3d(out, res, assembly, broken_contacts)
        write_crack_section_rows(out, rows)
    plot_humidity_maps(out, res, assembly)


# ---- several runs on one figure (paper Figures 3.3-3.14: elastic / viscoelastic, damage / none)

#: Line colour by behaviour and style by damage in the overlays.
#: Entries of a run's config that say where and how often it wrote, not what was run.
_NOT_CONDITIONS = ("out", "vtk_every", "save_state")


def differing_settings(runs):
    """The settings (config entries of results.json, but where the run wrote) whose values differ
    between the runs (results dicts), in name order: what a comparison has to name so that a reader
    knows what was varied (e.g. ['kind_params'] for a sweep of the ITZ strength)."""
    from dataclasses import asdict
    from .scenario import VALUE_BEFORE_FIELD, SwellingTest
    configs = [r.get("config") or {} for r in runs]
    keys = sorted(set().union(*configs) - set(_NOT_CONDITIONS)) if configs else []
    text = lambda v: json.dumps(v, sort_keys=True, default=str)  # noqa: E731
    # a field a run's record lacks (made before the field existed) holds what that swelldem did
    before = {**json.loads(json.dumps(asdict(SwellingTest()), default=float)), **VALUE_BEFORE_FIELD}
    return [k for k in keys if len({text(c.get(k, before.get(k))) for c in configs}) > 1]


def setting_text(res, key):
    """A setting's value as a comparison prints it: numbers with %g, lists spaced, dicts as
    NAME=VALUE with nested names joined by dots (kind_params {"ITZ": {"tensileStrength": 3e6}} ->
    ITZ.tensileStrength=3e+06, the form of --kind-param)."""
    v = (res.get("config") or {}).get(key)
    if isinstance(v, dict):
        return " ".join(_name_values(v)) or "defaults"  # {}: nothing set away from the scenario's values
    return _setting_value(v)


def _name_values(settings, prefix=""):
    """NAME=VALUE texts of a dict of settings, sorted, nested names joined by dots."""
    if not isinstance(settings, dict):
        return [f"{prefix}={_setting_value(settings)}"]
    return [p for k in sorted(settings) for p in _name_values(settings[k], f"{prefix}.{k}" if prefix else str(k))]


def _setting_value(v):
    """A setting's value as text: numbers with %g, lists spaced."""
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, (list, tuple)):
        return " ".join(_setting_value(x) for x in v)
    return str(v)


def run_label(res, settings=()):
    """behaviour, damage, and the given settings (e.g. differing_settings of the runs compared)."""
    base = f"{res['behaviour']}, {'damage' if res['damage'] else 'no damage'}"
    extra = [f"{k} {setting_text(res, k)}" for k in settings if k not in ("behaviour", "damage")]
    return base + ("; " + ", ".join(extra) if extra else "")


def _style(res, k):
    """Each run its own colour (runs of one behaviour and damage setting, e.g. a sweep, must not
    draw alike); dashed with damage."""
    return {"color": f"C{k % 10}", "ls": "--" if res["damage"] else "-"}


def plot_strain_overlay(path, runs, title):
    """Swelling strain in x (the paper's "one direction") of several runs against log time, with
    the free swelling of the first run's scenario. runs: [(label, results dict)]."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    t_last = 0.0
    for k, (label, res) in enumerate(runs):
        t = np.array(res["times_days"])
        if len(t):
            ax.semilogx(t, np.array(res.get("swelling_strain_x") or [np.nan] * len(t)) * 1e6, marker="o", ms=2.5, label=label,
                        **_style(res, k))
            t_last = max(t_last, t[-1])
    ax.set(xlabel="time [day]", ylabel="swelling strain in x [1e-6]", title=title)
    ax.grid(True, which="both", lw=0.3)
    if runs and t_last > 0:
        _free_swelling_curve(ax, runs[0][1], t_last, _max(*(r.get("swelling_strain_x") for _, r in runs)))
    elif runs:
        ax.legend(fontsize=7, loc="upper left")
    _save(fig, path)


def plot_unbalanced_overlay(path, runs, title):
    """The unbalanced-force ratio of several runs against their cumulative iterations, log scale;
    dots at the step ends."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for k, (label, res) in enumerate(runs):
        it, ratio, full = _history(res)
        st = _style(res, k)
        if full:
            ax.semilogy(it, ratio, lw=0.7, alpha=0.9, label=f"{label} ({res.get('iterations', '?')} iterations)", **st)
        ends, at_end = _step_ends(res), np.asarray(res.get("unbalanced_ratio") or [], dtype=float)
        n = min(len(ends), len(at_end))
        ax.semilogy(ends[:n], at_end[:n], "o", ms=2.5, color=st["color"], label=None if full else f"{label}: step ends only")
    if runs and _tolerance(runs[0][1]):
        ax.axhline(_tolerance(runs[0][1]), color="k", lw=0.8, ls=":", label=f"tolerance {_tolerance(runs[0][1]):g}")
    ax.plot([], [], "o", ms=2.5, color="0.3", label="step ends")
    ax.set(xlabel="cumulative iterations [-]", ylabel="unbalanced-force ratio [-]", title=title)
    ax.grid(True, which="major", axis="y", lw=0.3)
    ax.legend(fontsize=7)
    _save(fig, path)


def plot_force_overlay(path, runs, title):
    """The paper's Figures 3.6-3.8 / 3.12-3.14 form: one row per run (e.g. elastic top,
    viscoelastic bottom), one column per contact kind, the 5 % / 95 % normal-force quantiles
    against log time with the tensile capacity; the rows of a column share their force axis."""
    plt = _plt()
    fig, axes = plt.subplots(len(runs), 3, figsize=(13, 3.2 * len(runs) + 0.6), sharex=True, sharey="col", squeeze=False)
    for r, (label, res) in enumerate(runs):
        for c, name in enumerate(KIND_NAMES):
            ax = axes[r, c]
            if res["n_contacts_by_kind"].get(name):
                _force_panel(ax, res, name, legend=(r == len(runs) - 1))
            ax.set_title(f"{name}: {label}", fontsize=9)
            if c == 0:
                ax.set_ylabel("normal force [kN]\n(tension > 0)")
            if r == len(runs) - 1:
                ax.set_xlabel("time [day]")
    fig.suptitle(title, fontsize=11)
    _save(fig, path)


def write_overlays(out, runs, prefix, title):
    """<prefix>_strain.png, <prefix>_unbalanced.png and <prefix>_forces.png of `runs` ([(label,
    results dict)]) in `out`; returns the file names."""
    names = [f"{prefix}_strain.png", f"{prefix}_unbalanced.png", f"{prefix}_forces.png"]
    plot_strain_overlay(os.path.join(out, names[0]), runs, title)
    plot_unbalanced_overlay(os.path.join(out, names[1]), runs, title)
    plot_force_overlay(os.path.join(out, names[2]), runs, title)
    return names


def write_results(out, res):
    """res as out/results.json (written to a temporary file, then renamed: never half a file)."""
    with open(os.path.join(out, "results.json.tmp"), "w") as f:
        json.dump(res, f, indent=1, default=float)
    os.replace(os.path.join(out, "results.json.tmp"), os.path.join(out, "results.json"))


#: The per-step curves of a run, next to results.json: a CSV with units in its header, and the same
#: columns in the text form of yade.plot.saveDataTxt.
CURVES_FILE, PLOT_DATA_FILE = "curves.csv", "plot_data.txt"

#: The per-step series of results.json's top level, in the curves' order: key -> (name, unit). Platen
#: series join only for an axis with platens (they are 0 on a free side); the bars' when present.
STEP_SERIES = {"times_days": ("t", "d"), "swelling_strain_x": ("swelling_strain_x", "-"),
               "swelling_strain_y": ("swelling_strain_y", "-"), "swelling_strain_z": ("swelling_strain_z", "-"),
               "swelling_strain_area": ("swelling_strain_area", "-"), "swelling_strain_volume": ("swelling_strain_volume", "-"),
               "platen_stress_x_Pa": ("platen_stress_x", "Pa"), "platen_disp_x_m": ("platen_disp_x", "m"),
               "platen_stress_y_Pa": ("platen_stress_y", "Pa"), "platen_disp_y_m": ("platen_disp_y", "m"),
               "platen_stress_z_Pa": ("platen_stress_z", "Pa"), "platen_disp_z_m": ("platen_disp_z", "m"),
               "rebar_stress_max_Pa": ("rebar_stress_max", "Pa"), "rebar_stress_mean_Pa": ("rebar_stress_mean", "Pa"),
               "unbalanced_ratio": ("unbalanced_ratio", "-"), "iterations_per_step": ("iterations", "-"),
               "step_at_round_off": ("step_at_round_off", "-"), "round_off_ratio": ("round_off_ratio", "-")}
#: Unit of a per-kind series by the suffix of its results.json key (none: a count or a ratio, '-').
_SUFFIX_UNITS = (("_kN", "kN"), ("_Pa", "Pa"), ("_m", "m"))


def _series_unit(key):
    for suffix, unit in _SUFFIX_UNITS:
        if key.endswith(suffix):
            return key[:-len(suffix)], unit
    return key, "-"


def curve_columns(res):
    """The run's per-step series as columns [(CSV header 'name [unit]', plot_data name, values)], in
    the order of STEP_SERIES, then per kind of results.json's per_kind each of its series with, after
    'broken', the broken share of the kind's bonded contacts [%]. The plot_data name is the series'
    results.json key, per kind in the flat form '<series>_<KIND>' (broken share: broken_pct_<KIND>);
    booleans become 0/1."""
    n = len(res.get("times_days") or [])
    cfg = res.get("config") or {}
    cols = []
    for key, (name, unit) in STEP_SERIES.items():
        values = res.get(key)
        if not isinstance(values, list) or len(values) != n:
            continue
        if key.startswith("platen_") and cfg.get(f"boundary_{key.split('_')[2]}", "free") == "free":
            continue
        cols.append((f"{name} [{unit}]", key, values))
    for kind, series in (res.get("per_kind") or {}).items():
        for key, values in series.items():
            if not isinstance(values, list) or len(values) != n:
                continue
            name, unit = _series_unit(key)
            cols.append((f"{kind} {name} [{unit}]", f"{key}_{kind}", values))
            total = (res.get("n_contacts_by_kind") or {}).get(kind)
            if key == "broken" and total is not None:
                share = [100.0 * v / total if total else float("nan") for v in values]
                cols.append((f"{kind} broken_pct [%]", f"broken_pct_{kind}", share))
    return [(h, p, [int(v) if isinstance(v, bool) else v for v in values]) for h, p, values in cols]


def truncate_steps(res, k):
    """Cuts every per-step series of `res` (STEP_SERIES, per_kind's) to its first k steps."""
    for key in STEP_SERIES:
        if isinstance(res.get(key), list):
            del res[key][k:]
    for series in (res.get("per_kind") or {}).values():
        for values in series.values():
            if isinstance(values, list):
                del values[k:]


def _replace(path, text):
    with open(path + ".tmp", "w", newline="") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def write_curves(out, res):
    """out/curves.csv and out/plot_data.txt, one row per converged step (curve_columns), each
    written to a temporary file, then renamed. The CSV's floats are repr's, which read back to the
    same doubles as results.json's. plot_data.txt is what yade.plot.saveDataTxt(file, vars=names)
    writes from yade.plot.data holding these columns: '# ' and the names joined by two tabs, then a
    row per step of str() values joined by a tab; numpy.genfromtxt(file, names=True) reads it, and
    yade.plot.data = {name: list(column)} gives it back to yade.plot."""
    cols = curve_columns(res)
    n = len(cols[0][2]) if cols else 0
    import io
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([h for h, _, _ in cols])
    w.writerows([[repr(c[2][i]) if isinstance(c[2][i], float) else c[2][i] for c in cols] for i in range(n)])
    _replace(os.path.join(out, CURVES_FILE), buf.getvalue())
    lines = ["# " + "\t\t".join(p for _, p, _ in cols)] + ["\t".join(str(c[2][i]) for c in cols) for i in range(n)]
    _replace(os.path.join(out, PLOT_DATA_FILE), "\n".join(lines) + "\n")


#: A variation is shown only against a reference force of at least this [kN]: the paper prints "-"
#: against its 0.0 kN references (0.1 kN precision), and a reference near 0 makes any percentage
#: meaningless.
VARIATION_MIN_REFERENCE_KN = 0.05


def paper_variation(reference, res):
    """The paper's variation columns [%] of run `res` against `reference` per kind, {kind: (5 %,
    95 %)}, when the pair is one of the paper's (Table 3.4: viscoelastic against elastic, no
    damage; Table 3.6: the same with damage; Table 3.7: viscoelastic with damage against elastic
    without); None otherwise."""
    ref, run = paper_key(reference), paper_key(res)
    if ref is None or run is None or ref[0] != run[0] or ref[1] != "el" or run[1] != "ve":
        return None
    table = {("nodmg", "nodmg"): "3.4", ("dmg", "dmg"): "3.6", ("nodmg", "dmg"): "3.7"}.get((ref[2], run[2]))
    return {k: v[:2] for k, v in VARIATION[table][ref[0]].items()} if table else None


def compare(reference, others, names=None):
    """Rows of the paper's Table 3.7: each run's final 5 %/95 % quantiles and broken contacts per
    kind, with the variation in percent against the reference run, (value - ref) / ref as the
    paper computes it (a compressive quantile that shrinks varies by a negative percentage), and
    the paper's values and variations where the paper has the run ('paper_*'; None elsewhere).
    Each row says how its run ended ('run', run_state) and the time of its last step [day];
    names: one name per run, reference first (e.g. its folder), kept as 'name'."""
    ref_rows = {r["kind"]: r for r in final_rows(reference)}
    table = []
    for n, res in enumerate([reference] + list(others)):
        state = run_state(res)
        t_last = res["times_days"][-1] if res["times_days"] else float("nan")
        paper_values = TABLE_FORCES.get(paper_key(res), {})
        paper_var = paper_variation(reference, res) if n else None
        for r in final_rows(res):
            # a kind the reference has not (the bars' BOND against a run without bars) varies against nothing
            rr = ref_rows.get(r["kind"], {"fn_p05_kN": float("nan"), "fn_p95_kN": float("nan")})
            var = lambda a, b: 100.0 * (a - b) / b if not math.isnan(b) and abs(b) >= VARIATION_MIN_REFERENCE_KN else float("nan")
            pv = paper_values.get(r["kind"], {})
            pvar = paper_var.get(r["kind"], (None, None)) if paper_var else (None, None)
            table.append({"scenario": res["scenario"], "behaviour": res["behaviour"], "damage": res["damage"],
                          "kind": r["kind"], "fn_p05_kN": r["fn_p05_kN"], "var_p05_pct": var(r["fn_p05_kN"], rr["fn_p05_kN"]),
                          "fn_p95_kN": r["fn_p95_kN"], "var_p95_pct": var(r["fn_p95_kN"], rr["fn_p95_kN"]),
                          "broken": r["broken"], "broken_pct": r["broken_pct"], "born_broken": r["born_broken"],
                          "paper_fn_p05_kN": pv.get("p05"), "paper_var_p05_pct": pvar[0],
                          "paper_fn_p95_kN": pv.get("p95"), "paper_var_p95_pct": pvar[1],
                          "paper_broken": pv.get("broken"), "paper_broken_pct": pv.get("broken_pct"),
                          "run": state, "t_last_days": t_last, "name": names[n] if names else ""})
    return table


def compare_md(rows, reference_name, reference, runs=None):
    """The Markdown lines of the Table 3.7 form of compare() rows; reference_name: how the
    reference run is named under the table (its folder); runs: [(name, results dict)], reference
    first, to name the settings in which they differ."""
    fmt = lambda v: "-" if v is None or v != v else f"{round(v)}"  # NaN (no reference value) and None print as "-"
    scenario = reference["scenario"]
    named = any(r.get("name") for r in rows)  # runs of the same behaviour and damage (a sweep) need their names
    lines = [f"# {LABEL.get(scenario, scenario)}: normal contact forces (kN) and variation to the reference (%)", "",
             "| behaviour | damage | contact | 5 % | paper | var. % | paper | 95 % | paper | var. % | paper | broken (%) | paper | run |"
             + (" name |" if named else ""),
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|" + ("---|" if named else "")]
    for r in rows:
        mark = "" if r["run"] == "finished" else " †"
        paper_broken = "-" if r["paper_broken"] is None else f"{r['paper_broken']} ({r['paper_broken_pct']:.1f})"
        lines.append(f"| {r['behaviour']}{mark} | {'yes' if r['damage'] else 'no'} | {r['kind']} | {r['fn_p05_kN']:.2f} | "
                     f"{_f(r['paper_fn_p05_kN'], '{:.1f}')} | {fmt(r['var_p05_pct'])} | {fmt(r['paper_var_p05_pct'])} | "
                     f"{r['fn_p95_kN']:.2f} | {_f(r['paper_fn_p95_kN'], '{:.1f}')} | {fmt(r['var_p95_pct'])} | {fmt(r['paper_var_p95_pct'])} | "
                     f"{r['broken']} ({r['broken_pct']:.1f}) | {paper_broken} | {r['run']} |" + (f" {r['name']} |" if named else ""))
    lines += ["", f"Reference: {reference_name} ({reference['behaviour']}, damage {'on' if reference['damage'] else 'off'}). "
              "Variation: (value - reference) / reference; '-' where the reference is below 0.05 kN in magnitude (the paper's 0.0) "
              "or the paper has no such run. "
              "Paper: Tables 3.4, 3.6 and 3.7 (100 x 100 mm). " + size_note(reference)]
    differ = differing_settings([r for _, r in runs]) if runs else []
    if differ:
        lines.append("Settings that differ between the runs: " + "; ".join(
            f"{k}: " + ", ".join(f"{setting_text(r, k)} ({n})" for n, r in runs) for k in differ) + ".")
    elif runs and len(runs) > 1:
        lines.append("The runs have the same settings (seeds, solver and every option alike).")
    states = {r["run"] for r in rows}
    if states != {"finished"}:
        ref_state = rows[0]["run"] if rows else "finished"
        lines.append("† not finished: the numbers are those of the run's last step done, not of the end of the test"
                     + (" (the reference too: every variation is against an unfinished run)." if ref_state != "finished" else "."))
    return lines


def paper_tables_md(runs, folders=None):
    """The Markdown lines of our runs next to the paper's Tables 3.4 (no damage) and 3.6 (damage),
    with the variation of each viscoelastic run to the elastic one of the same damage setting
    (ours and the paper's), then one line per run. runs: {run_key(results dict): results dict}
    (the folder names of scripts/paper_study.py); folders: {key: the run's folder name}, shown
    beside the key in the runs table where the two differ."""
    fmt = lambda v: "-" if v is None or v != v else f"{round(v)}"
    lines, unfinished = [], False
    for damage, table in (("nodmg", "3.4"), ("dmg", "3.6")):
        lines += [f"### Normal contact forces {'with' if damage == 'dmg' else 'without'} damage (paper Table {table})", "",
                  "| analysis | behaviour | contact | 5 % ours | 5 % paper | var. % ours | var. % paper | 95 % ours | 95 % paper | "
                  "var. % ours | var. % paper | broken % ours | broken % paper |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for sc in SCENARIOS:
            ref = runs.get(f"{sc}-el-{damage}")
            ref_rows = {r["kind"]: r for r in final_rows(ref)} if ref is not None else {}
            for beh in BEHAVIOUR_KEYS:
                res = runs.get(f"{sc}-{beh}-{damage}")
                if res is None:
                    lines.append(f"| {LABEL[sc]} | {BEHAVIOUR_WORDS[beh]} | (not run) | | | | | | | | | | |")
                    continue
                state = run_state(res)
                # a run that did not finish shows its last step's numbers, marked with how it ended
                mark = "" if state == "finished" else f" ({state}) †"
                unfinished |= bool(mark)
                for r in final_rows(res, KIND_NAMES):
                    kind = r["kind"]
                    p = TABLE_FORCES[(sc, beh, damage)][kind]
                    if beh == "el":
                        ours, theirs = (None, None), (None, None)
                    else:
                        rr = ref_rows.get(kind)
                        var = lambda a, b: 100.0 * (a - b) / b if abs(b) >= VARIATION_MIN_REFERENCE_KN else None
                        ours = (var(r["fn_p05_kN"], rr["fn_p05_kN"]), var(r["fn_p95_kN"], rr["fn_p95_kN"])) if rr else (None, None)
                        theirs = VARIATION[table][sc][kind][:2]
                    lines.append(f"| {LABEL[sc]} | {BEHAVIOUR_WORDS[beh]}{mark} | {kind} | {r['fn_p05_kN']:.2f} | {p['p05']:.1f} | "
                                 f"{fmt(ours[0])} | {fmt(theirs[0])} | {r['fn_p95_kN']:.2f} | {p['p95']:.1f} | {fmt(ours[1])} | "
                                 f"{fmt(theirs[1])} | {r['broken_pct']:.1f} | {p['broken_pct']:.1f} |")
        lines.append("")
    if unfinished:
        lines += ["† not finished: the numbers are those of the run's last step done, not of the end of the test.", ""]
    lines += ["Variation: of the aging viscoelastic run to the elastic run of the same damage setting, (value - elastic) / elastic; "
              "'-' for the elastic run itself and where the elastic value is below 0.05 kN in magnitude (the paper's 0.0). Broken: contacts bonded at the start that broke; "
              "contacts made during the run (born broken) are not counted. The paper's ASR-fine elastic ITZ and AGG 95 % values "
              "(0.6, 1.2 kN) contradict its own variations (-69 %, -67 % to 3.3, 3.7 kN), which imply about 10.6 and 11.2 kN.", "",
              "### Runs", "",
              "| run | particles | contacts | size (mm) | final strain x, y (1e-6) | iterations | wall (s) | last step (day) | new contacts | status |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in runs.items():
        folder = (folders or {}).get(name, name)
        name = name if folder == name else f"{name} (folder {folder})"
        sx, sy = (r["swelling_strain_x"] or [float("nan")])[-1], (r["swelling_strain_y"] or [float("nan")])[-1]
        born = [row["born_broken"] for row in final_rows(r)]
        born = "-" if None in born else str(sum(born))
        t_last = f"{r['times_days'][-1]:g}" if r["times_days"] else "-"
        size = (r.get("config") or {}).get("size_mm")
        size = f"{size[0]:g} x {size[1]:g}" if size else "?"
        lines.append(f"| {name} | {r.get('n_particles', '?')} | {sum(r['n_contacts_by_kind'].values())} | {size} | {sx * 1e6:.0f}, {sy * 1e6:.0f} | "
                     f"{r.get('iterations', '?')} | {r.get('wall_s', float('nan')):.0f} | {t_last} | {born} | {run_state(r)[:60]} |")
    return lines


# -- over seeds: the same run on several mesostructures -------------------------------------------

def seed_series(runs, get):
    """(times [day], mean, min, max) over the runs (one each seed, the same schedule) of the series
    get(res); the runs' common steps only (a run that stopped early shortens them)."""
    n = min(len(r["times_days"]) for r in runs)
    v = np.array([np.asarray(get(r), dtype=float)[:n] for r in runs])
    return np.asarray(runs[0]["times_days"][:n], dtype=float), v.mean(axis=0), v.min(axis=0), v.max(axis=0)


def _mean_range(values, fmt="{:.2f}"):
    v = [x for x in values if x == x]
    if not v:
        return "-"
    if len(v) == 1:
        return fmt.format(v[0])
    return f"{fmt.format(sum(v) / len(v))} ({fmt.format(min(v))} to {fmt.format(max(v))})"


def paper_tables_seeds_md(groups, seeds):
    """The paper's Tables 3.4 and 3.6 with ours over seeds: per row the mean and (min to max) of the
    5 % and 95 % quantiles [kN] and broken shares [%] of the run on each seed. groups: {run_key:
    [results dict per seed]}; seeds: the seeds, in the runs' order."""
    lines, unfinished = [], False
    for damage, table in (("nodmg", "3.4"), ("dmg", "3.6")):
        lines += [f"### Normal contact forces {'with' if damage == 'dmg' else 'without'} damage (paper Table {table}), "
                  f"ours over seeds {', '.join(map(str, seeds))}", "",
                  "| analysis | behaviour | contact | 5 % ours: mean (min to max) | 5 % paper | 95 % ours: mean (min to max) | 95 % paper | "
                  "broken % ours: mean (min to max) | broken % paper |", "|---|---|---|---|---|---|---|---|---|"]
        for sc in SCENARIOS:
            for beh in BEHAVIOUR_KEYS:
                runs = groups.get(f"{sc}-{beh}-{damage}") or []
                if not runs:
                    lines.append(f"| {LABEL[sc]} | {BEHAVIOUR_WORDS[beh]} | (not run) | | | | | | |")
                    continue
                done = sum(run_state(r) == "finished" for r in runs)
                mark = "" if done == len(seeds) else f" ({done} of {len(seeds)} seeds finished) †"
                unfinished |= bool(mark)
                rows = [{r["kind"]: r for r in final_rows(res, KIND_NAMES)} for res in runs]
                for kind in KIND_NAMES:
                    p = TABLE_FORCES[(sc, beh, damage)][kind]
                    col = lambda k: [r[kind][k] for r in rows]  # noqa: E731
                    lines.append(f"| {LABEL[sc]} | {BEHAVIOUR_WORDS[beh]}{mark} | {kind} | {_mean_range(col('fn_p05_kN'))} | "
                                 f"{p['p05']:.1f} | {_mean_range(col('fn_p95_kN'))} | {p['p95']:.1f} | "
                                 f"{_mean_range(col('broken_pct'), '{:.1f}')} | {p['broken_pct']:.1f} |")
        lines.append("")
    if unfinished:
        lines += ["† not every seed's run finished: a run that did not shows its last step's numbers.", ""]
    lines += ["Mean and range over the seeds' mesostructures; a difference between two rows smaller than their ranges is not "
              "one the study can tell from the draw of the mesostructure.", ""]
    return lines


def plot_strain_seeds(path, groups, title):
    """Swelling strain in x against log time of several runs over seeds: per run its mean (line)
    and the seeds' min-max (band), with the free swelling of the first run's scenario. groups:
    [(label, [results dict per seed])]."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    t_last = 0.0
    for k, (label, runs) in enumerate(groups):
        t, mean, lo, hi = seed_series(runs, lambda r: r.get("swelling_strain_x") or [np.nan] * len(r["times_days"]))
        st = _style(runs[0], k)
        ax.fill_between(t, lo * 1e6, hi * 1e6, color=st["color"], alpha=0.2, lw=0)
        ax.semilogx(t, mean * 1e6, marker="o", ms=2.5, label=f"{label}: mean, band min-max of {len(runs)} seeds", **st)
        t_last = max(t_last, t[-1]) if len(t) else t_last
    ax.set(xlabel="time [day]", ylabel="swelling strain in x [1e-6]", title=title)
    ax.grid(True, which="both", lw=0.3)
    if groups and t_last > 0:
        _free_swelling_curve(ax, groups[0][1][0], t_last, _max(*(r.get("swelling_strain_x") for _, rs in groups for r in rs)))
    _save(fig, path)


def plot_forces_seeds(path, groups, title):
    """plot_force_overlay over seeds: per run (row) and kind (column) the 5 % and 95 % quantiles'
    means over the seeds (lines) and their min-max (bands), with the first seed's tensile capacity."""
    plt = _plt()
    fig, axes = plt.subplots(len(groups), 3, figsize=(13, 3.2 * len(groups) + 0.6), sharex=True, sharey="col", squeeze=False)
    for r, (label, runs) in enumerate(groups):
        for c, name in enumerate(KIND_NAMES):
            ax = axes[r, c]
            if runs[0]["n_contacts_by_kind"].get(name):
                for q, ls in (("fn_p95_kN", "-"), ("fn_p05_kN", "--")):
                    t, mean, lo, hi = seed_series(runs, lambda res: res["per_kind"][name][q])
                    ax.fill_between(t, lo, hi, color=COLORS[name], alpha=0.2, lw=0)
                    ax.semilogx(t, mean, ls, color=COLORS[name], label=f"{'95' if q == 'fn_p95_kN' else '5'} % quantile: mean, band min-max")
                _capacity(ax, runs[0], name)
                ax.axhline(0, color="0.3", lw=0.5)
                ax.grid(True, which="major", lw=0.3)
                if r == len(groups) - 1:
                    ax.legend(fontsize=6.5, loc="best")
            ax.set_title(f"{name}: {label} ({len(runs)} seeds)", fontsize=9)
            if c == 0:
                ax.set_ylabel("normal force [kN]\n(tension > 0)")
            if r == len(groups) - 1:
                ax.set_xlabel("time [day]")
    fig.suptitle(title, fontsize=11)
    _save(fig, path)
