"""The ``railcontact`` Python package (``python/``) against the ``railcontact`` command.

The package's evaluations go through the command's own case, solve and JSON code, so its
results must equal the command's JSON bit for bit: the default case and cases with other
models, poses, the pressure grid and the traction field. ``solve_batch`` must equal a loop of
``solve`` calls bit for bit (each row from the initialized state), refuse rows it cannot solve
row by row, and release the GIL. Errors carry the command's messages.

The package is the wheel ``tests/run_all.sh`` builds (``maturin build``) and installs into the
test venv; the command is $RAILCONTACT_CLI, else ``cargo run --release -p railcontact-cli``.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
import threading
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

import railcontact
from test_packaging import GLIBC_BASELINE, _glibc_versions, _version

REPO_ROOT = Path(__file__).resolve().parents[2]
WHEELS = REPO_ROOT / "target" / "wheels"


def command() -> list[str]:
    exe = os.environ.get("RAILCONTACT_CLI")
    return [exe] if exe else ["cargo", "run", "-q", "--release", "-p", "railcontact-cli", "--"]


def cli_solve(case: dict, *extra: str) -> tuple[int, dict | None, str]:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "case.json"
        path.write_text(json.dumps(case))
        run = subprocess.run(
            command() + ["solve", str(path), *extra],
            cwd=REPO_ROOT,
            capture_output=True,
            text=True,
        )
    doc = json.loads(run.stdout) if run.stdout.strip() else None
    return run.returncode, doc, run.stderr


def same_bits(a, b) -> bool:
    """Equal as the command printed them: floats bit for bit, arrays element by element."""
    if isinstance(a, np.ndarray):
        return np.array_equal(a, np.array(b), equal_nan=True) and a.dtype.kind in "fi"
    if isinstance(a, float) and isinstance(b, float):
        return np.float64(a).tobytes() == np.float64(b).tobytes()
    return a == b


def assert_equal_to_command(case: dict, **options) -> dict:
    extra = []
    if options.get("grid"):
        extra += ["--grid", str(options["grid"])]
    if options.get("traction"):
        extra += ["--traction"]
    code, doc, stderr = cli_solve(case, *extra)
    assert code in (0, 3), stderr
    ours = railcontact.solve(case, **options)
    assert list(ours) == list(doc)
    for key, value in doc.items():
        if key == "strips":
            assert list(ours[key]) == list(value), key
            for patch, rows in value.items():
                for field in rows[0]:
                    column = [r[field] for r in rows]
                    assert same_bits(ours[key][patch][field], column), (key, patch, field)
        elif key in ("grid", "traction"):
            assert list(ours[key]) == list(value), key
            for patch, rows in value.items():
                assert same_bits(ours[key][patch], rows), (key, patch)
        else:
            assert same_bits(ours[key], value), key
    return ours


def test_default_case_equals_the_command():
    out = assert_equal_to_command({})
    assert out["right.p1.Fn"] > 0.0


@pytest.mark.parametrize(
    "case",
    [
        {"normalModel": 6, "y": 0.003, "yaw": 0.002},
        {"normalModel": 7, "tangentialModel": 5, "y": -0.002, "planarPatch": True},
        {"normalModel": 2, "creepageMode": 2, "xi": 0.002, "eta": -0.001, "phi": 0.1, "mu": 0.4},
        {"normalModel": 1, "wearModel": 1, "y": 0.005},
    ],
)
def test_cases_equal_the_command(case):
    assert_equal_to_command(case)


def test_grid_and_traction_equal_the_command():
    out = assert_equal_to_command({"normalModel": 6}, grid=5, traction=True)
    assert set(out["traction"]) and set(out["grid"])


def test_batch_equals_a_loop_of_single_solves():
    rng = np.random.default_rng(7)
    n = 12
    inputs = {
        "y": rng.uniform(-0.006, 0.006, n),
        "yaw": rng.uniform(-0.003, 0.003, n),
        "vy": rng.uniform(-0.2, 0.2, n),
    }
    case = {"normalModel": 6}
    # Independent rows: a loop of `solve`.
    batch = railcontact.solve_batch(case, inputs, independent=True)
    assert set(railcontact.real_outputs()) <= set(batch)
    assert batch["status"].tolist() == [0] * n
    for k in range(n):
        single = railcontact.solve({**case, **{name: float(v[k]) for name, v in inputs.items()}})
        for name in railcontact.real_outputs():
            assert same_bits(float(batch[name][k]), single[name]), (k, name)
    # Rows as steps: a loop of one Wheelset's calls.
    carried = railcontact.solve_batch(case, inputs)
    ws = railcontact.Wheelset(case)
    for k in range(n):
        step = ws.solve(**{name: float(v[k]) for name, v in inputs.items()})
        for name in railcontact.real_outputs():
            assert same_bits(float(carried[name][k]), step[name]), (k, name)


def test_batch_refuses_rows_it_cannot_solve_and_goes_on():
    # y = 0.05 m lies beyond the flange: no contact inside the profiles (the command's exit 2).
    batch = railcontact.solve_batch({}, {"y": np.array([0.0, 0.05, 0.001])})
    assert batch["status"].tolist() == [0, 2, 0]
    assert np.isnan(batch["right.p1.Fn"][1])
    assert batch["right.p1.Fn"][0] > 0 and batch["right.p1.Fn"][2] > 0


def test_batch_releases_the_gil():
    # A thread that counts while a long batch runs: it advances (the GIL is released).
    counted = []
    done = threading.Event()

    def count():
        k = 0
        while not done.is_set():
            k += 1
            time.sleep(0)
        counted.append(k)

    t = threading.Thread(target=count)
    t.start()
    railcontact.solve_batch({"normalModel": 7}, {"y": np.linspace(-0.004, 0.004, 200)})
    done.set()
    t.join()
    assert counted[0] > 100


def test_errors_carry_the_command_messages():
    code, _, stderr = cli_solve({"mu": -1.0})
    assert code == 1
    with pytest.raises(railcontact.RailcontactError) as e:
        railcontact.solve({"mu": -1.0})
    reason = str(e.value).split(": ", 1)[1]
    assert reason in stderr
    with pytest.raises(railcontact.RailcontactError, match='unknown key "noSuchKey"'):
        railcontact.solve({"noSuchKey": 1})
    with pytest.raises(railcontact.DiscardError):
        railcontact.solve({"y": 0.05})
    with pytest.raises(railcontact.RailcontactError, match="not a Real input"):
        railcontact.solve_batch({}, {"mu": np.array([0.3])})
    with pytest.raises(railcontact.RailcontactError, match="outside the allowed range"):
        railcontact.solve_batch({}, {"vx": np.array([1.0, np.nan])})
    with pytest.raises(railcontact.RailcontactError, match="values, the first column has"):
        railcontact.solve_batch({}, {"y": np.zeros(3), "yaw": np.zeros(2)})


def test_the_wheel_is_abi3_manylinux2014_and_needs_no_newer_glibc(tmp_path):
    # The wheel tests/run_all.sh built: one file, tagged for CPython ≥ 3.11 through the stable
    # ABI and for manylinux2014, whose native module references no glibc symbol version newer
    # than 2.17; and the installed package is that build.
    wheels = sorted(WHEELS.glob("railcontact-*.whl"))
    assert len(wheels) == 1, wheels
    name = wheels[0].name
    assert "-cp311-abi3-" in name and "manylinux2014_x86_64" in name, name
    with zipfile.ZipFile(wheels[0]) as z:
        native = [n for n in z.namelist() if n.startswith("railcontact/_native") and n.endswith(".so")]
        assert len(native) == 1, z.namelist()
        z.extract(native[0], tmp_path)
    symbols, required = _glibc_versions(tmp_path / native[0])
    assert symbols and required
    too_new = {v: sorted(s) for v, s in symbols.items() if _version(v) > GLIBC_BASELINE}
    assert not too_new, too_new
    assert all(_version(v) <= GLIBC_BASELINE for v in required), required
    installed = Path(railcontact._native.__file__).read_bytes()
    with zipfile.ZipFile(wheels[0]) as z:
        assert z.read(native[0]) == installed
