"""The real-track example (examples/track_runs.py) in its short form: a suspended wheelset
through a curve entry, on elastic rails and on random irregularities, stepped against the packed
WheelRailContact FMU through FMPy. docs/vehicle.md ("Real track") gives the full form."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import example_module


@pytest.fixture(scope="module")
def example(wrc_fmu_path: Path):
    return example_module("track_runs", wrc_fmu_path.parent)


@pytest.fixture(scope="module")
def numbers(example) -> dict:
    return example.study(full=False, out=None)


def test_the_wheelset_settles_in_the_curve_where_it_rolls_freely(numbers) -> None:
    n = numbers
    # R = 500 m turning right: the wheelset runs outwards (left), by the shift whose
    # rolling-radius difference matches the curve (2 κ r0 e0 = 1.4 mm of Δr: 4.5 mm on S1002/UIC60).
    assert -0.006 < n["curve_y_free_rolling_m"] < -0.003, n
    # Balanced cant, no lateral spring: it settles there within 0.1 mm, without angle of attack
    # (below 0.2 mrad) and without longitudinal force (below 1 % of μQ = 180 N).
    assert abs(n["curve_y_end_m"] - n["curve_y_free_rolling_m"]) < 1e-4, n
    assert abs(n["curve_yaw_end_rad"]) < 2e-4, n
    assert abs(n["curve_fx_end_n"]) < 0.01 * 0.3 * 60e3, n
    assert n["curve_tgamma_end_n"] > 0 and n["curve_yq_max"] < 0.1, n


def test_elastic_rails_carry_the_wheels_forces(numbers) -> None:
    n = numbers
    # Every step the rail's force is the wheel's reversed, exactly.
    assert n["elastic_force_balance"] == 0.0, n
    # The massless supports settle at F/k (within 2 %: the force still drifts with the wheelset).
    assert abs(n["elastic_rail_dy_end_m"] / n["elastic_rail_dy_static_m"] - 1) < 0.02, n
    assert abs(n["elastic_rail_roll_end_rad"] / n["elastic_rail_roll_static_rad"] - 1) < 0.02, n
    # The rails' roll (0.4 mrad, the load's moment about the rail top) tilts the rail crowns and
    # moves the free-rolling shift, by less than a millimetre.
    assert abs(n["elastic_y_end_m"] - n["curve_y_end_m"]) < 1e-3, n


def test_irregularities_are_reproducible_and_followed(example, numbers) -> None:
    track, again, other = (example.Irregularities(seed=s) for s in (1, 1, 2))
    for s in (0.0, 13.7, 250.0):
        assert track.rails(s, 30.0) == again.rails(s, 30.0)
        assert track.rails(s, 30.0) != other.rails(s, 30.0)
    # Over a long track the sample variance of the sum of cosines is the spectrum's integral
    # over the band (within 3 %: 400 harmonics, 30 km).
    s = np.linspace(0.0, 30_000.0, 60_001)
    arg = np.outer(s, track.omega) + track.phase["alignment"]
    sample = np.cos(arg) @ track.amplitude["alignment"]
    assert abs(np.var(sample) / track.variance("alignment") - 1) < 0.03
    # The wheelset follows the rails' alignment (the long wavelengths dominate), safely.
    assert numbers["irregularity_y_alignment_correlation"] > 0.9, numbers
    assert numbers["irregularity_yq_max"] < 0.8, numbers
