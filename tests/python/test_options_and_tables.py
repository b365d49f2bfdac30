# SPDX-License-Identifier: GPL-2.0-or-later
"""Issue 14, bad input: every script checks all its options (NaN and infinity included) before any
work, with one message form and exit status 2; the table scripts refuse malformed results.json
files by name and mark runs that did not finish. Mostly plain Python; the scripts that need YADE
run through the launcher and stop at their checks (a few seconds each)."""
import dataclasses
import json
import math
import os
import subprocess
import sys
import time

import pytest

from conftest import LAUNCHER, REPO, build_dir, script_stderr

from swelldem import options, report, scenario  # noqa: E402  (conftest puts py/ on the path)

FORM = "swelldem: {} = {} is out of range; allowed: "


# ------------------------------------------------------------------ the shared checks

@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, -1.0, "3", True, None])
def test_number_refuses_what_is_not_a_finite_value_in_range(value):
    with pytest.raises(options.OptionError) as e:
        options.number("eps_inf", value, lo=0)
    assert str(e.value) == FORM.format("eps_inf", repr(value)) + "0 < eps_inf < inf"


def test_number_bounds_and_message():
    assert options.number("x", 0.0, lo=0, lo_incl=True) == 0.0
    assert options.number("x", 1.0, lo=0, hi=1, hi_incl=True) == 1.0
    with pytest.raises(options.OptionError, match=r"^swelldem: x = 1.0 is out of range; allowed: 0 < x < 1 \[mm\]$"):
        options.number("x", 1.0, lo=0, hi=1, unit="mm")
    with pytest.raises(options.OptionError, match=r"size_mm = \(12.0, nan\) is out of range; allowed: 2 numbers, each 0 < size_mm"):
        options.numbers("size_mm", (12.0, math.nan), count=2, lo=0)
    with pytest.raises(options.OptionError, match=r"size_mm = \(12.0,\) is out of range"):
        options.numbers("size_mm", (12.0,), count=2, lo=0)
    with pytest.raises(options.OptionError, match=r"seed = 1.5 is out of range; allowed: an integer >= 0"):
        options.integer("seed", 1.5, lo=0)
    assert isinstance(options.OptionError("x"), ValueError), "scripts treat the plugin's ValueErrors and these alike"


def test_a_loose_tolerance_warns_on_stderr(capsys):
    assert options.tolerance("tolerance", 1e-3) == 1e-3
    assert capsys.readouterr().err == ""
    assert options.tolerance("tolerance", 0.9) == 0.9
    err = capsys.readouterr().err
    assert "swelldem: warning: tolerance = 0.9 is looser than the useful range (<= 0.001" in err and "docs/performance.md" in err
    for bad in (0, 1, math.nan, math.inf):
        with pytest.raises(options.OptionError, match="tolerance = .* is out of range; allowed: 0 < tolerance < 1"):
            options.tolerance("tolerance", bad)


def test_refuse_bad_exits_2_with_the_message(capsys):
    with pytest.raises(SystemExit) as e:
        with options.refuse_bad("prog.py"):
            options.number("young", math.inf, lo=0, unit="Pa")
    assert e.value.code == 2
    assert capsys.readouterr().err == "prog.py: swelldem: young = inf is out of range; allowed: 0 < young < inf [Pa]\n"


NUMERIC_FIELDS = [f.name for f in dataclasses.fields(scenario.SwellingTest) if f.type in (float, "float")]


@pytest.mark.parametrize("bad", [math.nan, math.inf])
@pytest.mark.parametrize("name", NUMERIC_FIELDS)
def test_every_numeric_field_of_a_swelling_test_refuses_nan_and_infinity(name, bad):
    """Every float field, including any added later (the list is read from the dataclass)."""
    assert len(NUMERIC_FIELDS) >= 10
    test = scenario.SwellingTest(**{name: bad})
    with pytest.raises(options.OptionError, match="^" + FORM.format(name, repr(bad)).replace("(", r"\(")):
        test.validate()


# ------------------------------------------------------------------ scripts

def _refused(cmd, needle, out_dir):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300, cwd=REPO,
                       env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir(), "PYTHONPATH": os.path.join(REPO, "py")})
    assert p.returncode == 2, (p.returncode, p.stdout[-1500:], p.stderr[-1500:])
    assert needle in p.stderr, p.stderr[-2000:]
    assert "Traceback" not in p.stderr
    assert not out_dir.exists() or not any(out_dir.iterdir()), "nothing is written before the checks pass"


YADE_SCRIPTS = [
    # the cases: NaN passed the Python check and switched swelling off, or reached the plugin late
    ("table_3_2.py", ("--eps-inf", "nan"), "table_3_2.py: " + FORM.format("eps_inf", "nan")),
    ("table_3_2.py", ("--size-mm", "nan", "10"), "table_3_2.py: " + FORM.format("size_mm", "(nan, 10.0)")),
    ("table_3_2.py", ("--tolerance", "inf"), FORM.format("tolerance", "inf")),
    ("table_3_2.py", ("--t-start", "5000"), FORM.format("t_start", "5000.0") + "0 < t_start < 3650"),
    ("table_3_2.py", ("--young", "nan"), FORM.format("young", "nan")),
    ("table_3_2.py", ("--steps-per-decade", "20000"), "stepsPerDecade = 20000 is out of range"),  # the plugin's check, still first
    ("two_particles.py", ("--steps-per-decade", "nan"), FORM.format("steps_per_decade", "nan")),
    ("bench/bench_implicit_damage.py", ("--size-mm", "nan", "10"), FORM.format("size_mm", "(nan, 10.0)")),
    ("bench/bench_implicit_damage.py", ("--tolerance", "-1"), FORM.format("tolerance", "-1.0")),
    ("two_particles.py", ("--t-start", "inf"), FORM.format("t_start", "inf")),
]


@pytest.mark.parametrize("script,args,needle", YADE_SCRIPTS, ids=[f"{s}{' '.join(a)}" for s, a, _ in YADE_SCRIPTS])
def test_yade_scripts_refuse_bad_options_before_work(tmp_path, script, args, needle):
    out = tmp_path / "out"
    _refused([LAUNCHER, "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", script), *args, "--out", str(out)], needle, out)


PLAIN_SCRIPTS = [
    ("make_mesostructure.py", ("--thickness-m", "nan", "--out", "{out}"), FORM.format("thickness_m", "nan")),
    ("make_mesostructure.py", ("--size-mm", "inf", "10", "--out", "{out}"), FORM.format("width_mm", "inf")),
    ("bench/bench_mesostructure.py", ("--size-mm", "10", "nan", "--json", "{out}/b.json"), FORM.format("size_mm", "(10.0, nan)")),
    ("bench/bench_solvers.py", ("--adr-tolerance", "nan", "--out", "{out}"), FORM.format("adr_tolerance", "nan")),
    ("bench/bench_accuracy.py", ("--size-mm", "inf", "--out", "{out}"), FORM.format("size_mm", "inf")),
    ("bench/bench_accuracy.py", ("--reference", '{"tolerance": -1}', "--out", "{out}"), FORM.format("reference tolerance", "-1")),
    ("bench/bench_adr_vs_yade.py", ("--tolerances", "1e-3", "nan", "--out", "{out}/a.json"), FORM.format("tolerances", "(0.001, nan)")),
    ("bench/bench_law_cost.py", ("--radius-scale", "nan", "--out", "{out}/l.json"), FORM.format("radius_scale", "nan")),
    ("bench/bench_scaling.py", ("--sizes-mm", "20", "inf", "--out", "{out}/s.json"), FORM.format("sizes_mm", "(20.0, inf)")),
    ("cohesive/compare_cohesive_laws.py", ("--deps", "nan", "--out", "{out}"), FORM.format("deps", "nan")),
    ("cohesive/compare_cohesive_laws.py", ("--eps-inf", "inf", "--out", "{out}"), FORM.format("eps_inf", "inf")),
]


@pytest.mark.parametrize("script,args,needle", PLAIN_SCRIPTS, ids=[f"{s}{' '.join(a[:2])}" for s, a, _ in PLAIN_SCRIPTS])
def test_plain_scripts_refuse_bad_options_before_work(tmp_path, script, args, needle):
    out = tmp_path / "out"
    cmd = [sys.executable, os.path.join(REPO, "scripts", script)] + [a.replace("{out}", str(out)) for a in args]
    _refused(cmd, needle, out)


# ------------------------------------------------------------------ the table scripts' input

def results(status="finished", **changes):
    """A small results.json of a swelling test (two steps), as swelldem.scenario writes it."""
    per_kind = {k: {"fn_p05_kN": [-1.0, -2.0], "fn_p95_kN": [1.0, 2.0], "broken": [0, b], "born_broken": [0, 1]}
                for k, b in (("MORTAR", 3), ("ITZ", 5), ("AGG", 1))}
    res = {"scenario": "isr", "behaviour": "viscoelastic", "damage": True, "status": status, "times_days": [10.0, 100.0],
           "swelling_strain_x": [1e-4, 2e-4], "swelling_strain_y": [1e-4, 2e-4], "n_particles": 100,
           "n_contacts_by_kind": {"MORTAR": 100, "ITZ": 20, "AGG": 30}, "per_kind": per_kind, "iterations": 10,
           "wall_s": 2.0, "updated": time.time()}
    res.update(changes)
    return res


def write(folder, content):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "results.json").write_text(content if isinstance(content, str) else json.dumps(content))
    return folder


def compare(tmp_path, ref, *runs):
    return subprocess.run([sys.executable, os.path.join(REPO, "scripts", "compare_runs.py"), "--reference", str(ref),
                           *map(str, runs), "--out", str(tmp_path / "cmp")], capture_output=True, text=True, timeout=120)


BAD_FILES = {
    "truncated": (json.dumps(results())[:300], "truncated or malformed JSON (Unterminated string"),
    "not JSON": ("status: finished\n", "truncated or malformed JSON (Expecting value: line 1 column 1"),
    "a list": ("[1, 2, 3]", "a JSON list, not an object"),
    "foreign": (json.dumps({"case": "isr", "eps_final": 1e-3}), "not a swelling test's results.json (scripts/swelling_test.py): no scenario"),
    "per-kind series short": (json.dumps(results(times_days=[1.0, 10.0, 100.0])), "per_kind MORTAR lacks one of fn_p05_kN"),
}


@pytest.mark.parametrize("case", list(BAD_FILES))
def test_table_scripts_refuse_a_bad_results_json_by_name(tmp_path, case):
    content, needle = BAD_FILES[case]
    good = write(tmp_path / "good", results())
    bad = write(tmp_path / "isr-ve-dmg", content)
    for p, who in ((compare(tmp_path, good, bad), "compare_runs.py"),
                   (subprocess.run([sys.executable, os.path.join(REPO, "scripts", "paper_tables.py"), str(tmp_path)],
                                   capture_output=True, text=True, timeout=120), "paper_tables.py")):
        assert p.returncode == 1, (who, p.returncode, p.stderr[-2000:])
        assert f"{who}: {bad / 'results.json'}: " in p.stderr and needle in p.stderr, (who, p.stderr[-2000:])
        assert "Traceback" not in p.stderr
    assert compare(tmp_path, good, tmp_path / "missing").stderr.startswith(f"compare_runs.py: {tmp_path / 'missing' / 'results.json'}: cannot be read")


def test_run_state():
    now = 1.0e9
    assert report.run_state(results()) == "finished"
    assert report.run_state(results("failed: swelldem: stopped")) == "failed: swelldem: stopped"
    assert report.run_state(results("interrupted: SIGTERM")) == "interrupted: SIGTERM"
    assert report.run_state(results("running", updated=now - 30), now).startswith("running (last update")
    # a run killed outright (SIGKILL) stays 'running'; an old update says the process is gone
    assert report.run_state(results("running", updated=now - 7200), now) == "unfinished (last update 2001-09-08 23:46:40 UTC)"
    # slow runs: 10 x the mean step time before a run is taken for dead (here 2 steps in 1000 s)
    assert report.run_state(results("running", updated=now - 3000, wall_s=1000.0), now).startswith("running")
    assert report.run_state(results("running", updated=None), now) == "unfinished (no update time)"


def test_compare_runs_marks_runs_that_did_not_finish(tmp_path):
    ref = write(tmp_path / "ref", results(behaviour="elastic", damage=False))
    dead = write(tmp_path / "dead", results("running", updated=time.time() - 7200))
    failed = write(tmp_path / "failed", results("failed: swelldem: AdrLogTimeIntegrator stopped at physical step 7"))
    p = compare(tmp_path, ref, dead, failed)
    assert p.returncode == 0, p.stderr
    md = (tmp_path / "cmp" / "compare.md").read_text()
    rows = [line for line in md.splitlines() if line.startswith("| viscoelastic")]
    assert len(rows) == 6 and all(r.startswith("| viscoelastic † |") for r in rows)
    assert sum("unfinished (last update " in r for r in rows) == 3
    assert sum("failed: swelldem: AdrLogTimeIntegrator stopped" in r for r in rows) == 3
    assert "† not finished: the numbers are those of the run's last step done" in md
    assert all("| finished | ref |" in r for r in md.splitlines() if r.startswith("| elastic"))
    # each row names its run (its folder): rows of runs of the same behaviour are told apart
    assert sum(r.endswith("| dead |") for r in rows) == 3 and sum(r.endswith("| failed |") for r in rows) == 3
    csv_rows = list(__import__("csv").DictReader(open(tmp_path / "cmp" / "compare.csv")))
    assert [r["run"] for r in csv_rows].count("finished") == 3 and {r["t_last_days"] for r in csv_rows} == {"100.0"}


def test_paper_tables_marks_runs_that_did_not_finish(tmp_path):
    write(tmp_path / "isr-el-dmg", results("interrupted: SIGINT", behaviour="elastic"))
    write(tmp_path / "isr-ve-dmg", results())
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "paper_tables.py"), str(tmp_path)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    el = [r for r in lines if r.startswith("| ISR | elastic (")]
    ve = [r for r in lines if r.startswith("| ISR | aging viscoelastic |") and "(not run)" not in r]
    assert len(el) == 3 and all("(interrupted: SIGINT) †" in r for r in el)
    assert len(ve) == 3
    assert any(r.startswith("| isr-el-dmg |") and r.endswith("| interrupted: SIGINT |") for r in lines)
    # broken of the bonded contacts (3 of 100 MORTAR), the one new contact per kind apart
    assert any(r.startswith("| ISR | aging viscoelastic | MORTAR |") and "| 3.0 |" in r for r in lines)
    assert any(r.startswith("| isr-ve-dmg |") and "| 3 | finished |" in r for r in lines)


def paper_tables(folder):
    return subprocess.run([sys.executable, os.path.join(REPO, "scripts", "paper_tables.py"), str(folder)],
                          capture_output=True, text=True, timeout=120)


def test_paper_tables_reads_the_run_from_its_results_not_its_folder_name(tmp_path):
    """A run with damage, viscoelastic, in a folder named as an elastic run without damage: tabulated
    as what its results.json says (Table 3.6's viscoelastic rows), its folder shown beside it."""
    write(tmp_path / "isr-el-nodmg", results(behaviour="viscoelastic", damage=True))
    p = paper_tables(tmp_path)
    assert p.returncode == 0, p.stderr
    nodmg, dmg = p.stdout.split("### Normal contact forces with damage")
    assert "| ISR | elastic | (not run) |" in nodmg and "| ISR | aging viscoelastic | (not run) |" in nodmg
    assert sum(r.startswith("| ISR | aging viscoelastic | ") and "(not run)" not in r for r in dmg.splitlines()) == 3
    assert "| ISR | elastic | (not run) |" in dmg
    assert any(r.startswith("| isr-ve-dmg (folder isr-el-nodmg) |") for r in dmg.splitlines())
    assert not any(r.startswith("| isr-el-nodmg |") for r in p.stdout.splitlines())


def test_paper_tables_refuses_two_runs_of_the_same_case_naming_both(tmp_path):
    write(tmp_path / "a", results(behaviour="elastic", damage=False))
    write(tmp_path / "isr-el-nodmg", results(behaviour="elastic", damage=False))
    write(tmp_path / "isr-ve-dmg", results())
    p = paper_tables(tmp_path)
    assert p.returncode == 1 and p.stdout == "" and "Traceback" not in p.stderr
    assert p.stderr == (f"paper_tables.py: {tmp_path / 'a' / 'results.json'} and {tmp_path / 'isr-el-nodmg' / 'results.json'} are both "
                        "runs of isr-el-nodmg (isr, elastic, damage off); allowed: one run of each scenario, behaviour and damage in a folder\n")


def old_form(res):
    """res as results.json held it in swelldem's earlier form: the iteration counts as
    adr_iterations and adr_iterations_per_step, and each per-kind series also as a flat key
    '<series>_<KIND>' beside per_kind."""
    old = dict(res)
    old["adr_iterations"] = old.pop("iterations")
    old["adr_iterations_per_step"] = old.pop("iterations_per_step")
    for kind, series in res["per_kind"].items():
        for name, values in series.items():
            old[f"{name}_{kind}"] = values
    return old


def test_an_old_form_results_json_is_read_in_todays_form(tmp_path):
    """report.load_results, which the table scripts use, reads a results.json of the earlier form
    under today's names, without the flat copies of the per-kind series; paper_tables.py tabulates
    it with its iterations."""
    today = results(updated=1.0e9, iterations=17, iterations_per_step=[7, 10])
    path = write(tmp_path / "isr-ve-dmg", old_form(today)) / "results.json"
    on_disk = json.loads(path.read_text())
    assert on_disk["broken_ITZ"] == [0, 5] and on_disk["adr_iterations"] == 17 and "iterations" not in on_disk
    assert report.load_results(str(path)) == today
    p = paper_tables(tmp_path)
    assert p.returncode == 0, p.stderr
    assert any(r.startswith("| isr-ve-dmg |") and "| 17 | 2 | 100 | 3 | finished |" in r for r in p.stdout.splitlines()), p.stdout


@pytest.mark.parametrize("content", ["nothing", "empty run folders"])
def test_paper_tables_refuses_a_folder_without_runs(tmp_path, content):
    if content == "empty run folders":  # e.g. runs refused before any work, or a study stopped before its first step
        (tmp_path / "isr-el-nodmg").mkdir()
        (tmp_path / "notes.md").write_text("x")
    p = paper_tables(tmp_path)
    assert p.returncode == 1 and p.stdout == "" and "Traceback" not in p.stderr
    assert p.stderr == (f"paper_tables.py: folder = {str(tmp_path)!r} holds no run (no <run>/results.json); allowed: a folder of "
                        "swelling-test runs, one per subfolder <run>/results.json (scripts/paper_study.py --out)\n")


# ------------------------------------------------------------------ an output folder that cannot be written

BAD_OUT = {"/proc/x": lambda tmp: "/proc/x",
           "an existing file": lambda tmp: str(tmp / "file"),
           "a path under a file": lambda tmp: str(tmp / "file" / "run")}
OUT_SCRIPTS = {"swelling_test.py": [LAUNCHER, "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"),
                                    "--size-mm", "12", "12"],
               "boundary_study.py": [LAUNCHER, "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "boundary_study.py"),
                                     "--size-mm", "12", "12"],
               "paper_study.py": [sys.executable, os.path.join(REPO, "scripts", "paper_study.py"), "--size-mm", "12", "12", "--jobs", "1"]}


@pytest.mark.parametrize("case", list(BAD_OUT))
@pytest.mark.parametrize("script", list(OUT_SCRIPTS))
def test_an_unusable_output_folder_is_one_line_and_exit_2_before_any_work(tmp_path, script, case):
    """The one check of every script's output folder (swelldem.options.output_folder): one line on
    stderr naming out, its value and what is allowed, exit status 2, no traceback, nothing made."""
    (tmp_path / "file").write_text("kept\n")
    out = BAD_OUT[case](tmp_path)
    before = sorted(os.listdir(tmp_path))
    p = subprocess.run(OUT_SCRIPTS[script] + ["--out", out], capture_output=True, text=True, timeout=300, cwd=str(tmp_path),
                       env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir(), "PYTHONPATH": os.path.join(REPO, "py")})
    assert p.returncode == 2, (p.returncode, p.stdout[-1500:], p.stderr[-1500:])
    assert "Traceback" not in p.stderr
    lines = script_stderr(p.stderr)
    assert len(lines) == 1, p.stderr
    assert lines[0].startswith(f"{script}: " + FORM.format("out", repr(out)) + "a folder that exists or can be made, and written into ("), lines[0]
    assert "mesostructure" not in p.stdout, "refused before any work"
    assert sorted(os.listdir(tmp_path)) == before and (tmp_path / "file").read_text() == "kept\n"
    assert not os.path.exists("/proc/x")


def test_output_folder_and_file_checks_make_nothing(tmp_path):
    assert options.output_folder("out", str(tmp_path / "new" / "deeper")) == str(tmp_path / "new" / "deeper")
    assert options.output_folder("out", str(tmp_path)) == str(tmp_path)
    assert options.output_file("out", str(tmp_path / "new" / "b.json")) == str(tmp_path / "new" / "b.json")
    assert os.listdir(tmp_path) == [], "a check leaves nothing behind (its probe is removed)"
    (tmp_path / "f").write_text("")
    for check, value, why in ((options.output_folder, "", "a folder name"),
                              (options.output_folder, str(tmp_path / "f"), f"({tmp_path / 'f'} is a file)"),
                              (options.output_folder, str(tmp_path / "f" / "g" / "h"), f"({tmp_path / 'f'} is a file, not a folder)"),
                              (options.output_folder, "/proc/x/y", "(/proc takes no new folder: "),
                              (options.output_file, str(tmp_path), f"({tmp_path} is a folder)"),
                              (options.output_file, str(tmp_path / "f" / "b.json"), f"({tmp_path / 'f'} is a file)")):
        with pytest.raises(options.OptionError) as e:
            check("out", value)
        assert str(e.value).startswith(FORM.format("out", repr(value))) and why in str(e.value), str(e.value)
    assert sorted(os.listdir(tmp_path)) == ["f"]


def test_compare_runs_names_the_setting_a_sweep_varies(tmp_path):
    """The guide's sweep (ITZ tensile strength 2 against 3 MPa): two runs of one behaviour and damage
    setting. compare.md names the setting and each run's value, the legends carry it, and the two
    runs draw in different colours."""
    base = {"scenario": "isr", "behaviour": "viscoelastic", "damage": True, "seed": 1, "out": "x", "vtk_every": 0}
    a = write(tmp_path / "itz2", results(config=dict(base, kind_params={"ITZ": {"tensileStrength": 2e6}}, out="itz2")))
    b = write(tmp_path / "itz3", results(config=dict(base, kind_params={"ITZ": {"tensileStrength": 3e6}}, out="itz3", vtk_every=5)))
    p = compare(tmp_path, a, b)
    assert p.returncode == 0, p.stderr
    md = (tmp_path / "cmp" / "compare.md").read_text()
    assert ("Settings that differ between the runs: kind_params: ITZ.tensileStrength=2e+06 (itz2), "
            "ITZ.tensileStrength=3e+06 (itz3).") in md
    ra, rb = json.loads((a / "results.json").read_text()), json.loads((b / "results.json").read_text())
    assert report.differing_settings([ra, rb]) == ["kind_params"]  # where a run wrote is not a condition
    assert report.run_label(rb, ["kind_params"]) == "viscoelastic, damage; kind_params ITZ.tensileStrength=3e+06"
    assert report._style(ra, 0)["color"] != report._style(rb, 1)["color"]
    same = compare(tmp_path, a, a)
    assert "The runs have the same settings" in (tmp_path / "cmp" / "compare.md").read_text() and same.returncode == 0
