# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's study in one command: its 12 swelling tests (ISR, ASR-fine, ASR-coarse x elastic,
aging viscoelastic x without, with damage) on one specimen size, then its Tables 3.4, 3.6 and
3.7 next to the paper's values and its figures, all in one folder with an index.md.

  /usr/bin/python3 scripts/paper_study.py --size-mm W H --jobs N --out DIR [--seed S | --seeds S ...] [--steps-per-decade K]
      [--solver adr|implicit] [--scheduler tcp://HOST:PORT]

Each run is scripts/swelling_test.py in its own process (scripts/yade-swelldem -j 1), into
DIR/<scenario>-<el|ve>-<nodmg|dmg>/ with its log DIR/<run>.log, on N local Dask workers or, with
--scheduler ADDRESS, on the workers of a running Dask scheduler (swelldem.study). Resumable: a
run whose results.json says 'finished' with the same settings is kept, any other (failed,
interrupted, killed, absent) runs again; a finished run of other settings in DIR stops the study
before any work (choose another DIR). A run whose worker died runs again on another. Ctrl-C or
SIGTERM stops the running jobs (their results.json says 'interrupted'); the next call goes on from
there. Progress: one line per run started and ended, DIR/progress.md, and DIR/runs.md (the worker
and wall time of each run).

DIR then holds index.md (the runs, the three tables, the figures and the paper's figure each one
matches), tables.md, study.csv and per scenario <scenario>_strain.png, <scenario>_unbalanced_nodmg.png,
<scenario>_unbalanced_dmg.png, <scenario>_forces_nodmg.png, <scenario>_forces_dmg.png
(docs/paper-study.md). With --seeds S1 S2 ... the 12 runs are made on each seed's mesostructure,
in DIR/<run>-s<seed>/, and the tables (tables.md, study.csv) and the strain and force figures give
the mean over the seeds and their min-max range (the seed-to-seed spread a conclusion must clear);
each run keeps its own figures. Exit status 0 when every run finished, 1 when one did not (the tables and
figures show what there is), 2 for bad options (before any work). The solver is the paper's ADR
unless --solver implicit."""
import argparse
import csv
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper, report, scenario, study  # noqa: E402
from swelldem.scenario import SwellingTest  # noqa: E402

#: The plugin's range of LogTimeSolver.stepsPerDecade, checked here so that it stops the study before any run.
STEPS_PER_DECADE_MAX = 10000


def run_names():
    """The 12 runs, the slowest first (damage, then ASR-fine's long kinetics) so that N processes
    end close together."""
    order = {"asr-fine": 0, "isr": 1, "asr-coarse": 2}
    names = [f"{sc}-{b}-{d}" for d in ("dmg", "nodmg") for sc in sorted(paper.SCENARIOS, key=order.get) for b in paper.BEHAVIOUR_KEYS]
    return names


def split(name):
    sc, b, d = name.rsplit("-", 2)
    return sc, b, d


def folder(name, seed, seeds):
    """A run's folder: <run> for a study of one seed, <run>-s<seed> over several."""
    return name if len(seeds) == 1 else f"{name}-s{seed}"


def runs_of(a):
    """The 12 runs on each seed as a study's runs (swelldem.study): each its SwellingTest fields."""
    runs = []
    for seed in a.seeds:
        for name in run_names():
            sc, b, d = split(name)
            runs.append(study.Run(folder(name, seed, a.seeds), {"scenario": sc, "behaviour": paper.BEHAVIOUR_KEYS[b], "damage": d == "dmg",
                                                                 "size_mm": tuple(float(v) for v in a.size_mm), "seed": seed,
                                                                 "steps_per_decade": float(a.steps_per_decade), "solver": a.solver}))
    return runs


def check(a):
    """Every option, in the one message form (swelldem.options), before any work; the settings of
    finished runs already in DIR must be this study's."""
    options.output_folder("out", a.out)
    options.integer("jobs", a.jobs, lo=1)
    options.number("steps_per_decade", a.steps_per_decade, lo=0, hi=STEPS_PER_DECADE_MAX, hi_incl=True,
                   allowed=f"0 < steps_per_decade <= {STEPS_PER_DECADE_MAX} [1/decade]")
    # the swelling test's own checks (size, seed, the mesostructure generator's limits), and the
    # finished runs in DIR against this study's settings
    if a.seed is not None and a.seeds_given:
        options.bad("seeds", tuple(a.seeds_given), f"left out when --seed is given ({a.seed})")
    for s in a.seeds:
        options.integer("seeds", s, lo=0)
    if len(set(a.seeds)) != len(a.seeds):
        options.bad("seeds", tuple(a.seeds), "distinct seeds")
    SwellingTest(size_mm=tuple(a.size_mm), seed=a.seeds[0], steps_per_decade=a.steps_per_decade, solver=a.solver, out=a.out).validate()
    study.check(runs_of(a), a.out)


FIGURES = {  # file suffix -> (what it shows, the paper's figures of the same form per scenario)
    "strain": ("swelling strain in x against log time, the four runs and the free swelling of the swelling phase",
               {"isr": "Figures 3.3 and 3.9 (right)", "asr-fine": "Figures 3.4 and 3.10 (right)", "asr-coarse": "Figures 3.5 and 3.11 (right)"}),
    "unbalanced_nodmg": ("unbalanced-force ratio against cumulative iterations, elastic and viscoelastic, no damage",
                         {"isr": "Figure 3.3 (left)", "asr-fine": "Figure 3.4 (left)", "asr-coarse": "Figure 3.5 (left)"}),
    "unbalanced_dmg": ("unbalanced-force ratio against cumulative iterations, elastic and viscoelastic, with damage",
                       {"isr": "Figure 3.9 (left)", "asr-fine": "Figure 3.10 (left)", "asr-coarse": "Figure 3.11 (left)"}),
    "forces_nodmg": ("5 % / 95 % normal-force quantiles per kind against log time with the tensile capacity f_t A; "
                     "elastic (top), viscoelastic (bottom), no damage", {"isr": "Figure 3.6", "asr-fine": "Figure 3.7", "asr-coarse": "Figure 3.8"}),
    "forces_dmg": ("the same with damage", {"isr": "Figure 3.12", "asr-fine": "Figure 3.13", "asr-coarse": "Figure 3.14"}),
}


def report_study(a):
    """tables.md, study.csv, the overlay figures and index.md from the runs in DIR; returns
    whether every run finished."""
    runs = {}
    for name in run_names():
        path = os.path.join(a.out, name, "results.json")
        if os.path.exists(path):
            try:
                runs[name] = report.load_results(path)
            except report.ResultsError as e:
                print(f"paper_study: {e}; left out of the tables", file=sys.stderr)
    ordered = {n: runs[n] for n in sorted(runs)}
    lines = report.paper_tables_md(ordered) + [""]
    csv_rows = []
    for sc in paper.SCENARIOS:
        ref = runs.get(f"{sc}-el-nodmg")
        others = [runs[f"{sc}-{k}"] for k in ("ve-nodmg", "el-dmg", "ve-dmg") if f"{sc}-{k}" in runs]
        lines.append(f"### Table 3.7 form: {report.LABEL[sc]}, variation to the elastic run without damage")
        lines.append("")
        if ref is None:
            lines += [f"(no {sc}-el-nodmg run: no reference)", ""]
            continue
        rows = report.compare(ref, others, names=[f"{sc}-el-nodmg"] + [f"{sc}-{k}" for k in ("ve-nodmg", "el-dmg", "ve-dmg")
                                                                         if f"{sc}-{k}" in runs])
        csv_rows += rows
        lines += report.compare_md(rows, f"{sc}-el-nodmg", ref)[2:] + [""]
    tables = "\n".join(lines)
    with open(os.path.join(a.out, "tables.md"), "w") as f:
        f.write(f"# The paper's Tables 3.4, 3.6 and 3.7: ours ({a.size_mm[0]:g} x {a.size_mm[1]:g} mm) and the paper's\n\n" + tables + "\n")
    if csv_rows:
        with open(os.path.join(a.out, "study.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(csv_rows[0]))
            w.writeheader()
            w.writerows(csv_rows)
    figures = []
    for sc in paper.SCENARIOS:
        have = lambda keys: [(report.run_label(runs[f"{sc}-{k}"]), runs[f"{sc}-{k}"]) for k in keys if f"{sc}-{k}" in runs]
        label = report.LABEL[sc]
        made = {}
        four = have(("el-nodmg", "ve-nodmg", "el-dmg", "ve-dmg"))
        if four:
            report.plot_strain_overlay(os.path.join(a.out, f"{sc}_strain.png"), four, f"{label}: swelling strain")
            made["strain"] = f"{sc}_strain.png"
        for d, words in (("nodmg", "no damage"), ("dmg", "with damage")):
            pair = have((f"el-{d}", f"ve-{d}"))
            if pair:
                report.plot_unbalanced_overlay(os.path.join(a.out, f"{sc}_unbalanced_{d}.png"), pair, f"{label}, {words}: convergence")
                report.plot_force_overlay(os.path.join(a.out, f"{sc}_forces_{d}.png"), pair, f"{label}, {words}: normal contact forces")
                made[f"unbalanced_{d}"], made[f"forces_{d}"] = f"{sc}_unbalanced_{d}.png", f"{sc}_forces_{d}.png"
        figures.append((sc, made))
    all_done = len(runs) == 12 and all(report.run_state(r) == "finished" for r in runs.values())
    # the tolerance the runs record (the ADR's class default unless told otherwise): stated by the runs, not here
    tols = sorted({r["tolerance"] for r in runs.values() if r.get("tolerance")})
    adr = f"ADR tolerance {', '.join(f'{t:g}' for t in tols)}" if tols else "ADR at its default tolerance"
    index = [f"# The paper's study at {a.size_mm[0]:g} x {a.size_mm[1]:g} mm", "",
             f"12 swelling tests (scripts/swelling_test.py), seed {a.seeds[0]}, {a.steps_per_decade:g} steps a decade, "
             f"{adr if a.solver == 'adr' else 'implicit solver (exact equilibria)'}. {report.size_note({'config': {'size_mm': a.size_mm}})} "
             f"{'Every run finished.' if all_done else 'Not every run finished: see the status column and the runs logs (<run>.log).'}",
             "", "Command: `" + " ".join(["/usr/bin/python3", "scripts/paper_study.py", "--size-mm", f"{a.size_mm[0]:g}", f"{a.size_mm[1]:g}",
                                           "--jobs", str(a.jobs), "--out", a.out, "--seed", str(a.seeds[0]),
                                           "--steps-per-decade", f"{a.steps_per_decade:g}", "--solver", a.solver]) + "`", "",
             "## Tables", "", tables, "", "## Figures", ""]
    for sc, made in figures:
        index += [f"### {report.LABEL[sc]}", ""]
        for key, (what, paper_fig) in FIGURES.items():
            if key in made:
                index += [f"- `{made[key]}`: {what}; the paper's {paper_fig[sc]}.", "", f"![{made[key]}]({made[key]})", ""]
        for b in paper.BEHAVIOUR_KEYS:
            name = f"{sc}-{b}-dmg"
            if os.path.exists(os.path.join(a.out, name, "crack_map.png")):
                index += [f"- `{name}/crack_map.png`: broken contacts at the end, {paper.BEHAVIOUR_WORDS[b]}; the paper's Figure 3.15 "
                          "(central line); crack_map_<day>d.png in the same folder at earlier times.", "",
                          f"![{name} crack map]({name}/crack_map.png)", ""]
        index += [f"Each run's own figures and table: `{sc}-<el|ve>-<nodmg|dmg>/` (swelling_strain.png, unbalanced.png, "
                  "force_quantiles.png, table.md).", ""]
    with open(os.path.join(a.out, "index.md"), "w") as f:
        f.write("\n".join(index) + "\n")
    return all_done


def report_seeds(a):
    """tables.md, study.csv, the figures over seeds and index.md from the runs of several seeds
    in DIR; returns whether every run finished."""
    groups, n_done = {}, 0
    for name in run_names():
        runs = []
        for seed in a.seeds:
            path = os.path.join(a.out, folder(name, seed, a.seeds), "results.json")
            if os.path.exists(path):
                try:
                    runs.append(report.load_results(path))
                except report.ResultsError as e:
                    print(f"paper_study: {e}; left out of the tables", file=sys.stderr)
        n_done += sum(report.run_state(r) == "finished" for r in runs)
        if runs:
            groups[name] = runs
    seeds_text = ", ".join(map(str, a.seeds))
    lines = report.paper_tables_seeds_md(groups, a.seeds)
    tables = "\n".join(lines)
    with open(os.path.join(a.out, "tables.md"), "w") as f:
        f.write(f"# The paper's Tables 3.4 and 3.6: ours ({a.size_mm[0]:g} x {a.size_mm[1]:g} mm, seeds {seeds_text}) and the paper's\n\n"
                + tables + "\n")
    rows = []
    for name, runs in groups.items():
        sc, b, d = split(name)
        for kind in paper.KIND_NAMES:
            finals = [{r["kind"]: r for r in report.final_rows(res, paper.KIND_NAMES)}[kind] for res in runs]
            row = {"run": name, "scenario": sc, "behaviour": paper.BEHAVIOUR_KEYS[b], "damage": d == "dmg", "kind": kind, "seeds": len(runs)}
            for k in ("fn_p05_kN", "fn_p95_kN", "broken_pct"):
                v = [x[k] for x in finals]
                row.update({f"{k}_mean": sum(v) / len(v), f"{k}_min": min(v), f"{k}_max": max(v)})
            rows.append(row)
    if rows:
        with open(os.path.join(a.out, "study.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    index = [f"# The paper's study at {a.size_mm[0]:g} x {a.size_mm[1]:g} mm over seeds {seeds_text}", "",
             f"12 swelling tests (scripts/swelling_test.py) on each of {len(a.seeds)} mesostructures, {a.steps_per_decade:g} steps a "
             f"decade, solver {a.solver}; {n_done} of {12 * len(a.seeds)} runs finished. {report.size_note({'config': {'size_mm': a.size_mm}})} "
             "Tables and figures give the mean over the seeds and their min-max range.", "",
             "Command: `" + " ".join(["/usr/bin/python3", "scripts/paper_study.py", "--size-mm", f"{a.size_mm[0]:g}", f"{a.size_mm[1]:g}",
                                       "--jobs", str(a.jobs), "--out", a.out, "--seeds", *map(str, a.seeds),
                                       "--steps-per-decade", f"{a.steps_per_decade:g}", "--solver", a.solver]) + "`", "",
             "## Tables", "", tables, "", "## Figures", ""]
    for sc in paper.SCENARIOS:
        label = report.LABEL[sc]
        have = lambda keys: [(report.run_label(groups[f"{sc}-{k}"][0]), groups[f"{sc}-{k}"]) for k in keys if f"{sc}-{k}" in groups]  # noqa: E731
        index += [f"### {label}", ""]
        four = have(("el-nodmg", "ve-nodmg", "el-dmg", "ve-dmg"))
        if four:
            report.plot_strain_seeds(os.path.join(a.out, f"{sc}_strain.png"), four, f"{label}: swelling strain, seeds {seeds_text}")
            index += [f"- `{sc}_strain.png`: swelling strain in x, mean and min-max over the seeds; the paper's "
                      f"{FIGURES['strain'][1][sc]}.", "", f"![{sc}_strain.png]({sc}_strain.png)", ""]
        for d, words in (("nodmg", "no damage"), ("dmg", "with damage")):
            pair = have((f"el-{d}", f"ve-{d}"))
            if pair:
                name = f"{sc}_forces_{d}.png"
                report.plot_forces_seeds(os.path.join(a.out, name), pair, f"{label}, {words}: normal contact forces, seeds {seeds_text}")
                index += [f"- `{name}`: 5 % / 95 % normal-force quantiles, mean and min-max over the seeds; the paper's "
                          f"{FIGURES[f'forces_{d}'][1][sc]}.", "", f"![{name}]({name})", ""]
        index += [f"Each run's own figures (convergence, crack maps) and table: `{sc}-<el|ve>-<nodmg|dmg>-s<seed>/`.", ""]
    with open(os.path.join(a.out, "index.md"), "w") as f:
        f.write("\n".join(index) + "\n")
    return n_done == 12 * len(a.seeds)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size-mm", nargs=2, type=float, required=True, metavar=("W", "H"), help="specimen width and height [mm] (paper: 100 100)")
    ap.add_argument("--jobs", type=int, required=True, help="runs at a time: local Dask workers, one process and one thread each [-]")
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT) whose workers run the "
                                                      "study instead of local ones (docs/guide.md, \"Studies on a cluster\")")
    ap.add_argument("--out", required=True, help="folder of the study (made if absent; an earlier call's folder resumes it)")
    ap.add_argument("--seed", type=int, default=None, help="seed of the mesostructure, the same for the 12 runs [-] (default 1)")
    ap.add_argument("--seeds", type=int, nargs="+", default=None, dest="seeds_given",
                    help="several seeds: the 12 runs on each, in <run>-s<seed>/, the tables and figures over them (mean and min-max) [-]")
    ap.add_argument("--steps-per-decade", type=float, default=10.0, help="physical steps per decade of log time [1/decade]")
    # The study reproduces the paper, its method included; the implicit solver runs it in a fraction
    # of the time, with broken shares within the ADR's seed-to-seed spread (docs/performance.md, 1b).
    scenario.add_solver_argument(ap, default="adr")
    a = ap.parse_args(argv)
    a.seeds = a.seeds_given or [1 if a.seed is None else a.seed]
    with options.refuse_bad("paper_study.py"):  # exit status 2, as argparse's, before any work
        check(a)
    completed = study.run_study(runs_of(a), a.out, jobs=a.jobs, scheduler=a.scheduler, prog="paper_study")
    all_done = report_study(a) if len(a.seeds) == 1 else report_seeds(a)
    print(f"paper_study: tables and figures in {a.out}/index.md")
    study.end("paper_study.py", completed, all_done)


if __name__ == "__main__":
    main(sys.argv[1:])
