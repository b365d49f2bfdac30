# SPDX-License-Identifier: GPL-2.0-or-later
"""docs/guide.md, the newcomer's path, run end to end with real YADE: the commands are taken from
the guide's code blocks (so the page cannot drift from what runs) and run in a scratch folder that
links the repository's scripts/ and py/: the own-scene tutorial, a small first run with its
ParaView files, a two-line yade-batch sweep and its comparison table, and a specimen too small
for its aggregates. The outputs are checked against expectations computed here: log-time step
times, bounds from the paper's data and the kinds' strengths, and the ParaView files read with
VTK's own reader (python3-vtk9) and refitted with numpy."""
import csv
import json
import math
import os
import re
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import REPO, build_dir
from swelldem import meso, paper

GUIDE = os.path.join(REPO, "docs", "guide.md")


def guide_text():
    with open(GUIDE) as f:
        return f.read()


def code_blocks(lang, text=None):
    """The guide's fenced code blocks of language `lang`, in order."""
    return re.findall(r"^```" + lang + r"\n(.*?)^```", text or guide_text(), flags=re.S | re.M)


def guide_command(key):
    """The one command of the guide's sh blocks that contains `key` (continuation lines joined)."""
    commands = [c.strip() for b in code_blocks("sh") for c in re.sub(r"\\\n\s*", "", b).splitlines()
                if key in c and not c.lstrip().startswith("#")]
    assert len(commands) == 1, f"the guide has {len(commands)} sh commands with {key!r}: {commands}"
    return commands[0].split("  #")[0]


def quoted_after(command_key):
    """The indented block (a message the guide quotes) that follows the sh block holding `command_key`."""
    text = guide_text()
    at = text.index(command_key)
    rest = text[text.index("```\n", at) + 4:]
    m = re.match(r"\n((?:    .*\n)+)", rest)
    assert m, f"no indented block after the command with {command_key!r}"
    return m.group(1).strip()


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    """A folder standing for the repository's top: scripts/ and py/ linked, outputs written here."""
    w = tmp_path_factory.mktemp("guide")
    for d in ("scripts", "py"):
        os.symlink(os.path.join(REPO, d), w / d)
    return w


def run(command, cwd, timeout=300):
    env = dict(os.environ, SWELLDEM_BUILD_DIR=build_dir(), OMP_NUM_THREADS="1")
    return subprocess.run(["sh", "-c", command], cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)


def run_ok(command, cwd, timeout=300):
    p = run(command, cwd, timeout)
    assert p.returncode == 0, f"{command}\nSTDOUT:\n{p.stdout[-3000:]}\nSTDERR:\n{p.stderr[-3000:]}"
    return p


def log_times(t0, t1, per_decade):
    """Physical times of a run from t0 to t1 [day], per_decade a decade: t0 10^(k/N), then t1."""
    n = math.ceil(per_decade * math.log10(t1 / t0) - 1e-9)
    return [t0 * 10 ** (k / per_decade) for k in range(1, n)] + [t1]


def test_the_guide_quotes_the_tutorial_script_verbatim():
    section = guide_text().split("## 4. ")[1].split("\n## ")[0]
    blocks = code_blocks("python", section)
    assert len(blocks) >= 5
    with open(os.path.join(REPO, "scripts", "tutorial_own_scene.py")) as f:
        script = f.read()
    for b in blocks:
        assert b in script, f"guide block not in scripts/tutorial_own_scene.py:\n{b}"


def test_the_tutorial_runs_and_writes_its_table_and_plots(work):
    p = run_ok(guide_command("tutorial_own_scene.py"), work)
    out = work / "out" / "tutorial"
    with open(out / "history.csv") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], [[float(v) for v in r] for r in rows[1:]]
    assert all(re.search(r"\[.+\]$", h) for h in header), header  # a unit on every column
    col = {h: k for k, h in enumerate(header)}
    times = [r[col["time [day]"]] for r in rows]
    assert times == pytest.approx(log_times(1.0, 3650.0, 5), rel=1e-5)  # the CSV holds 6 digits
    # Free swelling of mortar reaches the paper's Table 3.2 strain; the aggregates and the ITZ,
    # which do not swell here, hold the specimen below it.
    eps = [(r[col["strain x [-]"]] + r[col["strain y [-]"]]) / 2 for r in rows]
    assert 0 < eps[-1] < paper.TABLE_3_2_EPS_FINAL
    # The kinds' own strengths bound their forces: Fn <= f_t x facet area for every contact
    # (intact ones up to their strength, broken ones in compression only).
    a = meso.generate(seed=1, width_mm=20, height_mm=20, aggregate_area_fraction=0.30)
    for name, ft in (("MORTAR", 3.5e6), ("ITZ", 1.5e6), ("AGG", 6e6)):
        k = paper.KIND_IDS[name]
        bound_kN = ft * a.facet_area_m2[a.kind == k].max() / 1e3
        assert max(r[col[f"Fn 95 % {name} [kN]"]] for r in rows) <= bound_kN
        broken = [r[col[f"broken {name} [-]"]] for r in rows]
        assert broken == sorted(broken) and broken[-1] <= (a.kind == k).sum()
    assert rows[-1][col["broken ITZ [-]"]] > 0  # the weakest kind cracks
    for png in ("history.png", "mesostructure.png"):
        with open(out / png, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    assert "tutorial: 18 steps" in p.stdout
    # swelldem.dem.standard_outputs: the swelling test's outputs of the same run, against the
    # tutorial's own recording (its own loop over the contacts, 6 digits) and the ParaView files
    res = json.loads((out / "results.json").read_text())
    assert res["status"] == "finished" and res["scenario"] == "tutorial, mortar swelling"
    assert res["times_days"] == pytest.approx(times, rel=1e-5)
    assert [(x + y) / 2 for x, y in zip(res["swelling_strain_x"], res["swelling_strain_y"])] == pytest.approx(eps, rel=1e-5, abs=1e-11)
    for name in ("MORTAR", "ITZ", "AGG"):  # the tutorial counts every broken contact, born broken ones too
        d = res["per_kind"][name]
        assert [b + n for b, n in zip(d["broken"], d["born_broken"])] == [r[col[f"broken {name} [-]"]] for r in rows]
    last = ET.parse(out / "vtk" / "contacts.pvd").getroot().findall("Collection/DataSet")[-1]
    assert float(last.get("timestep")) == pytest.approx(3650.0)
    cells = read_vtp(out / "vtk" / last.get("file"))[1]
    assert int(((cells["kindId"] == 1) & (cells["broken"] == 1) & (cells["bonded"] == 1)).sum()) == res["per_kind"]["ITZ"]["broken"][-1]
    with open(out / "curves.csv") as f:
        assert len(list(csv.reader(f))) == len(times) + 1
    table = (out / "table.md").read_text()
    assert table.startswith("# tutorial, mortar swelling, viscoelastic, damage on")
    itz = res["per_kind"]["ITZ"]["broken"][-1]
    assert f"| ITZ | {res['n_contacts_by_kind']['ITZ']} |" in table and f"| {itz} (" in table
    assert undocumented(out, documented_names(2, 3, 4)) == []  # what the own scene wrote, named in the guide
    for png in ("swelling_strain.png", "unbalanced.png", "force_quantiles.png", "crack_map.png", "crack_map_100d.png", "crack_map_200d.png"):
        with open(out / png, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", png


def read_vtp(path):
    from conftest import read_vtp as read
    poly, cells, points, fields = read(path)
    return poly, cells, points, {k: v[0] for k, v in fields.items()}


def documented_names(*sections):
    r"""Regular expressions of the file names the guide's given sections (their '## N. ' numbers)
    name in backticks: `crack_map_<day>d.png` -> crack_map_.+d\.png; a folder `vtk/` as vtk."""
    text = guide_text()
    names = set()
    for n in sections:
        part = text.split(f"\n## {n}. ")[1].split("\n## ")[0]
        names |= {t.rstrip("/") for t in re.findall(r"`([A-Za-z_<>0-9]+(?:\.[a-z.]+|/))`", part)}
    return [re.compile("^" + ".+".join(re.escape(p) for p in re.split(r"<[^>]+>", name)) + "$") for name in names]


def undocumented(folder, patterns):
    """The files and folders under `folder` (one level into its folders) whose names match none of `patterns`."""
    found = [p.name for p in folder.iterdir()] + [p.name for d in folder.iterdir() if d.is_dir() for p in d.iterdir()]
    return [name for name in found if not any(r.match(name) for r in patterns)]


def test_a_first_run_and_its_paraview_files(work):
    pytest.importorskip("vtk", reason="the ParaView files are read with VTK's reader: apt-get install python3-vtk9")
    from vtk.util.numpy_support import vtk_to_numpy
    command = guide_command("out/first")
    assert "--vtk-every 1" in command
    p = run_ok(command, work)
    out = work / "out" / "first"
    res = json.loads((out / "results.json").read_text())
    assert res["status"] == "finished"
    times = res["times_days"]
    assert times == pytest.approx(log_times(1.0, 3650.0, 2), rel=1e-12)
    # every file the run wrote is named in the guide's sections 2 and 3, and the console lists them
    assert undocumented(out, documented_names(2, 3)) == []
    listed = [line for line in p.stdout.splitlines() if line.startswith("results, tables and plots in ")]
    assert len(listed) == 1 and all(f.name in listed[0] for f in out.iterdir()), listed
    collections = {}
    for name in ("particles", "contacts"):
        root = ET.parse(out / "vtk" / f"{name}.pvd").getroot()
        collections[name] = [(float(d.get("timestep")), d.get("file")) for d in root.find("Collection")]
        assert [t for t, _ in collections[name]] == pytest.approx(times, rel=1e-12)  # one file a step, days
    files = sorted(os.listdir(out / "vtk"))
    assert len(files) == 2 * len(times) + 2
    n_bonded = sum(res["n_contacts_by_kind"].values())
    for s, ((_, pfile), (_, cfile)) in enumerate(zip(collections["particles"], collections["contacts"])):
        contacts, c, _, cf = read_vtp(out / "vtk" / cfile)
        assert cf["TimeValue"] == pytest.approx(times[s], rel=1e-12) and cf["step"] == s
        bonded = c["bonded"] == 1
        assert bonded.sum() == n_bonded and (~bonded).sum() == sum(res["per_kind"][k]["born_broken"][s] for k in paper.KIND_NAMES)
        for name, k in paper.KIND_IDS.items():
            of_kind = c["kindId"] == k
            assert (of_kind & bonded).sum() == res["n_contacts_by_kind"][name]
            assert (of_kind & bonded & (c["broken"] == 1)).sum() == res["per_kind"][name]["broken"][s]
            # forces in N in the files, in kN in results.json
            q05, q95 = np.quantile(c["Fn"][of_kind], [0.05, 0.95]) / 1e3
            assert (q05, q95) == pytest.approx((res["per_kind"][name]["fn_p05_kN"][s], res["per_kind"][name]["fn_p95_kN"][s]), rel=1e-9, abs=1e-15)
        # The strain refitted from the files: discs with at least 2 bonded contacts, weights r^2,
        # displacement u = a + G X (least squares), X the start position = centre - displacement.
        particles, pa, pp, _ = read_vtp(out / "vtk" / pfile)
        assert particles.GetNumberOfPolys() == res["n_particles"]
        pts = vtk_to_numpy(particles.GetPoints().GetData())[:, :2].reshape(res["n_particles"], -1, 2)
        u = pp["displacement"][:, :2].reshape(res["n_particles"], -1, 2)[:, 0]  # point data: each polygon's vertices move with its disc
        X = pts.mean(axis=1) - u
        body = vtk_to_numpy(contacts.GetPointData().GetArray("id"))
        ends = body[vtk_to_numpy(contacts.GetLines().GetData()).reshape(-1, 3)[:, 1:][bonded]]
        coordination = np.bincount(ends.ravel(), minlength=res["n_particles"])
        w = np.sqrt(np.where(coordination >= 2, pa["radius"] ** 2, 0.0))
        A = np.column_stack([np.ones(len(X)), X]) * w[:, None]
        G = np.linalg.lstsq(A, u * w[:, None], rcond=None)[0]
        assert (G[1, 0], G[2, 1]) == pytest.approx((res["swelling_strain_x"][s], res["swelling_strain_y"][s]), rel=1e-6, abs=1e-12)
    # The guide's Python snippet prints the ITZ's 95 % quantile at the last step in kN.
    snippet = next(b for b in code_blocks("python") if "vtkXMLPolyDataReader" in b)
    p = subprocess.run(["/usr/bin/python3", "-c", snippet], cwd=work, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    t, q95 = map(float, re.search(r"t = (\S+) d: ITZ 95 % quantile (\S+) kN", p.stdout).groups())
    assert t == pytest.approx(3650.0) and q95 == pytest.approx(res["per_kind"]["ITZ"]["fn_p95_kN"][-1], abs=1e-4)


def test_a_sweep_with_yade_batch_and_its_comparison(work):
    table = code_blocks("text")[0]
    assert table.startswith("description")
    (work / "my_sweep.table").write_text(table)
    lines = [ln.split() for ln in table.strip().splitlines()]
    jobs = {ln[0]: dict(zip(lines[0][1:], ln[1:])) for ln in lines[1:]}
    assert len(jobs) == 2
    run_ok(guide_command("yade-batch"), work, timeout=600)
    sweep = work / "out" / "my_sweep"
    res = {}
    for name, cols in jobs.items():
        res[name] = r = json.loads((sweep / name / "results.json").read_text())
        assert r["status"] == "finished" and r["yade_tags"]["description"] == name
        c = r["config"]
        assert tuple(c["size_mm"]) == (16, 16) and c["seed"] == int(cols["seed"])
        assert r["times_days"] == pytest.approx(log_times(1.0, 3650.0, float(cols["steps_per_decade"])), rel=1e-12)
        assert (sweep / f"{name}.log").exists()
    low, high = res["itz_2MPa"], res["itz_3MPa"]
    assert high["config"]["kind_params"] == {"ITZ": {"tensileStrength": 3e6}}
    # the same mesostructure; a 50 % stronger ITZ breaks fewer of its contacts
    assert low["n_contacts_by_kind"] == high["n_contacts_by_kind"]
    assert 0 < high["per_kind"]["ITZ"]["broken"][-1] < low["per_kind"]["ITZ"]["broken"][-1]
    run_ok(guide_command("compare_runs.py"), work)
    md = (sweep / "compare" / "compare.md").read_text()
    assert "forces (kN)" in md and "Reference: out/my_sweep/itz_2MPa" in md
    # the reference sets no kind parameter: the scenario's 2 MPa
    assert "Settings that differ between the runs: kind_params: defaults (itz_2MPa), ITZ.tensileStrength=3e+06 (itz_3MPa)." in md
    # one row per kind and run, named by its folder: the ITZ broken counts, read by the table's header
    lines = [line for line in md.splitlines() if line.startswith("| ")]
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    rows = [dict(zip(header, (c.strip() for c in line.strip("|").split("|")))) for line in lines[2:]]
    itz = {r["name"]: r["broken (%)"] for r in rows if r["contact"] == "ITZ"}
    n_itz = low["n_contacts_by_kind"]["ITZ"]
    assert itz == {name: f"{r['per_kind']['ITZ']['broken'][-1]} ({100 * r['per_kind']['ITZ']['broken'][-1] / n_itz:.1f})" for name, r in
                   (("itz_2MPa", low), ("itz_3MPa", high))}


def test_a_specimen_too_small_for_its_aggregates_is_refused_as_the_guide_says(work):
    command = guide_command("out/too_small")
    p = run(command, work, timeout=120)
    assert p.returncode == 1 and "Traceback" not in p.stderr, p.stderr[-3000:]
    assert quoted_after("out/too_small") in p.stderr
    # below 11 mm the parameter check refuses the specimen, in the words the guide quotes
    quoted = re.search(r"\n    (swelldem: sieve_fractions_mm = .*)\n", guide_text()).group(1)
    with pytest.raises(meso.MesoParameterError) as ei:
        meso.generate(seed=1, width_mm=10, height_mm=10)
    assert str(ei.value) == quoted


def test_the_size_table_of_the_guide_holds_for_seeds_1_to_3():
    section = guide_text().split("## 8. ")[1].split("\n## ")[0]
    rows = re.findall(r"^\| (\d+) \| [^|]+ \| ([^|]+) \|$", section, flags=re.M)
    assert len(rows) >= 5
    for size, failing in rows:
        expected = sorted(int(s) for s in re.findall(r"\d+", failing))
        got = []
        for seed in (1, 2, 3):
            try:
                meso.generate(seed=seed, width_mm=int(size), height_mm=int(size))
            except meso.AggregatePlacementError:
                got.append(seed)
        assert got == expected, f"{size} mm: seeds {got} fail, the guide says {expected}"
