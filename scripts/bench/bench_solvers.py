# SPDX-License-Identifier: GPL-2.0-or-later
"""The two log-time solvers side by side on the same swelling tests: wall time and its ratio
(ADR / implicit, both measured in this run, one after the other, so that the machine's drift hits
both), iterations, peak memory, and the agreement of the results (final strains; per-kind 5 % and
95 % force quantiles over all steps, relative to the kind's force range; broken counts).

    /usr/bin/python3 scripts/bench/bench_solvers.py --sizes-mm 20 40 --scenarios isr asr-fine asr-coarse
        --behaviours elastic viscoelastic [--damage] [--adr-tolerance 1e-8] [--threads 1] --out out/bench/solvers

Each run is `scripts/yade-swelldem -n -j THREADS -x scripts/swelling_test.py ...` under GNU time
(peak memory), in OUT/<size>-<scenario>-<behaviour>-<dmg|nodmg>-<solver>/. A finished run is
reused (delete its folder to time it again). Prints a Markdown table and writes OUT/solvers.json
and OUT/solvers.md; with more than one size, OUT/cost_vs_size.png: each solver's solve time
(results.json wall_s) against the disc count, log-log, with its fitted power of N.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper  # noqa: E402
from swelldem.report import load_results  # noqa: E402


def run_one(out, size, scenario, behaviour, damage, solver, tolerance, threads, seed):
    if os.path.exists(os.path.join(out, "run.json")):
        with open(os.path.join(out, "run.json")) as f:
            return json.load(f)
    os.makedirs(out, exist_ok=True)
    cmd = ["/usr/bin/time", "-v", "-o", os.path.join(out, "time.txt"), os.path.join(REPO, "scripts", "yade-swelldem"), "-n", "-j",
           str(threads), "-x", os.path.join(REPO, "scripts", "swelling_test.py"), "--scenario", scenario, "--behaviour", behaviour,
           "--size-mm", str(size), str(size), "--seed", str(seed), "--solver", solver, "--out", out]
    if not damage:
        cmd.append("--no-damage")
    if tolerance is not None:  # else the solver's own default
        cmd += ["--tolerance", str(tolerance)]
    t0 = time.time()
    with open(os.path.join(out, "log.txt"), "w") as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
    wall = time.time() - t0
    with open(os.path.join(out, "time.txt")) as f:
        rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", f.read()).group(1)) / 1024
    res = {}
    if os.path.exists(os.path.join(out, "results.json")):
        res = load_results(os.path.join(out, "results.json"))
    rec = {"rc": rc, "wall_s": wall, "run_wall_s": res.get("wall_s"), "peak_MB": rss, "status": res.get("status"),
           "iterations": res.get("iterations"), "n_particles": res.get("n_particles"),
           "strain": [res["swelling_strain_x"][-1], res["swelling_strain_y"][-1]] if res.get("swelling_strain_x") else None,
           "per_kind": res.get("per_kind")}
    with open(os.path.join(out, "run.json"), "w") as f:
        json.dump(rec, f)
    return rec


def agreement(a, b):
    """Largest |difference| of the per-kind quantiles over all steps / the kind's force range, and
    the relative difference of the final strains."""
    worst = 0.0
    for kind, d in a["per_kind"].items():
        e = b["per_kind"][kind]
        rng = max(max(abs(x) for x in d["fn_p05_kN"] + d["fn_p95_kN"]), 1e-30)
        for q in ("fn_p05_kN", "fn_p95_kN"):
            worst = max(worst, max(abs(x - y) for x, y in zip(d[q], e[q])) / rng)
    strain = max(abs(x - y) / abs(x) for x, y in zip(a["strain"], b["strain"]))
    return worst, strain


def plot_cost_vs_size(rows, path):
    """Solve time of both solvers against the disc count, per scenario and behaviour, with the
    least-squares exponent of each curve (time ~ N^p) in the legend."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    groups = {}
    for row in rows:
        groups.setdefault(row["case"].split("-", 1)[1], []).append(row)
    for case, rs in groups.items():
        rs = [r for r in rs if r["adr"]["run_wall_s"] and r["implicit"]["run_wall_s"]]
        if len(rs) < 2:
            continue
        n = np.array([r["implicit"]["n_particles"] for r in rs], float)
        for solver, style in (("adr", "o-"), ("implicit", "s-")):
            t = np.array([r[solver]["run_wall_s"] for r in rs], float)
            p = np.polyfit(np.log(n), np.log(t), 1)[0]
            ax.loglog(n, t, style, label=f"{solver}, {case} (~N^{p:.2f})")
    n0 = np.array([min(r["implicit"]["n_particles"] for r in rows), max(r["implicit"]["n_particles"] for r in rows)], float)
    ax.loglog(n0, rows[0]["implicit"]["run_wall_s"] * n0 / n0[0], "k:", lw=1, label="proportional to N")
    ax.set_xlabel("discs")
    ax.set_ylabel("solve time of the whole run [s]")
    ax.set_title("Cost against specimen size (1 thread)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[20.0])
    ap.add_argument("--scenarios", nargs="+", default=["isr"])
    ap.add_argument("--behaviours", nargs="+", default=["viscoelastic"])
    ap.add_argument("--damage", action="store_true", help="damage on (default off)")
    ap.add_argument("--adr-tolerance", type=float, default=None, help="ADR tolerance (absent: AdrLogTimeIntegrator's default)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(REPO, "out", "bench", "solvers"))
    with options.refuse_bad("bench_solvers.py"):  # every option before any run (NaN, infinity), exit 2
        a = ap.parse_args()
        options.output_folder("out", a.out)
        # a benchmark may measure a loose tolerance on purpose: range checked, no warning
        if a.adr_tolerance is not None:
            options.tolerance("adr_tolerance", a.adr_tolerance, useful_max=1.0)
        options.numbers("sizes_mm", a.sizes_mm, lo=0, unit="mm")
        for sc in a.scenarios:
            options.choice("scenarios", sc, tuple(paper.SCENARIOS))
        for be in a.behaviours:
            options.choice("behaviours", be, ("elastic", "viscoelastic"))
        options.integer("threads", a.threads, lo=1)
        options.integer("seed", a.seed, lo=0)
    rows = []
    for size in a.sizes_mm:
        for sc in a.scenarios:
            for be in a.behaviours:
                tag = f"{size:g}-{sc}-{be}-{'dmg' if a.damage else 'nodmg'}"
                r = {}
                for solver, tol in (("implicit", None), ("adr", a.adr_tolerance)):
                    r[solver] = run_one(os.path.join(a.out, f"{tag}-{solver}"), size, sc, be, a.damage, solver, tol, a.threads, a.seed)
                row = {"case": tag, "adr": r["adr"], "implicit": r["implicit"]}
                if r["adr"]["strain"] and r["implicit"]["strain"]:
                    row["force_agreement"], row["strain_agreement"] = agreement(r["adr"], r["implicit"])
                    row["wall_ratio"] = r["adr"]["wall_s"] / r["implicit"]["wall_s"]
                rows.append(row)
                print(json.dumps({k: v for k, v in row.items() if k not in ("adr", "implicit")}), flush=True)
    lines = ["| case | discs | ADR wall s | implicit wall s | ADR / implicit | ADR iterations | implicit iterations | peak MB (ADR / impl.) "
             "| quantiles: max diff / kind range | strains: max rel. diff | broken M/I/A (ADR; implicit) |", "|" + "---|" * 11]
    for row in rows:
        ad, im = row["adr"], row["implicit"]

        def broken(r):
            return "/".join(str(r["per_kind"][k]["broken"][-1]) for k in paper.KIND_NAMES) if r["per_kind"] else "-"
        lines.append(f"| {row['case']} | {im['n_particles']} | {ad['wall_s']:.1f} | {im['wall_s']:.1f} | {row.get('wall_ratio', float('nan')):.1f} | "
                     f"{ad['iterations']} | {im['iterations']} | {ad['peak_MB']:.0f} / {im['peak_MB']:.0f} | "
                     f"{row.get('force_agreement', float('nan')):.1e} | {row.get('strain_agreement', float('nan')):.1e} | "
                     f"{broken(ad)}; {broken(im)} |")
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(a.out, "solvers.json"), "w") as f:
        json.dump(rows, f, indent=1)
    with open(os.path.join(a.out, "solvers.md"), "w") as f:
        f.write(table + "\n")
    if len(a.sizes_mm) > 1:
        plot_cost_vs_size(rows, os.path.join(a.out, "cost_vs_size.png"))


if __name__ == "__main__":
    main()
