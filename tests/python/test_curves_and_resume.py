# SPDX-License-Identifier: GPL-2.0-or-later
"""A run's per-step curves (curves.csv, plot_data.txt in yade.plot.saveDataTxt's form), its saved
state (--save-state: state.yade after every step, final.yade.gz at the end) and --resume DIR: a run
stopped by SIGTERM, or killed, after some steps and resumed ends with the results of the run that
was not stopped, bit for bit. 12 mm ISR specimens, viscoelastic with damage, 5 steps a decade."""
import csv
import json
import math
import os
import re
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import LAUNCHER, REPO, build_dir, script_stderr, without_keys

SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")
ARGS = ("--scenario", "isr", "--size-mm", "12", "12", "--seed", "1", "--steps-per-decade", "5", "--save-state")
ENV = {**os.environ, "SWELLDEM_BUILD_DIR": build_dir()}
#: What may differ between a resumed run and the run that was not stopped: wall times, the times of
#: the writes, the resumes' record, the process's yade tags and the output folder.
# linear_solver: the direct solve's cost (factorization time; a resumed run analyses its graph again)
NOT_PHYSICAL = ("wall_s", "updated", "resumed", "yade_tags", "out", "linear_solver")


def swelling_test(*args, check=True):
    p = subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *args], capture_output=True, text=True, timeout=600, env=ENV)
    if check:
        assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    return p


def physical(v):
    """v without the NOT_PHYSICAL keys, at any depth."""
    return without_keys(v, NOT_PHYSICAL)


def results(out):
    return json.loads((out / "results.json").read_text())


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """Uninterrupted runs with --save-state, ADR and implicit: {solver: folder}."""
    tmp = tmp_path_factory.mktemp("reference")
    for solver in ("adr", "implicit"):
        swelling_test(*ARGS, "--solver", solver, "--out", str(tmp / solver))
    return {solver: tmp / solver for solver in ("adr", "implicit")}


@pytest.fixture(scope="module")
def interrupted(tmp_path_factory):
    """An ADR run stopped by SIGTERM after at least 11 of its 18 steps, once its ITZ has begun to
    crack (from step 10, 100 d; the ADR's steps take 0.05 to 0.4 s at 12 mm, so the signal comes
    before the end)."""
    out = tmp_path_factory.mktemp("interrupted") / "run"
    p = subprocess.Popen([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *ARGS, "--solver", "adr", "--out", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV)
    deadline = time.time() + 300
    while time.time() < deadline and p.poll() is None:
        try:
            if len(results(out)["times_days"]) >= 11:
                break
        except (OSError, ValueError):
            pass
        time.sleep(0.05)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=300)
    assert p.returncode == 1, err[-3000:]
    # the one line says where the run stopped: its step and how far into it
    assert re.search(r"interrupted by SIGTERM during step (\d+)/18 \(t = [0-9.e+]+ to [0-9.e+]+ d\), \d+ iterations into it, "
                     r"\d+ in all; results so far in ", err), err[-3000:]
    return out


def read_curves(out):
    with open(out / "curves.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(v) for v in r] for r in rows[1:]]


def test_curves_csv_holds_every_per_step_series_of_results_json(reference):
    out = reference["adr"]
    res = results(out)
    head, rows = read_curves(out)
    n = len(res["times_days"])
    assert len(rows) == n == res["n_steps"] == 18
    expected = {"t [d]": res["times_days"], "swelling_strain_x [-]": res["swelling_strain_x"],
                "swelling_strain_y [-]": res["swelling_strain_y"], "swelling_strain_area [-]": res["swelling_strain_area"],
                "unbalanced_ratio [-]": res["unbalanced_ratio"], "iterations [-]": res["iterations_per_step"],
                "step_at_round_off [-]": [int(v) for v in res["step_at_round_off"]], "round_off_ratio [-]": res["round_off_ratio"]}
    for kind in ("MORTAR", "ITZ", "AGG"):
        d = res["per_kind"][kind]
        expected.update({f"{kind} fn_p05 [kN]": d["fn_p05_kN"], f"{kind} fn_p95 [kN]": d["fn_p95_kN"],
                         f"{kind} broken [-]": d["broken"],
                         f"{kind} broken_pct [%]": [100.0 * v / res["n_contacts_by_kind"][kind] for v in d["broken"]],
                         f"{kind} born_broken [-]": d["born_broken"]})
    assert head == list(expected)  # the free specimen has no platen or bar columns
    for c, name in enumerate(head):
        assert [r[c] for r in rows] == expected[name], name  # the same doubles: repr's in the CSV
    assert sum(res["per_kind"]["ITZ"]["broken"]) > 0


def test_curves_of_a_platen_run_hold_its_platen_stress(tmp_path):
    """Only the axis with platens gets platen columns, the values results.json holds."""
    out = tmp_path / "run"
    swelling_test("--scenario", "isr", "--behaviour", "elastic", "--no-damage", "--size-mm", "12", "12", "--steps-per-decade", "2",
                  "--boundary-x", "fixed", "--out", str(out))
    res = results(out)
    head, rows = read_curves(out)
    assert [h for h in head if h.startswith("platen")] == ["platen_stress_x [Pa]", "platen_disp_x [m]"]
    assert [r[head.index("platen_stress_x [Pa]")] for r in rows] == res["platen_stress_x_Pa"]
    assert min(res["platen_stress_x_Pa"]) < 0  # the restrained swelling compresses the platens


PLOT_DATA = r"""
import sys, numpy
from yade import plot
path, again = sys.argv[1], sys.argv[2]
d = numpy.genfromtxt(path, names=True, dtype=None, encoding="utf-8")   # the reader saveDataTxt's doc names
plot.data = {name: [v.item() for v in d[name]] for name in d.dtype.names}
plot.saveDataTxt(again, vars=d.dtype.names)   # YADE's own writer, from the loaded columns
dump({name: plot.data[name] for name in d.dtype.names})
"""


def test_plot_data_is_what_yade_plot_writes_and_reads(reference, yade_run, tmp_path):
    """YADE 2023.02a's yade.plot writes with saveDataTxt and has no reader of its own (its doc
    reads the file with numpy.genfromtxt(names=True)): in real YADE, the file loaded that way into
    yade.plot.data and written again by saveDataTxt is the same file, byte for byte, and its
    columns are results.json's series."""
    out = reference["adr"]
    res = results(out)
    data = yade_run(PLOT_DATA, out / "plot_data.txt", tmp_path / "again.txt", threads=1)
    assert (tmp_path / "again.txt").read_bytes() == (out / "plot_data.txt").read_bytes()
    assert data["times_days"] == res["times_days"]
    assert data["swelling_strain_y"] == res["swelling_strain_y"]
    assert data["fn_p95_kN_ITZ"] == res["per_kind"]["ITZ"]["fn_p95_kN"]
    assert data["broken_AGG"] == res["per_kind"]["AGG"]["broken"]
    assert len(data) == len(read_curves(out)[0])


def test_save_state_leaves_the_final_scene(reference):
    for out in reference.values():
        assert (out / "final.yade.gz").exists() and not (out / "state.yade").exists()
        assert results(out)["config"]["save_state"] is True


def assert_same_run(out, ref):
    assert physical(results(out)) == physical(results(ref))
    for name in ("curves.csv", "plot_data.txt", "table.csv"):
        assert (out / name).read_bytes() == (ref / name).read_bytes(), name
    a, b = np.load(out / "contact_breaks.npz"), np.load(ref / "contact_breaks.npz")
    for k in b.files:
        # a box's breaks have no segment in a plane (NaN), which is equal to itself here
        assert np.array_equal(a[k], b[k], equal_nan=a[k].dtype.kind == "f"), f"contact_breaks.npz {k}: {a[k][a[k] != b[k]][:8]} against {b[k][a[k] != b[k]][:8]}"


def test_a_run_stopped_by_sigterm_and_resumed_equals_the_uninterrupted_one(reference, interrupted, tmp_path):
    out = tmp_path / "run"
    shutil.copytree(interrupted, out)
    stopped = results(out)
    k = len(stopped["times_days"])
    assert stopped["status"] == "interrupted: SIGTERM" and 11 <= k < 18 and (out / "state.yade").exists()
    assert stopped["per_kind"]["ITZ"]["broken"][-1] > 0  # the breaks before the stop are kept with their steps
    assert [r[0] for r in read_curves(out)[1]] == stopped["times_days"]  # the stopped run keeps its curves
    p = swelling_test("--resume", str(out))
    assert f"swelldem: resumed from {out / 'state.yade'}: " in p.stdout
    res = results(out)
    assert res["status"] == "finished" and res["resumed"][0]["steps_done"] in (k, k - 1)
    assert_same_run(out, reference["adr"])


KILLED = r"""
import os, shutil, signal, sys
from swelldem import scenario
test = scenario.SwellingTest(scenario="isr", size_mm=(12.0, 12.0), seed=1, steps_per_decade=5, save_state=True, out=sys.argv[1])
def kill():   # after the recorder has written step 11 and saved the state: killed as by SIGKILL, no word
    rows = len(open(sys.argv[1] + "/curves.csv").read().splitlines()) - 1
    if rows == 10:   # the state a step behind, as left by a kill between results.json's write and the save
        shutil.copy(sys.argv[1] + "/state.yade", sys.argv[1] + "/state-10.yade")
    if rows == 11:
        os.kill(os.getpid(), signal.SIGKILL)
scenario.run(test, after_step=kill)
"""


@pytest.mark.parametrize("behind", [False, True])
def test_a_killed_implicit_run_resumed_equals_the_uninterrupted_one(reference, yade_run, tmp_path, behind):
    """Killed after step 11 (its state saved), or with the state of step 10 only (killed between
    the step's results and its save): the results of the steps the state has not done are dropped
    and done again."""
    out = tmp_path / "run"
    yade_run(KILLED, out, threads=1, check=False)
    assert yade_run.proc.returncode == -signal.SIGKILL
    killed = results(out)
    assert killed["status"] == "running" and len(killed["times_days"]) == 11 and killed["per_kind"]["ITZ"]["broken"][-1] > 0
    if behind:
        os.replace(out / "state-10.yade", out / "state.yade")
    swelling_test("--resume", str(out))
    assert results(out)["resumed"][0]["steps_done"] == (10 if behind else 11)
    assert_same_run(out, reference["implicit"])


def test_resume_refuses_other_settings_and_folders_it_cannot_continue(reference, interrupted, tmp_path):
    out = tmp_path / "run"
    shutil.copytree(interrupted, out)
    before = (out / "results.json").read_bytes()
    cases = [(("--resume", str(out), "--seed", "2"),
              f"swelldem: seed = 2 is out of range; allowed: 1, the run's in {out} (--resume continues it with its own settings)"),
             (("--resume", str(out), "--steps-per-decade", "10"),
              f"swelldem: steps_per_decade = 10.0 is out of range; allowed: 5.0, the run's in {out} (--resume continues it with its own settings)"),
             (("--resume", str(out), "--out", str(tmp_path / "other")),
              f"swelldem: out = '{tmp_path / 'other'}' is out of range; allowed: {out}, the folder --resume continues, or left out"),
             (("--resume", str(reference["adr"])),
              f"swelldem: resume = '{reference['adr']}' is out of range; allowed: the folder of a run that did not finish (this one finished)"),
             (("--resume", str(tmp_path / "none")),
              f"swelldem: resume = '{tmp_path / 'none'}' is out of range; allowed: the folder of a run made with --save-state")]
    for args, message in cases:
        p = swelling_test(*args, check=False)
        assert (p.returncode, script_stderr(p.stderr)) == (2, [f"swelling_test.py: {message}"]), args
    # a run made without --save-state has no state to go on from
    plain = tmp_path / "plain"
    shutil.copytree(interrupted, plain)
    os.remove(plain / "state.yade")
    p = swelling_test("--resume", str(plain), check=False)
    assert script_stderr(p.stderr) == [f"swelling_test.py: swelldem: resume = '{plain}' is out of range; allowed: the folder of a "
                                       f"run made with --save-state (no state.yade in it)"]
    assert (out / "results.json").read_bytes() == before  # refused before any work
    assert math.isfinite(results(out)["wall_s"])


KILLED_3D = r"""
import os, signal, sys
from swelldem import scenario
test = scenario.SwellingTest(scenario="isr", dim=3, size_mm=(12.0, 12.0, 12.0), aggregate_area_fraction=0.2, seed=1,
                             steps_per_decade=2, save_state=True, out=sys.argv[1])
def kill():   # after step 5, the cracking step (day 316): its factor and Woodbury columns are in the state
    if len(open(sys.argv[1] + "/curves.csv").read().splitlines()) - 1 == 5:
        os.kill(os.getpid(), signal.SIGKILL)
scenario.run(test, after_step=kill)
"""


def test_a_killed_3d_implicit_run_resumed_equals_the_uninterrupted_one(yade_run, tmp_path):
    """A 12 mm box with damage, killed after its cracking step and resumed: its last three steps
    (33, 18 and 6 Newton iterations, a sliding contact's columns solved in blocks) end as in the
    run that was not stopped, to the bit."""
    ref = tmp_path / "ref"
    swelling_test("--dim", "3", "--size-mm", "12", "12", "12", "--aggregate-area-fraction", "0.2", "--seed", "1",
                  "--steps-per-decade", "2", "--save-state", "--out", str(ref))
    out = tmp_path / "run"
    yade_run(KILLED_3D, out, threads=1, check=False)
    assert yade_run.proc.returncode == -signal.SIGKILL
    killed = results(out)
    assert killed["status"] == "running" and len(killed["times_days"]) == 5 and killed["per_kind"]["ITZ"]["broken"][-1] > 0
    swelling_test("--resume", str(out))
    assert results(out)["resumed"][0]["steps_done"] == 5
    assert_same_run(out, ref)
