"""xarray Dataset and netCDF file of the adhesion map (thin wrapper of :mod:`dhfield.analysis.adhesion_map`).

Dimensions ``model`` (string labels, the reference first), ``skew_angle_deg`` (crossing
angle [deg]) and ``mu``; ``beta0`` is an auxiliary coordinate on ``skew_angle_deg``.
Variables, with the units and names of :mod:`dhfield.core.schema`:

* ``force_pi_r_dgamma`` (model, skew_angle_deg, mu): load-control pull-off W/(pi R dgamma);
* ``relative_deviation`` (model, skew_angle_deg, mu): from the reference model;
* ``model_status`` (model, skew_angle_deg, mu): CF flags of
  :data:`dhfield.analysis.adhesion_map.STATUS_MEANINGS` (refused points: NaN, code 2);
* ``validated_region`` (skew_angle_deg, mu): CF flag, 1 inside the BEM ground truth's extent;
* ``warning`` (model): the model's warnings and refusals over the grid, one line.

Global attributes: provenance (:func:`dhfield.io.provenance_attrs`), ``reference_model``,
``reference_note`` (where the reference is validated: it is the recommended model, not the
BEM), ``model_labels`` and the validated extent as ``param_validated_*``.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..core import schema
from ..analysis.adhesion_map import MODEL_LABELS, STATUS_MEANINGS, AdhesionMap
from . import provenance_attrs, read_netcdf, write_netcdf
from .cf import coordinate, finalize, flag_variable, label_coordinate, variable

__all__ = ["adhesion_map_dataset", "write_adhesion_map", "read_adhesion_map"]

_DIMS = ("model", "skew_angle_deg", "mu")


def adhesion_map_dataset(result: AdhesionMap, **extra_attrs) -> xr.Dataset:
    """Build the CF Dataset of an :class:`dhfield.analysis.adhesion_map.AdhesionMap`.

    Parameters
    ----------
    result : AdhesionMap
        The map.
    **extra_attrs
        Recorded as ``param_*`` global attributes (e.g. the command that built it).

    Returns
    -------
    xarray.Dataset
        The map on (model, crossing angle, mu), CF-annotated.
    """
    if not isinstance(result, AdhesionMap):
        raise ValueError(f"result must be a dhfield.analysis.adhesion_map.AdhesionMap; got {type(result).__name__}")
    note_attrs = schema.attrs("warning")
    note_attrs.pop("units", None)
    data = {
        "force_pi_r_dgamma": variable("force_pi_r_dgamma", _DIMS, result.force, qualifier="load control"),
        "relative_deviation": variable("relative_deviation", _DIMS, result.deviation),
        "model_status": flag_variable("model_status", _DIMS, result.status, STATUS_MEANINGS),
        "validated_region": flag_variable("validated_region", _DIMS[1:], result.validated.astype(np.int8),
                                          ("false", "true")),
        "warning": ("model", np.array([result.notes.get(m, "") for m in result.models], dtype=str), note_attrs),
    }
    data["relative_deviation"][2]["comment"] = result.reference_note
    beta0 = coordinate("beta0", result.beta0)
    coords = {"model": label_coordinate("model", list(result.models)),
              "skew_angle_deg": coordinate("skew_angle_deg", result.crossing_angle_deg),
              "mu": coordinate("mu", result.mu),
              "beta0": ("skew_angle_deg", beta0[1], beta0[2])}
    ds = xr.Dataset(data, coords=coords)
    for v in ("force_pi_r_dgamma", "relative_deviation", "model_status"):
        ds[v].encoding.update(zlib=True, complevel=4, shuffle=True)  # lossless; the map is smooth
    ds.attrs.update(provenance_attrs(
        "Adhesion map for elliptical contacts: load-control pull-off of each model against the recommended "
        "model md-elliptic (MD elliptical), over crossing angle and mu",
        control="load", validated_beta0_min=result.validated_beta0[0],
        validated_beta0_max=result.validated_beta0[1], validated_mu_min=result.validated_mu[0],
        validated_mu_max=result.validated_mu[1], **extra_attrs))
    ds.attrs["reference_model"] = result.reference
    ds.attrs["reference_note"] = result.reference_note
    ds.attrs["model_labels"] = "; ".join(f"{m}: {MODEL_LABELS.get(m, m)}" for m in result.models)
    ds.attrs["crossing_angle_to_beta0"] = ("beta0 = dhfield.core.geometry.ellipticity_from_skew_angle(theta_skew): "
                                           "equal cylinders, Eqs. (3)-(4) and (8)")
    return finalize(ds)


def write_adhesion_map(result: AdhesionMap, path, **extra_attrs):
    """Write the adhesion map to netCDF atomically (:func:`dhfield.io.write_netcdf`).

    Parameters
    ----------
    result : AdhesionMap
        The map.
    path : str or path-like
        The netCDF file.
    **extra_attrs
        Recorded as ``param_*`` global attributes.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    return write_netcdf(adhesion_map_dataset(result, **extra_attrs), path)


def read_adhesion_map(path) -> AdhesionMap:
    """Read a file of :func:`write_adhesion_map` back into an :class:`~dhfield.analysis.adhesion_map.AdhesionMap`.

    Parameters
    ----------
    path : str or path-like
        The netCDF file.

    Returns
    -------
    AdhesionMap
        The map.

    Raises
    ------
    ValueError
        If the file is not an adhesion-map file.
    """
    ds = read_netcdf(path)
    need = ("force_pi_r_dgamma", "relative_deviation", "model_status", "validated_region", "warning")
    missing = [v for v in need if v not in ds]
    if missing or "reference_model" not in ds.attrs:
        raise ValueError(f"path must be an adhesion-map file of dhfield.io.adhesion_map; {str(path)!r} lacks "
                         f"{', '.join(missing) or 'the attribute reference_model'}")
    ds = ds.transpose(*_DIMS)
    models = tuple(str(m) for m in ds["model"].values)
    a = ds.attrs
    return AdhesionMap(
        crossing_angle_deg=ds["skew_angle_deg"].values.astype(float), mu=ds["mu"].values.astype(float),
        beta0=ds["beta0"].values.astype(float), models=models,
        force=ds["force_pi_r_dgamma"].values.astype(float), deviation=ds["relative_deviation"].values.astype(float),
        status=ds["model_status"].values.astype(np.int8), reference_force=ds["force_pi_r_dgamma"].values[0],
        validated=ds["validated_region"].values.astype(bool),
        validated_beta0=(float(a["param_validated_beta0_min"]), float(a["param_validated_beta0_max"])),
        validated_mu=(float(a["param_validated_mu_min"]), float(a["param_validated_mu_max"])),
        notes={m: str(n) for m, n in zip(models, ds["warning"].values)},
        reference=str(a["reference_model"]), reference_note=str(a["reference_note"]))
