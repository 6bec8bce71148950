"""The wear-prediction loop end to end: closed-loop runs, wear records, profile updates, again.

Each iteration runs the suspended wheelset of ``examples/wheelset_hunting.py`` in closed loop with
the WheelRailContact FMU (ANALYN, FASTSIM, the USFD wear function: ``wearModel`` = 1) for a set of
cases — speeds and initial lateral disturbances, each a share of the traffic — each run writing
its wear record at ``fmi2Terminate`` (``wearOutput``). ``railcontact wear`` then sums the records,
scales them to the iteration's running distance (limited to 0.1 mm of depth per update), smooths
and removes them from the profiles; the next iteration runs on the worn wheel and rail. After
every update the equivalent conicity (EN 15302, ``railcontact conicity``) of the worn pair is
computed. Figures: the wheel's profile change and λ(3 mm) against the distance run.

The runs are short (the wheelset oscillates a few times after its disturbance, then runs
centred), so each update stands for a running distance far beyond what was simulated: what
matters is where the wear goes across the profiles, and each update is limited in depth as wear
loops are (docs/theory.md §10.6).

Run: ``.venv/bin/python examples/wear_loop.py [--iterations N] [--out DIR]`` after
``cargo run --release -p fmu-pack`` (the FMU as for wheelset_hunting.py; the command from
$RAILCONTACT_CLI, else ``cargo run --release -p railcontact-cli``). Without ``--full`` the short
form CI runs through tests/python/test_wear_loop.py (two iterations, about half a minute).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from wheelset_hunting import REPO_ROOT, Host, Wheelset, simulate, svg_plot  # noqa: E402

#: (speed [m/s], initial lateral disturbance [m], duration [s]) of the runs of one iteration.
CASES_SHORT = [(20.0, 3e-3, 0.6), (30.0, 1e-3, 0.6)]
CASES_FULL = [(10.0, 3e-3, 2.0), (20.0, 3e-3, 2.0), (30.0, 2e-3, 2.0), (40.0, 1e-3, 2.0)]
#: Running distance one update stands for [m] (limited to MAX_DEPTH of wear).
DISTANCE = 2e6
MAX_DEPTH = 1e-4
#: Communication step of the runs [s].
STEP = 5e-4
#: Normal model of the runs (ANALYN).
NORMAL_MODEL = 6


def command() -> list[str]:
    exe = os.environ.get("RAILCONTACT_CLI")
    return [exe] if exe else ["cargo", "run", "--quiet", "--release", "-p", "railcontact-cli", "--"]


def cli(*args: str) -> dict:
    text = subprocess.run(
        command() + list(args), cwd=REPO_ROOT, check=True, capture_output=True, text=True
    ).stdout
    return json.loads(text)


def wheel_depths(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The wheel's bins [m] and the depth an update removed there [m] (its depth.csv)."""
    rows = [line.split(",") for line in path.read_text().splitlines()]
    rows = [r for r in rows if r[0] == "wheel"]
    return np.array([float(r[1]) for r in rows]), np.array([float(r[2]) for r in rows])


def loop(iterations: int, cases: list[tuple[float, float, float]], out: Path) -> dict:
    host = Host()
    ws = Wheelset()
    profiles = {"wheelProfile": "S1002", "railProfile": "UIC60"}
    inclination = {}  # the FMU's default 1:40 until the rail is a worn (mounted) one
    history = []
    distance = 0.0
    try:
        for it in range(iterations + 1):
            case = out / f"case_{it}.json"
            case.write_text(json.dumps({**profiles, **inclination, "normalModel": NORMAL_MODEL}))
            cone = cli("conicity", str(case), "--amplitudes", "0.003")
            entry = {
                "iteration": it,
                "distance": distance,
                "conicity": cone["conicity"][0]["harmonic"],
                "wheelProfile": profiles["wheelProfile"],
            }
            history.append(entry)
            print(f"iteration {it}: {distance:.4g} m, λ(3 mm) = {entry['conicity']:.4f}", flush=True)
            if it == iterations:
                break
            records = []
            for k, (speed, y0, duration) in enumerate(cases):
                record = out / f"wear_{it}_{k}.csv"
                contact = host.contact(
                    NORMAL_MODEL, wearModel=1, wearOutput=str(record), **profiles, **inclination
                )
                run = simulate(contact, ws, speed, STEP, duration, y0)
                contact.close()
                if run.t[-1] < duration - 2 * STEP:
                    raise RuntimeError(f"iteration {it}, case {k}: the run stopped at {run.t[-1]} s")
                records += ["--record", str(record)]
            worn = out / f"worn_{it + 1}"
            update = cli(
                "wear", str(case), *records, "--distance", str(DISTANCE),
                "--max-depth", str(MAX_DEPTH), "--out", str(worn),
            )
            entry["update"] = update
            distance += update["distance"]
            profiles = {"wheelProfile": update["wheelProfile"], "railProfile": update["railProfile"]}
            inclination = {"railInclination": 0.0}
    finally:
        host.close()
    return {"history": history}


def figures(result: dict, out: Path) -> None:
    history = result["history"]
    dist = np.array([h["distance"] for h in history]) / 1e3
    lam = np.array([h["conicity"] for h in history])
    svg_plot(
        out / "wear_loop_conicity.svg",
        [("λ(3 mm)", "#1f77b4", dist, lam)],
        "Equivalent conicity of the worn pair", "distance run [km]", "λ [-]",
    )
    # The wheel's depth worn since the start, after each update (the updates' depth tables).
    series, total = [], None
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"]
    for i, h in enumerate(h for h in history if "update" in h):
        y, depth = wheel_depths(Path(h["update"]["depths"]))
        total = depth if total is None else total + depth
        series.append((f"update {i + 1}", colours[i % len(colours)], y * 1e3, total * 1e6))
    if series:
        svg_plot(
            out / "wear_loop_wheel.svg", series,
            "Wheel depth worn since the start, after each update", "y [mm]", "depth [µm]",
        )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--iterations", type=int, default=2)
    parser.add_argument("--full", action="store_true", help="the longer runs and four cases")
    parser.add_argument("--out", type=Path, help="directory of the records, profiles and figures")
    args = parser.parse_args()
    out = args.out or Path(tempfile.mkdtemp(prefix="railcontact-wear-"))
    out.mkdir(parents=True, exist_ok=True)
    result = loop(args.iterations, CASES_FULL if args.full else CASES_SHORT, out)
    figures(result, out)
    (out / "wear_loop.json").write_text(json.dumps(result, indent=2))
    print(f"records, profiles, figures and wear_loop.json in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
