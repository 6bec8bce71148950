"""Fixtures (one per test run) and shared helpers for the host tests of the packed FMUs.

The FMUs are taken from ``$RAILCONTACT_FMU_DIR/<Model>.fmu`` when that variable is set, else
from ``$CARGO_TARGET_DIR/fmu/<Model>.fmu`` when that one is (relative to the working directory,
as Cargo reads it), else from ``<repo>/target/fmu/<Model>.fmu`` — where
``cargo run --release -p fmu-pack`` writes them. A missing FMU is a failure, never a skip: these
tests are the acceptance gate of the packed FMUs.

``bundled_fmu_dir`` packs a second set with the benchmark profiles in ``resources/`` by running
the packer's command (``cargo run --release -p fmu-pack -- --resource … --out DIR``); the
benchmark files come from ``tests/data`` (``data_file``).

``run_libcosim`` and ``run_ecos`` run ``libcosim_driver.py`` and ``ecos_driver.py`` (the libcosim
and Ecos hosts, each in a subprocess).

The fixtures ``fmu_path``, ``model_description``, ``unzipdir`` and ``shared_library`` are those
of HertzContact (``test_hertz_contact.py``); ``wrc_fmu_path``, ``wrc_model_description``,
``wrc_unzipdir`` and ``wrc_shared_library`` those of WheelRailContact
(``test_wheel_rail_contact.py``). The checks and helpers both modules use live here:
``assert_fmpy_validates``, ``assert_exports_exactly_the_34_fmi2_functions``, ``bits``, the log
router ``LOG`` (one per process — FMPy's native logger proxy keeps a single Python logger in a
static variable, so two routers would steal each other's messages) and the ``Slave`` wrapper.
"""

from __future__ import annotations

import importlib.util
import itertools
import json
import math
import os
import shutil
import subprocess
import sys
import threading
from ctypes import byref
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Mapping

import fmpy
import numpy as np
import pytest
from fmpy import calloc, free
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2Discard,
    fmi2Error,
    fmi2Warning,
)
from fmpy.logging import addLoggerProxy
from fmpy.model_description import ModelDescription, read_model_description
from fmpy.validation import validate_fmu

REPO_ROOT = Path(__file__).resolve().parents[2]
FMU_FILE_NAME = "HertzContact.fmu"
WRC_FMU_FILE_NAME = "WheelRailContact.fmu"
FMU_FILE_NAMES = (FMU_FILE_NAME, WRC_FMU_FILE_NAME)
FMU_DIR_ENV = "RAILCONTACT_FMU_DIR"

STEP = 1e-3  # s; the default experiments' step size (both models)

EXPECTED_FMI2_EXPORTS = frozenset(
    {
        # 25 common functions
        "fmi2GetTypesPlatform", "fmi2GetVersion", "fmi2SetDebugLogging", "fmi2Instantiate",
        "fmi2FreeInstance", "fmi2SetupExperiment", "fmi2EnterInitializationMode",
        "fmi2ExitInitializationMode", "fmi2Terminate", "fmi2Reset", "fmi2GetReal",
        "fmi2GetInteger", "fmi2GetBoolean", "fmi2GetString", "fmi2SetReal", "fmi2SetInteger",
        "fmi2SetBoolean", "fmi2SetString", "fmi2GetFMUstate", "fmi2SetFMUstate",
        "fmi2FreeFMUstate", "fmi2SerializedFMUstateSize", "fmi2SerializeFMUstate",
        "fmi2DeSerializeFMUstate", "fmi2GetDirectionalDerivative",
        # 9 co-simulation functions
        "fmi2SetRealInputDerivatives", "fmi2GetRealOutputDerivatives", "fmi2DoStep",
        "fmi2CancelStep", "fmi2GetStatus", "fmi2GetRealStatus", "fmi2GetIntegerStatus",
        "fmi2GetBooleanStatus", "fmi2GetStringStatus",
    }
)


def require_tool(name: str) -> str:
    path = shutil.which(name)
    if path is None:
        pytest.fail(f"`{name}` is not installed (Debian: binutils / libc-bin); this check cannot run")
    return path


def cargo_target_dir() -> Path:
    """Cargo's target directory: ``$CARGO_TARGET_DIR`` or ``<repo>/target``."""
    env = os.environ.get("CARGO_TARGET_DIR")
    return Path(env).resolve() if env else REPO_ROOT / "target"


def packed_fmu(file_name: str) -> Path:
    """Path of a packed FMU; fails the test (never skips) when it is missing."""
    env = os.environ.get(FMU_DIR_ENV)
    default_dir = cargo_target_dir() / "fmu"
    fmu_dir = Path(env) if env else default_dir
    path = (fmu_dir / file_name).resolve()
    if not path.is_file():
        origin = f"${FMU_DIR_ENV}={env!r}" if env else f"the default {default_dir}"
        pytest.fail(
            f"{file_name} not found at {path} (FMU directory from {origin}). Build and pack it "
            f"with `cargo run --release -p fmu-pack` in {REPO_ROOT}, or point {FMU_DIR_ENV} at the "
            f"directory that contains {file_name}.",
            pytrace=False,
        )
    return path


def validated_description(path: Path) -> ModelDescription:
    """The FMU's modelDescription.xml, parsed (and XSD-validated) by FMPy."""
    return read_model_description(str(path), validate=True)


def extracted(path: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The FMU extracted once per test run; every FMU2Slave of the run loads it from here."""
    target = tmp_path_factory.mktemp(f"{path.stem}_unzipped")
    return Path(fmpy.extract(str(path), unzipdir=str(target)))


def linux64_library(unzipdir: Path, md: ModelDescription) -> Path:
    """The FMU's linux64 shared library inside the extracted FMU; fails when it is missing."""
    identifier = md.coSimulation.modelIdentifier
    path = unzipdir / "binaries" / "linux64" / f"{identifier}.so"
    if not path.is_file():
        pytest.fail(f"the FMU has no binaries/linux64/{identifier}.so", pytrace=False)
    return path


def assert_fmpy_validates(path: Path) -> None:
    """FMPy's validation, by its command line and its API, finds no problem in the FMU."""
    # FMPy 0.3.32's command line is `fmpy.cli` (`fmpy.command_line` does not exist in 0.3.32);
    # it exits with the number of problems.
    proc = subprocess.run(
        [sys.executable, "-m", "fmpy.cli", "validate", str(path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, f"fmpy validate: exit {proc.returncode}\n{proc.stdout}\n{proc.stderr}"
    assert "No problems found" in proc.stdout
    assert validate_fmu(str(path)) == []


def assert_exports_exactly_the_34_fmi2_functions(library: Path) -> None:
    """The library's dynamic symbols starting with fmi2 (``nm -D``) are the standard's 34."""
    nm = require_tool("nm")
    out = subprocess.run([nm, "-D", "--defined-only", str(library)], capture_output=True, text=True, check=True).stdout
    symbols = [line.split()[-1] for line in out.splitlines() if line.strip()]
    fmi2 = sorted(s for s in symbols if s.startswith("fmi2"))
    assert len(fmi2) == 34, fmi2
    assert set(fmi2) == EXPECTED_FMI2_EXPORTS


def packed_fmu_fixtures(prefix: str, file_name: str):
    """The fixtures (one per test run) of one packed FMU, named ``{prefix}fmu_path`` (its path),
    ``{prefix}model_description``, ``{prefix}unzipdir`` (extracted once) and
    ``{prefix}shared_library`` (its linux64 library)."""

    @pytest.fixture(scope="session", name=f"{prefix}fmu_path")
    def path_fixture() -> Path:
        return packed_fmu(file_name)

    @pytest.fixture(scope="session", name=f"{prefix}model_description")
    def description_fixture(request: pytest.FixtureRequest) -> ModelDescription:
        return validated_description(request.getfixturevalue(f"{prefix}fmu_path"))

    @pytest.fixture(scope="session", name=f"{prefix}unzipdir")
    def unzipdir_fixture(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
        return extracted(request.getfixturevalue(f"{prefix}fmu_path"), tmp_path_factory)

    @pytest.fixture(scope="session", name=f"{prefix}shared_library")
    def library_fixture(request: pytest.FixtureRequest) -> Path:
        unzipped = request.getfixturevalue(f"{prefix}unzipdir")
        return linux64_library(unzipped, request.getfixturevalue(f"{prefix}model_description"))

    return path_fixture, description_fixture, unzipdir_fixture, library_fixture


# HertzContact (test_hertz_contact.py) and WheelRailContact (test_wheel_rail_contact.py).
fmu_path, model_description, unzipdir, shared_library = packed_fmu_fixtures("", FMU_FILE_NAME)
wrc_fmu_path, wrc_model_description, wrc_unzipdir, wrc_shared_library = packed_fmu_fixtures("wrc_", WRC_FMU_FILE_NAME)


# ---------------------------------------------------------------------------------------------
# The benchmark files and FMUs with them in resources/


def example_module(name: str, fmu_dir: Path):
    """examples/<name>.py imported as the module ``name``, its FMUs taken from ``fmu_dir``
    (``RAILCONTACT_FMU_DIR``, unless already set)."""
    os.environ.setdefault("RAILCONTACT_FMU_DIR", str(fmu_dir))
    spec = importlib.util.spec_from_file_location(name, REPO_ROOT / "examples" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def data_file(relative: str) -> Path:
    """A file of the vendored test data (``tests/data``); fails (never skips) when missing."""
    path = REPO_ROOT / "tests" / "data" / relative
    if not path.is_file():
        pytest.fail(f"test data file {path} not found", pytrace=False)
    return path


BUNDLED_PROFILES = ("profiles/MBench_S1002_v3.prw", "profiles/MBench_UIC60_v3.prr")


def bundled_profile_values(by_path: bool = False) -> dict[str, str]:
    """Start values of ``wheelProfile`` and ``railProfile`` naming ``BUNDLED_PROFILES``: by bare file
    name (the copies bundled in an FMU's resources) or, with ``by_path``, by their path in tests/data."""
    return {
        name: str(data_file(relative)) if by_path else Path(relative).name
        for name, relative in zip(("wheelProfile", "railProfile"), BUNDLED_PROFILES)
    }


@dataclass(frozen=True)
class PackerRun:
    out_dir: Path
    stdout: str


@pytest.fixture(scope="session")
def bundled_fmu_dir(tmp_path_factory: pytest.TempPathFactory) -> PackerRun:
    """Both FMUs packed with the benchmark wheel and rail profiles in resources/, by the packer's
    documented command (the library is already built: cargo only checks it is up to date)."""
    cargo = require_tool("cargo")
    out_dir = tmp_path_factory.mktemp("bundled") / "fmu"
    command = [cargo, "run", "--release", "-q", "-p", "fmu-pack", "--"]
    for relative in BUNDLED_PROFILES:
        command += ["--resource", str(data_file(relative))]
    command += ["--out", str(out_dir)]
    proc = subprocess.run(command, cwd=REPO_ROOT, capture_output=True, text=True, timeout=1200)
    if proc.returncode != 0:
        pytest.fail(f"{' '.join(command)}: exit {proc.returncode}\n{proc.stdout}\n{proc.stderr}", pytrace=False)
    return PackerRun(out_dir, proc.stdout)


# ---------------------------------------------------------------------------------------------
# Co-simulation engines, each in a subprocess (libcosim aborts its process when the FMU returns
# fmi2Error from fmi2GetReal; Ecos is kept apart the same way)


def run_driver(script: str, config: dict, tmp_path: Path) -> tuple[subprocess.CompletedProcess, dict | None]:
    """Runs the driver `script` (beside this file) on `config`; returns the finished process and
    the result it wrote (None if it wrote none)."""
    stem = script.split("_")[0]
    config_path, result_path = tmp_path / f"{stem}_config.json", tmp_path / f"{stem}_result.json"
    config_path.write_text(json.dumps(config), encoding="utf-8")
    proc = subprocess.run(
        [sys.executable, str(Path(__file__).resolve().parent / script), str(config_path), str(result_path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    result = json.loads(result_path.read_text(encoding="utf-8")) if result_path.is_file() else None
    return proc, result


def run_libcosim(config: dict, tmp_path: Path) -> tuple[subprocess.CompletedProcess, dict | None]:
    """Runs libcosim_driver.py (libcosimpy) on `config`."""
    return run_driver("libcosim_driver.py", config, tmp_path)


def run_ecos(config: dict, tmp_path: Path) -> tuple[dict, str]:
    """Runs ecos_driver.py on `config`; returns its result and its output (Ecos's log)."""
    proc, result = run_driver("ecos_driver.py", config, tmp_path)
    log = proc.stdout + proc.stderr
    assert proc.returncode == 0, f"Ecos driver died (exit {proc.returncode}):\n{log[-4000:]}"
    assert result is not None, f"Ecos driver wrote no result:\n{log[-4000:]}"
    return result, log


# ---------------------------------------------------------------------------------------------
# Shared helpers


def bits(values: np.ndarray) -> np.ndarray:
    """The IEEE-754 bit patterns of float64 values, for bit-for-bit comparisons."""
    return np.ascontiguousarray(values, dtype=np.float64).view(np.uint64)


# ---------------------------------------------------------------------------------------------
# Logging: one process-wide logger, messages routed per instance by componentEnvironment


@dataclass(frozen=True)
class LogMessage:
    instance: str
    status: int
    category: str
    text: str


def _decode(b: bytes | None) -> str:
    return b.decode("utf-8", errors="replace") if b is not None else ""


class LogRouter:
    """Collects the FMU's log messages per instance.

    fmpy's proxy formats the printf-style message and calls a single static Python logger; each
    instance gets its own `componentEnvironment` key so its messages land in its own list.
    """

    def __init__(self) -> None:
        self._sinks: dict[int, list[LogMessage]] = {}
        self._keys = itertools.count(1)
        self._lock = threading.Lock()
        self.unrouted: list[LogMessage] = []
        self._callback = fmi2CallbackLoggerTYPE(self._on_message)  # kept alive for the process

    def _on_message(self, env, instance, status, category, message) -> None:
        msg = LogMessage(_decode(instance), int(status), _decode(category), _decode(message))
        self._sinks.get(env or 0, self.unrouted).append(msg)

    def new_callbacks(self) -> tuple[fmi2CallbackFunctions, list[LogMessage]]:
        """A callbacks struct for one instance and the list its messages arrive in."""
        with self._lock:
            key = next(self._keys)
            sink: list[LogMessage] = []
            self._sinks[key] = sink
        callbacks = fmi2CallbackFunctions()
        callbacks.logger = self._callback
        callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        callbacks.componentEnvironment = key
        # (Re)installs this router as the proxy's target, whatever simulate_fmu installed before.
        addLoggerProxy(byref(callbacks))
        return callbacks, sink


LOG = LogRouter()


# ---------------------------------------------------------------------------------------------
# One FMU2Slave instance with name-based access


class Slave:
    """An FMU2Slave of the extracted FMU with name-based get/set, time tracking and its log."""

    _names = itertools.count()

    def __init__(self, md: ModelDescription, unzipdir: Path, name: str | None = None) -> None:
        self.md = md
        self.vars = {v.name: v for v in md.modelVariables}
        # Real outputs (Integer outputs such as WheelRailContact's nPatches are read with get()).
        self.output_names = [v.name for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
        self._output_vrs = [self.vars[n].valueReference for n in self.output_names]
        # Default names: the model identifier's capitals in lower case and a counter (hc0, wrc1, …).
        prefix = "".join(c for c in md.coSimulation.modelIdentifier if c.isupper()).lower()
        self.name = name or f"{prefix}{next(Slave._names)}"
        self.callbacks, self.messages = LOG.new_callbacks()
        self.fmu = FMU2Slave(
            guid=md.guid,
            unzipDirectory=str(unzipdir),
            modelIdentifier=md.coSimulation.modelIdentifier,
            instanceName=self.name,
        )
        try:
            self.fmu.instantiate(callbacks=self.callbacks)
        except Exception:
            self.fmu.freeLibrary()
            raise
        self.time = 0.0
        self._freed = False

    # -- values
    def set(self, **values: float | int | str | bool) -> None:
        """Sets variables one call each, so a rejected value is attributed to its variable."""
        setters = {
            "Integer": (self.fmu.setInteger, int),
            "Real": (self.fmu.setReal, float),
            "String": (self.fmu.setString, str),
            "Boolean": (self.fmu.setBoolean, bool),
        }
        for name, value in values.items():
            v = self.vars[name]
            if v.type not in setters:  # pragma: no cover
                raise TypeError(f"{name}: {v.type}")
            setter, cast = setters[v.type]
            setter([v.valueReference], [cast(value)])

    def get(self, name: str) -> float | int | str | bool:
        v = self.vars[name]
        getter = {
            "Integer": self.fmu.getInteger,
            "String": self.fmu.getString,
            "Boolean": self.fmu.getBoolean,
        }.get(v.type, self.fmu.getReal)
        value = getter([v.valueReference])[0]
        return value.decode("utf-8") if isinstance(value, bytes) else value

    def output_array(self) -> np.ndarray:
        """All outputs, in model-description order; never NaN or ±∞ (docs/conventions.md)."""
        values = np.array(self.fmu.getReal(self._output_vrs), dtype=np.float64)
        bad = {n: x for n, x in zip(self.output_names, values) if not math.isfinite(x)}
        assert not bad, f"{self.name}: non-finite outputs {bad}"
        return values

    def outputs(self) -> dict[str, float]:
        return dict(zip(self.output_names, self.output_array().tolist()))

    # -- life cycle
    def initialize(
        self,
        params: Mapping[str, float | int] | None = None,
        inputs: Mapping[str, float] | None = None,
        stop_time: float | None = None,
    ) -> "Slave":
        self.fmu.setupExperiment(startTime=0.0, stopTime=stop_time)
        self.set(**(params or {}))
        self.set(**(inputs or {}))
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.time = 0.0
        return self

    def step(self, h: float = STEP) -> None:
        self.fmu.doStep(currentCommunicationPoint=self.time, communicationStepSize=h)
        self.time = self.time + h  # the FMU computes its time the same way

    def run(self, sequence: Iterable[Mapping[str, float]], h: float = STEP) -> np.ndarray:
        """For each entry: set those inputs, step, read all outputs. Returns one row per step."""
        rows = []
        for inputs in sequence:
            self.set(**inputs)
            self.step(h)
            rows.append(self.output_array())
        return np.array(rows)

    def errors(self) -> list[LogMessage]:
        return [m for m in self.messages if m.status >= fmi2Error]

    def warnings(self) -> list[LogMessage]:
        return [m for m in self.messages if m.status in (fmi2Warning, fmi2Discard)]

    def free(self) -> None:
        if self._freed:
            return
        self._freed = True
        try:
            self.fmu.terminate()
        except FMICallException:
            pass  # not initialized, or already terminated: freeing is still legal
        self.fmu.freeInstance()


def slave_factory(model_description: ModelDescription, unzipdir: Path):
    """Generator behind the `new_slave`/`new_wrc` fixtures: yields a factory making initialized
    `Slave`s of one FMU, and frees every slave it made at teardown (newest first)."""
    created: list[Slave] = []

    def factory(
        params: Mapping[str, float | int | str] | None = None,
        inputs: Mapping[str, float] | None = None,
        initialize: bool = True,
        name: str | None = None,
        stop_time: float | None = None,
    ) -> Slave:
        slave = Slave(model_description, unzipdir, name)
        created.append(slave)
        if initialize:
            slave.initialize(params, inputs, stop_time)
        return slave

    yield factory
    for slave in reversed(created):
        slave.free()


@pytest.fixture
def new_wrc(wrc_model_description: ModelDescription, wrc_unzipdir: Path):
    """Factory of WheelRailContact slaves: `new_wrc(params=..., inputs=..., initialize=True,
    name=None)`; frees them at teardown."""
    yield from slave_factory(wrc_model_description, wrc_unzipdir)
