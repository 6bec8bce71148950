"""Host tests of the packed WheelRailContact FMU (FMI 2.0 Co-Simulation) in FMPy.

What is checked, in file order:

1. packaging: `fmpy validate`, exactly the 34 `fmi2*` exports;
2. the default experiment through `fmpy.simulate_fmu` with a lateral-shift input (built-in S1002 on
   UIC60 at 1:40, 78.5 kN per wheel) and the Manchester benchmark (tests/data/README.md) through the
   FMU with the benchmark profile files;
3. failures: a malformed profile file and an unknown built-in profile name fail initialization
   with fmi2Error and a log message; a pose off the rail makes fmi2DoStep return fmi2Discard with
   Terminated = true, and `simulate_fmu` stops there; NaN inputs are rejected and logged;
4. wheel lift-off, FMU state get/set, two instances in one process.

Nothing is skipped: a missing FMU or missing benchmark file fails. The benchmark files are those of
``tests/data``. Shared helpers (the `Slave` wrapper, the
process-wide log router) are in conftest.py.
"""

from __future__ import annotations

import csv
import json
import math
import re
import subprocess
import sys
from pathlib import Path
from typing import Mapping

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Discard, fmi2Error, fmi2LastSuccessfulTime, fmi2Terminated
from fmpy.model_description import ModelDescription

from conftest import (
    Slave,
    assert_exports_exactly_the_34_fmi2_functions,
    assert_fmpy_validates,
    bits,
    data_file,
)


# Start values of the model description (modelDescription/WheelRailContact.json).
Q_DEFAULT = 78_500.0  # N per wheel

# Contact classes by the contact angle (the same limits as tests/manchester.rs): tread below
# 0.2 rad, flange at and above 0.6 rad (the Manchester reference: tread ≤ 0.12 rad, flange root
# 0.29–0.42 rad, flange 0.80–1.16 rad).
TREAD_MAX_ANGLE = 0.2
FLANGE_MIN_ANGLE = 0.6

PATCHES = (1, 2, 3)


# ---------------------------------------------------------------------------------------------
# Fixtures and helpers


def dominant_angle(out: Mapping[str, float], side: str = "right") -> float:
    """Contact angle of the patch with the largest normal force."""
    k = max(PATCHES, key=lambda k: out[f"{side}.p{k}.Fn"])
    return out[f"{side}.p{k}.contactAngle"]


def side_outputs(names: list[str], side: str) -> list[str]:
    return [n for n in names if n.startswith(f"{side}.")]


# ---------------------------------------------------------------------------------------------
# 1. Packaging


def test_fmpy_validate_reports_no_problems(wrc_fmu_path: Path) -> None:
    assert_fmpy_validates(wrc_fmu_path)


def test_shared_library_exports_exactly_34_fmi2_functions(wrc_shared_library: Path) -> None:
    assert_exports_exactly_the_34_fmi2_functions(wrc_shared_library)


# ---------------------------------------------------------------------------------------------
# 2. Default experiment and the Manchester benchmark


def test_default_experiment_with_a_lateral_shift_sweep(
    wrc_fmu_path: Path, wrc_model_description: ModelDescription
) -> None:
    """Default experiment (0 … 8 ms, 1 ms steps) with y ramped 0 → 8 mm over the experiment."""
    de = wrc_model_description.defaultExperiment
    stop = float(de.stopTime)
    assert (float(de.startTime), stop, float(de.stepSize)) == (0.0, 0.008, 0.001)
    signal = np.array([(0.0, 0.0), (stop, 0.008)], dtype=[("time", np.float64), ("y", np.float64)])
    outputs = ["y", "left.Fz", "right.Fz", "right.nPatches"] + [
        f"right.p{k}.{q}" for k in PATCHES for q in ("Fn", "contactAngle")
    ]
    result = simulate_fmu(str(wrc_fmu_path), input=signal, output=outputs)
    assert len(result) == 9 and result["time"][-1] == pytest.approx(stop)
    for name in result.dtype.names:
        assert np.all(np.isfinite(result[name])), f"{name}: {result[name]}"
    # The recorded `y` is the input the step ending at that time was computed with (FMPy applies
    # inputs at the step's start): 0, 0, 1, …, 7 mm.
    y = result["y"]
    assert y == pytest.approx([0.0, 0.0, 0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.007], abs=1e-12)
    # Vertical balance: the load balance is solved to 1e-9 relative; 1e-6 leaves room only for
    # the bracket fallback at a patch merge (wheelset.rs), never for a wrong force.
    for side in ("left", "right"):
        assert result[f"{side}.Fz"] == pytest.approx(np.full(len(result), -Q_DEFAULT), rel=1e-6), side
    rows = [dict(zip(result.dtype.names, row)) for row in result]
    angles = np.array([dominant_angle(r) for r in rows])
    # The right contact angle increases with the shift (strictly, wherever y increases).
    increasing = np.diff(y) > 0
    assert np.all(np.diff(angles)[increasing] > 0), list(zip(y, angles))
    # The jump onto the flange (|γ| ≥ 0.6 rad, from below 0.6 rad in one 1 mm step) happens
    # within the sweep, before 8 mm.
    flange = np.flatnonzero(np.abs(angles) >= FLANGE_MIN_ANGLE)
    assert flange.size, f"no flange contact up to 7 mm: {list(zip(y, angles))}"
    first = flange[0]
    assert y[first] < 0.008 and abs(angles[first - 1]) < FLANGE_MIN_ANGLE, list(zip(y, angles))
    assert angles[first] - angles[first - 1] > 0.3, list(zip(y, angles))
    assert abs(angles[0]) < TREAD_MAX_ANGLE  # centred: tread contact


def _manchester_pose(y_mm: float) -> dict[str, float]:
    """The wheelset pose of the Manchester A-2.2 state at y_mm, read from CONTACT's input file."""
    text = data_file("reference/manchester/mbench_a22_right.inp").read_text().splitlines()
    for i, line in enumerate(text):
        if "S, Y, FZ, ROLL, YAW, PITCH" not in line:
            continue
        _, y, fz, roll, yaw, _ = (float(x) for x in line.split()[:6])
        if abs(y - y_mm) > 1e-9:
            continue
        vpitch = float(text[i + 1].split()[5])
        # railcontact's roll (positive lowers the right wheel) = +CONTACT ROLL (tests/manchester.rs
        # checks the sign on the data); ω = −VPITCH (forward rolling is negative pitch in CONTACT).
        return {"y": y / 1000.0, "roll": roll, "yaw": yaw, "Qleft": fz, "Qright": fz, "vx": 2.0, "omega": -vpitch}
    pytest.fail(f"no state with Y = {y_mm} in mbench_a22_right.inp")


def _manchester_reference(y_mm: float) -> dict[str, float]:
    with data_file("reference/manchester/summary_right.csv").open(newline="") as f:
        for row in csv.DictReader(f):
            if abs(float(row["y_ws_mm"]) - y_mm) < 1e-9:
                return {k: float(v) for k, v in row.items()}
    pytest.fail(f"no state with y_ws_mm = {y_mm} in summary_right.csv")


def test_manchester_right_wheel_at_2mm_through_the_fmu(new_wrc) -> None:
    params = {
        "wheelProfile": str(data_file("profiles/MBench_S1002_v3.prw")),
        "railProfile": str(data_file("profiles/MBench_UIC60_v3.prr")),
        "railInclination": 0.0,  # the benchmark rail is already canted 1:40
        "trackGauge": 1.435,
        "flangeBackDistance": 1.36,
        "wheelRadius": 0.46,
        "E": 2.0 * 82e9 * 1.28,  # G = 82 000 N/mm², ν = 0.28
        "nu": 0.28,
        "mu": 0.3,
    }
    slave = new_wrc(params=params, inputs=_manchester_pose(2.0))
    assert slave.get("wheelProfile") == params["wheelProfile"]
    slave.step()
    out = slave.outputs()
    ref = _manchester_reference(2.0)
    # Right wheel: railcontact's angle = −CONTACT's, yRail = +ycp (docs/conventions.md).
    assert slave.get("right.nPatches") == 1
    angle = dominant_angle(out)
    # Required: contact angle within 0.01 rad, position on the rail within 1 mm.
    assert angle == pytest.approx(-ref["contact_angle_rad"], abs=0.01)
    assert out["right.p1.yRail"] * 1000.0 == pytest.approx(ref["ycp_rail_mm"], abs=1.0)
    assert out["right.Fz"] == pytest.approx(-1e4, rel=1e-6)
    assert not slave.errors() and not slave.warnings()


# ---------------------------------------------------------------------------------------------
# 3. Failures


def _initialize_expecting_error(slave: Slave, **params: str) -> FMICallException:
    slave.fmu.setupExperiment(startTime=0.0)
    slave.set(**params)
    with pytest.raises(FMICallException) as excinfo:
        slave.fmu.enterInitializationMode()
        slave.fmu.exitInitializationMode()
    return excinfo.value


def test_malformed_profile_file_fails_initialization(new_wrc, tmp_path: Path) -> None:
    lines = data_file("profiles/MBench_S1002_v3.prw").read_text().splitlines()
    line_no = 60  # a point row "6.3414676E+01	2.4573554E+01"
    assert lines[line_no - 1].split() == ["6.3414676E+01", "2.4573554E+01"], lines[line_no - 1]
    lines[line_no - 1] = "6.3414676E+01\t2.45x3554E+01"
    bad = tmp_path / "malformed wheel.prw"  # a space in the path, too
    bad.write_text("\n".join(lines) + "\n")

    slave = new_wrc(initialize=False)
    error = _initialize_expecting_error(slave, wheelProfile=str(bad))
    assert error.status == fmi2Error
    errors = slave.errors()
    assert errors, slave.messages
    text = " | ".join(m.text for m in errors)
    assert str(bad) in text, text
    assert re.search(rf"\bline {line_no}\b", text), text
    assert "2.45x3554E+01" in text and "non-numeric" in text, text
    assert all(m.instance == slave.name for m in errors)


def test_unknown_builtin_profile_fails_initialization(new_wrc) -> None:
    slave = new_wrc(initialize=False)
    error = _initialize_expecting_error(slave, wheelProfile="S9999")
    assert error.status == fmi2Error
    text = " | ".join(m.text for m in slave.errors())
    assert "S9999" in text and "unknown built-in profile" in text, slave.messages


# Poses off the rail. The first is far off the profiles; the second is one the model's own
# criterion (the closest approach at a profile end) catches, so the Discard mechanics are
# exercised too.
OFF_RAIL_POSES = [
    pytest.param({"y": 0.045}, id="y=45mm"),
    pytest.param({"y": 0.05, "roll": -0.05}, id="y=50mm,roll=-0.05"),
]


@pytest.mark.parametrize("pose", OFF_RAIL_POSES)
def test_pose_off_the_rail_discards_and_terminates(new_wrc, pose: dict[str, float]) -> None:
    slave = new_wrc(stop_time=0.01)
    last_good = slave.run([{}, {}])[-1]
    good = slave.time
    slave.set(**pose)
    try:
        slave.step()
    except FMICallException as e:
        status = e.status
    else:
        out = slave.outputs()
        pytest.fail(
            f"fmi2DoStep returned OK for the pose {pose}: the right wheel was placed at z = "
            f"{out['right.z'] * 1e3:.2f} mm with contact angle {dominant_angle(out):.4f} rad at yRail = "
            f"{out['right.p1.yRail'] * 1e3:.2f} mm (left: z = {out['left.z'] * 1e3:.2f} mm) instead of "
            f"being discarded"
        )
    assert status == fmi2Discard, f"fmi2DoStep returned status {status}: {slave.messages}"
    assert slave.fmu.getBooleanStatus(fmi2Terminated) is True
    assert slave.fmu.getRealStatus(fmi2LastSuccessfulTime) == good
    discards = [m for m in slave.messages if m.status == fmi2Discard]
    assert discards and "cannot continue" in discards[-1].text, slave.messages
    # FMI 2.0 allows fmi2GetReal in stepFailed, and FMPy's simulate_fmu reads the outputs at the
    # last successful time before it stops: they must be readable, and be the last good ones.
    try:
        after = slave.output_array()
    except FMICallException as e:
        pytest.fail(
            f"fmi2GetReal of the outputs after the discarded step returned status {e.status} "
            f"(last log: {slave.messages[-1].text!r}); the outputs at the last successful time "
            f"t = {good} must stay readable"
        )
    assert np.array_equal(bits(after), bits(last_good))


_SIMULATE_UNTIL_DISCARD = r"""
import json, sys
import numpy as np
from fmpy import simulate_fmu
fmu, pose = sys.argv[1], json.loads(sys.argv[2])
names = list(pose)
dtype = [("time", np.float64)] + [(n, np.float64) for n in names]
zero = tuple(0.0 for _ in names)
bad = tuple(float(pose[n]) for n in names)
# Good poses up to t = 3 ms, the pose off the rail from the step starting at 3 ms on.
signal = np.array([(0.0, *zero), (0.003, *zero), (0.003, *bad), (0.01, *bad)], dtype=dtype)
try:
    result = simulate_fmu(fmu, input=signal, stop_time=0.01, output_interval=0.001, output=["right.Fz"])
    print(json.dumps({"outcome": "returned", "times": [float(t) for t in result["time"]]}))
except Exception as e:
    print(json.dumps({"outcome": "raised", "error": f"{type(e).__name__}: {e}"}))
"""


@pytest.mark.parametrize("pose", OFF_RAIL_POSES)
def test_simulate_fmu_stops_at_a_pose_off_the_rail(wrc_fmu_path: Path, pose: dict[str, float]) -> None:
    # A subprocess with a timeout: if Terminated were false, FMPy would retry the step forever
    # (docs/integration.md, "Hosts and their behaviour").
    try:
        proc = subprocess.run(
            [sys.executable, "-c", _SIMULATE_UNTIL_DISCARD, str(wrc_fmu_path), json.dumps(pose)],
            capture_output=True,
            text=True,
            timeout=60,
        )
    except subprocess.TimeoutExpired:
        pytest.fail("simulate_fmu did not return within 60 s: it loops on the discarded step")
    assert proc.returncode == 0, proc.stderr
    report = json.loads(proc.stdout.strip().splitlines()[-1])
    assert report["outcome"] == "returned", f"simulate_fmu raised instead of stopping: {report['error']}"
    # Stopped at the last good time (3 ms), not at the stop time.
    assert report["times"][-1] < 0.01 - 1e-12, (
        f"simulate_fmu ran to the stop time: no step was discarded for the pose {pose}"
    )
    assert report["times"][-1] == pytest.approx(0.003, abs=1e-12), report["times"]


@pytest.mark.parametrize(
    "name", ["y", "yaw", "roll", "Qleft", "Qright", "vx", "vy", "yawRate", "omega"]
)
def test_nan_input_is_rejected_and_logged(new_wrc, name: str) -> None:
    slave = new_wrc(inputs={"y": 0.003})
    with pytest.raises(FMICallException) as excinfo:
        slave.set(**{name: math.nan})
    assert excinfo.value.status == fmi2Error
    pattern = rf"\b{re.escape(name)} = NaN is outside the allowed range \S"
    errors = slave.errors()
    assert any(re.search(pattern, m.text) for m in errors), (pattern, slave.messages)
    assert all(m.instance == slave.name for m in errors)
    # The old value is kept and the instance steps on as a fresh one does.
    assert not math.isnan(slave.get(name))
    rows = slave.run([{}, {"y": 0.004}])
    assert np.array_equal(bits(rows), bits(new_wrc(inputs={"y": 0.003}).run([{}, {"y": 0.004}])))


# ---------------------------------------------------------------------------------------------
# 4. Lift-off, states, instances


def test_left_wheel_lift_off_gives_zero_left_forces(new_wrc) -> None:
    lifted = new_wrc(inputs={"y": 0.003, "Qleft": 0.0})
    lifted.step()
    out = lifted.outputs()
    assert not lifted.errors() and not lifted.warnings(), lifted.messages
    assert lifted.get("left.nPatches") == 0
    left = side_outputs(lifted.output_names, "left")
    nonzero = {n: out[n] for n in left if n != "left.z" and out[n] != 0.0}
    assert not nonzero, nonzero
    # Each wheel is solved on its own: the right wheel is exactly as with a loaded left wheel.
    loaded = new_wrc(inputs={"y": 0.003})
    loaded.step()
    ref = loaded.outputs()
    right = side_outputs(lifted.output_names, "right")
    assert [out[n] for n in right] == [ref[n] for n in right]
    assert out["right.Fz"] == pytest.approx(-Q_DEFAULT, rel=1e-6)


def test_fmu_state_round_trip_is_bit_exact_over_a_y_ramp(new_wrc) -> None:
    slave = new_wrc(inputs={"y": 0.001}, stop_time=1.0)
    slave.run([{"y": 0.001}, {"y": 0.0015}])
    t_saved = slave.time
    at_save = slave.output_array()
    state = slave.fmu.getFMUstate()
    # 20 steps, 0 → 7.6 mm: through the flange-root and flange transitions.
    ramp = [{"y": 0.0004 * i, "yaw": 2.4e-3 * 0.4 * i} for i in range(20)]
    first = slave.run(ramp)
    slave.run([{"y": -0.004, "Qleft": 50_000.0}])  # diverge

    slave.fmu.setFMUstate(state)
    slave.time = t_saved
    assert slave.fmu.getRealStatus(fmi2LastSuccessfulTime) == t_saved
    assert np.array_equal(bits(slave.output_array()), bits(at_save))
    again = slave.run(ramp)
    assert np.array_equal(bits(again), bits(first))
    slave.fmu.freeFMUstate(state)
    assert not slave.errors() and not slave.warnings()


def test_two_instances_with_different_y_are_independent(wrc_model_description, wrc_unzipdir) -> None:
    configs = {"wrc_a": 0.002, "wrc_b": 0.0065}
    sequences = {
        name: [{"y": y0 + 1e-4 * i, "yaw": 1e-3 * i} for i in range(5)] for name, y0 in configs.items()
    }

    def make(name: str) -> Slave:
        return Slave(wrc_model_description, wrc_unzipdir, name).initialize(inputs={"y": configs[name]})

    # Each sequence ends with its last input repeated: the re-run below after the other
    # instance's error (steps are warm-started from the previous one, so the history counts).
    alone = {}
    for name in configs:
        slave = make(name)
        try:
            alone[name] = slave.run(sequences[name] + [sequences[name][-1]])
        finally:
            slave.free()
    assert not np.array_equal(alone["wrc_a"], alone["wrc_b"])

    slaves = {name: make(name) for name in configs}
    try:
        rows: dict[str, list[np.ndarray]] = {name: [] for name in configs}
        for i in range(5):
            for name, slave in slaves.items():
                rows[name].append(slave.run([sequences[name][i]])[0])
        for name in configs:
            assert np.array_equal(bits(np.array(rows[name])), bits(alone[name][:5])), name
        # An error in one instance is reported under its name and leaves the other alone.
        with pytest.raises(FMICallException):
            slaves["wrc_b"].set(y=math.nan)
        assert slaves["wrc_b"].errors() and all(m.instance == "wrc_b" for m in slaves["wrc_b"].errors())
        assert not slaves["wrc_a"].messages
        assert np.array_equal(
            bits(slaves["wrc_a"].run([sequences["wrc_a"][-1]])[0]), bits(alone["wrc_a"][-1])
        )
    finally:
        for slave in slaves.values():
            slave.free()


# ---------------------------------------------------------------------------------------------
# 5. Non-elliptic normal models (normalModel 2–7)

NORMAL_MODELS = {2: "Linder", 3: "Kik-Piotrowski", 4: "STRIPES-B", 5: "STRIPES-A&B", 6: "ANALYN", 7: "coupled strips"}


def _central_params(model: int) -> dict[str, float | int | str]:
    """The central case (tests/data/README.md): benchmark profiles, E = 210 GPa."""
    return {
        "wheelProfile": str(data_file("profiles/MBench_S1002_v3.prw")),
        "railProfile": str(data_file("profiles/MBench_UIC60_v3.prr")),
        "railInclination": 0.0,
        "E": 2.1e11,
        "nu": 0.28,
        "normalModel": model,
    }


@pytest.mark.parametrize("model", sorted(NORMAL_MODELS))
def test_every_normal_model_runs_a_lateral_sweep_in_fmpy(new_wrc, model: int) -> None:
    # Required: finite, positive area and pmax on shifts −1…+6 mm at 78.5 kN.
    slave = new_wrc(params=_central_params(model))
    for y_mm in np.arange(-1.0, 6.0 + 1e-9, 0.5):
        slave.set(y=y_mm / 1000.0)
        slave.step()
        out = slave.outputs()
        assert all(math.isfinite(v) for v in out.values()), (NORMAL_MODELS[model], y_mm)
        for side in ("left", "right"):
            n = slave.get(f"{side}.nPatches")
            assert n >= 1
            # A patch keeps its output slot while it exists, so the occupied slots need not be
            # the first n: n of the three carry a patch.
            occupied = [k for k in range(1, 4) if out[f"{side}.p{k}.Fn"] > 0.0]
            assert len(occupied) == n, (NORMAL_MODELS[model], y_mm, side)
            for k in occupied:
                assert out[f"{side}.p{k}.area"] > 0.0 and out[f"{side}.p{k}.pmax"] > 0.0
            # The load balance holds whatever the model (tolerance: 1e−6 of the load).
            assert out[f"{side}.Fz"] == pytest.approx(-Q_DEFAULT, rel=1e-6)
    assert not slave.errors()


def test_central_case_area_and_pmax_through_the_fmu(new_wrc) -> None:
    # ANALYN (normalModel 6) against the exact theory, through the FMU, within the
    # required tolerances (area ±10 %, pmax ±15 %); reference/central/normal_dy0_summary.csv.
    with open(data_file("reference/central/normal_dy0_summary.csv"), newline="") as f:
        ref = next(csv.DictReader(f))
    slave = new_wrc(params=_central_params(6))
    slave.step()
    out = slave.outputs()
    area = sum(out[f"right.p{k}.area"] for k in range(1, slave.get("right.nPatches") + 1))
    pmax = max(out[f"right.p{k}.pmax"] for k in range(1, slave.get("right.nPatches") + 1))
    assert area * 1e6 == pytest.approx(float(ref["area_mm2"]), rel=0.10)
    assert pmax / 1e6 == pytest.approx(float(ref["pmax_MPa"]), rel=0.15)


# ---------------------------------------------------------------------------------------------
# 6. Tangential contact on non-elliptic patches (tangentialModel 1–4, planarPatch)

TANGENTIAL_MODELS = {1: "model's own", 2: "equivalent ellipse", 3: "FaStrip", 4: "local ellipses", 5: "FaStrip, coupled coefficients"}


@pytest.mark.parametrize("planar", [True, False])
@pytest.mark.parametrize("tangential", sorted(TANGENTIAL_MODELS))
def test_tangential_options_through_the_fmu(new_wrc, tangential: int, planar: bool) -> None:
    # Every option with ANALYN on the central case and prescribed creepages: finite outputs,
    # the linear-limit sign Fx < 0 for ξ > 0 (docs/conventions.md), |F| ≤ μN (+0.2 %: the
    # elements' midpoint sum of the pressure, tests/tangential.rs), the load balance and a
    # positive maximum traction.
    params = _central_params(6) | {
        "tangentialModel": tangential,
        "planarPatch": planar,
        "creepageMode": 2,
    }
    slave = new_wrc(params=params)
    slave.set(xi=1e-3, eta=0.0, phi=0.0)
    slave.step()
    out = slave.outputs()
    assert all(math.isfinite(v) for v in out.values())
    fn = out["right.p1.Fn"]
    assert out["right.p1.Fx"] < 0.0
    assert math.hypot(out["right.p1.Fx"], out["right.p1.Fy"]) <= 0.3 * fn * 1.002
    assert out["right.p1.maxTraction"] > 0.0
    assert out["right.Fz"] == pytest.approx(-Q_DEFAULT, rel=1e-6)
    assert not slave.errors()


def test_pure_spin_through_the_fmu(new_wrc) -> None:
    # The recommended option (ANALYN, tangentialModel 1, planar patch) against the exact theory
    # (reference/central/pure_spin_summary.csv), within the required Mz ±15 %, Fy ±10 %.
    with open(data_file("reference/central/pure_spin_summary.csv"), newline="") as f:
        ref = next(csv.DictReader(f))
    params = _central_params(6) | {"planarPatch": True, "creepageMode": 2, "mu": 0.3}
    slave = new_wrc(params=params)
    slave.set(xi=0.0, eta=0.0, phi=float(ref["cphi_per_mm"]) * 1e3)
    slave.step()
    out = slave.outputs()
    assert out["right.p1.Fy"] == pytest.approx(float(ref["fs_N"]), rel=0.10)
    assert out["right.p1.Mz"] == pytest.approx(float(ref["mn_Nmm"]) * 1e-3, rel=0.15)


@pytest.mark.parametrize(
    ("variable", "value", "largest"), [("normalModel", 8, 7), ("tangentialModel", 6, 5)]
)
def test_model_option_out_of_range_is_rejected_and_logged(new_wrc, variable: str, value: int, largest: int) -> None:
    slave = new_wrc(initialize=False)
    with pytest.raises(FMICallException):
        slave.set(**{variable: value})
    message = rf"\b{variable} = {value} is outside the allowed range integer in \[1, {largest}\]"
    assert any(re.search(message, m.text) for m in slave.errors()), slave.messages


def test_directional_derivatives_through_fmpy(new_wrc, wrc_model_description: ModelDescription) -> None:
    """FMPy reads providesDirectionalDerivative and gets ∂(right.Fy)/∂y, ∂(right.Fy)/∂vy and
    ∂(right.Fx)/∂omega at a tread pose within 2 % of its own central differences over fmi2DoStep
    from a saved FMU state (steps 3× the FMU's own, docs/integration.md); the call leaves the
    outputs and the next step as they were."""
    assert wrc_model_description.coSimulation.providesDirectionalDerivative
    pose = {"y": 0.002, "yaw": 5e-4, "vx": 20.0, "vy": 0.01, "omega": 20.0 / 0.46 * (1 + 3e-4)}
    slave = new_wrc(inputs=pose, stop_time=1.0)
    slave.run([pose, pose])
    state = slave.fmu.getFMUstate()
    t0 = slave.time
    vr = slave.vars
    at_save = bits(slave.output_array())
    for output, knob, h in [("right.Fy", "y", 3e-5), ("right.Fy", "vy", 6e-5), ("right.Fx", "omega", 1.3e-4)]:
        slave.fmu.setFMUstate(state)
        slave.time = t0
        (d,) = slave.fmu.getDirectionalDerivative([vr[output].valueReference], [vr[knob].valueReference], [1.0])
        assert np.array_equal(bits(slave.output_array()), at_save)
        sides = []
        for x in (pose[knob] + h, pose[knob] - h):
            slave.fmu.setFMUstate(state)
            slave.time = t0
            sides.append(slave.run([{knob: x}])[0][slave.output_names.index(output)])
        host = (sides[0] - sides[1]) / (2 * h)
        assert host != 0.0 and d == pytest.approx(host, rel=0.02), (output, knob, d, host)
    # The next step after a derivative call is the one without it.
    slave.fmu.setFMUstate(state)
    slave.time = t0
    plain = slave.run([pose])
    slave.fmu.setFMUstate(state)
    slave.time = t0
    slave.fmu.getDirectionalDerivative([vr["left.Mz"].valueReference], [vr["yawRate"].valueReference], [1.0])
    assert np.array_equal(bits(slave.run([pose])), bits(plain))
    slave.fmu.freeFMUstate(state)
    assert not slave.errors()
