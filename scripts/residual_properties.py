# SPDX-License-Identifier: GPL-2.0-or-later
"""Residual stiffness and strength of a swollen specimen (issue 16): a swelling run, saved at the
test ages, then virtual tension, compression and SDT tests on each saved state and on the
undamaged specimen of the same age.

    scripts/yade-swelldem -j 1 -n -x scripts/residual_properties.py --scenario isr --behaviour viscoelastic \\
        --size-mm 20 20 --seed 1 --test-ages 100 300 3650 --out out/residual/isr-ve-1

Writes DIR/residual.json (per tested age: age_days, expansion (area strain) and expansion_linear
(mean of the x and y strains), E_rel, ft_rel, fc_rel, SDI, PDI and the undamaged reference's,
lower-bound flags of the strengths, with the curves), DIR/residual.csv, DIR/residual_curves.png,
DIR/residual_vs_expansion.png (E/E0, f/f0 and SDI against the linear expansion) and DIR/swelling/
(the swelling run's own results, scenario.run). Every swelling-test option of
scripts/swelling_test.py is accepted (--help). Bad values stop before any work with
'swelldem: <option> = <value> is out of range; allowed: <range>' and exit status 2.
"""
import argparse
import csv
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "py"))

from swelldem import options, report, residual, scenario  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
scenario.add_arguments(ap)
ap.add_argument("--test-ages", type=float, nargs="+", required=True, metavar="D",
                help="ages at which the swollen specimen is tested [day], within (t-start, t-end]")
ap.add_argument("--tests", nargs="+", default=list(residual.TESTS), help=f"tests to run, of {', '.join(residual.TESTS)}")
ap.add_argument("--sdt-fraction", type=float, default=residual.SDT_FRACTION,
                help="SDT load level, fraction of the undamaged specimen's compressive strength at the same age (0, 1) [-]")
ap.add_argument("--sdt-cycles", type=int, default=residual.SDT_CYCLES, help="SDT load-unload cycles (>= 1)")
ap.add_argument("--sdt-steps", type=int, default=5,
                help="SDT: ADR steps per branch on the undamaged specimen (the strain step is its target strain / this) [-]")
ap.add_argument("--strain-step-tension", type=float, default=4e-6, help="strain increment per ADR step, tension test [-]")
ap.add_argument("--strain-step-compression", type=float, default=25e-6, help="strain increment per ADR step, compression and SDT [-]")
ap.add_argument("--test-tolerance", type=float, default=1e-4,
                help="unbalanced-force tolerance of the tests' steps (0 < tolerance < 1) [-]")
ap.add_argument("--test-solver", default="adr", help="quasi-static solver of the tests: adr or implicit (see docs/residual-properties.md)")
ap.add_argument("--reference-cache", default="",
                help="folder where the undamaged specimen's tests are kept and reused (same seed, size, age, kinds and test "
                     "settings: they do not depend on the scenario or behaviour); empty: none")
ap.add_argument("--skip-swelling", action="store_true", help="reuse DIR/swelling (its saved states) instead of running it again")
args = ap.parse_args(sys.argv[1:])
if "compression" not in args.tests and "sdt" in args.tests:
    args.tests.append("compression")  # the SDT load level is a fraction of the reference's f_c


def fail(msg):
    print(f"residual_properties.py: {msg}", file=sys.stderr)
    sys.exit(2)


try:
    test = scenario.from_arguments(args)
    test.validate()
    if args.reference_cache:
        options.output_folder("reference_cache", args.reference_cache)
    residual.check_request(args.test_ages, test.t_start_days, test.t_end, args.tests, args.sdt_fraction, args.sdt_cycles)
    for name, v in (("--strain-step-tension", args.strain_step_tension), ("--strain-step-compression", args.strain_step_compression)):
        if not (0 < v < 1e-3):
            residual._bad(name, f"{v:g}", "0 < step < 1e-3 [-]")
    if not args.sdt_steps >= 1:
        residual._bad("--sdt-steps", args.sdt_steps, "an integer >= 1")
    if not (0 < args.test_tolerance < 1):
        residual._bad("--test-tolerance", f"{args.test_tolerance:g}", "0 < tolerance < 1 [-]")
    if args.test_solver not in ("adr", "implicit"):
        residual._bad("--test-solver", args.test_solver, "adr, implicit")
except ValueError as e:
    fail(str(e))

import numpy as np  # noqa: E402

from swelldem import meso  # noqa: E402

out = test.out
test.out = os.path.join(out, "swelling")
ages = sorted(args.test_ages)
t0 = time.time()
if not args.skip_swelling:
    saver = residual.AgeSaver(ages, test.out)
    os.makedirs(test.out, exist_ok=True)
    swell = scenario.run_or_exit(test, "residual_properties.py", extra_times=ages, after_step=saver)
else:
    swell = report.load_results(os.path.join(test.out, "results.json"))
t_swell = time.time() - t0
assembly = meso.load(os.path.join(test.out, "assembly.npz"))
times = np.asarray(swell["times_days"])


def expansion_at(age):
    """(area strain, x strain, y strain) [-] of the swelling run at `age` [day]."""
    k = int(np.argmin(np.abs(times - age)))
    ex, ey = swell["swelling_strain_x"][k], swell["swelling_strain_y"][k]
    return float((1 + ex) * (1 + ey) - 1), float(ex), float(ey)


def linear_expansion_at(age):
    """The linear expansion [-] of the swelling run at `age` [day]: the mean of its x and y
    strains, what a laboratory reports as the mean length change of a prism in its two
    directions (about half the area strain, `expansion`)."""
    _, ex, ey = expansion_at(age)
    return 0.5 * (ex + ey)


def ending(r):
    """How a test ended, in words for its progress line."""
    if r["status"] == "done":
        return "done"
    if r.get("peak_lower_bound"):
        return f"{r['status']} before its peak: its peak stress is a lower bound of the strength (flagged in residual.csv)"
    if "peak_Pa" in r:
        return f"{r['status']} past its peak (the specimen has failed): the normal end of a strength test"
    if "SDI" in r:
        return f"{r['status']} after {r['cycles_done']} of {args.sdt_cycles} cycles: no SDI or PDI at this age"
    return r["status"]


def run_tests(prepare, age, which, fc_ref=None, e_ref=None):
    """Each test on a fresh copy (prepare() fills O); which: the specimen, named in the progress lines."""
    res = {}
    for name in ("tension", "compression", "sdt"):
        if name not in args.tests:
            continue
        prepare()
        if name == "sdt":
            # the same strain step for the swollen specimen as for the undamaged one: a softer
            # specimen takes more steps to the same load
            deps = args.sdt_fraction * fc_ref / e_ref / args.sdt_steps
            legs = residual.sdt_legs(deps, args.sdt_fraction * fc_ref, args.sdt_cycles)
            r = residual.run_test(assembly, "compression", legs, age, tolerance=args.test_tolerance,
                                  max_steps=8 * args.sdt_steps * args.sdt_cycles + 20, solver_name=args.test_solver)
            r["strain_step"] = deps
            r.update(residual.sdt_indices(r["strain"], r["stress_Pa"], r["branch"]))
            r["target_Pa"] = args.sdt_fraction * fc_ref
        else:
            step = args.strain_step_tension if name == "tension" else args.strain_step_compression
            r = residual.run_test(assembly, name, residual.strength_legs(name, step, 200 * step), age,
                                  tolerance=args.test_tolerance, max_steps=220, solver_name=args.test_solver)
            r.update(residual.strength_result(r))
            if name == "compression" and fc_ref is None:
                fc_ref, e_ref = r["peak_Pa"], r["modulus_Pa"]
        res[name] = r
        print(f"swelldem residual: age {age:g} d, {which}, {name}: {ending(r)}; {r['steps']} steps, {r['iterations']} iterations, "
              f"{r['wall_s']:.1f} s", flush=True)
    return res


kinds = scenario.make_kinds(test)
settings = {k: getattr(args, k) for k in ("tests", "sdt_fraction", "sdt_cycles", "sdt_steps", "strain_step_tension",
                                          "strain_step_compression", "test_tolerance")}
if args.test_solver != "adr":  # (caches made before the option existed stay valid for the ADR)
    settings["test_solver"] = args.test_solver
settings.update(seed=test.seed, size_mm=list(test.size_mm), aggregate_area_fraction=test.aggregate_area_fraction,
                kinds={n: repr(sorted(residual.kinds_for_test({0: k})[0].dict().items())) for n, k in kinds.items()})


def reference(age):
    """The undamaged specimen's tests at `age`, from the cache when it has them with these settings."""
    path = os.path.join(args.reference_cache, f"ref_seed{test.seed}_{test.size_mm[0]:g}x{test.size_mm[1]:g}_{age:g}d.json")
    if args.reference_cache and os.path.exists(path):
        with open(path) as f:
            cached = json.load(f)
        if cached["settings"] == dict(settings, age=age):
            print(f"swelldem residual: age {age:g} d undamaged specimen from {path}", flush=True)
            return cached["results"]
    res = run_tests(lambda: residual.fresh_specimen(assembly, kinds), age, "reference (undamaged specimen, not swollen)")
    if args.reference_cache:
        os.makedirs(args.reference_cache, exist_ok=True)
        with open(path, "w") as f:
            json.dump({"settings": dict(settings, age=age), "results": res}, f)
    return res


rows, per_age = [], []
for age in ages:
    ref = reference(age)
    fc0, e0 = (ref["compression"]["peak_Pa"], ref["compression"]["modulus_Pa"]) if "compression" in ref else (None, None)
    path = residual.AgeSaver.path(test.out, age)
    area, ex, ey = expansion_at(age)
    dmg = run_tests(lambda: residual.load_copy(path), age,
                    f"swollen specimen (linear expansion {100 * linear_expansion_at(age):.3f} %, area {100 * area:.3f} %)",
                    fc_ref=fc0, e_ref=e0)
    entry = {"age_days": age, "expansion": area, "strain_x": ex, "strain_y": ey}
    for key, name in (("E", "compression"), ("fc", "compression"), ("Et", "tension"), ("ft", "tension")):
        if name in ref:
            q = "modulus_Pa" if key.startswith("E") else "peak_Pa"
            entry[f"{key}0_Pa"] = ref[name][q]
            entry[f"{key}_Pa"] = dmg[name][q]
            entry[f"{key}_rel"] = dmg[name][q] / ref[name][q]
    if "sdt" in dmg:
        entry.update({"SDI": dmg["sdt"]["SDI"], "PDI": dmg["sdt"]["PDI"], "SDI0": ref["sdt"]["SDI"], "PDI0": ref["sdt"]["PDI"],
                      "sdt_cycles_done": dmg["sdt"]["cycles_done"], "sdt_status": dmg["sdt"]["status"],
                      "sdt_target_Pa": dmg["sdt"]["target_Pa"]})
    for name in dmg:
        entry[f"broken_before_{name}"] = dmg[name]["broken"][0]
    entry["n_contacts"] = int(len(assembly.kind))
    entry.update(expansion_linear=linear_expansion_at(age), expansion_area_pct=100 * area, expansion_linear_pct=100 * linear_expansion_at(age))
    for key, name in (("fc", "compression"), ("ft", "tension")):  # a peak the test stopped short of: a lower bound
        if name in ref:
            entry[f"{key}0_lower_bound"] = bool(ref[name].get("peak_lower_bound", False))
            entry[f"{key}_lower_bound"] = bool(dmg[name].get("peak_lower_bound", False))
    rows.append(entry)
    per_age.append({"age_days": age, "reference": ref, "swollen": dmg})

result = {"scenario": test.scenario, "behaviour": test.behaviour, "damage": test.damage, "seed": test.seed,
          "size_mm": list(test.size_mm), "tests": args.tests, "sdt_fraction": args.sdt_fraction, "sdt_cycles": args.sdt_cycles,
          "modulus_window_of_peak": list(residual.MODULUS_WINDOW), "strain_step_tension": args.strain_step_tension,
          "strain_step_compression": args.strain_step_compression, "test_tolerance": args.test_tolerance,
          "test_solver": args.test_solver,
          "swelling_status": swell.get("status"), "swelling_wall_s": t_swell, "wall_s": time.time() - t0,
          "ages": rows, "curves": per_age}
os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "residual.json"), "w") as f:
    json.dump(result, f, indent=1)
keys = list(dict.fromkeys(k for r in rows for k in r))
with open(os.path.join(out, "residual.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys)
    w.writeheader()
    w.writerows(rows)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

tests = [t for t in residual.TESTS if t in args.tests]
fig, axes = plt.subplots(1, len(tests), figsize=(5 * len(tests), 4), squeeze=False)
colors = plt.cm.viridis(np.linspace(0, 0.85, len(ages)))
for j, name in enumerate(tests):
    ax = axes[0, j]
    for c, pa in zip(colors, per_age):
        for which, ls in (("reference", "--"), ("swollen", "-")):
            r = pa[which][name]
            lab = f"{pa['age_days']:g} d " + ("undamaged" if which == "reference" else
                                              f"swollen ({linear_expansion_at(pa['age_days']) * 100:.3f} % linear)")
            ax.plot(np.asarray(r["strain"]) * 1e6, np.asarray(r["stress_Pa"]) / 1e6, ls, color=c, label=lab, lw=1.2)
    ax.set_xlabel("strain (1e-6)" + (", compression positive" if name != "tension" else ""))
    ax.set_ylabel("stress (MPa)")
    ax.set_title(name if name != "sdt" else f"SDT, {args.sdt_cycles} cycles to {args.sdt_fraction:g} f_c0")
    ax.grid(alpha=0.3)
axes[0, 0].legend(fontsize=7)
fig.suptitle(f"{test.scenario}, {test.behaviour}, {test.size_mm[0]:g} x {test.size_mm[1]:g} mm, seed {test.seed}")
fig.tight_layout()
fig.savefig(os.path.join(out, "residual_curves.png"), dpi=110)
plt.close(fig)
residual.plot_against_expansion(os.path.join(out, "residual_vs_expansion.png"), rows,
                                f"{test.scenario}, {test.behaviour}, {test.size_mm[0]:g} x {test.size_mm[1]:g} mm, seed {test.seed}")
print(f"swelldem residual: wrote {os.path.join(out, 'residual.json')} ({time.time() - t0:.0f} s)")
