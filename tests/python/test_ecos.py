"""Both FMUs in a third host, Ecos (ecospy), against FMPy: the same outputs, bit for bit.

Ecos runs in a subprocess (``ecos_driver.py``). Its variables are named ``instance::variable``;
values set before ``init`` are start values, values set between steps are inputs of the next
step, and it reads outputs after initialization and after every step — the same sequence of FMI
calls as the FMPy side here (``simulate_fmu`` for the default experiment, the ``Slave`` wrapper
for an input sweep), so even WheelRailContact's warm start (which carries the previous step's
solution into the next) must give identical bits.

How Ecos reacts to fmi2Discard and fmi2Error is in ``test_host_behaviour.py``.
"""

from __future__ import annotations

from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.model_description import ModelDescription, read_model_description

from conftest import (
    FMU_FILE_NAMES,
    WRC_FMU_FILE_NAME,
    PackerRun,
    Slave,
    bits,
    bundled_profile_values,
    packed_fmu,
    run_ecos,
)

# The input each model's sweep drives (the same sweeps as fmu-pack's default experiments).
SWEEPS = {
    "HertzContact": ("eta", 0.0, -0.004),
    "WheelRailContact": ("y", 0.0, 0.008),
}


def outputs_by_type(md: ModelDescription) -> dict[str, list[str]]:
    out = {"Real": [], "Integer": []}
    for v in md.modelVariables:
        if v.causality == "output":
            out[v.type].append(v.name)
    return out


def experiment(md: ModelDescription) -> tuple[float, int]:
    de = md.defaultExperiment
    step = float(de.stepSize)
    return step, round((float(de.stopTime) - float(de.startTime)) / step)


@pytest.mark.parametrize("file_name", FMU_FILE_NAMES)
def test_default_experiment_in_ecos_matches_fmpy_bit_for_bit(file_name: str, tmp_path: Path) -> None:
    fmu = packed_fmu(file_name)
    md = read_model_description(str(fmu))
    step, steps = experiment(md)
    read = outputs_by_type(md)
    result, log = run_ecos(
        {"fmu": str(fmu), "instance": "m", "step_size": step, "steps": [{}] * steps, "read": read}, tmp_path
    )
    assert result["init"], log
    assert result["times"] == pytest.approx([step * (k + 1) for k in range(steps)], rel=1e-12)
    # FMPy's default experiment: start values, DefaultExperiment's stop time and step size.
    reference = simulate_fmu(str(fmu), output=read["Real"] + read["Integer"], output_interval=step)
    assert len(reference) == steps + 1 == len(result["rows"])
    for name in read["Real"] + read["Integer"]:
        ecos = np.array([row[name] for row in result["rows"]], dtype=np.float64)
        assert np.array_equal(bits(ecos), bits(reference[name].astype(np.float64))), name
    assert "error" not in log.lower(), log


@pytest.mark.parametrize("file_name", FMU_FILE_NAMES)
def test_input_sweep_in_ecos_matches_fmpy_bit_for_bit(file_name: str, tmp_path: Path) -> None:
    fmu = packed_fmu(file_name)
    md = read_model_description(str(fmu))
    model = md.coSimulation.modelIdentifier
    step, steps = experiment(md)
    name, start, stop = SWEEPS[model]
    values = [start + (stop - start) * (k + 1) / steps for k in range(steps)]
    read = outputs_by_type(md)
    result, log = run_ecos(
        {
            "fmu": str(fmu),
            "instance": "m",
            "step_size": step,
            "start": {name: start},
            "steps": [{name: v} for v in values],
            "read": read,
        },
        tmp_path,
    )
    assert result["init"], log

    unzipdir = tmp_path / "unzipped"
    fmpy.extract(str(fmu), unzipdir=str(unzipdir))
    slave = Slave(md, unzipdir)
    try:
        slave.initialize(inputs={name: start})
        rows = [slave.output_array()]
        integers = [[slave.get(n) for n in read["Integer"]]]
        for v in values:
            rows.extend(slave.run([{name: v}]))
            integers.append([slave.get(n) for n in read["Integer"]])
    finally:
        slave.free()
    assert slave.output_names == read["Real"]
    ecos_reals = np.array([[row[n] for n in read["Real"]] for row in result["rows"]], dtype=np.float64)
    assert np.array_equal(bits(ecos_reals), bits(np.array(rows))), model
    assert [[row[n] for n in read["Integer"]] for row in result["rows"]] == integers
    # The sweep changes the outputs (not a comparison of constants).
    assert len({tuple(r) for r in np.array(rows).tolist()}) > steps // 2


def test_a_bundled_profile_loads_by_its_bare_name_in_ecos(bundled_fmu_dir: PackerRun, tmp_path: Path) -> None:
    read = {"Real": ["right.Fy", "right.Fz", "right.p1.Fn", "right.p1.contactAngle"], "Integer": ["right.nPatches"]}
    steps = [{"y": 0.001 * k} for k in range(1, 7)]
    common = {"railInclination": 0.0, "normalModel": 6}
    bundled, log = run_ecos(
        {
            "fmu": str(bundled_fmu_dir.out_dir / WRC_FMU_FILE_NAME),
            "instance": "wrc",
            "step_size": 0.001,
            "start": {**common, **bundled_profile_values()},
            "steps": steps,
            "read": read,
            # Ecos reports an FMU's errors only in its debug log (test_host_behaviour.py).
            "log_level": "debug",
        },
        tmp_path,
    )
    assert bundled["init"] and "fmi2Error" not in log, log
    by_path, _ = run_ecos(
        {
            "fmu": str(packed_fmu(WRC_FMU_FILE_NAME)),
            "instance": "wrc",
            "step_size": 0.001,
            "start": {**common, **bundled_profile_values(by_path=True)},
            "steps": steps,
            "read": read,
        },
        tmp_path,
    )
    assert bundled["rows"] == by_path["rows"]  # floats read back from JSON bit for bit
    # In contact (a patch keeps its output slot while it exists, so slot 1 may be empty).
    assert bundled["rows"][-1]["right.Fz"] < 0.0 and bundled["rows"][-1]["right.nPatches"] >= 1
