"""What each host does when WheelRailContact returns fmi2Discard (a pose off the rail) or
fmi2Error (an input value it rejects; an initialization that fails because a profile cannot be
loaded) — the behaviours docs/integration.md ("Hosts and their behaviour") describes, pinned so
that a host upgrade that changes them is noticed.

* FMPy: every fmi2Error raises ``FMICallException`` (here: a failed initialization; rejected
  values in ``test_wheel_rail_contact.py::test_nan_input_is_rejected_and_logged``); on Discard
  ``simulate_fmu`` stops at the last successful time and returns the results so far
  (``test_wheel_rail_contact.py::test_simulate_fmu_stops_at_a_pose_off_the_rail``).
* libcosim: Discard or a rejected input fails the step, the execution goes to its error state
  and time stays at the last successful step; a failed initialization aborts the whole process.
* Ecos: nothing stops it. It logs the FMU's message at debug level only, keeps stepping (time
  advances) and serves the last values read; a rejected input keeps its old value; after a
  failed initialization ``init`` still reports success.

The libcosim and Ecos runs are subprocesses (``libcosim_driver.py``, ``ecos_driver.py``).
"""

from __future__ import annotations

import math
import signal
from pathlib import Path

import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Error

from conftest import WRC_FMU_FILE_NAME, packed_fmu, run_ecos, run_libcosim

OFF_RAIL = 0.045  # m: lateral shift with the right wheel on its flange tip (derailing)
MISSING = "not_bundled.prw"
Q_DEFAULT = 78_500.0  # N; the wheel loads' start value
READ = {"Real": ["y", "right.Fy", "right.Fz", "left.Fz"], "Integer": ["right.nPatches"]}


# ---------------------------------------------------------------------------------------------
# FMPy


def test_fmpy_raises_when_initialization_fails() -> None:
    with pytest.raises(FMICallException) as excinfo:
        simulate_fmu(str(packed_fmu(WRC_FMU_FILE_NAME)), start_values={"wheelProfile": MISSING})
    assert excinfo.value.status == fmi2Error


# ---------------------------------------------------------------------------------------------
# libcosim


def test_libcosim_stops_in_its_error_state_on_discard(tmp_path: Path) -> None:
    config = {
        "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
        "step_ns": 1_000_000,
        "instances": {"wrc": {}},
        "phases": [{"steps": 2, "set": {}}, {"steps": 3, "set": {"wrc": {"y": OFF_RAIL}}}],
    }
    proc, result = run_libcosim(config, tmp_path)
    assert proc.returncode == 3, f"exit {proc.returncode}\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    assert [p["time_ns"] for p in result["phases"]] == [2_000_000]
    # The discarded step (the first with the pose off the rail) is not taken: time stays at 2 ms.
    assert result["failed"] == {"phase": 1, "time_ns": 2_000_000, "state": "ERROR"}


def test_libcosim_stops_in_its_error_state_on_a_rejected_input(tmp_path: Path) -> None:
    config = {
        "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
        "step_ns": 1_000_000,
        "instances": {"wrc": {}},
        "phases": [{"steps": 1, "set": {}}, {"steps": 2, "set": {"wrc": {"Qleft": math.nan}}}],
    }
    proc, result = run_libcosim(config, tmp_path)
    assert proc.returncode == 3, f"exit {proc.returncode}\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    assert result["failed"] == {"phase": 1, "time_ns": 1_000_000, "state": "ERROR"}


def test_libcosim_aborts_the_process_when_initialization_fails(tmp_path: Path) -> None:
    config = {
        "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
        "step_ns": 1_000_000,
        "instances": {"wrc": {"wheelProfile": MISSING}},
        "phases": [{"steps": 1, "set": {}}],
    }
    proc, result = run_libcosim(config, tmp_path)
    # An uncaught C++ exception: std::terminate → abort (SIGABRT), the model's message with it.
    assert proc.returncode == -signal.SIGABRT, f"exit {proc.returncode}\n{proc.stderr[-3000:]}"
    assert result is None
    assert "terminate called" in proc.stderr and MISSING in proc.stderr, proc.stderr[-3000:]


# ---------------------------------------------------------------------------------------------
# Ecos


def test_ecos_ignores_discard_and_keeps_stepping(tmp_path: Path) -> None:
    result, log = run_ecos(
        {
            "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
            "instance": "wrc",
            "step_size": 0.001,
            "steps": [{}, {"y": OFF_RAIL}, {}, {}],
            "read": READ,
            "log_level": "debug",
        },
        tmp_path,
    )
    assert result["init"]
    # Time advances through and past the discarded step …
    assert result["times"] == pytest.approx([0.001, 0.002, 0.003, 0.004], abs=1e-12)
    # … the input is taken, the outputs stay those of the last successful step …
    rows = result["rows"]
    assert [r["y"] for r in rows] == [0.0, 0.0, OFF_RAIL, OFF_RAIL, OFF_RAIL]
    for r in rows[2:]:
        assert {k: v for k, v in r.items() if k != "y"} == {k: v for k, v in rows[1].items() if k != "y"}
    # … and the FMU's messages appear only in Ecos's debug log: the discarded step, then every
    # later fmi2DoStep refused with fmi2Error.
    assert "fmi2Discard step at t = 0.001 discarded" in log, log
    assert log.count("fmi2Error fmi2DoStep must not be called in state StepFailed") == 2, log


def test_ecos_ignores_a_rejected_input(tmp_path: Path) -> None:
    result, log = run_ecos(
        {
            "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
            "instance": "wrc",
            "step_size": 0.001,
            "steps": [{}, {"Qleft": math.nan}, {}],
            "read": {"Real": ["Qleft", "left.Fz"]},
            "log_level": "debug",
        },
        tmp_path,
    )
    assert result["times"] == pytest.approx([0.001, 0.002, 0.003], abs=1e-12)
    # The FMU kept the old load, and Ecos carried on with it.
    assert [r["Qleft"] for r in result["rows"]] == [Q_DEFAULT] * 4
    assert all(r["left.Fz"] == pytest.approx(-Q_DEFAULT, rel=1e-9) for r in result["rows"])
    assert "fmi2Error Qleft = NaN is outside the allowed range" in log, log


def test_ecos_reports_success_when_initialization_fails(tmp_path: Path) -> None:
    result, log = run_ecos(
        {
            "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
            "instance": "wrc",
            "step_size": 0.001,
            "start": {"wheelProfile": MISSING},
            "steps": [{}, {}],
            "read": READ,
            "log_level": "debug",
        },
        tmp_path,
    )
    assert result["init"] is True
    assert result["times"] == pytest.approx([0.001, 0.002], abs=1e-12)
    # No model behind the values: the wheel loads read as 0, not the −78.5 kN a model gives.
    assert all(r["right.Fz"] == 0.0 and r["left.Fz"] == 0.0 for r in result["rows"]), result["rows"]
    assert "fmi2Error initialization failed" in log and MISSING in log, log
    assert "fmi2DoStep must not be called in state InitializationMode" in log, log
