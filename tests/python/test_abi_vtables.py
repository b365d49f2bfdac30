# SPDX-License-Identifier: GPL-2.0-or-later
"""Vtable comparison: every swelldem class against a stock YADE class of the same kind, slot by
slot, read from the ELF files (swelldem.abi)."""
import os

import pytest

from conftest import REPO, build_dir, plugin_classes
from swelldem import abi

PLUGIN = os.path.join(build_dir(), "pkg", "yade", "libswelldem.so")


def pairs():
    with open(os.path.join(REPO, "pkg", "yade", "compat", "abi_pairs.txt")) as f:
        return [tuple(line.split()) for line in f if line.strip() and not line.startswith("#")]


@pytest.mark.parametrize("ours,stock", pairs())
def test_vtable_matches_stock_class_of_same_kind(ours, stock):
    slots = abi.vtable(PLUGIN, ours)
    assert len(slots) > 10
    assert abi.compare_vtables(PLUGIN, ours, stock) == []


def test_every_plugin_class_is_paired():
    # A class added to the registry without an ABI pair would escape the check.
    classes = set(plugin_classes())
    assert classes and classes == {p[0] for p in pairs()}


def test_comparison_detects_a_different_kind():
    # An engine compared with a law functor must show differences: the check can fail.
    assert abi.compare_vtables(PLUGIN, pairs()[0][0], "Law2_ScGeom_FrictPhys_CundallStrack")
