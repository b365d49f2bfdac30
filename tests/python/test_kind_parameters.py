# SPDX-License-Identifier: GPL-2.0-or-later
"""ContactKind's attributes come from the core's one parameter table: a parameter declared there
is a validated, saved Python attribute and reaches the law (here elasticLag, the load duration of
the aging-elastic modulus), and a scenario sets it per kind with --kind-param."""
import math

import pytest


def test_elastic_lag_reaches_the_law_and_is_validated(yade_run):
    res = yade_run(r"""
W = yade.wrapper
k = W.ContactKind(name="MORTAR", behaviour="aging-elastic", elasticLag=0.1)
e01 = k.modulus(28.0)
k.elasticLag = 0.01
e001 = k.modulus(28.0)
err = None
try:
    k.elasticLag = -1.0
except ValueError as e:
    err = str(e)
dump({"e01": e01, "e001": e001, "j01": k.compliance(28.1, 28.0), "j001": k.compliance(28.01, 28.0), "err": err,
      "kept": k.elasticLag, "q": [k.q1, k.q2, k.q3, k.q4], "doc": W.ContactKind.elasticLag.__doc__})
""", threads=1)
    assert res["e01"] == pytest.approx(1 / res["j01"], rel=1e-12)
    assert res["e001"] == pytest.approx(1 / res["j001"], rel=1e-12)
    # B3 closed form (n = 0.1, m = 0.5, lambda0 = 1 d) at a load duration of 0.1 d, t' = 28 d, evaluated here:
    q1, q2, q3, q4 = res["q"]
    tp, t = 28.0, 28.1
    Z = tp ** -0.5 * math.log(1 + (t - tp) ** 0.1)
    Qf = 1 / (0.086 * tp ** (2 / 9) + 1.21 * tp ** (4 / 9))
    r = 1.7 * tp ** 0.12 + 8
    Q = Qf * (1 + (Qf / Z) ** r) ** (-1 / r)
    J = q1 + q2 * Q + q3 * math.log(1 + (t - tp) ** 0.1) + q4 * math.log(t / tp)
    assert res["e01"] == pytest.approx(1 / J, rel=1e-9)
    assert res["err"] and "elasticLag" in res["err"] and "-1" in res["err"]
    assert res["kept"] == 0.01, "a refused value leaves the kind as it was"
    assert "[day]" in res["doc"]
