"""Runs one FMU instance in Ecos (ecospy) and writes what it outputs as JSON.

Used by ``test_ecos.py`` in a *subprocess*, like ``libcosim_driver.py``: a host that crashes or
aborts must fail one test, not the pytest session, and Ecos writes the FMU's log messages (at its
``debug`` level) to the process's output, where the tests read them.

Usage: ``python ecos_driver.py CONFIG.json RESULT.json``. CONFIG::

    {"fmu": "/abs/WheelRailContact.fmu",
     "instance": "wrc",                      # Ecos names variables "wrc::right.Fy"
     "step_size": 0.001,
     "start": {"wheelProfile": "S1002", "normalModel": 6, "y": 0.0},   # set before init
     "steps": [{}, {"y": 0.001}, ...],       # per step: inputs set, then one step
     "read": {"Real": ["right.Fy", ...], "Integer": ["right.nPatches", ...]},
     "log_level": "debug"}                   # optional; Ecos's levels (trace … off)

Values are set by their JSON type: string → set_string, integer → set_integer, boolean →
set_bool, number → set_real. RESULT: ``{"init": bool, "times": [t after each step], "rows":
[{name: value} after init, then after each step]}``. JSON keeps every float's bits (Python writes
the shortest representation that reads back to the same double).
"""

from __future__ import annotations

import json
import sys

from ecospy import EcosLib, EcosSimulation, EcosSimulationStructure


def set_value(sim: EcosSimulation, name: str, value) -> None:
    if isinstance(value, bool):
        sim.set_bool(name, value)
    elif isinstance(value, str):
        sim.set_string(name, value)
    elif isinstance(value, int):
        sim.set_integer(name, value)
    else:
        sim.set_real(name, float(value))


def main(config_path: str, result_path: str) -> int:
    with open(config_path, encoding="utf-8") as f:
        cfg = json.load(f)
    EcosLib.set_log_level(cfg.get("log_level", "warn"))
    prefix = f"{cfg['instance']}::"
    reals = cfg["read"].get("Real", [])
    integers = cfg["read"].get("Integer", [])

    def row(sim: EcosSimulation) -> dict:
        values = {n: sim.get_real(prefix + n) for n in reals}
        values.update({n: sim.get_integer(prefix + n) for n in integers})
        return values

    result = {"init": None, "times": [], "rows": []}
    with EcosSimulationStructure() as structure:
        structure.add_model(cfg["instance"], cfg["fmu"])
        with EcosSimulation(structure=structure, step_size=float(cfg["step_size"])) as sim:
            for name, value in cfg.get("start", {}).items():
                set_value(sim, prefix + name, value)
            result["init"] = bool(sim.init())
            sys.stdout.flush()
            result["rows"].append(row(sim))
            for inputs in cfg["steps"]:
                for name, value in inputs.items():
                    set_value(sim, prefix + name, value)
                result["times"].append(sim.step())
                result["rows"].append(row(sim))
            sim.terminate()
    with open(result_path, "w", encoding="utf-8") as f:
        json.dump(result, f)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
