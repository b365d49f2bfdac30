# SPDX-License-Identifier: GPL-2.0-or-later
"""ABI checks of the plugin against the installed YADE, from the ELF files alone (readelf, c++filt).

`vtable(lib, cls)` lists the slots of yade::cls's virtual table as written in a shared library;
`compare_vtables(...)` checks that a swelldem class has, slot for slot, the same entry points as a
stock YADE class of the same kind: same offsets, same function names and signatures (the class
qualifier aside). A virtual function missing or misplaced in pkg/yade/compat fails it.
"""
import functools
import glob
import os
import re
import struct
import subprocess

YADE_LIB_DIR = "/usr/lib/x86_64-linux-gnu/yade-double"


def _run(*cmd):
    return subprocess.run(cmd, capture_output=True, text=True, check=True).stdout


@functools.lru_cache(None)
def _symbols(lib):
    by_name, by_addr = {}, {}
    for line in _run("readelf", "-W", "--dyn-syms", lib).splitlines():
        p = line.split()
        if len(p) >= 8 and p[0].endswith(":") and p[0] != "Num:" and p[6] != "UND":
            name = p[7].split("@")[0]
            addr, size = int(p[1], 16), int(p[2], 0)
            by_name.setdefault(name, (addr, size))
            by_addr.setdefault(addr, name)
    return by_name, by_addr


@functools.lru_cache(None)
def _relocations(lib):
    rel = {}
    for line in _run("readelf", "-W", "-r", lib).splitlines():
        m = re.match(r"^([0-9a-f]{8,16})\s+[0-9a-f]+\s+(R_X86_64_\w+)\s+(.*)$", line)
        if not m:
            continue
        where, kind, rest = int(m.group(1), 16), m.group(2), m.group(3).strip()
        if kind == "R_X86_64_RELATIVE":
            rel[where] = ("addr", int(rest, 16))
        else:
            s = re.match(r"^[0-9a-f]+\s+(\S+)\s*([+-])\s*([0-9a-f]+)$", rest)
            if s:
                rel[where] = ("sym", s.group(1).split("@")[0])
    return rel


@functools.lru_cache(None)
def _sections(lib):
    secs = []
    for line in _run("readelf", "-W", "-S", lib).splitlines():
        m = re.match(r"^\s*\[\s*\d+\]\s+(\S+)\s+(\S+)\s+([0-9a-f]+)\s+([0-9a-f]+)\s+([0-9a-f]+)", line)
        if m:
            secs.append((m.group(1), int(m.group(3), 16), int(m.group(4), 16), int(m.group(5), 16)))
    return secs


def _read_word(lib, addr):
    for name, va, off, size in _sections(lib):
        if va <= addr < va + size and name != ".bss":
            with open(lib, "rb") as f:
                f.seek(off + addr - va)
                return struct.unpack("<q", f.read(8))[0]
    return 0


def _demangle(names):
    if not names:
        return []
    return subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True).stdout.splitlines()


def mangled_vtable(cls):
    return f"_ZTVN4yade{len(cls)}{cls}E"


def find_library(cls, libs):
    for lib in libs:
        if mangled_vtable(cls) in _symbols(lib)[0]:
            return lib
    raise LookupError(f"no vtable for yade::{cls} in {libs}")


def vtable(lib, cls):
    """Slots of yade::cls's vtable in lib: ('offset', n) or ('fn', demangled name) per slot."""
    by_name, by_addr = _symbols(lib)
    addr, size = by_name[mangled_vtable(cls)]
    rel = _relocations(lib)
    raw = []
    for i in range(size // 8):
        r = rel.get(addr + 8 * i)
        if r is None:
            raw.append(("offset", _read_word(lib, addr + 8 * i)))
        elif r[0] == "sym":
            raw.append(("fn", r[1]))
        else:
            raw.append(("fn", by_addr.get(r[1], f"<local {r[1]:#x}>")))
    names = _demangle([v for k, v in raw if k == "fn"])
    it = iter(names)
    return [(k, next(it) if k == "fn" else v) for k, v in raw]



def _slot_key(kind, value):
    if kind == "offset":
        return ("offset", value)
    if value.startswith("typeinfo for"):
        return ("typeinfo",)
    fn = re.sub(r"yade::[\w:<>, ]+?::(~?\w+\[?[\w:]*\]?)\(", r"\1(", value)
    fn = re.sub(r"~\w+\(", "~dtor(", fn)
    return ("fn", fn)


def compare_vtables(ours_lib, ours, stock, stock_libs=None):
    """List of differences between the vtables of yade::ours (in ours_lib) and stock yade::stock."""
    stock_libs = stock_libs or sorted(glob.glob(os.path.join(YADE_LIB_DIR, "lib*.so")))
    a = vtable(ours_lib, ours)
    b = vtable(find_library(stock, stock_libs), stock)
    diffs = []
    if len(a) != len(b):
        diffs.append(f"{ours} has {len(a)} vtable slots, {stock} has {len(b)}")
    for i, (x, y) in enumerate(zip(a, b)):
        if _slot_key(*x) != _slot_key(*y):
            diffs.append(f"slot {i}: {ours}: {x[1]}  vs  {stock}: {y[1]}")
    return diffs
