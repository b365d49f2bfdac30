# SPDX-License-Identifier: GPL-2.0-or-later
"""scripts/paper_study.py end to end on a 12 x 12 mm specimen (3 steps a decade; real YADE, real
plugin, two processes at a time): the 12 runs, the folder it writes (tables with the paper's
values, overlay figures, index.md), what each run records for the figures (unbalanced-force
history, break steps, tensile capacity), checked against the runs' own series, the mesostructure
and the paper's Table 3.7 typed from the paper; then resuming (nothing runs again; an interrupted
run alone does) and the options refused before any work."""
import csv
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO, build_dir

STUDY = os.path.join(REPO, "scripts", "paper_study.py")
ARGS = ["--size-mm", "12", "12", "--steps-per-decade", "3"]
RUNS = [f"{sc}-{b}-{d}" for sc in ("isr", "asr-fine", "asr-coarse") for b in ("el", "ve") for d in ("nodmg", "dmg")]
KINDS = ("MORTAR", "ITZ", "AGG")
#: The paper's Table 3.7, aging viscoelastic with damage against elastic without, (5 %, 95 %) [%]; None: "-".
TABLE_3_7 = {"isr": {"MORTAR": (-87, -72), "ITZ": (-81, -87), "AGG": (None, -81)},
             "asr-fine": {"MORTAR": (-95, -84), "ITZ": (-94, -97), "AGG": (-160, -94)},
             "asr-coarse": {"MORTAR": (-68, -75), "ITZ": (-84, -87), "AGG": (-97, -96)}}
#: Table 3.5: tensile strength of each kind [Pa].
F_T = {"MORTAR": 4e6, "ITZ": 2e6, "AGG": 6e6}


def study(out, *args, jobs="2"):
    return subprocess.run([sys.executable, STUDY, *(args or ARGS), "--jobs", jobs, "--out", str(out)], capture_output=True, text=True,
                          timeout=1800, env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir()})


@pytest.fixture(scope="module")
def done(tmp_path_factory):
    out = tmp_path_factory.mktemp("study") / "s12"
    p = study(out)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    return out, p


def results(out, name):
    with open(out / name / "results.json") as f:
        return json.load(f)


def test_study_folder(done):
    out, p = done
    assert p.stdout.count(": running on ") == 12
    index = (out / "index.md").read_text()
    for sc in ("isr", "asr-fine", "asr-coarse"):
        for fig in ("strain", "unbalanced_nodmg", "unbalanced_dmg", "forces_nodmg", "forces_dmg"):
            name = f"{sc}_{fig}.png"
            assert (out / name).stat().st_size > 10000, name
            assert f"![{name}]({name})" in index
        for b in ("el", "ve"):
            assert f"({sc}-{b}-dmg/crack_map.png)" in index
    tables = (out / "tables.md").read_text()
    assert "(paper Table 3.4)" in tables and "(paper Table 3.6)" in tables and tables.count("### Table 3.7 form") == 3
    assert "Specimen 12 x 12 mm; the paper's is 100 x 100 mm" in index
    for name in RUNS:
        res = results(out, name)
        assert res["status"] == "finished" and res["config"]["size_mm"] == [12.0, 12.0], name
    assert "| isr-ve-dmg | finished" in (out / "progress.md").read_text()


def test_table_3_7_rows(done):
    """study.csv: our variations recomputed from the runs' results.json, the paper's from Table 3.7."""
    out, _ = done
    rows = list(csv.DictReader(open(out / "study.csv")))
    assert len(rows) == 3 * 4 * 3  # per scenario the reference and three runs, three kinds each
    for sc in TABLE_3_7:
        ref, ve = results(out, f"{sc}-el-nodmg"), results(out, f"{sc}-ve-dmg")
        for kind in KINDS:
            row = [r for r in rows if r["scenario"] == sc and r["behaviour"] == "viscoelastic" and r["damage"] == "True" and r["kind"] == kind][0]
            for q, col in (("p05", "var_p05_pct"), ("p95", "var_p95_pct")):
                a, b = ve["per_kind"][kind][f"fn_{q}_kN"][-1], ref["per_kind"][kind][f"fn_{q}_kN"][-1]
                if abs(b) >= 0.05:
                    assert float(row[col]) == pytest.approx(100 * (a - b) / b, rel=1e-9), (sc, kind, q)
                else:
                    assert row[col] == "nan"
            want = TABLE_3_7[sc][kind]
            got = tuple(None if row[c] == "" else float(row[c]) for c in ("paper_var_p05_pct", "paper_var_p95_pct"))
            assert got == want, (sc, kind)


def test_what_the_runs_record_for_the_figures(done):
    out, _ = done
    from swelldem import meso
    for name in RUNS:
        res = results(out, name)
        h = res["unbalanced_history"]
        # the solver's history ends at its last iteration and holds each step's converged ratio
        ends = np.cumsum(res["iterations_per_step"]).tolist()
        assert h["iteration"][-1] == res["iterations"] == ends[-1]
        at = dict(zip(h["iteration"], h["ratio"]))
        assert [at[e] for e in ends] == res["unbalanced_ratio"], name
        assert h["every"] == 20 and len(h["iteration"]) <= res["iterations"] / 20 + 2 * len(ends)
        # the break steps give back the broken counts of every step
        z = np.load(out / name / "contact_breaks.npz")
        assert len(z["pairs"]) == sum(res["n_contacts_by_kind"].values())
        for k, kind in enumerate(KINDS):
            counts = [int(((z["kind"] == k) & (z["break_step"] >= 0) & (z["break_step"] <= s)).sum()) for s in range(len(res["times_days"]))]
            assert counts == res["per_kind"][kind]["broken"], (name, kind)
        # tensile capacity: Table 3.5's f_t times the mesostructure's facet areas
        a = meso.load(str(out / name / "assembly.npz"))
        for k, kind in enumerate(KINDS):
            cap = F_T[kind] * a.facet_area_m2[a.kind == k] / 1e3
            got = res["tensile_capacity_kN"][kind]
            assert (got["min"], got["median"], got["max"]) == pytest.approx((cap.min(), np.median(cap), cap.max()), rel=1e-9)
    for sc, days in (("isr", (100, 200)), ("asr-fine", (5000, 10000))):
        for b in ("el", "ve"):
            for d in days:
                assert (out / f"{sc}-{b}-dmg" / f"crack_map_{d}d.png").stat().st_size > 10000
    assert any(results(out, f"isr-{b}-dmg")["per_kind"]["ITZ"]["broken"][-1] > 0 for b in ("el", "ve")), "the crack maps must show cracks"


def test_resume(done):
    out, _ = done
    stamps = {n: os.stat(out / n / "results.json").st_mtime_ns for n in RUNS}
    p = study(out)
    assert p.returncode == 0, p.stderr[-3000:]
    assert p.stdout.count("kept (finished in an earlier call)") == 12 and ": running on " not in p.stdout
    assert {n: os.stat(out / n / "results.json").st_mtime_ns for n in RUNS} == stamps
    # an interrupted run, and only it, runs again
    res = results(out, "isr-el-nodmg")
    res["status"] = "interrupted: SIGTERM"
    (out / "isr-el-nodmg" / "results.json").write_text(json.dumps(res))
    p = study(out)
    assert p.returncode == 0, p.stderr[-3000:]
    assert p.stdout.count(": running on ") == 1 and "isr-el-nodmg: running on" in p.stdout
    assert results(out, "isr-el-nodmg")["status"] == "finished"


@pytest.mark.parametrize("args,needle", [
    (["--size-mm", "12", "12", "--jobs", "0"], "swelldem: jobs = 0 is out of range; allowed: an integer >= 1"),
    (["--size-mm", "12", "nan", "--jobs", "1"], "swelldem: size_mm = (12.0, nan) is out of range"),
    (["--size-mm", "12", "12", "--jobs", "1", "--steps-per-decade", "0"], "swelldem: steps_per_decade = 0.0 is out of range"),
])
def test_bad_options_refused_before_work(tmp_path, args, needle):
    out = tmp_path / "bad"
    p = subprocess.run([sys.executable, STUDY, *args, "--out", str(out)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 2 and p.stderr.startswith("paper_study.py: ") and needle in p.stderr, p.stderr
    assert not out.exists()


def test_other_settings_in_a_study_folder_refused(done):
    out, _ = done
    p = study(out, "--size-mm", "20", "20", "--steps-per-decade", "3", jobs="1")
    assert p.returncode == 2 and "swelldem: out = " in p.stderr and "size_mm [12.0, 12.0]" in p.stderr, p.stderr
    assert "running" not in p.stdout


def test_seeds_tables_give_mean_and_range_over_the_seeds(done, tmp_path):
    """--seeds 1 3: the seed-1 runs of the study above, copied into <run>-s1, are kept; the seed-3
    runs are made; tables.md's rows hold the mean and range of the two runs' own final values."""
    import shutil
    out0, _ = done
    out = tmp_path / "seeds"
    for name in RUNS:
        shutil.copytree(out0 / name, out / f"{name}-s1")
    p = study(out, *ARGS, "--seeds", "1", "3")
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert p.stdout.count("kept (finished in an earlier call)") == 12 and p.stdout.count(": running on ") == 12
    tables = (out / "tables.md").read_text()
    for name, damage in (("isr-ve-dmg", "True"), ("asr-coarse-el-nodmg", "False")):
        a, b = results(out, f"{name}-s1"), results(out, f"{name}-s3")
        assert a["config"]["seed"] == 1 and b["config"]["seed"] == 3
        for kind in KINDS:
            v = [r["per_kind"][kind]["fn_p95_kN"][-1] for r in (a, b)]
            cell = f"{sum(v) / 2:.2f} ({min(v):.2f} to {max(v):.2f})"
            rows = [line for line in tables.splitlines() if f"| {kind} |" in line and cell in line]
            assert rows, (name, kind, cell)
        row = [r for r in csv.DictReader(open(out / "study.csv")) if r["run"] == name and r["kind"] == "AGG"][0]
        broken = [100.0 * r["per_kind"]["AGG"]["broken"][-1] / r["n_contacts_by_kind"]["AGG"] for r in (a, b)]
        assert np.isclose(float(row["broken_pct_max"]), max(broken)) and row["damage"] == damage and row["seeds"] == "2"
    index = (out / "index.md").read_text()
    for sc in ("isr", "asr-fine", "asr-coarse"):
        for fig in ("strain", "forces_nodmg", "forces_dmg"):
            assert f"![{sc}_{fig}.png]({sc}_{fig}.png)" in index and (out / f"{sc}_{fig}.png").stat().st_size > 20000
