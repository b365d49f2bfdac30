#!/usr/bin/python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Post-build ABI guard: each swelldem class must have a vtable of exactly the size of a stock YADE
class of the same kind (same base, same overridden entry points), and a typeinfo of the same
shape. A declaration that misses or adds a virtual function in pkg/yade/compat shows up here as
a size difference, at build time, instead of as a wrong call at run time.

usage: check_symbols.py PLUGIN.so YADE_LIB_DIR Ours:Stock [Ours:Stock ...]"""
import glob
import os
import subprocess
import sys


def dynamic_symbols(lib):
    out = subprocess.run(["readelf", "-W", "--dyn-syms", lib], capture_output=True, text=True, check=True).stdout
    sizes = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 8 and parts[0].endswith(":") and parts[6] != "UND":
            try:
                sizes[parts[7].split("@")[0]] = int(parts[2], 0)
            except ValueError:
                pass
    return sizes


def mangled(prefix, cls):
    return f"{prefix}N4yade{len(cls)}{cls}E"


def main():
    plugin, libdir, pairs = sys.argv[1], sys.argv[2], sys.argv[3:]
    ours = dynamic_symbols(plugin)
    stock = {}
    for lib in sorted(glob.glob(os.path.join(libdir, "lib*.so"))):
        for k, v in dynamic_symbols(lib).items():
            stock.setdefault(k, v)
    bad = []
    for pair in pairs:
        mine, theirs = pair.split(":")
        for kind, prefix in (("vtable", "_ZTV"), ("typeinfo", "_ZTI")):
            a, b = ours.get(mangled(prefix, mine)), stock.get(mangled(prefix, theirs))
            if a is None or b is None:
                bad.append(f"{kind} of {mine if a is None else theirs} not found in {'the plugin' if a is None else libdir}")
            elif a != b:
                bad.append(f"{kind} of {mine} is {a} bytes, stock {theirs} has {b} bytes: the declarations in "
                           f"pkg/yade/compat do not match this YADE's virtual functions")
            else:
                print(f"  {kind:8s} {mine:45s} {a:4d} bytes == {theirs}")
    if bad:
        sys.exit("swelldem: ABI check failed:\n  - " + "\n  - ".join(bad))


if __name__ == "__main__":
    main()
