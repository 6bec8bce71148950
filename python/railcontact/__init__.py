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
from typing import Any, Mapping

import numpy as np

from ._native import DiscardError, RailcontactError
from . import _native

__all__ = [
    "solve",
    "Wheelset",
    "solve_batch",
    "real_outputs",
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
    out, status = _native.solve_batch(_case_text(case), names, columns, independent)
    result = {name: np.frombuffer(data, dtype=np.float64) for name, data in out}
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
