"""xarray Dataset of a side-by-side model comparison (thin wrapper of :mod:`dhfield.analysis.compare`).

One record per model (the keys of :data:`dhfield.core.schema.PULL_OFF_KEYS`) on the
dimension ``model`` (string labels).  Numeric quantities carry the schema's
units and names; ``geometry``, ``at_zero_contact`` and ``bem_verified`` are CF flag variables;
``model_error`` is each model's estimated relative error against the BEM ground truth
(:mod:`dhfield.analysis.model_error`, where the records carry it);
``warning`` is a string; the scalar inputs (``beta0``, ``mu``, ``control``) are
global ``param_*`` attributes.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..core import schema
from . import provenance_attrs
from .cf import finalize, flag_variable, label_coordinate, variable

__all__ = ["comparison_dataset", "COMPARISON_VARIABLES", "GEOMETRIES"]

#: Numeric per-model variables, in schema order (the nondimensional pull-off of Eqs. 32-35).
COMPARISON_VARIABLES = tuple(k for k in schema.PULL_OFF_KEYS
                             if k not in ("model", "control", "geometry", "beta0", "mu", "at_zero_contact",
                                          "warning"))
#: Codes of the ``geometry`` flag variable: 0 ellipse, 1 circle.
GEOMETRIES = ("ellipse", "circle")


def comparison_dataset(records: dict, **extra_attrs) -> xr.Dataset:
    """Build a Dataset on the dimension ``model`` from :func:`dhfield.analysis.compare.compare` (scalar mu, beta0).

    Parameters
    ----------
    records : dict
        Model name -> pull-off record (:func:`dhfield.analysis.compare.pull_off`).
    **extra_attrs
        Recorded as ``param_*`` global attributes.

    Returns
    -------
    xarray.Dataset
        The records, CF-annotated.
    """
    names = list(records)
    if not names:
        raise ValueError("records must hold at least one model; got none")
    first = records[names[0]]
    data = {}
    for k in COMPARISON_VARIABLES:
        if k in first:
            data[k] = variable(k, "model", [float(records[n][k]) for n in names], nondimensional=True,
                               qualifier="at pull-off")
    data["geometry"] = flag_variable("geometry", "model", [records[n]["geometry"] for n in names], GEOMETRIES)
    if "at_zero_contact" in first:
        data["at_zero_contact"] = flag_variable("at_zero_contact", "model",
                                                [int(bool(records[n]["at_zero_contact"])) for n in names],
                                                ("false", "true"))
    if "model_error" in first:  # the trust group (dhfield.analysis.model_error)
        data["model_error"] = variable("model_error", "model", [float(records[n]["model_error"]) for n in names])
        data["bem_verified"] = flag_variable("bem_verified", "model",
                                             [int(bool(records[n]["bem_verified"])) for n in names], ("false", "true"))
    if "warning" in first:
        attrs = schema.attrs("warning")
        attrs.pop("units", None)
        data["warning"] = ("model", np.array([str(records[n]["warning"]) for n in names], dtype=str), attrs)
    ds = xr.Dataset(data, coords={"model": label_coordinate("model", names)})
    ds.attrs.update(provenance_attrs("Pull-off of the comparison models side by side (Zini et al. 2018, Fig. 9)",
                                     mu=float(first["mu"]), beta0=float(first["beta0"]),
                                     control=first["control"],
                                     mu_to_lambda="lambda = 2 (9/(16 pi))^(1/3) mu", **extra_attrs))
    return finalize(ds)
