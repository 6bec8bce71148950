"""Portability and packing of both FMUs: what a host on another Linux machine, or a user with a
measured profile, depends on.

1. The Linux library loads on glibc 2.17 and later: no symbol version newer than GLIBC_2.17,
   read from the packed ``binaries/linux64/*.so`` with binutils' ``objdump``.
2. The archive holds exactly one library, in the platform folder of the target it was built
   for (linux64 here).
3. ``fmu-pack --resource FILE … --out DIR`` bundles the files in every FMU's ``resources/``, and
   a bare file name in ``wheelProfile`` / ``railProfile`` loads the bundled file in FMPy (which
   unpacks the FMU to a temporary directory and passes its ``resources`` as a file: URI); a bare
   name that is not bundled fails initialization with a message listing where it was looked for.
"""

from __future__ import annotations

import re
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Error
from fmpy.model_description import read_model_description

from conftest import (
    BUNDLED_PROFILES,
    FMU_FILE_NAMES,
    WRC_FMU_FILE_NAME,
    PackerRun,
    bits,
    bundled_profile_values,
    packed_fmu,
    require_tool,
    data_file,
)

MODELS = ("HertzContact", "WheelRailContact")
GLIBC_BASELINE = (2, 17)

# =============================================================================================
# 1. glibc baseline


def _version(text: str) -> tuple[int, ...]:
    return tuple(int(x) for x in text.split("."))


def _glibc_versions(library: Path) -> tuple[dict[str, set[str]], set[str]]:
    """(symbol version → symbols referencing it, from ``objdump -T``; the versions the dynamic
    loader checks, from the version-reference section of ``objdump -p``)."""
    objdump = require_tool("objdump")
    symbols: dict[str, set[str]] = {}
    table = subprocess.run([objdump, "-T", str(library)], capture_output=True, text=True, check=True).stdout
    for line in table.splitlines():
        m = re.search(r"\(?GLIBC_([0-9.]+)\)?\s+(\S+)$", line)
        if m:
            symbols.setdefault(m.group(1), set()).add(m.group(2))
    headers = subprocess.run([objdump, "-p", str(library)], capture_output=True, text=True, check=True).stdout
    references = headers.split("Version References:", 1)
    required = set(re.findall(r"\bGLIBC_([0-9.]+)\b", references[1])) if len(references) == 2 else set()
    return symbols, required


@pytest.mark.parametrize("model", MODELS)
def test_linux_library_needs_no_glibc_newer_than_2_17(model: str, tmp_path: Path) -> None:
    fmu = packed_fmu(f"{model}.fmu")
    with zipfile.ZipFile(fmu) as z:
        library = Path(z.extract(f"binaries/linux64/{model}.so", tmp_path))
    symbols, required = _glibc_versions(library)
    assert symbols and required, "objdump found no glibc symbol versions: not a dynamically linked glibc library?"
    # Both views agree: every version the loader checks is used by some symbol.
    assert required == set(symbols), (required, sorted(symbols))
    too_new = {v: sorted(s) for v, s in symbols.items() if _version(v) > GLIBC_BASELINE}
    assert not too_new, (
        f"{model}: symbols need glibc newer than 2.17 (was the library linked against the build "
        f"machine's glibc? fmu-pack uses cargo-zigbuild for the 2.17 baseline): {too_new}"
    )


# =============================================================================================
# 2. Platform folder


@pytest.mark.parametrize("model", MODELS)
def test_the_archive_holds_one_library_in_the_linux64_folder(model: str) -> None:
    with zipfile.ZipFile(packed_fmu(f"{model}.fmu")) as z:
        binaries = [n for n in z.namelist() if n.startswith("binaries/")]
    assert binaries == [f"binaries/linux64/{model}.so"]


# =============================================================================================
# 3. Bundled resources


def test_packer_bundles_the_resources_in_every_fmu(bundled_fmu_dir: PackerRun) -> None:
    for file_name in FMU_FILE_NAMES:
        fmu = bundled_fmu_dir.out_dir / file_name
        with zipfile.ZipFile(fmu) as z:
            for relative in BUNDLED_PROFILES:
                name = Path(relative).name
                info = z.getinfo(f"resources/{name}")
                assert info.compress_type == zipfile.ZIP_DEFLATED
                assert z.read(info) == data_file(relative).read_bytes(), (file_name, name)
    # The packer ran both default experiments on the bundled FMUs and says how to use the files.
    assert "WheelRailContact: types platform" in bundled_fmu_dir.stdout
    assert 'wheelProfile = "MBench_S1002_v3.prw"' in bundled_fmu_dir.stdout


def _simulate(fmu: Path, start_values: dict) -> np.ndarray:
    """The default experiment with a lateral shift ramp 0 → 6 mm (FMPy interpolates it)."""
    signal = np.array([(0.0, 0.0), (0.008, 0.006)], dtype=[("time", np.float64), ("y", np.float64)])
    return simulate_fmu(str(fmu), start_values=start_values, input=signal)


def test_a_bare_profile_name_loads_the_bundled_file_in_fmpy(bundled_fmu_dir: PackerRun) -> None:
    common = {"railInclination": 0.0, "normalModel": 6}
    bundled = _simulate(
        bundled_fmu_dir.out_dir / WRC_FMU_FILE_NAME, {**common, **bundled_profile_values()}
    )
    by_path = _simulate(
        packed_fmu(WRC_FMU_FILE_NAME),
        {**common, **bundled_profile_values(by_path=True)},
    )
    builtin = _simulate(packed_fmu(WRC_FMU_FILE_NAME), common)
    assert len(bundled) == len(by_path) == 9
    # The same files through the same binary: the same results, bit for bit; and not those of the
    # built-in S1002/UIC60 (so the files were really read).
    for name in bundled.dtype.names:
        assert np.array_equal(bits(bundled[name]), bits(by_path[name])), name
    assert not np.array_equal(bundled["right.p1.Fn"], builtin["right.p1.Fn"])


def test_a_bare_name_that_is_not_bundled_lists_where_it_was_looked_for(new_wrc, wrc_unzipdir: Path) -> None:
    slave = new_wrc(initialize=False)
    with pytest.raises(FMICallException) as excinfo:
        slave.initialize(params={"wheelProfile": "MBench_S1002_v9.prw"})
    assert excinfo.value.status == fmi2Error
    text = " | ".join(m.text for m in slave.errors())
    resources = wrc_unzipdir / "resources" / "MBench_S1002_v9.prw"
    cwd = Path.cwd() / "MBench_S1002_v9.prw"
    for expected in (
        'wheelProfile = "MBench_S1002_v9.prw"',
        'unknown built-in profile "MBench_S1002_v9.prw"',
        f"looked in the FMU's resources folder ({resources})",
        f"and the working directory ({cwd})",
    ):
        assert expected in text, (expected, text)


def test_bundled_fmus_validate(bundled_fmu_dir: PackerRun) -> None:
    for file_name in FMU_FILE_NAMES:
        md = read_model_description(str(bundled_fmu_dir.out_dir / file_name), validate=True)
        assert md.coSimulation.modelIdentifier == file_name.removesuffix(".fmu")
