# SPDX-License-Identifier: GPL-2.0-or-later
"""The launcher behaves like `yade` with the plugin loaded; YADE's own self-test passes with the
plugin loaded; the build refuses a YADE whose feature set differs from the declarations'."""
import os
import shutil
import subprocess

from conftest import LAUNCHER, REPO, build_dir, plugin_classes


def _launch(*args, env=None, timeout=600):
    env = {**os.environ, "SWELLDEM_BUILD_DIR": build_dir(), **(env or {})}
    return subprocess.run([LAUNCHER, *args], capture_output=True, text=True, timeout=timeout, env=env)


def test_launcher_lists_plugin_classes(tmp_path):
    script = tmp_path / "list.py"
    script.write_text("import yade.system; print('PLUGIN', sorted(c for c in yade.system.childClasses('Serializable') "
                      "if c.startswith('Swelldem') or c in %r))\n" % plugin_classes())
    p = _launch("-n", "-x", str(script))
    assert p.returncode == 0, p.stderr
    line = [l for l in p.stdout.splitlines() if l.startswith("PLUGIN")][0]
    assert eval(line[len("PLUGIN"):]) == plugin_classes()


def test_launcher_passes_options_and_arguments_like_yade(tmp_path):
    ours, stock = _launch("--version"), subprocess.run(["yade", "--version"], capture_output=True, text=True)
    assert ours.returncode == 0 and ours.stdout == stock.stdout
    script = tmp_path / "args.py"
    script.write_text("import sys, swelldem, yade.config\nprint('ARGS', sys.argv[1:], swelldem.__name__, yade.config.prefix)\n")
    p = _launch("-j", "2", "-n", "-x", str(script), "--case", "isr", "7")
    assert p.returncode == 0, p.stderr
    assert "ARGS ['--case', 'isr', '7'] swelldem " + os.path.join(build_dir(), "prefix") in p.stdout


def test_launcher_says_how_to_build_when_not_built(tmp_path):
    p = _launch("-n", "-x", "/dev/null", env={"SWELLDEM_BUILD_DIR": str(tmp_path / "nowhere")})
    assert p.returncode == 2
    assert "not built" in p.stderr and "scripts/setup.sh" in p.stderr


def test_yade_self_test_passes_with_plugin_loaded():
    p = _launch("--test", timeout=900)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert "ALL TESTS PASSED" in p.stdout + p.stderr


def test_build_refuses_unexpected_yade_features(tmp_path):
    p = subprocess.run(["cmake", "-S", REPO, "-B", str(tmp_path / "b"), "-DSWELLDEM_EXPECTED_YADE_FEATURES=OPENMP VTK"],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode != 0
    assert "refusing to build against this YADE" in p.stderr
    assert "present in this YADE but not expected: CGAL" in p.stderr


def _overlay_with_plugin(tmp_path, patch=None):
    """A copy of the build's overlay prefix whose plugin file is a real copy, optionally patched."""
    src = os.path.join(build_dir(), "prefix")
    dst = tmp_path / "build" / "prefix"
    shutil.copytree(src, dst, symlinks=True)
    plugin = dst / "lib/x86_64-linux-gnu/yade-double/swelldem/libswelldem.so"
    data = open(os.path.realpath(os.path.join(src, "lib/x86_64-linux-gnu/yade-double/swelldem/libswelldem.so")), "rb").read()
    plugin.unlink()
    plugin.write_bytes(patch(data) if patch else data)
    return tmp_path / "build"


def _build_id(lib):
    out = subprocess.run(["readelf", "-n", lib], capture_output=True, text=True, check=True).stdout
    return out.split("Build ID:")[1].split()[0]


def test_plugin_refuses_other_yade_build(tmp_path):
    """A YADE replaced after the build (simulated by changing the libyade.so build id recorded in a
    copy of the plugin, the one thing a new build of YADE certainly changes) is refused when the
    plugin loads, with a message; the unpatched copy loads."""
    real_id = _build_id("/usr/lib/x86_64-linux-gnu/yade-double/libyade.so")
    other_id = "".join("0" if c != "0" else "1" for c in real_id)
    marker = b"libyade.so:" + real_id.encode()

    def patch(data):
        assert data.count(marker) == 1, "the plugin does not record libyade.so's build id"
        return data.replace(marker, b"libyade.so:" + other_id.encode())

    script = tmp_path / "probe.py"
    script.write_text("from yade import wrapper\nprint('LOADED', hasattr(wrapper, 'ContactKind'))\n")
    good = _launch("-n", "-x", str(script), env={"SWELLDEM_BUILD_DIR": str(_overlay_with_plugin(tmp_path / "good"))})
    assert "LOADED True" in good.stdout, good.stderr[-2000:]
    assert "refusing to load" not in good.stderr
    bad = _launch("-n", "-x", str(script), env={"SWELLDEM_BUILD_DIR": str(_overlay_with_plugin(tmp_path / "bad", patch))})
    assert "LOADED False" in bad.stdout, bad.stdout[-2000:] + bad.stderr[-2000:]
    assert "swelldem: refusing to load" in bad.stderr
    assert f"has build id {real_id}, the plugin was built against build id {other_id}" in bad.stderr
    assert "scripts/setup.sh" in bad.stderr
