"""Fleet studies: every wheel profile of a folder against every rail profile of another, on Dask.

For each (wheel, rail) pair, on the case's track and load (``docs/python.md``):

* the **equivalent conicity** λ(A) of EN 15302 (harmonic linearisation of the rigid wheelset's
  rolling-radius difference, the wheelset rolling to rest on both rails) at the amplitudes
  (1–6 mm unless told);
* the **contact-point map**: the rigid contact points over the lateral shift of the wheelset
  (on the wheel and on the rail profile, contact angles, rolling radii, Δr);
* the **largest contact pressure** and the largest **fatigue index** (``s.pk.fatigueIndex``:
  traction coefficient − k/pmax) of the loaded element over the lateral shifts, with the shift
  and side where they occur.

The pairs are independent tasks: run serially in this process, on a local Dask cluster of worker
processes (no set-up), or on any Dask cluster through its scheduler's address — the same code and
the same table each way. On a cluster, the profile folders must be readable by the workers at the
same paths.

Synthetic worn profiles (``make_example``) are built from the built-in S1002 wheel and UIC60 rail
by the wear shapes ``docs/python.md`` documents, reproducibly from a seed.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass, field
from os import PathLike
from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from . import DiscardError, Profile, RailcontactError, conicity, read_profile, solve_batch
from . import _native

__all__ = ["Study", "pairs", "check", "evaluate_pair", "run", "write", "make_example", "main"]

#: The sides of the wheelset, as the output names spell them.
SIDES = ("right", "left")
#: Patch slots per wheel in the outputs.
SLOTS = (1, 2, 3)


@dataclass(frozen=True)
class Study:
    """What a fleet study computes for each pair.

    ``case``: the base case (parameters and inputs by name, as ``railcontact.solve`` takes them:
    track, models, friction, ...); the pair's profiles replace ``wheelProfile``/``railProfile``.
    ``load``: the vertical load per wheel [N] (``Qleft``, ``Qright``); ``None`` keeps the case's.
    ``amplitudes``: the conicity's amplitudes [m]. ``shifts``: the lateral shifts [m] at which
    the loaded element is solved for pressure and fatigue. ``map_step``: spacing of the
    contact-point map's rows [m] (a multiple of the conicity's 0.05 mm Δr step)."""

    case: Mapping[str, Any] = field(default_factory=dict)
    load: float | None = None
    amplitudes: Sequence[float] = tuple(_native.CONICITY_AMPLITUDES)
    shifts: Sequence[float] = tuple(np.round(np.arange(-12, 13) * 5e-4, 10))
    map_step: float = 5e-4

    def pair_case(self, wheel: str, rail: str) -> dict[str, Any]:
        """The case of one pair."""
        case = dict(self.case)
        case["wheelProfile"] = wheel
        case["railProfile"] = rail
        if self.load is not None:
            case["Qleft"] = case["Qright"] = float(self.load)
        return case

    def conicity_columns(self) -> list[str]:
        return [f"conicity_{a * 1e3:g}mm" for a in self.amplitudes]


#: The contact-point map's columns, as the conicity's Δr table names them.
MAP_COLUMNS = (
    "deltaR",
    "roll",
    "yWheelRight",
    "yRailRight",
    "contactAngleRight",
    "rRight",
    "yWheelLeft",
    "yRailLeft",
    "contactAngleLeft",
    "rLeft",
)


def profile_files(directory: str | PathLike) -> list[Path]:
    """The profile files of ``directory``: its regular files not starting with ``.``, by name."""
    d = Path(directory)
    if not d.is_dir():
        raise RailcontactError(f"{d}: not a directory of profiles")
    files = sorted(p for p in d.iterdir() if p.is_file() and not p.name.startswith("."))
    if not files:
        raise RailcontactError(f"{d}: holds no profile files")
    return files


def pairs(wheels: str | PathLike, rails: str | PathLike) -> list[tuple[str, str]]:
    """Every (wheel file, rail file) of the two folders, wheels first, each by name."""
    return [(str(w), str(r)) for w in profile_files(wheels) for r in profile_files(rails)]


def evaluate_pair(wheel: str, rail: str, study: Study) -> tuple[dict[str, Any], dict[str, list]]:
    """One pair: its summary row and its contact-point map (columns). A profile the element
    refuses, or a pair without contact, gives a row with the message in ``error`` (and NaN)."""
    row: dict[str, Any] = {"wheel": Path(wheel).name, "rail": Path(rail).name, "error": ""}
    for name in study.conicity_columns():
        row[name] = math.nan
    row.update(
        pmax=math.nan, pmax_y=math.nan, pmax_side="", fatigueIndex=math.nan,
        fatigueIndex_y=math.nan, fatigueIndex_side="", refused=0,
    )
    empty: dict[str, list] = {"wheel": [], "rail": [], "y": [], **{c: [] for c in MAP_COLUMNS}}
    case = study.pair_case(wheel, rail)
    try:
        # The case's profiles are read and checked as the element reads them: a refused file
        # raises here with its message.
        con = conicity(case, amplitudes=study.amplitudes)
        loaded = solve_batch(case, {"y": np.asarray(study.shifts, dtype=np.float64)}, independent=True)
    except (RailcontactError, DiscardError) as e:
        row["error"] = str(e)
        return row, empty
    for name, lam in zip(study.conicity_columns(), con["conicity"]["harmonic"]):
        row[name] = float(lam)
    table = con["deltaR"]
    on_grid = np.abs(table["y"] / study.map_step - np.round(table["y"] / study.map_step)) < 1e-6
    rows = int(on_grid.sum())
    cmap = {"wheel": [row["wheel"]] * rows, "rail": [row["rail"]] * rows, "y": table["y"][on_grid].tolist()}
    for c in MAP_COLUMNS:
        cmap[c] = table[c][on_grid].tolist()
    shifts = np.asarray(study.shifts, dtype=np.float64)
    row["refused"] = int(np.sum(loaded["status"] == 2))
    for quantity in ("pmax", "fatigueIndex"):
        best = (-math.inf, math.nan, "")
        for side in SIDES:
            for k in SLOTS:
                values = loaded[f"{side}.p{k}.{quantity}"]
                fn = loaded[f"{side}.p{k}.Fn"]
                loaded_slot = np.where(fn > 0, values, -np.inf)
                i = int(np.argmax(loaded_slot))
                if loaded_slot[i] > best[0]:
                    best = (float(loaded_slot[i]), float(shifts[i]), side)
        if math.isfinite(best[0]):
            row[quantity], row[f"{quantity}_y"], row[f"{quantity}_side"] = best
    return row, cmap


def check(study: Study) -> None:
    """Raises ``RailcontactError`` for a study that no pair could run (a bad case key or value,
    an amplitude or shift out of range): the study on the built-in S1002/UIC60 pair."""
    case = study.pair_case("S1002", "UIC60")
    conicity(case, amplitudes=study.amplitudes)
    solve_batch(case, {"y": np.asarray(study.shifts, dtype=np.float64)}, independent=True)


def _evaluate_chunk(chunk: list[tuple[str, str]], study: Study) -> list[tuple[dict, dict]]:
    return [evaluate_pair(w, r, study) for w, r in chunk]


def _chunks(items: list, size: int) -> list[list]:
    return [items[i : i + size] for i in range(0, len(items), size)]


def _progress(total: int, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, unit="pair", disable=not enabled, file=sys.stderr)


def run(
    wheels: str | PathLike,
    rails: str | PathLike,
    study: Study | None = None,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    client: Any = None,
    serial: bool = False,
    chunk: int = 4,
    progress: bool = False,
):
    """The study over every pair of the two folders: ``(summary, contact_map)`` as pandas
    DataFrames — one summary row per pair (wheels in name order, then rails), the map's rows per
    pair and shift.

    Where it runs: ``serial`` in this process (no Dask); else on the Dask ``client`` given, or
    on the cluster whose scheduler is at ``scheduler`` (``"tcp://host:8786"``), or on a local
    cluster of ``workers`` worker processes (default: one per CPU) started for the run and closed
    after it. ``chunk`` pairs make one task. The table is the same every way."""
    import pandas as pd

    study = study or Study()
    todo = pairs(wheels, rails)
    check(study)
    if chunk < 1:
        raise RailcontactError(f"chunk = {chunk}: needs at least 1 pair per task")
    groups = _chunks(todo, chunk)
    results: list[list[tuple[dict, dict]]] = [[] for _ in groups]
    with _progress(len(todo), progress) as bar:
        if serial:
            for i, g in enumerate(groups):
                results[i] = _evaluate_chunk(g, study)
                bar.update(len(g))
        else:
            with _client(client, scheduler, workers) as c:
                from distributed import as_completed

                futures = c.map(_evaluate_chunk, groups, study=study, pure=False)
                index = {f.key: i for i, f in enumerate(futures)}
                for future in as_completed(futures):
                    i = index[future.key]
                    results[i] = future.result()
                    bar.update(len(groups[i]))
    flat = [pair for group in results for pair in group]
    summary = pd.DataFrame([row for row, _ in flat])
    columns: dict[str, list] = {}
    for _, cmap in flat:
        for name, values in cmap.items():
            columns.setdefault(name, []).extend(values)
    return summary, pd.DataFrame(columns)


class _client:
    """The Dask client of a run: the one given (left open), or one connected to ``scheduler``,
    or a local cluster of ``workers`` processes (both closed after the run)."""

    def __init__(self, client: Any, scheduler: str | None, workers: int | None):
        self.given, self.scheduler, self.workers = client, scheduler, workers
        self.own: list = []

    def __enter__(self):
        if self.given is not None:
            return self.given
        from distributed import Client, LocalCluster

        if self.scheduler is not None:
            c = Client(self.scheduler)
        else:
            if self.workers is not None and self.workers < 1:
                raise RailcontactError(f"workers = {self.workers}: needs at least 1")
            cluster = LocalCluster(
                n_workers=self.workers, threads_per_worker=1, processes=True,
                dashboard_address=None,
            )
            self.own.append(cluster)
            c = Client(cluster)
        self.own.insert(0, c)
        return c

    def __exit__(self, *exc):
        for thing in self.own:
            thing.close()
        return False


def table_paths(out: str | PathLike) -> tuple[Path, Path]:
    """The summary's and the contact-point map's files for ``out`` (``.parquet`` or ``.csv``)."""
    out = Path(out)
    if out.suffix.lower() not in (".parquet", ".csv"):
        raise RailcontactError(f"--out {out}: needs a .parquet or .csv file name")
    return out, out.with_name(f"{out.stem}.map{out.suffix}")


def write(summary, contact_map, out: str | PathLike) -> tuple[Path, Path]:
    """Writes the summary to ``out`` (``.parquet`` or ``.csv``) and the contact-point map next to
    it (``<stem>.map.parquet`` / ``.csv``); returns both paths."""
    out, map_path = table_paths(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    for frame, path in ((summary, out), (contact_map, map_path)):
        if out.suffix.lower() == ".parquet":
            frame.to_parquet(path, index=False)
        else:
            frame.to_csv(path, index=False)
    return out, map_path


# ---------------------------------------------------------------------------------------------
# Synthetic worn profiles

#: Ranges of the synthetic wear shapes [m] (docs/python.md).
WHEEL_TREAD_DEPTH = (0.0, 3e-3)
WHEEL_TREAD_CENTRE = (0.0, 10e-3)
WHEEL_TREAD_HALF_WIDTH = (25e-3, 45e-3)
WHEEL_FLANGE_THICKNESS = (0.0, 1.5e-3)
WHEEL_FLANGE_CENTRE = -37e-3
WHEEL_FLANGE_HALF_WIDTH = 10e-3
RAIL_TOP_DEPTH = (0.0, 2e-3)
RAIL_TOP_HALF_WIDTH = 30e-3
RAIL_GAUGE_THICKNESS = (0.0, 2e-3)
RAIL_GAUGE_CENTRE = -32e-3
RAIL_GAUGE_HALF_WIDTH = 8e-3


def bump(y: np.ndarray, centre: float, half_width: float) -> np.ndarray:
    """cos²(π(y − centre)/(2·half_width)) within half_width of the centre, 0 outside: a smooth
    wear shape of unit depth."""
    u = (y - centre) / half_width
    return np.where(np.abs(u) < 1.0, np.cos(0.5 * np.pi * u) ** 2, 0.0)


def worn_wheel(tread_depth: float, tread_centre: float, tread_half_width: float,
               flange_thickness: float) -> Profile:
    """S1002 with hollow tread wear (depth ``tread_depth`` [m] of a cos² bump across
    ``tread_half_width`` either side of ``tread_centre``, in the wheel profile frame) and flange
    wear (``flange_thickness`` [m] removed normal to the flange's face, a cos² bump about
    y = −37 mm, ±10 mm)."""
    s1002 = read_profile("S1002", "wheel")
    y = s1002.y
    slope = s1002.eval(y)[1]
    depth = tread_depth * bump(y, tread_centre, tread_half_width) + flange_thickness * np.sqrt(
        1.0 + slope**2
    ) * bump(y, WHEEL_FLANGE_CENTRE, WHEEL_FLANGE_HALF_WIDTH)
    return s1002.worn(y, depth, name="worn S1002")


def worn_rail(top_depth: float, gauge_thickness: float) -> Profile:
    """UIC60 (60E1) with top wear (``top_depth`` [m], a cos² bump ±30 mm about the crown) and
    gauge-face wear (``gauge_thickness`` [m] removed normal to the face, a cos² bump about
    y = −32 mm, ±8 mm, in the un-inclined rail frame)."""
    uic60 = read_profile("UIC60", "rail")
    y = uic60.y
    slope = uic60.eval(y)[1]
    depth = top_depth * bump(y, 0.0, RAIL_TOP_HALF_WIDTH) + gauge_thickness * np.sqrt(
        1.0 + slope**2
    ) * bump(y, RAIL_GAUGE_CENTRE, RAIL_GAUGE_HALF_WIDTH)
    return uic60.worn(y, depth, name="worn UIC60")


def make_example(directory: str | PathLike, wheels: int = 200, rails: int = 2, seed: int = 0) -> tuple[Path, Path]:
    """Writes ``wheels`` synthetic worn S1002 wheels into ``directory``/wheels and ``rails``
    rails into ``directory``/rails (the first rail new, the others worn), wear drawn uniformly
    from the documented ranges by NumPy's generator with ``seed``: the same seed, the same
    files. Every file is read back and checked as the element reads it. Returns both folders."""
    rng = np.random.default_rng(seed)
    root = Path(directory)
    folders = (root / "wheels", root / "rails")
    for f in folders:
        f.mkdir(parents=True, exist_ok=True)
    uniform = lambda bounds: float(rng.uniform(*bounds))  # noqa: E731
    for i in range(wheels):
        shape = dict(
            tread_depth=uniform(WHEEL_TREAD_DEPTH),
            tread_centre=uniform(WHEEL_TREAD_CENTRE),
            tread_half_width=uniform(WHEEL_TREAD_HALF_WIDTH),
            flange_thickness=uniform(WHEEL_FLANGE_THICKNESS),
        )
        header = "synthetic worn S1002 (railcontact.fleet): " + ", ".join(
            f"{k} {v:.6g} m" for k, v in shape.items()
        )
        worn_wheel(**shape).write(folders[0] / f"wheel_{i:04d}.txt", header)
    for i in range(rails):
        shape = dict(top_depth=0.0, gauge_thickness=0.0) if i == 0 else dict(
            top_depth=uniform(RAIL_TOP_DEPTH), gauge_thickness=uniform(RAIL_GAUGE_THICKNESS)
        )
        header = "synthetic worn UIC60 (railcontact.fleet): " + ", ".join(
            f"{k} {v:.6g} m" for k, v in shape.items()
        )
        worn_rail(**shape).write(folders[1] / f"rail_{i:02d}.txt", header)
    return folders


# ---------------------------------------------------------------------------------------------
# The console command


def _floats(text: str) -> list[float]:
    try:
        return [float(t) for t in text.split(",") if t.strip()]
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers: {e}") from None


def main(argv: Iterable[str] | None = None) -> int:
    """``railcontact-fleet``: see ``--help``."""
    import json

    p = argparse.ArgumentParser(
        prog="railcontact-fleet",
        description="Equivalent conicity (EN 15302), contact-point map, largest contact pressure "
        "and fatigue index of every wheel profile against every rail profile, on Dask.",
        epilog="Writes OUT (one row per pair) and OUT's stem + '.map' + suffix (the contact-point "
        "map, one row per pair and shift). Exit codes: 0 done (pairs that failed carry their "
        "message in the 'error' column), 1 bad arguments or files.",
    )
    p.add_argument("--wheels", metavar="DIR", help="folder of wheel profiles (any format the element reads)")
    p.add_argument("--rails", metavar="DIR", help="folder of rail profiles")
    p.add_argument("--out", metavar="FILE", help="the table: FILE.parquet or FILE.csv")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N", help="local Dask cluster of N worker processes (default: one per CPU)")
    where.add_argument("--scheduler", metavar="ADDRESS", help="the Dask cluster's scheduler, e.g. tcp://host:8786")
    where.add_argument("--serial", action="store_true", help="no Dask: every pair in this process")
    p.add_argument("--case", metavar="CASE.json", help="base case: track, models, friction (default: the element's start values)")
    p.add_argument("--load", type=float, metavar="Q", help="vertical load per wheel [N] (default: the case's)")
    p.add_argument("--amplitudes", type=_floats, metavar="A,..", default=list(_native.CONICITY_AMPLITUDES), help="conicity amplitudes [m] (default 0.001,...,0.006)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--make-example", metavar="DIR", help="write synthetic worn profiles into DIR/wheels and DIR/rails and stop")
    p.add_argument("--count", type=int, default=200, metavar="N", help="--make-example: number of wheels (default 200)")
    p.add_argument("--seed", type=int, default=0, help="--make-example: the generator's seed (default 0)")
    a = p.parse_args(None if argv is None else list(argv))
    try:
        if a.make_example:
            w, r = make_example(a.make_example, wheels=a.count, seed=a.seed)
            print(f"wrote {a.count} wheels into {w} and 2 rails into {r}")
            return 0
        if not (a.wheels and a.rails and a.out):
            p.error("--wheels, --rails and --out are required (or --make-example DIR)")
        table_paths(a.out)
        case = {}
        if a.case:
            try:
                case = json.loads(Path(a.case).read_text())
            except (OSError, ValueError) as e:
                raise RailcontactError(f"--case {a.case}: cannot read: {e}") from None
            if not isinstance(case, dict):
                raise RailcontactError(f"--case {a.case}: needs a JSON object")
        if a.load is not None and not (a.load > 0 and math.isfinite(a.load)):
            raise RailcontactError(f"--load = {a.load}: needs a load > 0 [N]")
        study = Study(case=case, load=a.load, amplitudes=tuple(a.amplitudes))
        summary, cmap = run(
            a.wheels, a.rails, study, workers=a.workers, scheduler=a.scheduler,
            serial=a.serial, progress=not a.no_progress,
        )
        out, map_path = write(summary, cmap, a.out)
    except RailcontactError as e:
        print(f"railcontact-fleet: {e}", file=sys.stderr)
        return 1
    failed = int((summary["error"] != "").sum())
    print(f"{len(summary)} pairs ({failed} failed) -> {out}, {map_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
