"""Reliability of the packed FMUs in FMPy (docs/reliability.md).

The checks, through FMPy and the FMUs' log (captured by FMPy's logger callback,
routed per instance by conftest.LOG):

(a) NaN, ±∞, negative loads, out-of-range parameters, an unknown profile name and malformed profile
    files get fmi2Error with a message naming the variable, the value and the allowed range (or
    the file, the line and the reason) — never a crash, never a NaN output, and the instance goes
    on as a fresh one would;
(b) 8 WheelRailContact instances in one process, with different models and inputs, give bit for
    bit the outputs of the same runs in 8 separate processes;
(c) an FMU state saved at step 1 000 of a random walk and restored reproduces the outputs of steps
    1 000–2 000 exactly (in the same instance and, serialized, in a fresh one); corrupted states
    are rejected.

Also: FMI call-order misuse (DoStep before initialization, fixed parameters after it, unknown value
references, a second fmi2FreeInstance).

Nothing is skipped: a missing FMU fails (conftest.py). The FMUs come from ``$RAILCONTACT_FMU_DIR``
or ``<repo>/target/fmu``.
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path
from typing import Mapping

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2Error, fmi2OK
from fmpy.model_description import ModelDescription

from conftest import STEP, Slave, bits, data_file, slave_factory


# Inputs of the WheelRailContact random walk, in the order of `random_walk`'s columns.
WALK_INPUTS = ("y", "yaw", "roll", "Qleft", "Qright", "vx", "vy", "yawRate", "omega")


@pytest.fixture
def new_hc(model_description: ModelDescription, unzipdir: Path):
    yield from slave_factory(model_description, unzipdir)


def shown(x: float) -> str:
    """A value as the FMU prints it (Rust's `Display` of f64) for the values used here."""
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(float(x)).removesuffix(".0") if float(x).is_integer() else repr(float(x))


def expect_error(slave: Slave, call, *patterns: str) -> None:
    """`call()` raises fmi2Error and a new error message of `slave` matches every regex."""
    before = len(slave.errors())
    with pytest.raises(FMICallException) as excinfo:
        call()
    assert excinfo.value.status == fmi2Error, excinfo.value
    new = slave.errors()[before:]
    assert new, f"fmi2Error without a log message ({slave.messages})"
    assert all(m.instance == slave.name for m in new)
    assert any(all(re.search(p, m.text) for p in patterns) for m in new), (patterns, [m.text for m in new])


def real_inputs_and_parameters(md: ModelDescription) -> list:
    return [v for v in md.modelVariables if v.type == "Real" and v.causality in ("input", "parameter")]


# ---------------------------------------------------------------------------------------------
# (a) Bad values and bad profiles


@pytest.mark.parametrize("model", ["HertzContact", "WheelRailContact"])
def test_nan_and_infinities_of_every_real_parameter_and_input_are_rejected(new_hc, new_wrc, model: str) -> None:
    slave = (new_hc if model == "HertzContact" else new_wrc)(initialize=False)
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()  # every variable settable and readable
    variables = real_inputs_and_parameters(slave.md)
    assert len(variables) >= 10
    for v in variables:
        before = slave.get(v.name)
        for x in (math.nan, math.inf, -math.inf):
            expect_error(
                slave,
                lambda: slave.set(**{v.name: x}),
                rf"^{re.escape(v.name)} = {re.escape(shown(x))} is outside the allowed range \S",
            )
            assert slave.get(v.name) == before, v.name
    slave.fmu.exitInitializationMode()
    slave.step()
    slave.output_array()  # finite (asserted by the helper)
    assert len(slave.errors()) == 3 * len(variables)


@pytest.mark.parametrize(
    ("model", "name", "value", "allowed"),
    [
        ("WheelRailContact", "Qleft", -1.0, r"\[0, 10000000\] \[N\]"),
        ("WheelRailContact", "Qright", -78500.0, r"\[0, 10000000\] \[N\]"),
        ("WheelRailContact", "y", 0.2, r"\[-0.05, 0.05\] \[m\]"),
        ("WheelRailContact", "mu", 0.0, r"\(0, 10\]"),
        ("WheelRailContact", "nu", 0.6, r"\[0, 0.5\]"),
        ("WheelRailContact", "nStrips", 0, r"integer in \[5, 200\]"),
        ("WheelRailContact", "nStrips", 201, r"integer in \[5, 200\]"),
        ("WheelRailContact", "normalModel", 8, r"integer in \[1, 7\]"),
        ("WheelRailContact", "tangentialModel", 0, r"integer in \[1, 5\]"),
        ("WheelRailContact", "ny", 0, r"integer in \[1, 1000\]"),
        ("HertzContact", "N", -1.0, r"\[0, 100000000\] \[N\]"),
        ("HertzContact", "B", 0.0, r"\[0.001, 100000\] \[1/m\]"),
        ("HertzContact", "xi", 11.0, r"\[-10, 10\]"),
        ("HertzContact", "nu", -0.1, r"\[0, 0.5\]"),
        ("HertzContact", "nx", 1001, r"integer in \[1, 1000\]"),
    ],
)
def test_negative_loads_and_out_of_range_values_are_rejected(
    new_hc, new_wrc, model: str, name: str, value: float, allowed: str
) -> None:
    new = new_hc if model == "HertzContact" else new_wrc
    slave = new(initialize=False)
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    before = slave.get(name)
    expect_error(slave, lambda: slave.set(**{name: value}), rf"^{name} = {re.escape(shown(value))} is outside the allowed range {allowed}")
    assert slave.get(name) == before
    slave.fmu.exitInitializationMode()
    rows = slave.run([{}, {}])
    # The rejected value changed nothing: the same outputs as a fresh instance.
    assert np.array_equal(bits(rows), bits(new().run([{}, {}])))


def test_zero_loads_are_not_errors(new_hc, new_wrc) -> None:
    hc = new_hc(inputs={"N": 0.0})
    hc.step()
    out = hc.outputs()
    assert out["Fx"] == out["Fy"] == out["a"] == 0.0
    wrc = new_wrc(inputs={"Qleft": 0.0, "Qright": 0.0})
    wrc.step()
    assert wrc.get("left.nPatches") == wrc.get("right.nPatches") == 0
    assert not hc.errors() and not wrc.errors()


def bad_profile_cases(tmp: Path) -> list[tuple[str, str, list[str]]]:
    """(parameter, value, regexes the error message must match)."""
    lines = data_file("profiles/MBench_S1002_v3.prw").read_text().splitlines()
    lines[59] = "6.3414676E+01\t2.45x3554E+01"  # line 60, a point row
    malformed = tmp / "malformed wheel.prw"
    malformed.write_text("\n".join(lines) + "\n")
    unsorted = tmp / "unsorted.csv"
    unsorted.write_text("y,z\n-70,28\n-60,20\n-65,10\n0,0\n60,1\n")
    binary = tmp / "binary.prr"
    binary.write_bytes(b"header.begin\n\x00\x01\x02\n")
    missing = tmp / "missing.prr"
    q = re.escape
    return [
        ("wheelProfile", "S9999", [r'wheelProfile = "S9999"', r'unknown built-in profile "S9999"', "S1002, UIC60, 60E1"]),
        ("railProfile", "UIC61", [r'railProfile = "UIC61"', "unknown built-in profile"]),
        ("railProfile", "S1002", [r'railProfile = "S1002"', "wheel profile but a rail profile is required"]),
        ("wheelProfile", str(malformed), [q(str(malformed)), r"\bline 60\b", q('non-numeric value "2.45x3554E+01"')]),
        ("wheelProfile", str(unsorted), [q(str(unsorted)), r"\bline 4\b", "non-monotonic"]),
        ("railProfile", str(binary), [q(str(binary)), r"\bline 2\b", "binary data"]),
        ("railProfile", str(missing), [q(str(missing)), "no such file"]),
    ]


@pytest.mark.parametrize("case", range(7))
def test_unknown_profile_names_and_malformed_profile_files_fail_initialization(
    new_wrc, tmp_path: Path, case: int
) -> None:
    name, value, patterns = bad_profile_cases(tmp_path)[case]
    slave = new_wrc(initialize=False)
    slave.fmu.setupExperiment(startTime=0.0)
    slave.set(**{name: value})  # strings are checked when the profiles load
    slave.fmu.enterInitializationMode()
    expect_error(slave, slave.fmu.exitInitializationMode, "^initialization failed: ", *patterns)
    # Still in initialization mode: fixing the value lets initialization finish.
    slave.set(**{name: "S1002" if name == "wheelProfile" else "UIC60"})
    slave.fmu.exitInitializationMode()
    slave.step()
    slave.output_array()


# ---------------------------------------------------------------------------------------------
# FMI call-order misuse


def test_call_order_misuse_gets_errors_with_messages(new_wrc, wrc_model_description, wrc_unzipdir) -> None:
    slave = new_wrc(initialize=False)
    expect_error(slave, lambda: slave.fmu.doStep(0.0, STEP), "fmi2DoStep must not be called in state Instantiated")
    expect_error(slave, lambda: slave.fmu.getReal([0]), "fmi2GetReal must not be called in state Instantiated")
    slave.initialize()
    expect_error(slave, lambda: slave.set(E=2.0e11), r"E \(Parameter, Fixed\) cannot be set in state StepComplete")
    expect_error(slave, lambda: slave.set(wheelProfile="S1002"), "wheelProfile .* cannot be set")
    n = len(wrc_model_description.modelVariables)
    expect_error(slave, lambda: slave.fmu.getReal([n + 5]), rf"unknown value reference {n + 5}\b")
    expect_error(slave, lambda: slave.fmu.setReal([n], [0.0]), rf"unknown value reference {n}\b")
    expect_error(slave, lambda: slave.fmu.getReal([slave.vars["normalModel"].valueReference]), "not a Real")
    expect_error(slave, lambda: slave.fmu.doStep(0.0, -STEP), "communicationStepSize = -0.001 must be finite and > 0")
    expect_error(slave, lambda: slave.fmu.doStep(math.nan, STEP), "currentCommunicationPoint = NaN")
    expect_error(slave, slave.fmu.enterInitializationMode, "must not be called in state StepComplete")
    slave.step()  # still usable
    slave.output_array()
    # Reset and re-initialize with other parameters: as a fresh instance.
    slave.fmu.reset()
    slave.time = 0.0
    slave.initialize(params={"normalModel": 6}, inputs={"y": 0.003})
    rows = slave.run([{}, {"y": 0.004}])
    assert np.array_equal(bits(rows), bits(new_wrc(params={"normalModel": 6}, inputs={"y": 0.003}).run([{}, {"y": 0.004}])))


def test_a_second_free_instance_is_ignored(wrc_model_description, wrc_unzipdir) -> None:
    # `keeper` holds the shared library loaded while `victim`'s instance is freed twice through
    # the raw fmi2FreeInstance (FMPy's freeInstance also unloads the library).
    keeper = Slave(wrc_model_description, wrc_unzipdir).initialize()
    victim = Slave(wrc_model_description, wrc_unzipdir).initialize()
    try:
        victim.step()
        component = victim.fmu.component
        victim.fmu.fmi2FreeInstance(component)
        victim.fmu.fmi2FreeInstance(component)  # ignored: not a live instance any more
        with pytest.raises(FMICallException) as excinfo:
            victim.fmu.doStep(victim.time, STEP)  # refused before the freed memory is touched
        assert excinfo.value.status == fmi2Error
        victim.fmu.freeLibrary()
        keeper.step()
        keeper.output_array()
    finally:
        keeper.free()


# ---------------------------------------------------------------------------------------------
# (b) 8 instances in one process against 8 separate processes


def random_walk(seed: int, steps: int) -> np.ndarray:
    """Inputs (columns WALK_INPUTS) of a reflected random walk of the wheelset pose and speeds."""
    rng = np.random.default_rng(seed)
    lo = np.array([-0.0065, -4e-3, -2e-3, 2e4, 2e4, 1.0, -0.2, -0.2, -5e-3])
    hi = np.array([0.0065, 4e-3, 2e-3, 1.5e5, 1.5e5, 60.0, 0.2, 0.2, 5e-3])
    step = np.array([2e-4, 2e-4, 1e-4, 2e3, 2e3, 0.5, 0.02, 0.02, 2e-4])
    x = np.array([0.0, 0.0, 0.0, 78_500.0, 78_500.0, 30.0, 0.0, 0.0, 0.0])
    rows = []
    for _ in range(steps):
        x = x + step * rng.uniform(-1.0, 1.0, size=x.size)
        x = np.where(x > hi, 2 * hi - x, x)
        x = np.where(x < lo, 2 * lo - x, x)
        x = np.clip(x, lo, hi)
        row = x.copy()
        row[8] = x[5] / 0.46 * (1.0 + x[8])  # omega: rolling at the nominal radius plus creepage
        rows.append(row)
    return np.array(rows)


def as_inputs(rows: np.ndarray) -> list[dict[str, float]]:
    return [dict(zip(WALK_INPUTS, map(float, r))) for r in rows]


CONFIGS = [
    {"normalModel": 1 + i % 7, "tangentialModel": 1 + (3 * i // 2) % 5, "planarPatch": i % 3 == 0} for i in range(8)
]

# One instance in its own process: the same FMPy calls as `Slave` (set each input, doStep, one
# getReal of the Real outputs); prints the outputs' bit patterns.
_RUN_ALONE = r"""
import json, sys
import numpy as np
from fmpy.fmi2 import FMU2Slave
from fmpy.model_description import read_model_description
job = json.load(sys.stdin)
md = read_model_description(job["unzipdir"])
vrs = {v.name: v.valueReference for v in md.modelVariables}
outputs = [v.valueReference for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
fmu = FMU2Slave(guid=md.guid, unzipDirectory=job["unzipdir"], modelIdentifier=md.coSimulation.modelIdentifier,
                instanceName="alone")
fmu.instantiate()
fmu.setupExperiment(startTime=0.0)
for name, value in job["params"].items():
    if isinstance(value, bool):
        fmu.setBoolean([vrs[name]], [value])
    else:
        fmu.setInteger([vrs[name]], [int(value)])
fmu.enterInitializationMode()
fmu.exitInitializationMode()
t, h, rows = 0.0, job["h"], []
for inputs in job["inputs"]:
    for name, value in inputs.items():
        fmu.setReal([vrs[name]], [value])
    fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
    t = t + h
    rows.append(np.array(fmu.getReal(outputs), dtype=np.float64).view(np.uint64).tolist())
fmu.terminate()
fmu.freeInstance()
print(json.dumps(rows))
"""


def test_eight_instances_in_one_process_match_separate_processes(wrc_model_description, wrc_unzipdir) -> None:
    steps = 300
    inputs = [as_inputs(random_walk(100 + i, steps)) for i in range(len(CONFIGS))]
    procs = []
    for i, params in enumerate(CONFIGS):
        job = {"unzipdir": str(wrc_unzipdir), "params": params, "inputs": inputs[i], "h": STEP}
        p = subprocess.Popen(
            [sys.executable, "-c", _RUN_ALONE],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        procs.append((p, json.dumps(job)))
    separate = []
    for p, job in procs:
        out, err = p.communicate(job, timeout=300)
        assert p.returncode == 0, err
        separate.append(np.array(json.loads(out.strip().splitlines()[-1]), dtype=np.uint64))

    slaves = [Slave(wrc_model_description, wrc_unzipdir, f"wrc8_{i}") for i in range(len(CONFIGS))]
    try:
        for slave, params in zip(slaves, CONFIGS):
            slave.initialize(params=params)
        together: list[list[np.ndarray]] = [[] for _ in slaves]
        for k in range(steps):  # interleaved: every instance steps once per round
            for i, slave in enumerate(slaves):
                together[i].append(slave.run([inputs[i][k]])[0])
        for i, slave in enumerate(slaves):
            assert np.array_equal(bits(np.array(together[i])), separate[i]), f"instance {i} {CONFIGS[i]}"
            assert not slave.errors() and not slave.warnings(), slave.messages
    finally:
        for slave in slaves:
            slave.free()
    assert not np.array_equal(separate[0], separate[1]), "the instances ran different cases"


# ---------------------------------------------------------------------------------------------
# (c) FMU state at step 1 000


@pytest.mark.parametrize("params", [{}, {"normalModel": 6, "tangentialModel": 3}], ids=["hertz", "analyn-fastrip"])
def test_state_saved_at_step_1000_reproduces_steps_1000_to_2000(new_wrc, params: Mapping[str, int]) -> None:
    walk = as_inputs(random_walk(7, 2000))
    slave = new_wrc(params=params)
    slave.run(walk[:1000])
    t_saved = slave.time
    state = slave.fmu.getFMUstate()
    serialized = slave.fmu.serializeFMUstate(state)
    first = slave.run(walk[1000:])

    slave.fmu.setFMUstate(state)
    slave.time = t_saved
    again = slave.run(walk[1000:])
    assert np.array_equal(bits(again), bits(first)), "SetFMUstate: steps 1000-2000 differ"
    slave.fmu.freeFMUstate(state)

    fresh = new_wrc(initialize=False)
    restored = fresh.fmu.deSerializeFMUstate(serialized)
    fresh.fmu.setFMUstate(restored)
    fresh.fmu.freeFMUstate(restored)
    fresh.time = t_saved
    third = fresh.run(walk[1000:])
    assert np.array_equal(bits(third), bits(first)), "deserialized in a fresh instance: steps 1000-2000 differ"
    assert not slave.errors() and not fresh.errors()


def test_corrupted_states_are_rejected(new_wrc, new_hc) -> None:
    slave = new_wrc()
    slave.run(as_inputs(random_walk(3, 10)))
    state = slave.fmu.getFMUstate()
    good = bytes(slave.fmu.serializeFMUstate(state))
    slave.fmu.freeFMUstate(state)
    at = slave.output_array()
    flipped = bytearray(good)
    flipped[len(good) // 2] ^= 0x10
    for bad, pattern in [
        (good[: len(good) - 1], "checksum mismatch|truncated"),
        (good[:20], "checksum mismatch|truncated"),
        (b"", "not a railcontact FMU state"),
        (bytes(flipped), "checksum mismatch"),
        (good + b"\x00", "checksum mismatch"),
    ]:
        expect_error(slave, lambda: slave.fmu.deSerializeFMUstate(bad), pattern)
    other = new_hc()
    other_state = other.fmu.getFMUstate()
    foreign = bytes(other.fmu.serializeFMUstate(other_state))
    other.fmu.freeFMUstate(other_state)
    expect_error(slave, lambda: slave.fmu.deSerializeFMUstate(foreign), "FMU state belongs to GUID")
    # Nothing changed.
    assert np.array_equal(bits(slave.output_array()), bits(at))
    restored = slave.fmu.deSerializeFMUstate(good)
    assert slave.fmu.fmi2SetFMUstate(slave.fmu.component, restored) == fmi2OK
    slave.fmu.freeFMUstate(restored)


# Random valid, invalid and extreme values of every WheelRailContact input, each followed by a
# step, in a subprocess with a timeout (a hang in the FMU must fail, not block the suite).
_STORM = r"""
import json, math, sys
import numpy as np
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2Error
from fmpy.model_description import read_model_description
unzipdir, seed, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
md = read_model_description(unzipdir)
inputs = [v for v in md.modelVariables if v.causality == "input"]
outputs = [v.valueReference for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier,
                instanceName="storm")
fmu.instantiate()
def start():
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
start()
rng = np.random.default_rng(seed)
specials = [math.nan, math.inf, -math.inf, -1.0, 0.0, 1e308, -1e308, 5e-324, -5e-324, 1e-300]
t, counts = 0.0, {"accepted": 0, "rejected": 0, "ok": 0, "not ok": 0}
for k in range(steps):
    v = inputs[rng.integers(len(inputs))]
    lo, hi = float(v.min), float(v.max)
    x = float(rng.choice(specials)) if rng.random() < 0.4 else float(rng.uniform(lo, hi))
    try:
        fmu.setReal([v.valueReference], [x])
        assert math.isfinite(x) and lo <= x <= hi, f"{v.name} = {x} accepted"
        counts["accepted"] += 1
    except FMICallException as e:
        assert e.status == fmi2Error, e
        assert not (math.isfinite(x) and lo <= x <= hi), f"{v.name} = {x} rejected"
        counts["rejected"] += 1
    try:
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=1e-3)
        t += 1e-3
        counts["ok"] += 1
    except FMICallException:
        counts["not ok"] += 1  # a pose off the profiles: Discard; start again
        fmu.reset()
        t = 0.0
        start()
        continue
    values = fmu.getReal(outputs)
    assert all(math.isfinite(y) for y in values), (k, v.name, x)
fmu.terminate()
fmu.freeInstance()
print(json.dumps(counts))
"""


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_no_crash_no_hang_and_no_nan_over_a_storm_of_bad_and_extreme_inputs(wrc_unzipdir: Path, seed: int) -> None:
    """Every call returns OK, Warning (an implausible state), Discard or Error; whatever is readable
    is finite; nothing hangs."""
    try:
        proc = subprocess.run(
            [sys.executable, "-c", _STORM, str(wrc_unzipdir), str(seed), "400"],
            capture_output=True,
            text=True,
            timeout=120,
        )
    except subprocess.TimeoutExpired:
        pytest.fail("the FMU hung (no return within 120 s)")
    assert proc.returncode == 0, f"exit {proc.returncode} (a crash is a negative signal)\n{proc.stderr}"
    counts = json.loads(proc.stdout.strip().splitlines()[-1])
    assert counts["rejected"] > 50 and counts["accepted"] > 50 and counts["ok"] > 100, counts
