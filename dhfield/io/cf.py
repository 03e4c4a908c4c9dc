"""CF metadata for every dhfield Dataset, from the one table :mod:`dhfield.core.schema`.

Every writer of :mod:`dhfield.io` (and the BEM-solution and sweep writers)
builds its variables with these helpers, so that a quantity carries the same
``units``, ``long_name`` and ``standard_name`` in every file, and every Dataset
is finished by :func:`finalize` (which :func:`dhfield.io.write_netcdf` applies
again before writing):

* dimensions in the one canonical order :data:`dhfield.core.schema.DIM_ORDER`
  (grids of the model parameters are always ``(beta0, mu)``);
* no ``_FillValue`` on coordinate variables (CF 1.10 section 2.5.1: coordinate
  variables have no missing values);
* categorical codes are small integers with ``flag_values`` and
  ``flag_meanings`` (CF section 3.5); string labels (``model``, ``closure``)
  carry a ``long_name`` and no ``units``.

The checks are those of the IOOS compliance-checker, test ``cf:1.10``; the test
suite runs it on every kind of file dhfield writes.
"""
from __future__ import annotations

import numpy as np

from ..core import schema

__all__ = ["variable_attrs", "variable", "coordinate", "flag_variable", "label_coordinate", "finalize"]


def variable_attrs(name: str, *, nondimensional: bool = False, qualifier: str | None = None) -> dict:
    """CF attributes of the quantity ``name`` of :data:`dhfield.core.schema.VARIABLES`.

    Parameters
    ----------
    name : str
        Key of :data:`dhfield.core.schema.VARIABLES`.
    nondimensional : bool
        True if the values are in the paper's units (Eqs. 32-35): ``units``
        becomes "1" and ``long_name`` names the scale.
    qualifier : str, optional
        Appended to ``long_name`` after a comma (e.g. "at pull-off",
        "analytic"), so that variants of one quantity keep its units.

    Returns
    -------
    dict
        ``long_name``, ``units`` and, where the schema has them,
        ``standard_name`` and ``description``.
    """
    attrs = schema.attrs(name, nondimensional=nondimensional)
    if qualifier:
        attrs["long_name"] = f"{attrs['long_name']}, {qualifier}"
    return attrs


def variable(name: str, dims, values, *, nondimensional: bool = False, qualifier: str | None = None,
             quantity: str | None = None):
    """``(dims, float array, attrs)`` for :class:`xarray.Dataset` of a schema quantity.

    ``quantity`` names the schema entry when the variable's own name differs
    (e.g. ``gap_analytic`` is the quantity ``gap``, qualified "analytic").

    Parameters
    ----------
    name : str
        Variable name, a key of :data:`dhfield.core.schema.VARIABLES` unless ``quantity`` is given.
    dims : str or tuple of str
        Dimension names.
    values : array_like
        The values, stored as float.
    nondimensional : bool
        True if the values are in the paper's units (see :func:`variable_attrs`).
    qualifier : str, optional
        Appended to ``long_name`` (see :func:`variable_attrs`).
    quantity : str, optional
        Schema key when it differs from ``name``.

    Returns
    -------
    tuple
        ``(dims, values, attrs)``, ready for ``xarray.Dataset(data_vars=...)``.
    """
    attrs = variable_attrs(quantity or name, nondimensional=nondimensional, qualifier=qualifier)
    return (dims, np.asarray(values, dtype=float), attrs)


def coordinate(name: str, values, *, nondimensional: bool = False, quantity: str | None = None):
    """``(name, float array, attrs)`` of a dimension coordinate (no fill value is written).

    Parameters
    ----------
    name : str
        Coordinate (and dimension) name.
    values : array_like
        The coordinate values, stored as float.
    nondimensional : bool
        True if the values are in the paper's units (see :func:`variable_attrs`).
    quantity : str, optional
        Schema key when it differs from ``name``.

    Returns
    -------
    tuple
        ``(name, values, attrs)``, ready for ``xarray.Dataset(coords=...)``.
    """
    attrs = variable_attrs(quantity or name, nondimensional=nondimensional)
    return (name, np.asarray(values, dtype=float), attrs)


def label_coordinate(name: str, labels, *, quantity: str | None = None):
    """``(name, str array, attrs)`` of a coordinate of string labels (``model``, ``closure``).

    Labels get ``long_name`` (and ``description``) but no ``units``: a string
    has no unit.

    Parameters
    ----------
    name : str
        Coordinate (and dimension) name.
    labels : array_like of str
        The labels.
    quantity : str, optional
        Schema key when it differs from ``name``.

    Returns
    -------
    tuple
        ``(name, labels, attrs)``.
    """
    attrs = variable_attrs(quantity or name)
    attrs.pop("units", None)
    return (name, np.asarray(labels, dtype=str), attrs)


def flag_variable(name: str, dims, labels, meanings, *, quantity: str | None = None):
    """``(dims, int8 codes, attrs)`` of a categorical variable (CF flags, section 3.5).

    Parameters
    ----------
    name : str
        Schema key (its ``long_name`` and ``description`` are used).
    dims : str or tuple of str
        Dimension names.
    labels : array_like of str or of int
        The category of every element: a string of ``meanings``, or already
        its code (position in ``meanings``).
    meanings : sequence of str
        The categories; code ``i`` means ``meanings[i]``.
    quantity : str, optional
        Schema key when it differs from ``name``.

    Returns
    -------
    tuple
        Codes 0..len(meanings)-1 with ``flag_values`` and ``flag_meanings``;
        no ``units`` (codes are not a quantity).
    """
    meanings = [str(m) for m in meanings]
    arr = np.asarray(labels)
    if arr.dtype.kind in "US":
        unknown = sorted(set(arr.ravel().tolist()) - set(meanings))
        if unknown:
            raise ValueError(f"{name} must be one of {meanings}; got {unknown}")
        codes = np.vectorize(meanings.index, otypes=[np.int8])(arr) if arr.size else arr.astype(np.int8)
    else:
        codes = arr.astype(np.int8)
    attrs = variable_attrs(quantity or name)
    attrs.pop("units", None)
    attrs["flag_values"] = np.arange(len(meanings), dtype=np.int8)
    attrs["flag_meanings"] = " ".join(m.replace(" ", "_") for m in meanings)
    return (dims, codes, attrs)


def finalize(ds):
    """``ds`` with canonical dimension order and CF-clean encodings.

    Transposes every variable into :data:`dhfield.core.schema.DIM_ORDER` and sets
    no ``_FillValue`` on coordinate variables.  Idempotent; returns a new
    Dataset (``ds`` is not modified).

    Parameters
    ----------
    ds : xarray.Dataset
        Any dhfield Dataset.

    Returns
    -------
    xarray.Dataset
        The finalized copy.
    """
    ds = ds.transpose(*schema.order_dims(ds.dims))
    ds = ds.copy()
    for name in ds.coords:
        ds[name].encoding["_FillValue"] = None
    return ds
