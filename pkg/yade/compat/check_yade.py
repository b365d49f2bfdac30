#!/usr/bin/python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Refuse a YADE whose version, precision or feature set differ from what swelldem's hand-written
declarations were written for: such a YADE would load the plugin and corrupt memory silently.

usage: check_yade.py YADE_LIB_DIR EXPECTED_FILE [--features "A B C"] [--version V]
The command-line values override the file (used to show what a mismatch looks like)."""
import argparse
import os
import runpy
import subprocess
import sys


def read_expected(path):
    exp = {}
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                key, _, value = line.partition(" ")
                exp[key] = value.strip()
    return exp


def main():
    os.environ.setdefault("HOME", "/tmp")  # YADE's config.py reads it
    ap = argparse.ArgumentParser()
    ap.add_argument("libdir")
    ap.add_argument("expected")
    ap.add_argument("--features", default=None, help="expected feature list (overrides the file)")
    ap.add_argument("--version", default=None, help="expected YADE version (overrides the file)")
    a = ap.parse_args()
    exp = read_expected(a.expected)
    if a.features:
        exp["features"] = a.features
    if a.version:
        exp["version"] = a.version
    config_py = os.path.join(a.libdir, "py", "yade", "config.py")
    if not os.path.exists(config_py):
        sys.exit(f"swelldem: no YADE found at {a.libdir} (missing {config_py}).\n"
                 f"  Install Debian's yade {exp['version']} (bash scripts/setup.sh does it).")
    env_prefix = os.environ.pop("YADE_PREFIX", None)  # read the system YADE, not an overlay
    cfg = runpy.run_path(config_py)
    if env_prefix is not None:
        os.environ["YADE_PREFIX"] = env_prefix
    problems = []
    if cfg["version"] != exp["version"]:
        problems.append(f"YADE version is {cfg['version']}, the declarations were written for {exp['version']}")
    real = "double" if cfg.get("highPrecisionBits") == 64 else f"{cfg.get('highPrecisionBits')}-bit"
    if real != exp.get("real", "double"):
        problems.append(f"YADE's Real is {real}, the declarations need {exp['real']}")
    have, want = set(f for f in cfg["features"] if f), set(exp["features"].split())
    if have != want:
        extra, missing = sorted(have - want), sorted(want - have)
        problems.append("YADE's feature set differs from the one the declarations were written for:"
                        + (f"\n      present in this YADE but not expected: {' '.join(extra)}" if extra else "")
                        + (f"\n      expected but absent from this YADE:    {' '.join(missing)}" if missing else "")
                        + "\n      (features such as OPENMP, MPI and OPENGL/QT5 add data members to Scene, Body and"
                        + " ForceContainer, so the class layouts would not match)")
    pkg = exp.get("package_version")
    if pkg:
        try:
            got = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "yade"], capture_output=True, text=True).stdout.strip()
        except OSError:
            got = ""
        if got and got != pkg:
            problems.append(f"Debian package yade is {got}, the declarations were checked against {pkg}")
    if problems:
        sys.exit("swelldem: refusing to build against this YADE.\n  - " + "\n  - ".join(problems)
                 + f"\n  Expected: {a.expected}. Re-derive pkg/yade/compat for this YADE before changing that file.")
    print(f"swelldem: YADE {cfg['version']} (Real = double, {len(have)} features) matches the declarations")


if __name__ == "__main__":
    main()
