# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's numerical swelling tests on a generated concrete specimen.

  scripts/yade-swelldem -n -x scripts/swelling_test.py --scenario isr|asr-fine|asr-coarse \
      --behaviour elastic|viscoelastic [--no-damage] [--size-mm W H] [--seed S] \
      [--steps-per-decade N] [--tolerance TOL] [--kind-param MORTAR.tensileStrength=5e6 ...] \
      [--solver-param fallbackIterations=3 ...] \
      [--temperature-c T | --temperature-csv FILE] [--boundary-x free|fixed|stress:S|spring:K] \
      [--boundary-y ...] [--boundary-z ... (3D)] [--rebar-ratio R] [--save-state] --out DIR
  scripts/yade-swelldem -n -x scripts/swelling_test.py --resume DIR
  scripts/yade-swelldem -n -x scripts/swelling_test.py --dim 3 --size-mm W H D [--solver implicit|adr] [--boundary-z ...] ... --out DIR

writes DIR/results.json, DIR/table.md, DIR/table.csv, DIR/*.png (swelling strain, unbalanced force,
force quantiles, crack map) and DIR/vtk/ (ParaView: particles and contacts .vtp files of the last step,
or of every k-th with --vtk-every k, and particles.pvd / contacts.pvd with the times in days),
DIR/curves.csv and DIR/plot_data.txt (every per-step series; the second in yade.plot.saveDataTxt's form)
and, with --save-state, DIR/state.yade after every step (--resume DIR continues a run stopped
after some steps from it, with the run's own settings) and DIR/final.yade.gz at the end.
A 3D box (--dim 3) writes the same, its crack maps as three mid-plane sections, with
DIR/crack_map_3d_view.png (the broken contacts in 3D) and DIR/crack_sections.csv (the sections' counts);
its results gain the z strain and the volume change, its ParaView files hold the spheres as points.
The options are the fields of swelldem.scenario.SwellingTest; --kind-param sets any ContactKind
attribute of one kind, --solver-param any setting of the solver (see `--help`).

As a yade-batch job, each table column sets the field of its name and each line writes into
out/<table name>/<description> (docs/scenarios.md, "Parameter sweeps with yade-batch"):

  mkdir -p out/swelling_sweep && yade-batch -j 2 --job-threads 1 --log 'out/swelling_sweep/@.log' \
      --executable "$PWD/scripts/yade-swelldem" scripts/swelling_sweep.table scripts/swelling_test.py"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))), "py"))
from swelldem import options, scenario  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
scenario.add_arguments(ap)
scenario.add_resume_argument(ap)
with options.refuse_bad("swelling_test.py"):  # exit status 2, as argparse's, before any work
    args = ap.parse_args(sys.argv[1:])
    # under yade-batch (YADE_BATCH set) the job's table line overrides the command line's values
    test = scenario.from_batch_table(scenario.from_arguments(args))
    if args.resume:
        test = scenario.resumed_test(args.resume, test, scenario.given_options(ap, sys.argv[1:]))
    prepared = scenario.prepare(test)
# a run that stops (failed, interrupted) ends with its one-line status on stderr and exit status 1
res = scenario.run_or_exit(test, "swelling_test.py", prepared, resume=bool(args.resume))
z = f" z {res['swelling_strain_z'][-1] * 1e6:.0f}e-6, volume {res['swelling_strain_volume'][-1] * 1e6:.0f}e-6" if test.dim == 3 else ""
print(f"swelling_test: {test.scenario} {test.behaviour} damage {'on' if test.damage else 'off'}, solver {test.solver}: "
      f"{res['n_particles']} particles, strain x {res['swelling_strain_x'][-1] * 1e6:.0f}e-6 y {res['swelling_strain_y'][-1] * 1e6:.0f}e-6{z}, "
      f"iterations {res['iterations']}, wall {res['wall_s']:.1f} s")
print(open(os.path.join(test.out, "table.md")).read())
# what the folder holds, listed from it: every file the run wrote (docs/guide.md, section 2, says what each is)
written = sorted(n + "/" if os.path.isdir(os.path.join(test.out, n)) else n for n in os.listdir(test.out))
print(f"results, tables and plots in {test.out}/: {', '.join(written)} (docs/guide.md, section 2)")
