"""Runs HertzContact instances in one libcosim execution and writes what they output as JSON.

Used by ``test_hertz_contact.py::test_libcosim_two_instances_match_fmpy`` and
``test_host_behaviour.py`` in a *subprocess*: libcosim aborts the whole process when an FMU
returns fmi2Error from fmi2GetReal (as during a failed initialization, see docs/integration.md),
and such an abort must fail one test, not kill the pytest session.

Usage: ``python libcosim_driver.py CONFIG.json RESULT.json``. CONFIG::

    {"fmu": "/abs/HertzContact.fmu",
     "step_ns": 1000000,
     "instances": {"left": {"E": 2.0e11, "eta": -6.25e-4}, "right": {...}},   # initial values
     "phases": [{"steps": 3, "set": {}}, {"steps": 2, "set": {"left": {"eta": 1e-4}}}]}

Initial values are Real, Integer or (JSON strings) String. Each phase first overrides inputs
(libcosim applies them before the next fmi2DoStep), then steps.
RESULT: ``{"phases": [{"time_ns": ..., "values": {instance: {variable: value}}}], "variables": ...}``
with every Real and Integer variable of every instance, read through a last-value observer
after each phase. libcosim itself calls fmi2Get* for every declared variable after each step.
When a step fails (an FMU returned fmi2Discard or fmi2Error), the result gets ``"failed":
{"phase": index, "time_ns": ..., "state": ...}`` with the execution's status after the failure,
is written, and the driver exits with status 3.
"""

from __future__ import annotations

import json
import sys

from libcosimpy.CosimEnums import CosimExecutionState, CosimVariableType
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave


def main(config_path: str, result_path: str) -> int:
    with open(config_path, encoding="utf-8") as f:
        cfg = json.load(f)
    log_output_level(CosimLogLevel.WARNING)

    execution = CosimExecution.from_step_size(int(cfg["step_ns"]))
    slaves = {}  # keep the CosimLocalSlave objects alive for the whole run
    index = {}
    for name in cfg["instances"]:
        slaves[name] = CosimLocalSlave(fmu_path=cfg["fmu"], instance_name=name)
        index[name] = execution.add_local_slave(slaves[name])
        if index[name] < 0:
            raise RuntimeError(f"libcosim could not add instance {name!r}")

    # name -> (value reference, type), per instance (identical for the same FMU)
    variables = {
        name: {
            v.name.decode(): (v.reference, CosimVariableType(v.type))
            for v in execution.slave_variables(index[name])
        }
        for name in cfg["instances"]
    }

    for name, values in cfg["instances"].items():
        for var, value in values.items():
            vr, vtype = variables[name][var]
            if vtype is CosimVariableType.REAL:
                ok = execution.real_initial_value(index[name], vr, float(value))
            elif vtype is CosimVariableType.INTEGER:
                ok = execution.integer_initial_value(index[name], vr, int(value))
            elif vtype is CosimVariableType.STRING:
                ok = execution.string_initial_value(index[name], vr, str(value))
            else:
                raise ValueError(f"{var}: unsupported type {vtype}")
            if not ok:
                raise RuntimeError(f"libcosim rejected initial value {name}.{var} = {value}")

    manipulator = CosimManipulator.create_override()
    observer = CosimObserver.create_last_value()
    if not (execution.add_manipulator(manipulator) and execution.add_observer(observer)):
        raise RuntimeError("libcosim could not add the manipulator/observer")

    result = {"phases": [], "variables": {k: v[0] for k, v in variables[next(iter(variables))].items()}}
    for phase_index, phase in enumerate(cfg["phases"]):
        for name, values in phase.get("set", {}).items():
            for var, value in values.items():
                vr, vtype = variables[name][var]
                if vtype is not CosimVariableType.REAL:
                    raise ValueError(f"{var}: only Real overrides are used")
                if not manipulator.slave_real_values(index[name], [vr], [float(value)]):
                    raise RuntimeError(f"libcosim rejected override {name}.{var} = {value}")
        if not execution.step(int(phase["steps"])):
            status = execution.status()
            result["failed"] = {
                "phase": phase_index,
                "time_ns": int(status.current_time),
                "state": CosimExecutionState(status.state).name,
            }
            with open(result_path, "w", encoding="utf-8") as f:
                json.dump(result, f)
            print(f"libcosim step failed: {status}", file=sys.stderr)
            return 3
        status = execution.status()
        if CosimExecutionState(status.state) is CosimExecutionState.ERROR:
            raise RuntimeError(f"libcosim execution in error state: {status}")
        snapshot = {}
        for name in cfg["instances"]:
            reals = [(n, vr) for n, (vr, t) in variables[name].items() if t is CosimVariableType.REAL]
            ints = [(n, vr) for n, (vr, t) in variables[name].items() if t is CosimVariableType.INTEGER]
            values = dict(zip([n for n, _ in reals], observer.last_real_values(index[name], [vr for _, vr in reals])))
            values.update(zip([n for n, _ in ints], observer.last_integer_values(index[name], [vr for _, vr in ints])))
            snapshot[name] = values
        result["phases"].append({"time_ns": int(status.current_time), "values": snapshot})

    with open(result_path, "w", encoding="utf-8") as f:
        json.dump(result, f)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
