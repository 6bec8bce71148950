"""Session fixtures for the host tests of the packed HertzContact FMU.

The FMU is taken from ``$RAILCONTACT_FMU_DIR/HertzContact.fmu`` when that variable is set, else
from ``<repo>/target/fmu/HertzContact.fmu`` (written by ``cargo run --release -p fmu-pack``).
A missing FMU is a failure, never a skip: these tests are the acceptance gate of the packed FMU.
"""

from __future__ import annotations

import os
from pathlib import Path

import fmpy
import pytest
from fmpy.model_description import ModelDescription, read_model_description

REPO_ROOT = Path(__file__).resolve().parents[2]
FMU_FILE_NAME = "HertzContact.fmu"
FMU_DIR_ENV = "RAILCONTACT_FMU_DIR"


@pytest.fixture(scope="session")
def fmu_path() -> Path:
    """Path of the packed FMU under test."""
    env = os.environ.get(FMU_DIR_ENV)
    fmu_dir = Path(env) if env else REPO_ROOT / "target" / "fmu"
    path = (fmu_dir / FMU_FILE_NAME).resolve()
    if not path.is_file():
        origin = f"${FMU_DIR_ENV}={env!r}" if env else f"the default {REPO_ROOT / 'target' / 'fmu'}"
        pytest.fail(
            f"{FMU_FILE_NAME} not found at {path} (FMU directory from {origin}). Build and pack it "
            f"with `cargo run --release -p fmu-pack` in {REPO_ROOT}, or point {FMU_DIR_ENV} at the "
            f"directory that contains {FMU_FILE_NAME}.",
            pytrace=False,
        )
    return path


@pytest.fixture(scope="session")
def model_description(fmu_path: Path) -> ModelDescription:
    """The FMU's modelDescription.xml, parsed (and XSD-validated) by FMPy."""
    return read_model_description(str(fmu_path), validate=True)


@pytest.fixture(scope="session")
def unzipdir(fmu_path: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The FMU extracted once per session; every FMU2Slave of the session loads it from here."""
    target = tmp_path_factory.mktemp("HertzContact_unzipped")
    return Path(fmpy.extract(str(fmu_path), unzipdir=str(target)))


@pytest.fixture(scope="session")
def shared_library(unzipdir: Path, model_description: ModelDescription) -> Path:
    """The FMU's linux64 shared library inside the extracted FMU."""
    identifier = model_description.coSimulation.modelIdentifier
    path = unzipdir / "binaries" / "linux64" / f"{identifier}.so"
    if not path.is_file():
        pytest.fail(f"the FMU has no binaries/linux64/{identifier}.so", pytrace=False)
    return path
