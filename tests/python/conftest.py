# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared fixtures: run a script in real YADE with the real plugin, through the launcher."""
import json
import os
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LAUNCHER = os.path.join(REPO, "scripts", "yade-swelldem")
sys.path.insert(0, os.path.join(REPO, "py"))


#: What YADE itself writes on stderr when it starts a script (`yade -n -x`), before the script's own lines.
YADE_STARTUP = ("TCP python prompt on ", "Running script ", "XMLRPC info provider on ", "Using python version")


def script_stderr(stderr):
    """The lines of a script's stderr without YADE's own start-up lines (and blank lines)."""
    return [line for line in stderr.splitlines() if line.strip() and not line.startswith(YADE_STARTUP)]


def without_keys(v, keys):
    """v without the entries named in `keys`, at any depth (dicts and lists): a results dict less
    what differs between two runs of the same physics (the clock, the folder)."""
    if isinstance(v, dict):
        return {k: without_keys(x, keys) for k, x in v.items() if k not in keys}
    if isinstance(v, list):
        return [without_keys(x, keys) for x in v]
    return v


#: Open MPI's settings for the tests' mpirun: CI runs as root, and a machine may count fewer slots
#: than the ranks asked for.
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMPI_MCA_rmaps_base_oversubscribe": "1"}


def mpirun(ranks):
    """The command prefix that runs the launcher on `ranks` MPI ranks ([] for one)."""
    return ["mpirun", "-n", str(ranks)] if ranks > 1 else []


def build_dir():
    return os.path.abspath(os.environ.get("SWELLDEM_BUILD_DIR") or os.path.join(REPO, "build"))


class YadeRun:
    """Runs `yade-swelldem -n -x script args` in a temporary folder; the script may write
    result.json there (helper `dump(obj)` is predefined in scripts given as text)."""

    def __init__(self, tmp_path):
        self.tmp = tmp_path

    def __call__(self, script, *args, timeout=600, threads=None, check=True, ranks=1):
        path = self.tmp / "script.py"
        prelude = ("import json as _json\n"
                   "def dump(obj):\n"
                   "    with open('result.json', 'w') as f: _json.dump(obj, f)\n")
        path.write_text(prelude + script)
        cmd = mpirun(ranks) + [LAUNCHER] + (["-j", str(threads)] if threads else []) + ["-n", "-x", str(path)] + [str(a) for a in args]
        env = dict(os.environ, SWELLDEM_BUILD_DIR=build_dir(), **(MPI_ENV if ranks > 1 else {}))
        proc = subprocess.run(cmd, cwd=self.tmp, capture_output=True, text=True, timeout=timeout, env=env)
        if check and proc.returncode != 0:
            raise AssertionError(f"yade-swelldem failed ({proc.returncode}):\nSTDOUT:\n{proc.stdout[-4000:]}\nSTDERR:\n{proc.stderr[-4000:]}")
        self.proc = proc
        res = self.tmp / "result.json"
        return json.loads(res.read_text()) if res.exists() else None


def swelling_pair(solver, angle=0.0):
    """Script text: two free discs (R 0.5 mm) in contact at `angle` [rad] from the x axis, one
    elastic swelling MORTAR kind (E 30 GPa, d_inf 1e-6 m, tau_c 50 d, tau_L 100 d), `solver` (a
    Python expression) as the integrator; names R, E, D_INF, kind, a, b, solver, ip2."""
    return f"""
import math
from yade import utils
from swelldem import dem
W = yade.wrapper
R, E, D_INF = 0.5e-3, 30e9, 1e-6
O.reset()
mat = W.ConcreteMat(young=E, poisson=0.2, density=2400, aggregateId=-1)
O.materials.append(mat)
kind = W.ContactKind(name="MORTAR", behaviour="elastic", young=E, shearRatio=0.3, swelling=True, swellDispInf=D_INF,
                     tauC=50.0, tauL=100.0)
a = O.bodies.append(dem.disc((0, 0), R, mat))
b = O.bodies.append(dem.disc((2 * R * math.cos({angle!r}), 2 * R * math.sin({angle!r})), R, mat))
solver = {solver}
ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kind, itz=kind, agg=kind)
O.engines = dem.engines(ip2, W.Law2_ScGeom_SwellPhys_AgingSwelling(), solver, detection_factor=1.05)
utils.createInteraction(a, b)
ip2.cohesive = False
"""


@pytest.fixture
def yade_run(tmp_path):
    return YadeRun(tmp_path)


def plugin_classes():
    """The classes listed in pkg/yade/PluginRegistry.cpp, the plugin's one list of YADE classes."""
    with open(os.path.join(REPO, "pkg", "yade", "PluginRegistry.cpp")) as f:
        listed = f.read().split("#define SWELLDEM_PLUGIN_CLASSES(X)")[1].split("\n\n")[0]
    return sorted(tok[2:-1] for tok in listed.replace("\\", " ").split() if tok.startswith("X("))


def _vtk_arrays(data):
    """{name: numpy array (numeric) or list of str (a vtkStringArray)} of a VTK field, point or cell data."""
    from vtk.util.numpy_support import vtk_to_numpy
    out = {}
    for i in range(data.GetNumberOfArrays()):
        a = data.GetAbstractArray(i)
        out[a.GetName()] = ([a.GetValue(k) for k in range(a.GetNumberOfValues())] if a.IsA("vtkStringArray")
                            else vtk_to_numpy(a))
    return out


def read_vtp(path):
    """A ParaView .vtp file of a run read with VTK's own reader (python3-vtk9): (vtkPolyData, cell
    arrays, point arrays, field arrays), each {name: numpy array or list of str}."""
    vtk = pytest.importorskip("vtk", reason="the ParaView files are read with VTK's reader: apt-get install python3-vtk9")
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    poly = r.GetOutput()
    return poly, _vtk_arrays(poly.GetCellData()), _vtk_arrays(poly.GetPointData()), _vtk_arrays(poly.GetFieldData())
