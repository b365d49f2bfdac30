#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# The paper-size swelling test timed end to end (issue 7): 100 x 100 mm, ISR, aging viscoelastic
# contacts, damage on, 10 steps a decade, the ADR at tolerance 1e-4, as scripts/swelling_test.py runs it.
#
#   sh scripts/bench/run_paper_size.sh [OUT [THREADS]]      (default out/paper100/isr-ve-dmg, 1 thread)
#
# Writes OUT/results.json (and the run's tables, plots, VTK), OUT.log (the progress lines) and
# OUT.time (GNU time -v: wall clock, peak memory as "Maximum resident set size"), then prints a
# summary: particles, contacts by kind, steps, ADR iterations, wall time, peak memory. It takes
# about 30-60 minutes on one core: run it on an idle machine, e.g. under nohup.
REPO=$(cd "$(dirname "$0")/../.." && pwd)
OUT=${1:-$REPO/out/paper100/isr-ve-dmg}
THREADS=${2:-1}
mkdir -p "$(dirname "$OUT")"
cd "$REPO" || exit 2
echo "run_paper_size: start $(date -u +%FT%TZ), load $(cut -d' ' -f1-3 /proc/loadavg), $THREADS thread(s), out $OUT"
/usr/bin/time -v -o "$OUT.time" "$REPO/scripts/yade-swelldem" -n -j "$THREADS" -x "$REPO/scripts/swelling_test.py" \
	--scenario isr --behaviour viscoelastic --size-mm 100 100 --seed 1 --steps-per-decade 10 --solver adr --tolerance 1e-4 \
	--out "$OUT" >"$OUT.log" 2>&1
rc=$?
echo "run_paper_size: end $(date -u +%FT%TZ), exit $rc, load $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT" "$REPO/py" <<'PY'
import json, re, sys
out = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from swelldem.report import load_results
r = load_results(out + "/results.json")
t = open(out + ".time").read()
wall = re.search(r"Elapsed \(wall clock\) time.*: (\S+)", t).group(1)
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1)) / 1024
n = r["n_contacts_by_kind"]
broken = {k: r["per_kind"][k]["broken"][-1] for k in n} if r["times_days"] else {}
print(f"run_paper_size: status {r['status']}; {r['n_particles']} particles, {sum(n.values())} contacts {n}; "
      f"{len(r['times_days'])} physical steps, {r['iterations']} ADR iterations; run wall {r['wall_s']:.0f} s "
      f"(process {wall}), peak memory {rss:.0f} MB; final strain x {r['swelling_strain_x'][-1]:.4g} y {r['swelling_strain_y'][-1]:.4g}; "
      f"broken {broken}")
summary = {"status": r["status"], "n_particles": r["n_particles"], "n_contacts_by_kind": n, "steps": len(r["times_days"]),
           "iterations": r["iterations"], "iterations_per_step": r["iterations_per_step"], "run_wall_s": r["wall_s"],
           "process_wall": wall, "peak_rss_MB": rss, "final_strain": [r["swelling_strain_x"][-1], r["swelling_strain_y"][-1]],
           "broken": broken}
json.dump(summary, open(out + ".summary.json", "w"), indent=1)
PY
exit $rc
