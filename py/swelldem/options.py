# SPDX-License-Identifier: GPL-2.0-or-later
"""Checks of user-given settings with one message form, shared by the scenarios and every script:

    swelldem: <name> = <value> is out of range; allowed: <range>

<name> is the setting's Python name (the option --eps-inf is eps_inf), <value> its repr (nan and
inf included). The plugin's constructors word their ValueErrors the same way, so a script can
treat both alike: `with options.refuse_bad("table_3_2.py"): ...` prints the message and exits
with status 2 (argparse's status for a bad command line) before any work starts.

Plain Python: it runs without YADE.
"""
import contextlib
import math
import numbers as _numbers
import os
import stat
import sys
import tempfile

#: The loosest ADR tolerance still worth running: docs/performance.md section 1 measures 3-6 % force
#: error at 1e-3 and 11-15 % at 1e-2 ("useless"); a looser value warns.
USEFUL_TOLERANCE_MAX = 1e-3


class OptionError(ValueError):
    """A setting out of its allowed range (a ValueError, as the plugin's own checks raise)."""


def message(name, value, allowed):
    return f"swelldem: {name} = {value!r} is out of range; allowed: {allowed}"


def bad(name, value, allowed):
    raise OptionError(message(name, value, allowed))


def is_number(v):
    return isinstance(v, _numbers.Real) and not isinstance(v, bool)


def _range_text(name, lo, hi, lo_incl, hi_incl, unit):
    parts = []
    if lo is not None:
        parts.append(f"{lo:g} {'<=' if lo_incl else '<'}")
    parts.append(name)
    if hi is not None:
        parts.append(f"{'<=' if hi_incl else '<'} {hi:g}")
    elif lo is not None:
        parts.append("< inf")
    text = " ".join(parts) if lo is not None or hi is not None else f"a finite number ({name})"
    return text + (f" [{unit}]" if unit else "")


def number(name, value, lo=None, hi=None, lo_incl=False, hi_incl=False, unit=None, allowed=None):
    """`value` as a float if it is a finite number within (lo, hi) (bounds included with
    lo_incl / hi_incl; None: unbounded), else OptionError. NaN and infinity are always refused:
    no setting of swelldem means anything at either."""
    ok = is_number(value) and math.isfinite(value)
    if ok and lo is not None:
        ok = value >= lo if lo_incl else value > lo
    if ok and hi is not None:
        ok = value <= hi if hi_incl else value < hi
    if not ok:
        bad(name, value, allowed or _range_text(name, lo, hi, lo_incl, hi_incl, unit))
    return float(value)


def integer(name, value, lo=None, hi=None, allowed=None):
    """`value` if it is an integer (not a bool) in [lo, hi] (None: unbounded), else OptionError."""
    ok = isinstance(value, _numbers.Integral) and not isinstance(value, bool)
    if ok and lo is not None:
        ok = value >= lo
    if ok and hi is not None:
        ok = value <= hi
    if not ok:
        if allowed is None:
            allowed = "an integer" + (f" >= {lo}" if lo is not None else "") + (f" <= {hi}" if hi is not None else "")
        bad(name, value, allowed)
    return int(value)


def numbers(name, values, count=None, **limits):
    """A tuple of finite numbers, each as number() checks it, `count` of them if given; the message
    shows the whole list (e.g. size_mm = (12.0, nan))."""
    values = tuple(values)
    try:
        if count is not None and len(values) != count:
            raise OptionError("count")
        for v in values:
            number(name, v, **limits)
    except OptionError:
        if limits.get("allowed"):
            bad(name, values, limits["allowed"])
        rng = _range_text(name, limits.get("lo"), limits.get("hi"), limits.get("lo_incl", False), limits.get("hi_incl", False),
                          limits.get("unit"))
        bad(name, values, (f"{count} numbers, each " if count else "numbers, each ") + rng)
    return tuple(float(v) for v in values)


def choice(name, value, allowed):
    """`value` if it is one of `allowed`, else OptionError listing them."""
    if value not in allowed:
        bad(name, value, ", ".join(str(a) for a in allowed))
    return value


def tolerance(name, value, useful_max=USEFUL_TOLERANCE_MAX, solver="adr"):
    """An unbalanced-force tolerance: 0 < value < 1; a value looser than `useful_max` is accepted
    but warns on stderr with what it costs under `solver` ('adr' or 'implicit'), since the run then
    reports an equilibrium it has not reached. (A setting left to the solver's own default is not
    passed here: the default lives in the plugin's class.)"""
    number(name, value, lo=0, hi=1, allowed=f"0 < {name} < 1")
    if value > useful_max:
        warn_loose_tolerance(name, value, useful_max, solver)
    return float(value)


#: What a loose tolerance costs, per solver (docs/performance.md sections 1 and 5).
LOOSE_TOLERANCE_COST = {
    "adr": "docs/performance.md section 1: 1e-3 leaves 3-6 % error on the forces, 1e-2 11-15 %",
    "implicit": ("the implicit solver meets it only after a Newton move, so a step whose contacts keep their state is exact "
                 "whatever it, but with damage the broken contacts' states are left unsettled (docs/performance.md section 5: "
                 "0.9 moved the strains by up to 0.7 % on 12 mm specimens); its default 1e-10 is the measured one"),
}


def warn_loose_tolerance(name, value, useful_max=USEFUL_TOLERANCE_MAX, solver="adr"):
    """One line on stderr (where a script's user looks; Python's warnings filter could hide it)."""
    sys.stderr.write(f"swelldem: warning: {name} = {value!r} is looser than the useful range (<= {useful_max:g}; "
                     f"{LOOSE_TOLERANCE_COST.get(solver, LOOSE_TOLERANCE_COST['adr'])}); the run goes on\n")


def _folder_problem(folder):
    """Why `folder` cannot be written into (made if absent), or None when it can: a part of the
    path is a file, the folder itself is a file, or its nearest existing folder refuses a new
    entry (read-only, /proc, no permission). Tried with a probe entry made and removed at once,
    the only test that holds for root and for special file systems alike; nothing is left."""
    head = os.path.abspath(folder)
    while True:
        try:
            st = os.stat(head)
            break
        except (FileNotFoundError, NotADirectoryError):
            if os.path.islink(head):
                return f"{head} is a link to nothing"
            parent = os.path.dirname(head)
            if parent == head:
                return f"{head} does not exist"
            head = parent
        except OSError as e:
            return f"{head}: {e.strerror}"
    if not stat.S_ISDIR(st.st_mode):
        return f"{head} is a file" if head == os.path.abspath(folder) else f"{head} is a file, not a folder"
    try:
        if head == os.path.abspath(folder):
            fd, probe = tempfile.mkstemp(prefix=".swelldem-probe-", dir=head)
            os.close(fd)
            os.remove(probe)
        else:
            os.rmdir(tempfile.mkdtemp(prefix=".swelldem-probe-", dir=head))
    except OSError as e:
        return f"{head} takes no new {'file' if head == os.path.abspath(folder) else 'folder'}: {e.strerror}"
    return None


def output_folder(name, path):
    """`path` if a script can write its results into it: an existing folder it may write into, or
    a new one (made later, by the script) under such a folder; OptionError otherwise, in the one
    message form, with the reason (e.g. 'swelldem: out = '/proc/x' is out of range; allowed: a
    folder that exists or can be made, and written into (/proc takes no new folder: No such file
    or directory)'). Creates nothing: a script calls it with its other checks, before any work."""
    if not isinstance(path, str) or not path:
        bad(name, path, "a folder name")
    why = _folder_problem(path)
    if why:
        bad(name, path, f"a folder that exists or can be made, and written into ({why})")
    return path


def output_file(name, path):
    """`path` if a script can write a file there (a benchmark's JSON): not a folder, and its folder
    as output_folder() checks it; OptionError otherwise. Creates nothing."""
    if not isinstance(path, str) or not path:
        bad(name, path, "a file name")
    full = os.path.abspath(path)
    if os.path.isdir(full):
        bad(name, path, f"a file to write, in a folder that exists or can be made ({full} is a folder)")
    why = _folder_problem(os.path.dirname(full))
    if why is None and os.path.exists(full) and not os.access(full, os.W_OK):
        why = f"{full} cannot be written: permission denied"
    if why:
        bad(name, path, f"a file to write, in a folder that exists or can be made ({why})")
    return path


@contextlib.contextmanager
def refuse_bad(prog):
    """Inside the block, a ValueError (a swelldem check or a plugin constructor) ends the program:
    '<prog>: <message>' on stderr and exit status 2, with no traceback."""
    try:
        yield
    except ValueError as e:
        sys.stderr.write(f"{prog}: {e}\n")
        sys.exit(2)
