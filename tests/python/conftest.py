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


def build_dir():
    return os.path.abspath(os.environ.get("SWELLDEM_BUILD_DIR") or os.path.join(REPO, "build"))


class YadeRun:
    """Runs `yade-swelldem -n -x script args` in a temporary folder; the script may write
    result.json there (helper `dump(obj)` is predefined in scripts given as text)."""

    def __init__(self, tmp_path):
        self.tmp = tmp_path

    def __call__(self, script, *args, timeout=600, threads=None, check=True):
        path = self.tmp / "script.py"
        prelude = ("import json as _json\n"
                   "def dump(obj):\n"
                   "    with open('result.json', 'w') as f: _json.dump(obj, f)\n")
        path.write_text(prelude + script)
        cmd = [LAUNCHER] + (["-j", str(threads)] if threads else []) + ["-n", "-x", str(path)] + [str(a) for a in args]
        env = dict(os.environ, SWELLDEM_BUILD_DIR=build_dir())
        proc = subprocess.run(cmd, cwd=self.tmp, capture_output=True, text=True, timeout=timeout, env=env)
        if check and proc.returncode != 0:
            raise AssertionError(f"yade-swelldem failed ({proc.returncode}):\nSTDOUT:\n{proc.stdout[-4000:]}\nSTDERR:\n{proc.stderr[-4000:]}")
        self.proc = proc
        res = self.tmp / "result.json"
        return json.loads(res.read_text()) if res.exists() else None


@pytest.fixture
def yade_run(tmp_path):
    return YadeRun(tmp_path)


def plugin_classes():
    """The classes listed in pkg/yade/PluginRegistry.cpp, the plugin's one list of YADE classes."""
    with open(os.path.join(REPO, "pkg", "yade", "PluginRegistry.cpp")) as f:
        listed = f.read().split("#define SWELLDEM_PLUGIN_CLASSES(X)")[1].split("\n\n")[0]
    return sorted(tok[2:-1] for tok in listed.replace("\\", " ").split() if tok.startswith("X("))
