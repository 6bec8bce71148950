"""The railcontact package's studies: equivalent conicity, profiles and the wear update against
the `railcontact` command (bit for bit), and fleet studies on Dask (a local cluster of 2 workers
gives the serial run's table; the synthetic profiles are reproducible and accepted by the
element).

Needs the installed wheel and the command, as test_package.py.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import railcontact
from railcontact import fleet
from test_package import REPO_ROOT, command, same_bits

PROFILES = REPO_ROOT / "tests" / "data" / "profiles"
BENCH_CASE = {
    "wheelProfile": str(PROFILES / "MBench_S1002_v3.prw"),
    "railProfile": str(PROFILES / "MBench_UIC60_v3.prr"),
    "railInclination": 0.0,
}


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(command() + list(args), cwd=REPO_ROOT, capture_output=True, text=True)


def cli_json(tmp_path: Path, sub: str, case: dict, *args: str) -> dict:
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    run = cli(sub, str(path), *args)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def assert_same_document(ours: dict, doc: dict) -> None:
    assert list(ours) == list(doc)
    for key, value in doc.items():
        if isinstance(value, list) and value and isinstance(value[0], dict):
            for field in value[0]:
                column = [np.nan if r[field] is None else r[field] for r in value]
                assert same_bits(ours[key][field], column), (key, field)
        else:
            assert same_bits(ours[key], value), key


# ------------------------------------------------------------------------------------------------
# Conicity


@pytest.mark.parametrize(
    "case, options, args",
    [
        ({}, {}, []),
        (BENCH_CASE, {"amplitudes": [0.0015, 0.004], "roll": False}, ["--amplitudes", "0.0015,0.004", "--no-roll"]),
        ({"normalModel": 6}, {"load": 60e3, "step": 1e-4}, ["--load", "60000", "--step", "0.0001"]),
    ],
)
def test_conicity_equals_the_command(tmp_path, case, options, args):
    doc = cli_json(tmp_path, "conicity", case, *args)
    ours = railcontact.conicity(case, **options)
    assert_same_document(ours, doc)


def test_conicity_of_the_new_profiles_and_its_contact_points():
    """S1002 on UIC60 1:40 at 1435 mm: λ(3 mm) ≈ 0.18 (EN 15302's reference pair; 0.17–0.20 in
    published tables, our test suite pins it to the Klingel integral); the contact points move
    outwards on both the wheel and the right rail as the wheelset shifts right."""
    out = railcontact.conicity()
    lam = dict(zip(out["conicity"]["amplitude"], out["conicity"]["harmonic"]))
    assert 0.15 < lam[0.003] < 0.21
    d = out["deltaR"]
    near = np.abs(d["y"]) <= 0.003
    assert np.all(np.diff(d["yWheelRight"][near]) <= 1e-12), "right wheel point moves to the flange"
    assert np.all(d["deltaR"][d["y"] > 0.001] > 0.0)


def test_conicity_errors_carry_the_command_messages(tmp_path):
    run = cli("conicity", "--amplitudes", "0.05")
    assert run.returncode == 1
    with pytest.raises(railcontact.RailcontactError) as e:
        railcontact.conicity(amplitudes=[0.05])
    assert str(e.value) in run.stderr


# ------------------------------------------------------------------------------------------------
# Profiles


def test_profiles_read_check_evaluate_and_write(tmp_path):
    s1002 = railcontact.read_profile("S1002", "wheel")
    assert (s1002.name, s1002.kind, s1002.smoothing) == ("S1002", "wheel", 0.0)
    # The taping line is the wheel profile's origin: z(0) = 0; the flange tip 28 mm below.
    z, dz, _ = s1002.eval([0.0])
    assert abs(z[0]) < 1e-9 and abs(s1002.z.max() - 0.028) < 1e-4
    bench = railcontact.read_profile(PROFILES / "MBench_UIC60_v3.prr", "rail", smoothing=1e-3)
    assert bench.kind == "rail" and bench.smoothing == 1e-3
    # Written and read back: the same points to the file's 1 nm.
    path = tmp_path / "s1002.txt"
    s1002.write(path, header="a copy")
    back = railcontact.read_profile(path, "wheel")
    assert np.max(np.abs(back.y - s1002.y)) < 1e-9 and np.max(np.abs(back.z - s1002.z)) < 1e-9
    assert path.read_text().startswith("# a copy\n")


def test_worn_profile_moves_along_the_normal():
    """A uniform depth d lowers a flat tread by d (the wear loop's depth is vertical) and moves
    the points along the normal by d/√(1 + z′²)."""
    s1002 = railcontact.read_profile("S1002", "wheel")
    y = np.array([-0.1, 0.1])
    worn = s1002.worn(y, [5e-4, 5e-4])
    slope = s1002.eval(s1002.y)[1]
    moved = np.hypot(worn.y - s1002.y, worn.z - s1002.z)
    assert np.allclose(moved, 5e-4 / np.sqrt(1 + slope**2), rtol=0, atol=1e-12)
    # Material is removed: the wheel's radius (z) decreases on the tread.
    tread = np.abs(s1002.y) < 0.02
    assert np.allclose(worn.z[tread] - s1002.z[tread], -5e-4 / (1 + slope[tread] ** 2), atol=1e-12)
    with pytest.raises(railcontact.RailcontactError, match="ascending"):
        s1002.worn([0.1, -0.1], [0.0, 0.0])


def test_profile_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("0 0\n1 abc\n")
    with pytest.raises(railcontact.RailcontactError, match="bad.txt") as e:
        railcontact.read_profile(bad, "wheel")
    case = tmp_path / "case.json"
    case.write_text(json.dumps({"wheelProfile": str(bad)}))
    run = cli("solve", str(case))
    assert run.returncode == 1 and str(e.value) in run.stderr
    with pytest.raises(railcontact.RailcontactError, match="'wheel' or 'rail'"):
        railcontact.read_profile("S1002", "axle")
    with pytest.raises(railcontact.RailcontactError):
        railcontact.read_profile("UIC60", "wheel")


# ------------------------------------------------------------------------------------------------
# The wear update


def wear_record(path: Path) -> None:
    """A hand-made wear record: a Gaussian band of worn mass on both wheels and rails."""
    lines = ["# railcontact wear record", "# distance_m,1e3", "# wheel_radius_m,4.6e-1",
             "# bin_m,5e-4", "side,body,y,mass,depth"]
    for side in ("left", "right"):
        for body, centre in (("wheel", 0.0), ("rail", -0.005)):
            for i in range(-40, 41):
                y = i * 5e-4
                mass = 1e-4 * math.exp(-(((y - centre) / 0.006) ** 2))
                lines.append(f"{side},{body},{y:e},{mass:e},0")
    path.write_text("\n".join(lines) + "\n")


def test_wear_update_equals_the_command(tmp_path):
    record = tmp_path / "run.csv"
    wear_record(record)
    case = {"normalModel": 6}
    doc = cli_json(tmp_path, "wear", case, "--record", str(record), "--distance", "1e6",
                   "--out", str(tmp_path / "cli"))
    ours = railcontact.wear_update(case, [record], distance=1e6, out=tmp_path / "py")
    for key in doc:
        if key in ("wheelProfile", "railProfile", "depths"):
            a, b = Path(doc[key]), Path(ours[key])
            assert a.name == b.name and a.read_bytes() == b.read_bytes(), key
        else:
            assert same_bits(ours[key], doc[key]), key
    assert ours["wheelDepthMax"] > 0.0


# ------------------------------------------------------------------------------------------------
# Fleet studies


@pytest.fixture(scope="module")
def example(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("fleet")
    fleet.make_example(root, wheels=6, rails=2, seed=7)
    # A file the element refuses, among the wheels: its pairs fail, the others go on.
    (root / "wheels" / "wheel_zz_broken.txt").write_text("# not a profile\n1 2\n")
    return root


def test_synthetic_profiles_are_reproducible_and_accepted(tmp_path, example):
    fleet.make_example(tmp_path, wheels=6, rails=2, seed=7)
    for sub in ("wheels", "rails"):
        for f in sorted((tmp_path / sub).iterdir()):
            assert f.read_bytes() == (example / sub / f.name).read_bytes(), f.name
            railcontact.read_profile(f, sub[:-1]).check()
    fleet.make_example(tmp_path / "other", wheels=1, rails=2, seed=8)
    assert (tmp_path / "other/wheels/wheel_0000.txt").read_bytes() != (
        example / "wheels/wheel_0000.txt"
    ).read_bytes()
    # The first rail is the new UIC60; the wear shapes stay within their documented ranges.
    new = railcontact.read_profile(example / "rails/rail_00.txt", "rail")
    uic60 = railcontact.read_profile("UIC60", "rail")
    assert np.max(np.abs(new.z - uic60.z)) < 1e-9
    worn = railcontact.read_profile(example / "wheels/wheel_0000.txt", "wheel")
    s1002 = railcontact.read_profile("S1002", "wheel")
    removed = np.hypot(worn.y - s1002.y, worn.z - s1002.z)
    assert 0.0 < removed.max() <= fleet.WHEEL_TREAD_DEPTH[1] + fleet.WHEEL_FLANGE_THICKNESS[1]


def test_fleet_on_a_local_cluster_equals_the_serial_run(example):
    serial = fleet.run(example / "wheels", example / "rails", serial=True)
    cluster = fleet.run(example / "wheels", example / "rails", workers=2, chunk=1)
    for a, b in zip(serial, cluster):
        pd.testing.assert_frame_equal(a, b, check_exact=True)
    summary, cmap = serial
    assert len(summary) == 7 * 2
    broken = summary["wheel"] == "wheel_zz_broken.txt"
    assert broken.sum() == 2 and summary["error"][broken].str.contains("wheel_zz_broken.txt").all()
    assert (summary["error"][~broken] == "").all()
    assert summary.loc[~broken, "conicity_1mm":"conicity_6mm"].notna().all().all()
    assert len(cmap) == 12 * 29  # 12 good pairs, shifts −7…+7 mm every 0.5 mm


def test_fleet_row_equals_the_package_calls(example):
    """One pair's row is what conicity() and solve_batch() give for its case."""
    study = fleet.Study(load=70e3)
    wheel, rail = example / "wheels/wheel_0003.txt", example / "rails/rail_01.txt"
    row, cmap = fleet.evaluate_pair(str(wheel), str(rail), study)
    case = study.pair_case(str(wheel), str(rail))
    con = railcontact.conicity(case)
    assert [row[c] for c in study.conicity_columns()] == list(con["conicity"]["harmonic"])
    out = railcontact.solve_batch(case, {"y": np.array(study.shifts)}, independent=True)
    pmax = [out[f"{s}.p{k}.pmax"] for s in fleet.SIDES for k in fleet.SLOTS]
    assert row["pmax"] == np.max(pmax)
    i = list(con["deltaR"]["y"]).index(cmap["y"][5])
    assert cmap["yRailRight"][5] == con["deltaR"]["yRailRight"][i]


def test_fleet_command_writes_parquet_and_csv(tmp_path, example):
    exe = Path(sys.executable).with_name("railcontact-fleet")
    for suffix in (".parquet", ".csv"):
        out = tmp_path / f"table{suffix}"
        run = subprocess.run(
            [str(exe), "--wheels", str(example / "wheels"), "--rails", str(example / "rails"),
             "--out", str(out), "--serial", "--load", "70000", "--no-progress"],
            capture_output=True, text=True,
        )
        assert run.returncode == 0, run.stderr
        read = pd.read_parquet if suffix == ".parquet" else pd.read_csv
        table = read(out)
        assert len(table) == 14 and len(read(tmp_path / f"table.map{suffix}")) == 12 * 29
    summary, _ = fleet.run(example / "wheels", example / "rails", fleet.Study(load=70e3), serial=True)
    table = pd.read_parquet(tmp_path / "table.parquet")
    pd.testing.assert_frame_equal(table, summary, check_exact=True)
    bad = subprocess.run([str(exe), "--wheels", str(example / "wheels"), "--rails",
                          str(tmp_path / "none"), "--out", str(tmp_path / "x.csv"), "--serial"],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and "not a directory of profiles" in bad.stderr
    bad = subprocess.run([str(exe), "--wheels", str(example / "wheels"), "--rails",
                          str(example / "rails"), "--out", str(tmp_path / "x.xlsx"), "--serial",
                          "--no-progress"], capture_output=True, text=True)
    assert bad.returncode == 1 and ".parquet or .csv" in bad.stderr


def test_fleet_refuses_a_bad_study_before_it_starts(example):
    with pytest.raises(railcontact.RailcontactError, match="noSuchKey"):
        fleet.run(example / "wheels", example / "rails", fleet.Study(case={"noSuchKey": 1}), serial=True)
    with pytest.raises(railcontact.RailcontactError, match="amplitude"):
        fleet.run(example / "wheels", example / "rails", fleet.Study(amplitudes=(0.05,)), serial=True)
