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

from .paper import KIND_NAMES

LABEL = {"isr": "ISR", "asr-fine": "ASR-fine agg.", "asr-coarse": "ASR-coarse agg."}
COLORS = {"MORTAR": "tab:blue", "ITZ": "tab:red", "AGG": "tab:green"}



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


def load_results(path):
    """The results dict of a swelling test's results.json at `path`; ResultsError naming the file
    when it is missing, is not JSON (truncated, malformed) or lacks what the tables read."""
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
    return res


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
    return "Newton" if res.get("solver") == "implicit" else "ADR"

def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def final_rows(res):
    """Per kind at the last step: 5 % and 95 % normal-force quantiles [kN], broken contacts (of the
    n_contacts bonded at the start) and their share, and the contacts made during the run (born
    broken; None in a results.json written before they were counted apart, whose 'broken' then
    includes them)."""
    rows = []
    for name in KIND_NAMES:
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


def write_tables(out, res):
    """table.md and table.csv in the form of the paper's Tables 3.4 / 3.6."""
    rows = final_rows(res)
    with open(os.path.join(out, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    t = res["times_days"][-1] if res["times_days"] else float("nan")
    lines = [f"# {LABEL.get(res['scenario'], res['scenario'])}, {res['behaviour']}, damage {'on' if res['damage'] else 'off'}: "
             f"normal contact forces at t = {t:g} days", "",
             "| contact | contacts | 5 % Fn (kN) | 95 % Fn (kN) | broken (%) | new contacts |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['kind']} | {r['n_contacts']} | {r['fn_p05_kN']:.2f} | {r['fn_p95_kN']:.2f} | "
                     f"{r['broken']} ({r['broken_pct']:.1f}) | {'-' if r['born_broken'] is None else r['born_broken']} |")
    sx, sy = res["swelling_strain_x"], res["swelling_strain_y"]
    lines += ["", "Broken: contacts bonded at the start that broke (share of the kind's contacts). New contacts: "
                  "contacts made during the run by discs coming into touch, born broken (compression only), not counted as broken."]
    state = run_state(res)
    if state != "finished":
        lines += ["", f"Run not finished ({state}): the numbers are those of its last step done."]
    if sx:
        lines += ["", f"Final swelling strain: x {sx[-1] * 1e6:.0f}e-6, y {sy[-1] * 1e6:.0f}e-6. "
                      f"{res['n_particles']} particles, {_iteration_name(res)} iterations {res['adr_iterations']}, wall {res['wall_s']:.1f} s."]
    with open(os.path.join(out, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return rows


def plot_curves(out, res):
    plt = _plt()
    t = np.array(res["times_days"])
    title = f"{LABEL.get(res['scenario'], res['scenario'])}, {res['behaviour']}, damage {'on' if res['damage'] else 'off'}"
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx(t, np.array(res["swelling_strain_x"]) * 1e6, "o-", ms=3, label="x")
    ax.semilogx(t, np.array(res["swelling_strain_y"]) * 1e6, "s-", ms=3, label="y")
    ax.set(xlabel="time [day]", ylabel="swelling strain [1e-6]", title=title)
    ax.grid(True, which="both", lw=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "swelling_strain.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    steps = np.arange(1, len(t) + 1)
    ax.semilogy(steps, res["unbalanced_ratio"], "o-", ms=3, label="at convergence")
    ro = np.array(res.get("step_at_round_off", [False] * len(t)), dtype=bool)
    if ro.any():  # steps whose load was too small for the tolerance: ended at the positions' round-off
        ax.semilogy(steps[ro], np.array(res["unbalanced_ratio"])[ro], "x", color="tab:red", label="at round-off limit")
    ax.axhline(res.get("tolerance") or res.get("config", {}).get("tolerance") or 1e-4, color="k", lw=0.5, ls=":", label="tolerance")
    ax.legend(fontsize=8)
    ax2 = ax.twinx()
    ax2.plot(np.arange(1, len(t) + 1), res["adr_iterations_per_step"], "-", color="gray", lw=1)
    ax2.set_ylabel(f"{_iteration_name(res)} iterations per step", color="gray")
    ax.set(xlabel="physical step", ylabel="unbalanced-force ratio", title=title)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "unbalanced.png"), dpi=120)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for name in KIND_NAMES:
        d = res["per_kind"][name]
        if res["n_contacts_by_kind"].get(name):
            axes[0].semilogx(t, d["fn_p05_kN"], "-", color=COLORS[name], label=f"{name} 5 %")
            axes[0].semilogx(t, d["fn_p95_kN"], "--", color=COLORS[name], label=f"{name} 95 %")
            axes[1].semilogx(t, d["broken"], "-", color=COLORS[name], label=name)
    axes[0].set(xlabel="time [day]", ylabel="normal contact force [kN] (tension > 0)", title=title)
    axes[1].set(xlabel="time [day]", ylabel="broken contacts", title="damage")
    for a in axes:
        a.grid(True, which="both", lw=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force_quantiles.png"), dpi=120)
    plt.close(fig)


def plot_crack_map(out, res, assembly, broken_contacts):
    """Broken contacts drawn as their Laguerre facets, coloured by kind, over the mesostructure."""
    plt = _plt()
    from matplotlib.collections import LineCollection
    fig, ax = plt.subplots(figsize=(7, 7 * assembly.height_m / assembly.width_m))
    for poly in assembly.polygons:
        p = np.asarray(poly) * 1e3
        ax.fill(p[:, 0], p[:, 1], color="0.85", lw=0.5, ec="0.5")
    index = {(int(i), int(j)): c for c, (i, j) in enumerate(assembly.contacts)}
    for k, name in enumerate(KIND_NAMES):
        segs = []
        for i, j, kind in broken_contacts:
            c = index.get((min(i, j), max(i, j)))
            if c is not None and kind == k:
                s = assembly.facet_segment_m[c] * 1e3
                segs.append([(s[0], s[1]), (s[2], s[3])])
        if segs:
            ax.add_collection(LineCollection(segs, colors=COLORS[name], linewidths=1.2, label=f"{name} ({len(segs)})"))
    ax.set_xlim(0, assembly.width_m * 1e3)
    ax.set_ylim(0, assembly.height_m * 1e3)
    ax.set_aspect("equal")
    ax.set(xlabel="x [mm]", ylabel="y [mm]",
           title=f"crack map: {LABEL.get(res['scenario'], res['scenario'])}, {res['behaviour']}, t = {res['times_days'][-1]:g} d")
    if broken_contacts:
        ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "crack_map.png"), dpi=130)
    plt.close(fig)


def write_all(out, res, assembly, broken_contacts):
    """Tables, curves and the crack map; broken_contacts: (id1, id2, kindId) of the broken contacts."""
    write_tables(out, res)
    plot_curves(out, res)
    plot_crack_map(out, res, assembly, broken_contacts)


def write_results(out, res):
    """res as out/results.json (written to a temporary file, then renamed: never half a file),
    with each per-kind series also as a flat key '<series>_<KIND>' (e.g. broken_ITZ)."""
    flat = dict(res)
    for name, d in res["per_kind"].items():
        for key, v in d.items():
            flat[f"{key}_{name}"] = v
    with open(os.path.join(out, "results.json.tmp"), "w") as f:
        json.dump(flat, f, indent=1, default=float)
    os.replace(os.path.join(out, "results.json.tmp"), os.path.join(out, "results.json"))


def compare(reference, others):
    """Rows of the paper's Table 3.7: each run's final 5 %/95 % quantiles and broken contacts per
    kind, with the variation in percent against the reference run, (value - ref) / ref as the
    paper computes it (a compressive quantile that shrinks varies by a negative percentage).
    Each row says how its run ended ('run', run_state) and the time of its last step [day]."""
    ref_rows = {r["kind"]: r for r in final_rows(reference)}
    table = []
    for res in [reference] + list(others):
        state = run_state(res)
        t_last = res["times_days"][-1] if res["times_days"] else float("nan")
        for r in final_rows(res):
            rr = ref_rows[r["kind"]]
            var = lambda a, b: 100.0 * (a - b) / b if not math.isnan(b) and abs(b) > 1e-12 else float("nan")
            table.append({"scenario": res["scenario"], "behaviour": res["behaviour"], "damage": res["damage"],
                          "kind": r["kind"], "fn_p05_kN": r["fn_p05_kN"], "var_p05_pct": var(r["fn_p05_kN"], rr["fn_p05_kN"]),
                          "fn_p95_kN": r["fn_p95_kN"], "var_p95_pct": var(r["fn_p95_kN"], rr["fn_p95_kN"]),
                          "broken": r["broken"], "broken_pct": r["broken_pct"], "born_broken": r["born_broken"],
                          "run": state, "t_last_days": t_last})
    return table
