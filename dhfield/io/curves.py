"""xarray Datasets and files for load curves and pull-off tables (thin wrappers).

Names, units and descriptions come from :mod:`dhfield.core.schema` (through
:mod:`dhfield.io.cf`); grids of the model parameters are on ``(beta0, mu)``.
CSV output is a plain table with a JSON sidecar (:mod:`dhfield.io.table`).
"""
from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np
import xarray as xr

from ..core import schema
from . import provenance_attrs, write_netcdf
from .cf import coordinate, finalize, variable
from .table import write_table

__all__ = ["load_curve_dataset", "pull_off_dataset", "write_load_curve", "load_curve_columns", "CURVE_VARIABLES"]

#: Array variables of a nondimensional load curve, in order (:data:`dhfield.core.schema.LOAD_CURVE_KEYS`).
CURVE_VARIABLES = schema.LOAD_CURVE_KEYS
#: Columns a curve may carry besides, written after them when present: the machine position of
#: :func:`dhfield.analysis.spring.add_machine_displacement` (``curve --machine-stiffness``).
OPTIONAL_CURVE_VARIABLES = ("machine_displacement",)

_TITLE = "Load curve of an adhesive contact (Zini et al. 2018, Eqs. 31-36)"


def load_curve_columns(curve):
    """Split a load curve into its array columns and scalar header.

    Parameters
    ----------
    curve : dhfield.core.records.LoadCurve or mapping
        A nondimensional curve (attributes or keys
        :data:`dhfield.core.schema.LOAD_CURVE_KEYS`), or an SI curve (keys
        :data:`dhfield.core.schema.LOAD_CURVE_SI_KEYS`, recognised by ``force``).

    Returns
    -------
    columns : dict
        Name -> 1-D array, in schema order (then :data:`OPTIONAL_CURVE_VARIABLES` present).
    header : dict
        Scalar parameters of the curve (model, beta0, mu, ...).
    nondimensional : bool
        True for a curve in the paper's units.
    """
    get = (lambda k: curve.get(k)) if isinstance(curve, Mapping) else (lambda k: getattr(curve, k, None))
    nondimensional = get("force") is None
    keys = schema.LOAD_CURVE_KEYS if nondimensional else schema.LOAD_CURVE_SI_KEYS
    missing = [k for k in keys if get(k) is None]
    if missing:
        raise ValueError(f"curve must have the load-curve keys {keys}; missing {missing}")
    optional = tuple(k for k in OPTIONAL_CURVE_VARIABLES if get(k) is not None)
    columns = {k: np.atleast_1d(np.asarray(get(k), dtype=float)) for k in keys + optional}
    header = {}
    for k in schema.LOAD_CURVE_HEADER_KEYS + ("control", "ellipticity"):
        v = get(k)
        if v is None:
            continue
        if not isinstance(v, str):
            v = np.asarray(v)
            if v.ndim:
                continue
            v = v.item()
        header[k] = v
    header.setdefault("model", "dh-elliptic")
    return columns, header, nondimensional


def load_curve_dataset(curve, **extra_attrs) -> xr.Dataset:
    """Build the Dataset of a load curve on the dimension ``point``.

    Parameters
    ----------
    curve : dhfield.core.records.LoadCurve or mapping
        See :func:`load_curve_columns`.
    **extra_attrs
        Recorded as ``param_*`` global attributes.

    Returns
    -------
    xarray.Dataset
        The curve, CF-annotated.
    """
    columns, header, nondim = load_curve_columns(curve)
    n = len(next(iter(columns.values())))
    data = {k: variable(k, "point", v, nondimensional=nondim) for k, v in columns.items()}
    ds = xr.Dataset(data, coords={"point": coordinate("point", np.arange(n))})
    scales = {"length_unit": "c_r = (R^2 dgamma/E*)^(1/3) (Eq. 33)"} if nondim else {}
    ds.attrs.update(provenance_attrs(_TITLE, **header, **scales, **extra_attrs))
    return finalize(ds)


def pull_off_dataset(results: dict, *, beta0, mu, input_dims=("mu", "beta0"), **extra_attrs) -> xr.Dataset:
    """Build the Dataset of pull-off results on a ``(beta0, mu)`` grid.

    Parameters
    ----------
    results : dict
        Name -> array on the two grids, laid out as ``input_dims`` says.  A
        name is a key of :data:`dhfield.core.schema.VARIABLES`, optionally followed
        by ``_<qualifier>`` (e.g. ``W_star_displacement_control``), which is
        added to the ``long_name``.
    beta0, mu : array_like
        1-D grids [-].
    input_dims : tuple
        Layout of the arrays of ``results``: ``("mu", "beta0")`` (shape
        (len(mu), len(beta0)), the default) or ``("beta0", "mu")``.  The
        Dataset is always on ``(beta0, mu)`` (:data:`dhfield.core.schema.GRID_DIMS`).
    **extra_attrs
        Recorded as ``param_*`` global attributes.

    Returns
    -------
    xarray.Dataset
        The results, CF-annotated.
    """
    if tuple(input_dims) not in (("mu", "beta0"), ("beta0", "mu")):
        raise ValueError(f"input_dims must be ('mu', 'beta0') or ('beta0', 'mu'); got {input_dims!r}")
    coords = {"beta0": coordinate("beta0", beta0), "mu": coordinate("mu", mu)}
    data = {}
    for name, arr in results.items():
        quantity, qualifier = _split(name)
        qual = "at pull-off" + (f", {qualifier.replace('_', ' ')}" if qualifier else "")
        data[name] = variable(name, tuple(input_dims), arr, nondimensional=True, quantity=quantity, qualifier=qual)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs("Pull-off of an adhesive contact on a (beta0, mu) grid", **extra_attrs))
    return finalize(ds)


def _split(name):
    if name in schema.VARIABLES:
        return name, ""
    for key in sorted(schema.VARIABLES, key=len, reverse=True):
        if name.startswith(key + "_"):
            return key, name[len(key) + 1:]
    raise ValueError(f"result name must be a dhfield.core.schema variable, optionally with a _suffix; got {name!r}")


def write_load_curve(curve, path, **extra_attrs) -> Path:
    """Write a load curve to ``.nc`` (netCDF4) or ``.csv`` (with a ``.csv.json`` sidecar), atomically.

    Parameters
    ----------
    curve : dhfield.core.records.LoadCurve or mapping
        See :func:`load_curve_columns`.
    path : str or path-like
        The output file, ending in ``.nc`` or ``.csv``.
    **extra_attrs
        Recorded as ``param_*`` attributes.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".nc":
        return write_netcdf(load_curve_dataset(curve, **extra_attrs), p)
    if suffix == ".csv":
        columns, header, nondim = load_curve_columns(curve)
        return write_table(columns, p, title=_TITLE, nondimensional=nondim, **header, **extra_attrs)
    raise ValueError(f"output file must end in .nc or .csv; got {str(p)!r}")
