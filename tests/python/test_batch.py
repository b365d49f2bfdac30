# SPDX-License-Identifier: GPL-2.0-or-later
"""scripts/swelling_test.py as a yade-batch job: the table line sets the SwellingTest fields,
each line writes into its own folder, and the job's O.tags survive the scene's O.reset()."""
import json
import os
import subprocess

from conftest import LAUNCHER, REPO, build_dir

SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")
TABLE = ("# two tiny jobs\n"
         "description  scenario  behaviour  size_mm  steps_per_decade  seed  kind_params\n"
         "isr_s1       'isr'     'elastic'  (12,12)  2                 1     {}\n"
         "\n"
         "isr_s3_ft5   'isr'     'elastic'  (12,12)  2                 3     {'MORTAR':{'tensileStrength':5e6}}\n")


def test_yade_batch_runs_each_line_into_its_folder(tmp_path):
    (tmp_path / "sweep.table").write_text(TABLE)
    (tmp_path / "logs").mkdir()
    env = dict(os.environ, SWELLDEM_BUILD_DIR=build_dir(), OMP_NUM_THREADS="1")
    proc = subprocess.run(["yade-batch", "-j", "1", "--job-threads", "1", "--disable-pynotify", "--plot-update", "0",
                           "--log", "logs/@.log", "--executable", LAUNCHER, "sweep.table", SCRIPT],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    jobs = {"isr_s1": (3, 1, {}), "isr_s3_ft5": (5, 3, {"MORTAR": {"tensileStrength": 5e6}})}
    assert sorted(os.listdir(tmp_path / "out" / "sweep")) == sorted(jobs)
    for name, (line, seed, kind_params) in jobs.items():
        r = json.loads((tmp_path / "out" / "sweep" / name / "results.json").read_text())
        assert r["status"] == "finished"
        c = r["config"]
        assert (c["scenario"], c["behaviour"], c["size_mm"], c["steps_per_decade"], c["seed"], c["kind_params"]) == \
               ("isr", "elastic", [12, 12], 2, seed, kind_params)
        assert c["out"] == os.path.join("out", "sweep", name)
        assert len(r["times_days"]) == 8  # 1 to 3650 days at 2 a decade
        # set by readParamsFromTable before the scene was built; read back after to_yade's O.reset()
        tags = r["yade_tags"]
        assert tags["description"] == name and tags["line"] == f"l{line}"
        assert tags["d.id"] == f"{name}.{tags['id']}" and f"seed={seed}" in tags["params"]
        assert "swelling_test: isr elastic damage on" in (tmp_path / "logs" / f"{name}.log").read_text()


def _job(tmp_path, table_line, *args):
    env = dict(os.environ, SWELLDEM_BUILD_DIR=build_dir(), OMP_NUM_THREADS="1", YADE_BATCH=table_line)
    return subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *args], cwd=tmp_path, capture_output=True, text=True,
                          timeout=120, env=env)


def test_a_bad_table_is_refused_before_work(tmp_path):
    (tmp_path / "bad.table").write_text("description scenario sise_mm\nx 'isr' (12,12)\ny isr (12,12)\n")
    p = _job(tmp_path, "bad.table:2")
    assert p.returncode == 2 and "batch table column = 'sise_mm' is out of range" in p.stderr, p.stderr[-2000:]
    (tmp_path / "bad.table").write_text("description scenario\nx 'isr'\ny isr\n")
    p = _job(tmp_path, "bad.table:3")
    assert p.returncode == 2 and "batch table value" in p.stderr and "strings quoted" in p.stderr, p.stderr[-2000:]
    p = _job(tmp_path, "bad.table:7")
    assert p.returncode == 2 and "batch table line = 'bad.table:7' is out of range" in p.stderr, p.stderr[-2000:]
    assert not (tmp_path / "out").exists()


def test_the_shipped_sweep_table_reads(yade_run):
    table = os.path.join(REPO, "scripts", "swelling_sweep.table")
    script = ("from swelldem import scenario\n"
              f"rows = [i for i, l in enumerate(open({table!r}), 1) if l.strip() and not l.startswith('#')][1:]\n"
              f"tests = [scenario.from_batch_table(scenario.SwellingTest(), {table!r} + ':' + str(i)) for i in rows]\n"
              "for t in tests: t.validate()\n"
              "dump([[t.out, t.behaviour, t.damage, list(t.size_mm), t.kind_params] for t in tests])\n")
    got = yade_run(script, threads=1, timeout=120)
    assert got == [["out/swelling_sweep/isr_el", "elastic", True, [30, 30], {}],
                   ["out/swelling_sweep/isr_ve", "viscoelastic", True, [30, 30], {}],
                   ["out/swelling_sweep/isr_ve_nodmg", "viscoelastic", False, [30, 30], {}],
                   ["out/swelling_sweep/isr_ve_ft5", "viscoelastic", True, [30, 30], {"MORTAR": {"tensileStrength": 5e6}}]]
