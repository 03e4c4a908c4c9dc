"""CSV tables with a JSON metadata sidecar.

A table is written as two files, both atomically (:func:`dhfield.io.atomic_path`):

* ``path`` -- plain CSV: one header row of variable names, then one row per
  record, numbers written with ``repr`` (round trip exact).  It opens with
  ``pandas.read_csv(path)`` and no arguments: no comment lines, no units in the
  header.
* ``path + ".json"`` -- the metadata: ``columns`` (name -> ``units``,
  ``long_name``, ... from :mod:`dhfield.core.schema`) and ``attributes`` (the
  provenance of :func:`dhfield.io.provenance_attrs`: source, references, input
  parameters).

If either write fails, neither file is replaced.
"""
from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from . import atomic_path, provenance_attrs
from .cf import variable_attrs

__all__ = ["write_table", "read_table", "sidecar_path"]


def sidecar_path(path) -> Path:
    """The JSON metadata file of the CSV ``path``: ``path + ".json"``.

    Parameters
    ----------
    path : path-like
        The CSV file.

    Returns
    -------
    pathlib.Path
        The sidecar's path.

    Examples
    --------
    >>> from dhfield.io.table import sidecar_path
    >>> sidecar_path("out/curve.csv").as_posix()
    'out/curve.csv.json'
    """
    p = Path(path)
    return p.with_name(p.name + ".json")


def _jsonable(value):
    if isinstance(value, np.ndarray):
        return [_jsonable(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    return value


def _cell(x) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "true" if x else "false"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        return repr(float(x))  # 'nan', 'inf' and '-inf' read back with pandas' defaults
    return str(x)


def write_table(columns, path, *, title: str, nondimensional: bool = False, quantities=None,
                **parameters) -> Path:
    """Write columns to CSV with a JSON sidecar of their metadata, atomically.

    Parameters
    ----------
    columns : mapping
        Column name -> 1-D array_like; all of one length.  Every name (or its entry in
        ``quantities``) must be a key of :data:`dhfield.core.schema.VARIABLES`.
    path : path-like
        CSV file to write (any suffix; ``.csv`` recommended).
    title : str
        Title recorded in the sidecar's ``attributes``.
    nondimensional : bool
        The values are in the paper's units (Eqs. 32-35): units "1" and the
        scale in each ``long_name``.
    quantities : mapping, optional
        Column name -> schema key, for columns named differently from their
        quantity.
    **parameters
        Input parameters, recorded as ``param_*`` attributes.

    Returns
    -------
    pathlib.Path
        The CSV path; the sidecar is :func:`sidecar_path` of it.
    """
    p = Path(path)
    quantities = dict(quantities or {})
    names = list(columns)
    cols = [np.atleast_1d(np.asarray(columns[n])) for n in names]
    lengths = {c.shape for c in cols}
    if len(lengths) > 1 or any(c.ndim != 1 for c in cols):
        raise ValueError(f"columns must be 1-D and of one length; got shapes {sorted(lengths)}")
    column_attrs = {}
    for n, c in zip(names, cols):
        column_attrs[n] = variable_attrs(quantities.get(n, n), nondimensional=nondimensional)
        if c.dtype.kind in "USO":
            column_attrs[n].pop("units", None)  # a label has no unit
    meta = {
        "columns": column_attrs,
        "attributes": {k: _jsonable(v) for k, v in provenance_attrs(title, **parameters).items()},
    }
    side = sidecar_path(p)
    with atomic_path(p) as tmp_csv, atomic_path(side) as tmp_json:
        with open(tmp_csv, "w", newline="") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(names)
            for row in zip(*cols):
                w.writerow([_cell(x) for x in row])
        with open(tmp_json, "w") as fh:
            json.dump(meta, fh, indent=1, allow_nan=False)
            fh.write("\n")
    return p


def read_table(path, required=()):
    """Read a CSV table (and its sidecar, if present).

    Parameters
    ----------
    path : path-like
        CSV file with a header row of column names.
    required : sequence of str
        Columns that must be present, numeric and finite.

    Returns
    -------
    frame : pandas.DataFrame
        The table, one column per CSV column.
    metadata : dict
        The sidecar's content, or ``{}`` if there is none.

    Raises
    ------
    ValueError
        One line naming the file (and the column): unreadable, empty, a
        required column missing, not numeric or not finite.
    """
    import pandas as pd

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"data file does not exist or is not a file; got {str(p)!r}")
    try:
        frame = pd.read_csv(p)
    except Exception as exc:  # noqa: BLE001 - any parser failure is an unreadable file
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise ValueError(f"data file {str(p)!r} is not a readable CSV table ({first})") from None
    frame.columns = [str(c).strip() for c in frame.columns]
    for name in required:
        if name not in frame.columns:
            raise ValueError(f"data file {str(p)!r} has no column {name!r} (columns: {', '.join(frame.columns)})")
        values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
        bad = ~np.isfinite(values)
        if bad.any():
            row = int(np.argmax(bad))
            value = frame[name].iloc[row]
            value = value.item() if isinstance(value, np.generic) else value  # nan, not np.float64(nan)
            raise ValueError(f"data file {str(p)!r}, column {name!r}: value {value!r} in data row "
                             f"{row + 1} is not a finite number")
        frame[name] = values
    if required and len(frame) == 0:
        raise ValueError(f"data file {str(p)!r} has a header but no data rows")
    metadata = {}
    side = sidecar_path(p)
    if side.is_file():
        try:
            metadata = json.loads(side.read_text())
        except (OSError, ValueError) as exc:
            raise ValueError(f"metadata file {str(side)!r} is not readable JSON ({exc})") from None
    return frame, metadata
