# SPDX-License-Identifier: GPL-2.0-or-later
"""The launcher behaves like `yade` with the plugin loaded; YADE's own self-test passes with the
plugin loaded; the build refuses a YADE whose feature set differs from the declarations'; at load,
the plugin refuses a libyade of another build and two copies of one (by the mapped images' build ids)."""
import os
import shutil
import subprocess

import pytest

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


YADE_LIB = "/usr/lib/x86_64-linux-gnu/yade-double/libyade.so"


def _patched_libyade():
    """libyade.so's bytes with the last byte of its GNU build id changed, and that new id."""
    real_id = _build_id(YADE_LIB)
    data = bytearray(open(YADE_LIB, "rb").read())
    at = data.find(bytes.fromhex(real_id))
    assert at > 0 and data.count(bytes.fromhex(real_id)) == 1
    data[at + len(real_id) // 2 - 1] ^= 0xFF
    return bytes(data), real_id[:-2] + f"{int(real_id[-2:], 16) ^ 0xFF:02x}"


def _work_script(tmp_path):
    script = tmp_path / "work.py"
    script.write_text("from yade import wrapper\nprint('WORK', hasattr(wrapper, 'ContactKind'))\n")
    return script


def _no_crash(p):
    assert p.returncode not in (134, 139, -6, -11), p.stderr[-2000:]
    assert "double free" not in p.stderr and "corruption" not in p.stderr, p.stderr[-2000:]


@pytest.mark.parametrize("patched", [False, True], ids=["same-build-copy", "other-build-copy"])
def test_two_copies_of_libyade_are_refused_before_any_work(tmp_path, patched):
    """A copy of libyade.so found through LD_LIBRARY_PATH (boot.so's dependency) besides the one YADE
    loads from its folder: two images of one library, whatever their build ids (stock YADE then dies
    at exit with "double free or corruption"). The plugin stops the process before the script, exit
    2, naming both files and, for a patched copy, its other build id."""
    copy = tmp_path / "libcopy"
    copy.mkdir()
    if patched:
        data, other_id = _patched_libyade()
        (copy / "libyade.so").write_bytes(data)
    else:
        shutil.copy(YADE_LIB, copy / "libyade.so")
    p = _launch("-n", "-x", str(_work_script(tmp_path)), env={"LD_LIBRARY_PATH": str(copy)})
    _no_crash(p)
    assert p.returncode == 2, p.stdout[-2000:] + p.stderr[-2000:]
    assert "WORK" not in p.stdout
    assert "swelldem: refusing to run: YADE's libraries are loaded twice" in p.stderr, p.stderr[-2000:]
    assert f"2 copies of libyade.so are mapped: {copy / 'libyade.so'} (build id " in p.stderr, p.stderr[-2000:]
    if patched:
        assert f"{copy / 'libyade.so'} has build id {other_id}, the plugin was built against build id {_build_id(YADE_LIB)}" in p.stderr


def test_a_libyade_of_another_build_loaded_alone_is_refused(tmp_path):
    """The only libyade.so of the process is a copy with another build id (a copied prefix whose
    libyade.so is the patched file, also first on LD_LIBRARY_PATH): recognised by its SONAME, read
    from the mapped image; the plugin's classes stay hidden and the process ends normally."""
    build = _overlay_with_plugin(tmp_path)
    libdir = build / "prefix/lib/x86_64-linux-gnu/yade-double"
    data, other_id = _patched_libyade()
    (libdir / "libyade.so").unlink()
    (libdir / "libyade.so").write_bytes(data)
    p = _launch("-n", "-x", str(_work_script(tmp_path)), env={"SWELLDEM_BUILD_DIR": str(build), "LD_LIBRARY_PATH": str(libdir)})
    _no_crash(p)
    assert p.returncode == 0, p.stderr[-2000:]
    assert "WORK False" in p.stdout, p.stdout[-2000:] + p.stderr[-2000:]
    assert "swelldem: refusing to load" in p.stderr
    assert f"{libdir / 'libyade.so'} has build id {other_id}, the plugin was built against build id {_build_id(YADE_LIB)}" in p.stderr
