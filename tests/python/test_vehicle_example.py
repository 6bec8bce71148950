"""The closed-loop vehicle example (examples/wheelset_hunting.py) in its short form: a suspended
wheelset stepped against the packed WheelRailContact FMU through FMPy. The numbers are the
example's own acceptance checks; docs/vehicle.md gives the full form's results."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from conftest import example_module


@pytest.fixture(scope="module")
def example(wrc_fmu_path: Path):
    return example_module("wheelset_hunting", wrc_fmu_path.parent)


def test_short_form_of_the_closed_loop_example(example) -> None:
    n = example.study(full=False, out=None)
    # Klingel at 10 m/s: the first cycle's wavelength within 1 % of the Klingel integration of
    # the element's loaded rolling-radius difference at the cycle's amplitude.
    assert abs(n["klingel_error"]) < 0.01, n
    # The rigid EN 15302 conicity at 3 mm of the default pair (S1002 on UIC60 1:40).
    assert 0.15 < n["rigid_lambda_harmonic_3mm"] < 0.22, n
    for model in (1, 6):
        linear = n[f"model{model}_critical_linear_m_per_s"]
        closed = n[f"model{model}_critical_closed_loop_h1ms_m_per_s"]
        # Closed-loop bisection against the linear Wickens model: within 10 %.
        assert abs(closed / linear - 1) < 0.10, (model, closed, linear)
    # Hertz and ANALYN: critical speeds within 5 % of each other (closed loop and linear).
    for kind in ("linear", "closed_loop_h1ms"):
        a = n[f"model1_critical_{kind}_m_per_s"]
        b = n[f"model6_critical_{kind}_m_per_s"]
        assert abs(a / b - 1) < 0.05, (kind, a, b)
    assert math.isfinite(n["chatter_explicit_max_abs_vy"])
