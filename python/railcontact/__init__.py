"""railcontact for Python: the wheel-rail contact element of the railcontact FMUs, called directly.

One evaluation, as the ``railcontact solve`` command prints it::

    import railcontact
    out = railcontact.solve({"y": 0.003, "normalModel": 6})
    print(out["right.p1.Fn"], out["strips"]["right.p1"]["pmax"])

A case is what a case file holds: parameters and inputs of the ``WheelRailContact`` FMU by name,
in SI units (``docs/python.md``). Every evaluation goes through the FMU's own model, so the
numbers are the command's and the FMU's, bit for bit. Bad input raises ``RailcontactError`` with
the command's message; a state the element refuses (no contact, a load the normal model cannot
carry) raises ``DiscardError``; an implausible contact state warns (``ImplausibleContactWarning``).
"""

from __future__ import annotations

import json
import warnings
from os import PathLike
from typing import Any, Mapping, Sequence

import numpy as np

from ._native import DiscardError, RailcontactError
from . import _native

__all__ = [
    "solve",
    "Wheelset",
    "solve_batch",
    "real_outputs",
    "conicity",
    "Profile",
    "read_profile",
    "wear_update",
    "RailcontactError",
    "DiscardError",
    "ImplausibleContactWarning",
]


class ImplausibleContactWarning(UserWarning):
    """The outputs describe a physically implausible contact state (the command's exit code 3)."""


def _case_text(case: Mapping[str, Any] | None) -> str:
    if case is None:
        return "{}"
    if not isinstance(case, Mapping):
        raise RailcontactError(f"case: needs a dict of parameter and input names, got {type(case).__name__}")
    return json.dumps(dict(case), allow_nan=True)


def _columns(rows: list) -> dict[str, np.ndarray] | np.ndarray:
    """Strips (records) as one NumPy array per field; grid points and traction elements (rows of
    numbers, the command's column order) as one 2-D array."""
    if rows and isinstance(rows[0], dict):
        return {key: np.array([r[key] for r in rows]) for key in rows[0]}
    return np.array(rows, dtype=np.float64)


def solve(
    case: Mapping[str, Any] | None = None, *, grid: int | None = None, traction: bool = False
) -> dict[str, Any]:
    """Evaluates ``case`` as ``railcontact solve`` does: every output by name, then ``"strips"``:
    per patch in contact ("left.p1", …) its strips across the rolling direction as NumPy arrays
    by field; with ``grid`` (points per strip) ``"grid"``, with ``traction`` ``"traction"``
    (the tangential solution's elements): per patch a 2-D array, one row per point or element
    in the command's columns (``docs/python.md``)."""
    text, warning = _native.solve_json(_case_text(case), grid, traction)
    doc = json.loads(text)
    for key in ("strips", "grid", "traction"):
        if key in doc:
            doc[key] = {patch: _columns(rows) for patch, rows in doc[key].items()}
    if warning is not None:
        warnings.warn(warning, ImplausibleContactWarning, stacklevel=2)
    return doc


def real_outputs() -> list[str]:
    """The names of the Real outputs, in the variable table's order."""
    return list(_native.real_outputs())


def solve_batch(
    case: Mapping[str, Any] | None, inputs: Mapping[str, Any], *, independent: bool = False
) -> dict[str, np.ndarray]:
    """Many evaluations of ``case`` in one call: row k sets each of ``inputs`` (Real input names
    → equally long 1-D arrays; parameters go in ``case``) to its k-th value and evaluates, the
    profiles loaded once. Each row starts from the state the last left, as the FMU's steps do
    (what a ``Wheelset`` gives row by row, bit for bit); with ``independent`` each starts afresh
    (what ``solve`` gives for that case, bit for bit). Returns every Real output as an array,
    and ``"status"``: 0 ok, 1 implausible state, 2 refused (its outputs NaN). Releases the GIL."""
    names = list(inputs)
    columns = []
    for name in names:
        column = np.ascontiguousarray(np.asarray(inputs[name], dtype=np.float64))
        if column.ndim != 1:
            raise RailcontactError(f"'{name}': needs a 1-D array, got shape {column.shape}")
        columns.append(column.tobytes())
    out_names, data, status = _native.solve_batch(_case_text(case), names, columns, independent)
    # One row-major matrix; each output a column view of it (no copy).
    matrix = np.frombuffer(data, dtype=np.float64).reshape(-1, len(out_names))
    result = {name: matrix[:, j] for j, name in enumerate(out_names)}
    result["status"] = np.frombuffer(status, dtype=np.int32)
    return result


class Wheelset:
    """The case's wheelset for loops: built once (profiles loaded), then ``solve(**inputs)``
    sets Real inputs and evaluates from the state the last call left, as the FMU's steps do::

        ws = railcontact.Wheelset({"normalModel": 6})
        for y in np.linspace(0, 0.005, 50):
            print(ws.solve(y=y)["right.p1.Fn"])
    """

    def __init__(self, case: Mapping[str, Any] | None = None):
        self._native = _native.Wheelset(_case_text(case))
        self._names = real_outputs()

    def solve(self, **inputs: float) -> dict[str, float]:
        """Every Real output by name; warns on an implausible state, raises ``DiscardError``
        on a refused one."""
        values, status = self._native.solve(list(inputs), [float(v) for v in inputs.values()])
        if status == 1:
            warnings.warn("implausible contact state", ImplausibleContactWarning, stacklevel=2)
        return dict(zip(self._names, values))


def conicity(
    case: Mapping[str, Any] | None = None,
    *,
    amplitudes: Sequence[float] = tuple(_native.CONICITY_AMPLITUDES),
    step: float = _native.CONICITY_STEP,
    roll: bool = True,
    load: float | None = None,
) -> dict[str, Any]:
    """The equivalent conicity (EN 15302) of the case's profiles on its track, as
    ``railcontact conicity`` prints it: ``"conicity"`` (per amplitude [m]: λ by harmonic
    linearisation and by Klingel integration, the wavelength [m]) and ``"deltaR"`` (per lateral
    shift ``y`` [m] of the rigid wheelset: Δr, roll, rolling radii, the contact points on the rails
    ``yRailRight``/``yRailLeft`` and the contact angles), each as NumPy arrays by field, and the
    set-up (``r0``, ``e0``, profiles, track). ``roll``: the wheelset rolls to rest on both rails;
    ``load``: the loaded element's rolling radii under this load per wheel [N] instead of the
    rigid contact's."""
    text = _native.conicity_json(
        _case_text(case), [float(a) for a in amplitudes], float(step), bool(roll), load
    )
    doc = json.loads(text)
    for key in ("conicity", "deltaR"):
        doc[key] = _columns(doc[key])
    return doc


class Profile:
    """A wheel or rail profile z(y) in its profile frame (metres; ``docs/conventions.md``): y
    lateral towards the field side, z downwards (wheel: radius increase over the taping line;
    rail: depth below the head's top). Read with ``read_profile`` or built with
    ``Profile.from_points``."""

    def __init__(self, native: Any):
        self._native = native

    @classmethod
    def from_points(
        cls, name: str, kind: str, y: Any, z: Any, smoothing: float = 0.0
    ) -> "Profile":
        """A profile through the points ``y``, ``z`` [m] (not checked: see ``check``)."""
        y = np.asarray(y, dtype=np.float64).tolist()
        z = np.asarray(z, dtype=np.float64).tolist()
        return cls(_native.Profile.from_points(name, kind, y, z, float(smoothing)))

    @property
    def name(self) -> str:
        return self._native.name

    @property
    def kind(self) -> str:
        """``"wheel"`` or ``"rail"``."""
        return self._native.kind

    @property
    def smoothing(self) -> float:
        """The smoothing length of the fitted spline [m] (0: interpolating)."""
        return self._native.smoothing

    @property
    def y(self) -> np.ndarray:
        """The points' lateral coordinates [m], ascending."""
        return np.array(self._native.points()[0])

    @property
    def z(self) -> np.ndarray:
        """The points' vertical coordinates [m]."""
        return np.array(self._native.points()[1])

    def eval(self, y: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The fitted spline at ``y`` [m]: z [m], dz/dy and d²z/dy² [1/m]."""
        out = self._native.eval(np.atleast_1d(np.asarray(y, dtype=np.float64)).tolist())
        return tuple(np.array(v) for v in out)

    def check(self) -> None:
        """The element's plausibility checks of profile files (units, wheel orientation,
        coverage of the running surface, gaps, steps, spikes); raises ``RailcontactError``."""
        self._native.check()

    def worn(self, y: Any, depth: Any, name: str | None = None) -> "Profile":
        """This profile worn by ``depth`` [m] given at the lateral positions ``y`` [m]
        (ascending; linear in between, 0 outside), applied along the surface normal as the wear
        loop's update applies it (``docs/theory.md`` §10.6). Not checked."""
        y = np.asarray(y, dtype=np.float64).tolist()
        depth = np.asarray(depth, dtype=np.float64).tolist()
        return Profile(self._native.worn(y, depth, name))

    def write(self, path: str | PathLike, header: str | None = None) -> None:
        """Writes the points as two-column text in mm (``header``: comment lines), a file the
        element reads as ``wheelProfile``/``railProfile``; the file is read back and checked as
        the element would, raising ``RailcontactError`` if it would be refused."""
        self._native.write(str(path), header)

    def __repr__(self) -> str:
        return repr(self._native)


def read_profile(spec: str | PathLike, kind: str, smoothing: float = 0.0) -> Profile:
    """A built-in profile (``"S1002"``, ``"UIC60"``, ``"60E1"``) or a profile file in any format
    the element reads (``.prw``, ``.prr``, ``.ban``, two-column text in mm), as the parameters
    ``wheelProfile``/``railProfile`` take it; ``kind`` is ``"wheel"`` or ``"rail"``. Files are
    checked (``Profile.check``); a file the element would refuse raises ``RailcontactError`` with
    its message."""
    return Profile(_native.Profile.load(str(spec), kind, float(smoothing)))


def wear_update(
    case: Mapping[str, Any] | None,
    records: Sequence[str | PathLike],
    *,
    distance: float,
    out: str | PathLike,
    max_depth: float = _native.WEAR_MAX_DEPTH,
    smoothing: float = _native.WEAR_SMOOTHING,
) -> dict[str, Any]:
    """The wear loop's profile update, as ``railcontact wear`` does it: the wear records
    (``wearOutput`` files of runs of ``case``) scaled to ``distance`` [m] of running (reduced so
    that no more than ``max_depth`` [m] is removed), smoothed (Gaussian of standard deviation
    ``smoothing`` [m]) and taken off the case's profiles; the worn wheel and rail are written
    into ``out`` and checked. Returns the command's JSON summary (paths of the worn profiles,
    depths, the distance used)."""
    text = _native.wear_update_json(
        _case_text(case),
        [str(r) for r in records],
        float(distance),
        float(max_depth),
        float(smoothing),
        str(out),
    )
    return json.loads(text)
