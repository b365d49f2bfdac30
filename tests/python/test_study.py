# SPDX-License-Identifier: GPL-2.0-or-later
"""Studies on Dask distributed (swelldem.study, scripts/study.py): a Dask scheduler and two workers
started as separate processes on this machine (loopback only, as on a cluster), a 4-run study
submitted to them with one worker killed while it runs a swelling test: the study still finishes,
every run's results.json equals the same run made by a local cluster (all but wall times and the
folder), and a second call does no work. Then the table's form, the options handed to
swelling_test.py (parsed back by its own parser) and bad input refused before any work."""
import json
import os
import re
import signal
import subprocess
import sys
import time

import pytest

from conftest import REPO, build_dir, without_keys

sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import scenario, study  # noqa: E402

STUDY = os.path.join(REPO, "scripts", "study.py")
WORKER = os.path.join(REPO, "scripts", "study-worker")
#: 2D ISR runs of 10 to 20 s each, long enough to kill a worker in the middle of one.
TABLE = """# four swelling tests
description  scenario    behaviour       damage  size_mm   steps_per_decade
isr_el       'isr'       'elastic'       True    (16,16)   3
isr_ve       'isr'       'viscoelastic'  True    =         =
fine_ve      'asr-fine'  'viscoelastic'  True    =         =
fine_nodmg   'asr-fine'  'viscoelastic'  False   =         =
"""
NAMES = ["isr_el", "isr_ve", "fine_ve", "fine_nodmg"]
#: What differs between two runs of the same settings: the clock, YADE's run id and the folder they were told.
CLOCK = {"wall_s", "updated", "factor_wall_s", "resumed"}

pytest.importorskip("distributed", reason="Dask distributed (Debian python3-distributed) is installed by scripts/setup.sh")


def env():
    return {**os.environ, "SWELLDEM_BUILD_DIR": build_dir(), "PYTHONPATH": os.path.join(REPO, "py")}


def results(folder):
    with open(os.path.join(folder, "results.json")) as f:
        res = json.load(f)
    res["config"].pop("out")
    for k in ("id", "d.id"):  # YADE's run id: the start time and the process id
        res["yade_tags"].pop(k, None)
    return without_keys(res, CLOCK)


def call(table, out, *args, timeout=900):
    return subprocess.run([sys.executable, STUDY, "--table", str(table), "--out", str(out), *args], capture_output=True, text=True,
                          timeout=timeout, env=env())


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    path = tmp_path_factory.mktemp("table") / "four.table"
    path.write_text(TABLE)
    return path


@pytest.fixture(scope="module")
def local(table, tmp_path_factory):
    out = tmp_path_factory.mktemp("local") / "study"
    p = call(table, out, "--jobs", "2")
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    return out


def start(cmd, log):
    return subprocess.Popen(cmd, stdout=open(log, "w"), stderr=subprocess.STDOUT, env=env(), start_new_session=True)


def test_a_study_on_a_scheduler_survives_a_killed_worker(table, local, tmp_path):
    sched_file = tmp_path / "scheduler.json"
    procs = [start([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                    "--dashboard-address", ":0", "--scheduler-file", str(sched_file)], tmp_path / "scheduler.log")]
    try:
        for _ in range(300):
            if sched_file.exists() and sched_file.stat().st_size:
                break
            time.sleep(0.1)
        address = json.loads(sched_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:"), address
        # no nanny: killing the worker process is the worker's death, as a lost machine
        workers = [start([WORKER, address, "--no-nanny", "--host", "127.0.0.1", "--name", f"w{i}"], tmp_path / f"worker{i}.log")
                   for i in range(2)]
        procs += workers
        out = tmp_path / "cluster"
        study_proc = subprocess.Popen([sys.executable, STUDY, "--table", str(table), "--out", str(out), "--scheduler", address],
                                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env())
        lines, killed = [], None
        for line in study_proc.stdout:
            lines.append(line)
            m = re.search(r"\] (\w+): running on (tcp://\S+) ", line)
            if m and killed is None:
                time.sleep(4)  # in the middle of the run: YADE started, the steps going
                run, worker_address = m.group(1), m.group(2)
                victim = [w for w in workers if worker_address.endswith(":" + worker_port(tmp_path, workers.index(w)))]
                assert len(victim) == 1, (worker_address, [worker_port(tmp_path, i) for i in range(2)])
                os.killpg(victim[0].pid, signal.SIGKILL)
                killed = run
        assert study_proc.wait(timeout=900) == 0, "".join(lines)[-4000:]
        text = "".join(lines)
        assert killed is not None, text
        record = json.loads((out / "runs.json").read_text())["runs"]
        # the killed worker's run ran again on the other worker and finished
        attempts = record[killed]["attempts"]
        assert len(attempts) == 2 and attempts[0]["worker"] != attempts[1]["worker"], record[killed]
        assert record[killed]["state"] == "finished"
        for name in NAMES:
            assert record[name]["state"] == "finished" and record[name]["wall_s"] > 0 and record[name]["host"], record[name]
            assert results(out / name) == results(local / name), name
        # a second call does no work
        stamps = {n: os.stat(out / n / "results.json").st_mtime_ns for n in NAMES}
        p = call(table, out, "--scheduler", address, timeout=300)
        assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
        assert p.stdout.count("kept (finished in an earlier call)") == 4 and "running on" not in p.stdout, p.stdout
        assert {n: os.stat(out / n / "results.json").st_mtime_ns for n in NAMES} == stamps
    finally:
        for p in procs:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
        for p in procs:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)


def worker_port(tmp_path, i):
    m = re.search(r"Listening to:\s+tcp://127\.0\.0\.1:(\d+)", (tmp_path / f"worker{i}.log").read_text())
    return m.group(1) if m else "?"


def test_local_study_records_and_summary(local):
    """The local cluster's record (one attempt a run, on one of two workers) and the summary's
    mean and range recomputed from the runs' results.json."""
    record = json.loads((local / "runs.json").read_text())["runs"]
    assert len({r["worker"] for r in record.values()}) == 2, record  # both workers ran
    for name in NAMES:
        assert record[name]["state"] == "finished" and len(record[name]["attempts"]) == 1
    summary = (local / "summary.md").read_text()
    res = results(local / "isr_ve")
    strain = res["swelling_strain_x"][-1] * 1e6
    assert re.search(rf"\| isr_ve \| 1 / 1 \| {strain:.4g} \|", summary), summary


def test_command_options_parse_back_to_the_same_test(tmp_path):
    """The options a worker hands to swelling_test.py, read by swelling_test.py's own parser."""
    import argparse
    settings = {"dim": 3, "scenario": "asr-fine", "damage": False, "size_mm": (12.0, 12.0, 24.0), "t_start_days": 28.0,
                "boundary_z": "stress:-1e+06", "eps_inf": 0.1 / 3, "seed": 7, "tolerance": None, "save_state": True,
                "kind_params": {"MORTAR": {"tensileStrength": 5e6}, "AGG": {"young": 6.1e10}},
                "solver_params": {"maxIterations": 40000, "stallTolerance": 2e-5}}
    ap = argparse.ArgumentParser()
    scenario.add_arguments(ap)
    got = scenario.from_arguments(ap.parse_args(study.command_options(settings) + ["--out", str(tmp_path)]))
    assert got == scenario.SwellingTest(out=str(tmp_path), **settings)


@pytest.mark.parametrize("text,args,needle", [
    ("description scenario colour\na 'isr' 1\n", [], "swelldem: table column = "),
    ("scenario seed\n'isr' 1\n", ["--seeds", "1", "2"], "sets its own seed (1)"),
    ("scenario size_mm\nisr (16,16)\n", [], "a Python literal without blanks"),
    ("scenario size_mm\n'isr' (16,16)\n'isr' =\n", [], "run names = "),
    ("scenario size_mm\n'isr' (1,1)\n", [], "run scenario=isr_size_mm=1x1: swelldem: sieve_fractions_mm"),
    ("scenario\n'isr'\n", ["--jobs", "0"], "swelldem: jobs = 0 is out of range"),
])
def test_bad_tables_and_options_refused_before_work(tmp_path, text, args, needle):
    table = tmp_path / "t.table"
    table.write_text(text)
    out = tmp_path / "out"
    p = call(table, out, *args, timeout=120)
    assert p.returncode == 2 and p.stderr.startswith("study.py: ") and needle in p.stderr, p.stderr
    assert not out.exists()


def test_other_settings_in_a_study_folder_refused(table, local, tmp_path):
    other = tmp_path / "other.table"
    other.write_text(TABLE.replace("(16,16)", "(18,18)"))
    p = call(other, local, timeout=120)
    assert p.returncode == 2 and "swelldem: out = " in p.stderr and "size_mm [16.0, 16.0] (asked [18.0, 18.0])" in p.stderr, p.stderr
