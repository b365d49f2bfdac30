# SPDX-License-Identifier: GPL-2.0-or-later
"""Swelling under applied stress and restraint (docs/boundaries.md): ISR and ASR-fine specimens,
elastic and viscoelastic, damage on, free, uniaxially loaded along x (-2.5, -5 MPa) and restrained
along x (fixed platens), y free. Writes DIR/boundary_study.csv, .md and boundary_strains.png
(strain along x, across (y) and area strain against time), restrained_stress.png (platen stress
of the restrained specimens against a hand estimate from the restrained single contact), and
each run's own folder.

  scripts/yade-swelldem -j 1 -n -x scripts/boundary_study.py --size-mm 20 20 --out out/boundaries

Hand estimate of the restrained stress: a single contact of the mortar kind, both discs held,
swelling with the scenario's kinetics, carries sigma_c(t) = Fn / A; a homogeneous network of such
contacts restrained along x and free along y carries sigma_x = beta (eps_free / eps_c) sigma_c(t),
with beta = 0.499 the measured ratio of the macroscopic to the contact modulus of the mortar
packing (docs/residual-properties.md), eps_free the free specimen's strain along x at the same
time and eps_c = d_inf xi / L the free strain of the single contact. It ignores the stiffer
aggregates, the ITZ's own creep and cracking: it says whether the platen stress has the right
size and time course, not more."""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))), "py"))
from swelldem import options, paper, scenario  # noqa: E402

# Loads as fractions of the model's own uniaxial compressive strength, about 7.6 MPa with the
# paper's strengths (tension cut-off, no shear failure; docs/cohesive-laws.md): -10 MPa is beyond
# it, and such a specimen fails under the load (the solver stops: no equilibrium).
CASES = (("free", "free"), ("-2.5 MPa", "stress:-2.5e6"), ("-5 MPa", "stress:-5e6"), ("restrained", "fixed"))
SCENARIOS = ("isr", "asr-fine")
BEHAVIOURS = ("elastic", "viscoelastic")
BETA = 0.499  # docs/residual-properties.md: calibrate_modulus_factor of the mortar packing


def parse(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size-mm", type=float, nargs=2, default=(20.0, 20.0), metavar=("W", "H"), help="specimen [mm]")
    p.add_argument("--seed", type=int, default=1, help="mesostructure seed")
    p.add_argument("--steps-per-decade", type=float, default=3.0, help="physical steps per decade [1/decade]")
    p.add_argument("--out", default="out/boundaries", help="output folder")
    scenario.add_solver_argument(p)
    return p.parse_args(argv)


def single_contact_stress(test):
    """sigma_c(t) [Pa] and eps_c(t) of one restrained contact of the mortar kind of `test`
    (two discs of the specimen's mean radius, both held), at the run's times."""
    from swelldem import dem
    import yade
    W = yade.wrapper
    kinds, solver = scenario.prepare(test)
    r = 0.4e-3  # about the packing's mean radius; sigma and eps do not depend on it
    d_inf = test.eps_inf * 2 * r
    kind = kinds["MORTAR"]
    kind.swellDispInf = d_inf
    ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kind, itz=kind, agg=kind, thickness=1.0)
    dem.build_scene([0.0, 2 * r], [0.0, 0.0], [r, r], [W.ConcreteMat(aggregateId=-1)], ip2,
                    W.Law2_ScGeom_SwellPhys_AgingSwelling(), solver, contacts=[(0, 1)], fixed=[0, 1])
    rows = []
    solver.stepHook = lambda: rows.append((solver.physTime, yade.Omega().interactions[0, 1].phys.Fn))
    solver.verbose = False
    dem.run_to_end(solver)
    t, fn = np.array(rows).T
    kin = paper.SCENARIOS[test.scenario]["kinetics"]
    eps_c = d_inf * (paper.larive_xi(t, kin) - paper.larive_xi(test.t_start_days, kin)) / (2 * r)
    return t, fn / (2 * r * 1.0), eps_c


def main(argv):
    with options.refuse_bad("boundary_study.py"):
        a = parse(argv)
        check(a)
    run(a)


def check(a):
    options.output_folder("out", a.out)
    options.numbers("size_mm", a.size_mm, count=2, lo=0, unit="mm", allowed="two finite lengths > 0 [mm]")
    options.integer("seed", a.seed, lo=0)
    options.number("steps_per_decade", a.steps_per_decade, lo=0)
    a.tests = tests = {}
    for sc in SCENARIOS:
        for beh in BEHAVIOURS:
            for label, bx in CASES:
                name = f"{sc}-{beh[:2]}-{bx.replace(':', '')}"
                tests[sc, beh, label] = scenario.SwellingTest(
                    scenario=sc, behaviour=beh, size_mm=tuple(a.size_mm), seed=a.seed, steps_per_decade=a.steps_per_decade,
                    solver=a.solver, boundary_x=bx, out=os.path.join(a.out, name))
            # the load alone (no swelling, eps_inf 0): laboratories subtract it, measured on a
            # non-reactive companion, to give the expansion due to the reaction
            for label, bx in CASES:
                if bx.startswith("stress"):
                    tests[sc, beh, label + ", load only"] = scenario.SwellingTest(
                        scenario=sc, behaviour=beh, size_mm=tuple(a.size_mm), seed=a.seed, steps_per_decade=a.steps_per_decade,
                        solver=a.solver, boundary_x=bx, eps_inf=0.0, out=os.path.join(a.out, f"{sc}-{beh[:2]}-{bx.replace(':', '')}-loadonly"))
            # the restrained specimen without damage too: the hand estimate knows no cracking
            tests[sc, beh, "restrained, no damage"] = scenario.SwellingTest(
                scenario=sc, behaviour=beh, size_mm=tuple(a.size_mm), seed=a.seed, steps_per_decade=a.steps_per_decade,
                solver=a.solver, boundary_x="fixed", damage=False, out=os.path.join(a.out, f"{sc}-{beh[:2]}-fixed-nodmg"))
    for t in tests.values():  # every run's options before any work
        t.validate()


def run(a):
    tests = a.tests
    os.makedirs(a.out, exist_ok=True)
    # resumable; a loaded specimen that cracked through (failed) is kept as it is
    results = scenario.run_all(tests, "boundary_study", keep_failed=True)
    single = {(sc, beh): single_contact_stress(tests[sc, beh, "restrained, no damage"]) for sc in SCENARIOS for beh in BEHAVIOURS}
    write(a.out, results, single)


STRAINS = (("swelling_strain_x", "along x (loaded)"), ("swelling_strain_y", "across (y, free)"),
           ("swelling_strain_area", "area (volumetric)"))


def strain_figure(plt, path, curves, colors, title, ylabel):
    """One row of three panels (strain along x, across, area, against time) per (scenario,
    behaviour); curves: {(scenario, behaviour): [(x boundary label, stopped, times [day],
    {STRAINS key: strains [-]})]}; title: a format of sc, beh and what."""
    fig, axes = plt.subplots(len(curves), 3, figsize=(13, 3.2 * len(curves)), squeeze=False)
    for i, ((sc, beh), lines) in enumerate(curves.items()):
        for label, stopped, t, values in lines:
            for j, (key, _) in enumerate(STRAINS):
                axes[i, j].semilogx(np.array(t), 1e6 * np.array(values[key]), color=colors[label],
                                    label=label + (" (stopped)" if stopped else ""))
        for j, (_, what) in enumerate(STRAINS):
            axes[i, j].set(title=title.format(sc=sc, beh=beh, what=what), xlabel="time [day]", ylabel=ylabel)
            axes[i, j].grid(True, which="both", lw=0.3)
        axes[i, 0].legend(fontsize=7, title="x boundary", title_fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write(out, results, single):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = []
    for (sc, beh, label), r in results.items():
        if not r["times_days"]:
            continue
        rows.append({"scenario": sc, "behaviour": beh, "boundary_x": label, "status": r["status"].split(":")[0],
                     "strain_x_1e-6": 1e6 * r["swelling_strain_x"][-1], "strain_y_1e-6": 1e6 * r["swelling_strain_y"][-1],
                     "strain_area_1e-6": 1e6 * r["swelling_strain_area"][-1], "platen_stress_x_MPa": r["platen_stress_x_Pa"][-1] / 1e6,
                     "broken_MORTAR": r["per_kind"]["MORTAR"]["broken"][-1], "broken_ITZ": r["per_kind"]["ITZ"]["broken"][-1],
                     "broken_AGG": r["per_kind"]["AGG"]["broken"][-1]})
    with open(os.path.join(out, "boundary_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| scenario | behaviour | x boundary | run | strain x [1e-6] | strain y [1e-6] | area strain [1e-6] | platen stress x [MPa] | broken M / I / A |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['scenario']} | {r['behaviour']} | {r['boundary_x']} | {r['status']} | {r['strain_x_1e-6']:.0f} | {r['strain_y_1e-6']:.0f} | "
                     f"{r['strain_area_1e-6']:.0f} | {r['platen_stress_x_MPa']:.2f} | {r['broken_MORTAR']} / {r['broken_ITZ']} / {r['broken_AGG']} |")
    with open(os.path.join(out, "boundary_study.md"), "w") as f:
        f.write("Final values (last step) of the boundary study; strains of the skeleton's affine fit, compression negative.\n\n"
                + "\n".join(lines) + "\n")

    colors = dict(zip([c[0] for c in CASES], ("k", "tab:blue", "tab:purple", "tab:red")))
    failed = {k for k, r in results.items() if r.get("status") != "finished"}
    pairs = [(sc, beh) for sc in SCENARIOS for beh in BEHAVIOURS]
    total = {(sc, beh): [(label, (sc, beh, label) in failed, results[sc, beh, label]["times_days"], results[sc, beh, label])
                         for label, _ in CASES] for sc, beh in pairs}
    strain_figure(plt, os.path.join(out, "boundary_strains.png"), total, colors, "{sc}, {beh}: strain {what}", "strain [1e-6]")

    # the expansion due to the swelling: total less the same load on a non-swelling specimen
    part, part_rows = {}, []
    for sc, beh in pairs:
        part[sc, beh] = []
        for label, bx in CASES:
            if bx == "fixed":
                continue
            r = results[sc, beh, label]
            base = results.get((sc, beh, label + ", load only"))
            n = len(r["times_days"]) if base is None else min(len(r["times_days"]), len(base["times_days"]))
            v = {key: np.array(r[key][:n]) - (np.array(base[key][:n]) if base is not None else 0.0) for key, _ in STRAINS}
            part[sc, beh].append((label, (sc, beh, label) in failed, r["times_days"][:n], v))
            part_rows.append((sc, beh, label, 1e6 * v["swelling_strain_x"][-1], 1e6 * v["swelling_strain_y"][-1],
                              1e6 * v["swelling_strain_area"][-1], r["times_days"][n - 1]))
    strain_figure(plt, os.path.join(out, "swelling_part.png"), part, colors, "{sc}, {beh}: {what}",
                  "swelling strain: total - load only [1e-6]")
    with open(os.path.join(out, "swelling_part.md"), "w") as f:
        f.write("Expansion due to the swelling: the loaded run's strain less that of the same load on a non-swelling specimen "
                "(eps_inf 0), at the last step both reached.\n\n| scenario | behaviour | x boundary | along x [1e-6] | across (y) [1e-6] | "
                "area [1e-6] | at day |\n|---|---|---|---|---|---|---|\n")
        for row in part_rows:
            f.write("| {} | {} | {} | {:.0f} | {:.0f} | {:.0f} | {:.0f} |\n".format(*row))

    fig, axes = plt.subplots(1, len(SCENARIOS), figsize=(11, 4), squeeze=False)
    hand_rows = []
    for i, sc in enumerate(SCENARIOS):
        ax = axes[0, i]
        for beh, color in zip(BEHAVIOURS, ("tab:blue", "tab:red")):
            r = results[sc, beh, "restrained, no damage"]
            free = results[sc, beh, "free"]
            t = np.array(r["times_days"])
            ax.semilogx(t, np.array(r["platen_stress_x_Pa"]) / 1e6, "-", color=color, label=f"{beh}: platens, no damage")
            cracked = results[sc, beh, "restrained"]
            ax.semilogx(cracked["times_days"], np.array(cracked["platen_stress_x_Pa"]) / 1e6, ":", color=color,
                        label=f"{beh}: platens, damage on")
            ts, sig_c, eps_c = single[sc, beh]
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = np.where(eps_c > 0, np.interp(ts, free["times_days"], free["swelling_strain_x"]) / eps_c, 0.0)
            hand = BETA * ratio * sig_c
            ax.semilogx(ts, hand / 1e6, "--", color=color, label=f"{beh}: hand estimate")
            hand_rows.append((sc, beh, r["platen_stress_x_Pa"][-1] / 1e6, hand[-1] / 1e6, float(np.min(r["platen_stress_x_Pa"])) / 1e6,
                              float(np.min(hand)) / 1e6))
        ax.set(title=f"{sc}: restrained along x", xlabel="time [day]", ylabel="platen stress x [MPa] (compression < 0)")
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "restrained_stress.png"), dpi=110)
    plt.close(fig)
    with open(os.path.join(out, "restrained_stress.md"), "w") as f:
        f.write("| scenario | behaviour | platens, final [MPa] | hand estimate, final [MPa] | platens, peak [MPa] | hand estimate, peak [MPa] |\n"
                "|---|---|---|---|---|---|\n")
        for row in hand_rows:
            f.write("| {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n".format(*row))
    print(f"boundary_study: tables and plots in {out}/")


main(sys.argv[1:])
