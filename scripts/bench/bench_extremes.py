#!/usr/bin/python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Both solvers at the extremes (docs/performance.md section 5): each case of the table below on a
12 x 12 mm specimen with damage, three seeds, `--solver adr` and `--solver implicit`, each through
scripts/swelling_test.py in its own process. For each case it tells whether every run finished,
the implicit runs' seed means of the final strains and broken shares against the ADR's seed range
(widened by the ADR's own error: see compare()), and the steps the
implicit solver handed to dynamic relaxation (fallback) with the time each took.

  /usr/bin/python3 scripts/bench/bench_extremes.py --out out/bench/extremes [--seeds 1 3 5] [--jobs 1]

Runs already ended in --out (finished or failed) are kept: delete a run's folder to remeasure. Writes
extremes.json, extremes.csv and extremes.md in --out."""
import argparse
import csv
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(BENCH_DIR))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem.paper import AGGREGATE_YOUNG, KIND_NAMES  # noqa: E402
from swelldem.report import load_results  # noqa: E402

LAUNCHER = os.path.join(REPO, "scripts", "yade-swelldem")
SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")
SIZE = ("--size-mm", "12", "12")

# name -> (what, arguments); damage is on in every case (the scenarios' default)
CASES = {
    "reference": ("ISR viscoelastic, 3 steps a decade", ("--steps-per-decade", "3")),
    "strength 1e-12": ("every tensile strength x 1e-12, viscoelastic", ("--steps-per-decade", "3", "--strength-scale", "1e-12")),
    "strength 1e-9 N10": ("strengths x 1e-9, 10 steps a decade", ("--steps-per-decade", "10", "--strength-scale", "1e-9")),
    "asr-coarse gel 1": ("ASR-coarse, every aggregate contact a gel pocket, strengths x 1e-9, N 10",
                         ("--scenario", "asr-coarse", "--gel-fraction", "1", "--steps-per-decade", "10", "--strength-scale", "1e-9")),
    "aggregate x1e3": ("aggregate contacts 1000 x stiffer, elastic",
                       ("--behaviour", "elastic", "--steps-per-decade", "3", "--aggregate-young", f"{AGGREGATE_YOUNG * 1e3:g}")),
    "aggregate x1e3 ve": ("aggregate contacts 1000 x stiffer, viscoelastic, 10 steps a decade",
                          ("--aggregate-young", f"{AGGREGATE_YOUNG * 1e3:g}")),
    "aggregate x1e6": ("aggregate contacts 1e6 x stiffer, elastic",
                       ("--behaviour", "elastic", "--steps-per-decade", "3", "--aggregate-young", f"{AGGREGATE_YOUNG * 1e6:g}")),
    "tolerance 0.9": ("--tolerance 0.9, viscoelastic", ("--steps-per-decade", "3", "--tolerance", "0.9")),
    "N 2": ("2 steps a decade", ("--steps-per-decade", "2")),
    "N 20": ("20 steps a decade", ("--steps-per-decade", "20")),
}
SOLVERS = ("adr", "implicit")
ADR_TOLERANCE_ERROR = 0.021  # strains and forces at the ADR's default 1e-4 (docs/performance.md section 1: 0.9-2.1 %)


def run_one(out, case, solver, seed, timeout):
    folder = os.path.join(out, "runs", f"{case.replace(' ', '_')}-{solver}-s{seed}")
    path = os.path.join(folder, "results.json")
    if os.path.exists(path):
        res = load_results(path)
        if res.get("status") != "running":  # finished or failed: kept (a killed run stays 'running')
            return folder, res, None
    args = [LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *SIZE, "--seed", str(seed), "--solver", solver, *CASES[case][1], "--out", folder]
    t0 = time.time()
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
        ended = None if p.returncode == 0 else f"exit {p.returncode}"
    except subprocess.TimeoutExpired:
        ended = f"timeout after {timeout} s"
    res = None
    if os.path.exists(path):
        res = load_results(path)
    print(f"bench_extremes: {case} {solver} seed {seed}: {res.get('status', '?')[:60] if res else 'no results'}"
          f"{' (' + ended + ')' if ended else ''} in {time.time() - t0:.0f} s", flush=True)
    return folder, res, ended


def summary(res):
    n = res["n_contacts_by_kind"]
    last = {k: res["per_kind"][k]["broken"][-1] if res["per_kind"][k]["broken"] else None for k in KIND_NAMES}
    return {"status": res["status"], "eps_x": res["swelling_strain_x"][-1] if res["swelling_strain_x"] else None,
            "eps_y": res["swelling_strain_y"][-1] if res["swelling_strain_y"] else None,
            "broken_pct": {k: (100.0 * last[k] / n[k] if n.get(k) and last[k] is not None else None) for k in KIND_NAMES},
            "iterations": res.get("iterations"), "wall_s": res.get("wall_s"), "steps": len(res["times_days"]),
            "fallback": res.get("fallback_steps", []), "n_contacts": n}


def compare(adr, imp, n_contacts):
    """The implicit runs' seed mean of each result against the ADR's seed range, widened by the
    ADR's own error: its tolerance error for the strains (ADR_TOLERANCE_ERROR of the value) and one
    contact of the kind for the broken shares. Returns {result: (implicit mean, lo, hi)}. Where the
    ADR breaks 95 % of the bonded contacts or more, the specimen is a loose assembly of discs with
    no unique equilibrium strain (any arrangement whose contacts carry nothing is one): its strains
    are not compared, only its broken shares ('loose' in the result)."""
    seeds = sorted(set(adr) & set(imp))
    if not seeds:
        return None
    out = {}
    total = sum(n_contacts.values())
    loose = all(sum(adr[s]["broken_pct"][k] * n_contacts[k] / 100 for k in KIND_NAMES) >= 0.95 * total for s in seeds)
    if loose:
        out["loose"] = True
    else:
        for key in ("eps_x", "eps_y"):
            vals = [adr[s][key] for s in seeds]
            mean = sum(imp[s][key] for s in seeds) / len(seeds)
            out[key] = (mean, min(vals) - ADR_TOLERANCE_ERROR * abs(min(vals)), max(vals) + ADR_TOLERANCE_ERROR * abs(max(vals)))
    for k in KIND_NAMES:
        vals = [adr[s]["broken_pct"][k] for s in seeds]
        if any(v is None for v in vals) or not n_contacts.get(k):
            continue
        one = 100.0 / n_contacts[k]
        out[f"broken_{k}"] = (sum(imp[s]["broken_pct"][k] for s in seeds) / len(seeds), max(0.0, min(vals) - one), min(100.0, max(vals) + one))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 3, 5], help="12 mm specimens of seeds 2 and 4 do not hold their aggregates")
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES), metavar="CASE", help=", ".join(CASES))
    ap.add_argument("--jobs", type=int, default=1, help="runs at a time")
    ap.add_argument("--timeout", type=float, default=3600, help="per run [s]")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    work = [(c, s, seed) for c in a.cases for s in SOLVERS for seed in a.seeds]
    with ThreadPoolExecutor(a.jobs) as pool:
        done = list(pool.map(lambda w: run_one(a.out, *w, a.timeout), work))
    table = {}
    for (case, solver, seed), (folder, res, ended) in zip(work, done):
        entry = summary(res) if res else {"status": "no results.json"}
        if ended and entry.get("status") == "running":
            entry["status"] = ended
        table.setdefault(case, {}).setdefault(solver, {})[seed] = entry
    rows = []
    for case in a.cases:
        per = table[case]
        fin = {s: {seed: e for seed, e in per[s].items() if e["status"] == "finished"} for s in SOLVERS}
        n_contacts = next((e["n_contacts"] for e in fin["adr"].values()), {})
        cmp = compare(fin["adr"], fin["implicit"], n_contacts)
        fb = [f for e in fin["implicit"].values() for f in e["fallback"]]
        row = {"case": case, "what": CASES[case][0]}
        for s in SOLVERS:
            row[f"{s}_finished"] = f"{len(fin[s])}/{len(per[s])}"
            row[f"{s}_ended"] = "; ".join(sorted({e["status"][:80] for e in per[s].values() if e["status"] != "finished"}))
            row[f"{s}_wall_s"] = sum(e["wall_s"] for e in fin[s].values())
            row[f"{s}_iterations"] = sum(e["iterations"] for e in fin[s].values())
        row["fallback_steps"] = len(fb)
        row["fallback_wall_s"] = " ".join(f"{f['wall_s']:.1f}" for f in fb)
        if cmp:
            loose = cmp.pop("loose", False)
            row["within"] = all(lo <= m <= hi for m, lo, hi in cmp.values())
            row["deviation"] = ("loose assembly, strains not compared; " if loose else "") + "; ".join(
                f"{k} {m:.3g} in [{lo:.3g}, {hi:.3g}]" if lo <= m <= hi else f"{k} {m:.3g} OUTSIDE [{lo:.3g}, {hi:.3g}]"
                for k, (m, lo, hi) in cmp.items())
        else:
            row["within"], row["deviation"] = None, "no seed finished with both solvers"
        rows.append(row)
    with open(os.path.join(a.out, "extremes.json"), "w") as f:
        json.dump({"runs": table, "rows": rows}, f, indent=1)
    with open(os.path.join(a.out, "extremes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| case | ADR finished | implicit finished | ADR s (iterations) | implicit s (iterations) | fallback steps (s each) | "
             "implicit within the ADR's range | implicit seed mean in [ADR range] (strains; broken shares in %) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        ended = {s: f" ({r[f'{s}_ended']})" if r[f"{s}_ended"] else "" for s in SOLVERS}
        lines.append(f"| {r['case']}: {r['what']} | {r['adr_finished']}{ended['adr']} | {r['implicit_finished']}{ended['implicit']} | "
                     f"{r['adr_wall_s']:.0f} ({r['adr_iterations']:,}) | {r['implicit_wall_s']:.0f} ({r['implicit_iterations']:,}) | "
                     f"{r['fallback_steps']}{' (' + r['fallback_wall_s'] + ')' if r['fallback_steps'] else ''} | "
                     f"{'yes' if r['within'] else ('no' if r['within'] is False else '-')} | {r['deviation']} |")
    with open(os.path.join(a.out, "extremes.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
