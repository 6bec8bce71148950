"""The wear-prediction loop's short form (examples/wear_loop.py): closed-loop runs of the example
wheelset write wear records, ``railcontact wear`` turns them into worn profiles, and the next
runs use them — without a Discard, with profiles that pass the element's checks, an update
limited to its largest depth, and a conicity for every iteration."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def loop(tmp_path_factory, wrc_fmu_path: Path):
    out = tmp_path_factory.mktemp("wear_loop")
    env = dict(os.environ, RAILCONTACT_FMU_DIR=str(wrc_fmu_path.parent))
    subprocess.run(
        [sys.executable, str(REPO / "examples" / "wear_loop.py"), "--iterations", "2", "--out", str(out)],
        cwd=REPO,
        env=env,
        check=True,
        timeout=900,
    )
    return out, json.loads((out / "wear_loop.json").read_text())


def test_every_iteration_runs_and_updates_within_its_depth(loop):
    out, result = loop
    history = result["history"]
    assert len(history) == 3
    distances = [h["distance"] for h in history]
    assert distances[0] == 0.0 and distances[1] > 0.0 and distances[2] > distances[1]
    for h in history[:-1]:
        update = h["update"]
        depth = max(update["wheelDepthMax"], update["railDepthMax"])
        assert 0.0 < depth <= 1e-4 * (1 + 1e-9)
        assert Path(update["wheelProfile"]).is_file() and Path(update["railProfile"]).is_file()
    for h in history:
        assert 0.0 < h["conicity"] < 1.0
    assert (out / "wear_loop_conicity.svg").is_file()
    assert (out / "wear_loop_wheel.svg").is_file()
