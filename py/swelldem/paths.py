# SPDX-License-Identifier: GPL-2.0-or-later
"""Where the repository, its build folder and the compiled libraries are."""
import os

REPO_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def build_dir():
    """The CMake build folder: $SWELLDEM_BUILD_DIR if set, else <repo>/build."""
    return os.environ.get("SWELLDEM_BUILD_DIR") or os.path.join(REPO_DIR, "build")


def built_library(relpath):
    """Absolute path of a library inside the build folder, with a clear error when it is missing."""
    path = os.path.join(build_dir(), relpath)
    if not os.path.exists(path):
        raise FileNotFoundError(
            f"swelldem: {path} is missing; build the project first "
            f"(bash scripts/setup.sh, or cmake -S {REPO_DIR} -B {build_dir()} && cmake --build {build_dir()})")
    return path
