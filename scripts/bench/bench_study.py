#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Wall time of the paper's study over seeds on a local Dask cluster against the same study run
serially, both in this call (the machine is shared: only the ratio is compared).

    /usr/bin/python3 scripts/bench/bench_study.py [--size-mm 40 40] [--seeds 1 2 3] [--jobs 2]
        [--solver implicit] [--steps-per-decade 10] [--out out/bench/study40] [--json FILE]

Runs scripts/paper_study.py twice from empty folders: --jobs 1 (serial: one worker) into
OUT/serial and --jobs N into OUT/parallel, which is kept as the study's result (tables.md,
index.md, the figures over seeds). Prints both wall times and their ratio, and writes them to
the JSON file (default OUT/bench_study.json)."""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

import _common as C  # noqa: E402  (puts py/ on the path)

STUDY = os.path.join(C.REPO_DIR, "scripts", "paper_study.py")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size-mm", type=float, nargs=2, default=[40.0, 40.0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--solver", default="implicit")
    ap.add_argument("--steps-per-decade", type=float, default=10.0)
    ap.add_argument("--out", default="out/bench/study40")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    rows = {}
    for label, jobs in (("serial", 1), ("parallel", a.jobs)):
        out = os.path.join(a.out, label)
        shutil.rmtree(out, ignore_errors=True)
        cmd = [sys.executable, STUDY, "--size-mm", *[f"{v:g}" for v in a.size_mm], "--seeds", *map(str, a.seeds), "--jobs", str(jobs),
               "--solver", a.solver, "--steps-per-decade", f"{a.steps_per_decade:g}", "--out", out]
        os.makedirs(a.out, exist_ok=True)
        t0 = time.time()
        with open(out + ".log", "w") as log:
            rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
        wall = time.time() - t0
        with open(os.path.join(out, "runs.json")) as f:
            runs = json.load(f)["runs"]
        rows[label] = {"jobs": jobs, "wall_s": wall, "exit": rc, "runs": len(runs),
                       "run_wall_sum_s": sum(r.get("wall_s") or 0.0 for r in runs.values()),
                       "finished": sum(r.get("state") == "finished" for r in runs.values())}
        print(f"bench_study: {label} (--jobs {jobs}): {wall:.0f} s, {rows[label]['finished']} of {len(runs)} runs finished, "
              f"runs' own wall times add up to {rows[label]['run_wall_sum_s']:.0f} s (exit {rc})", flush=True)
    ratio = rows["serial"]["wall_s"] / rows["parallel"]["wall_s"]
    print(f"bench_study: serial / parallel wall time = {ratio:.2f} ({a.jobs} workers)")
    path = a.json or os.path.join(a.out, "bench_study.json")
    with open(path, "w") as f:
        json.dump({"settings": vars(a), "rows": rows, "ratio_serial_over_parallel": ratio}, f, indent=1)


if __name__ == "__main__":
    main(sys.argv[1:])
