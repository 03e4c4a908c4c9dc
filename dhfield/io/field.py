"""netCDF output of one field case: Cartesian and polar maps of the BEM cross-check.

One :class:`xarray.Dataset` per case (:class:`dhfield.analysis.fields.FieldCase`):

* coordinates ``x``, ``y`` (cell centres) and, for the polar resampling, ``r``
  and ``theta_p``;
* on (x, y): the gridded pressure fed to the BEM, the analytic pressure, the
  analytic and numerical displacement and gap, their differences (analytic minus
  numerical) and a region flag (contact / annulus / outside);
* on (r, theta_p): the same displacement and gap variables, numerical ones
  interpolated from the grid (cubic splines), analytic ones evaluated directly,
  and, for DH cases, the annulus-identity error along each ray theta_p;
* ``units``, ``long_name`` (and ``description``) from :mod:`dhfield.core.schema` on
  every variable (``region`` is a CF flag variable), no ``_FillValue`` on the
  coordinates, dimensions in the order of :data:`dhfield.core.schema.DIM_ORDER`
  (:mod:`dhfield.io.cf`), and the global
  attributes of :func:`dhfield.io.provenance_attrs` (``Conventions``,
  ``source``, ``references``, ``history``) with every input parameter as a
  ``param_*`` attribute and the error summary as ``error_*`` attributes.

Lengths are nondimensional for model cases (units ``1``, with the length,
pressure and approach scales stored as attributes) and in metres otherwise.
Writes go through :func:`dhfield.io.write_netcdf` (atomic).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..analysis import field_metrics, fields, polar
from . import check_writable, provenance_attrs, write_netcdf
from .cf import coordinate, finalize, flag_variable, variable

__all__ = ["field_dataset", "polar_dataset", "write_field", "FIELD_VARIABLES"]

#: name -> (schema quantity, qualifier of its long_name) of the Cartesian variables.
FIELD_VARIABLES = {
    "pressure": ("pressure", "cell averages fed to the BEM (Eqs. 7/22)"),
    "pressure_analytic": ("pressure", "analytic at the cell centres (Eqs. 7/22)"),
    "displacement_analytic": ("displacement", "analytic (Eqs. 13/26)"),
    "displacement_numerical": ("displacement", "DC-FFT BEM (Love coefficients)"),
    "displacement_difference": ("displacement", "analytic minus numerical"),
    "gap_analytic": ("gap", "analytic (Eq. 27)"),
    "gap_numerical": ("gap", "from the BEM displacement, h = z - delta + omega_BEM"),
    "gap_difference": ("gap", "analytic minus numerical"),
}
#: Codes of the ``region`` flag variable.
REGIONS = ("contact_ellipse", "adhesive_annulus", "outside")


def _nondim(case) -> bool:
    return "a_star" in case.parameters


def _scale_attrs(case) -> dict:
    if "a_star" in case.parameters:
        return {"length_scale": "c_r = (R^2 dgamma/E*)^(1/3) (Eq. 32)",
                "pressure_scale": "E* c_r/R (Eq. 35)",
                "approach_scale": "c_r^2/R (Eq. 33)"}
    return {}


def _error_attrs(case) -> dict:
    out = {}
    for qty, stats in (("displacement", case.displacement_errors()), ("gap", case.gap_errors())):
        for region, st in stats.items():
            if st["count"]:
                out[f"error_{qty}_{region}_rel_max"] = st["rel_max"]
                out[f"error_{qty}_{region}_rel_rms"] = st["rel_rms"]
    out["error_normalisation"] = "max |analytic displacement| over the grid"
    return out


def polar_dataset(case, r_max=None, n_r=201, n_theta=91) -> xr.Dataset:
    """The displacement and gap of ``case`` on a polar grid ``(r, theta_p)``.

    Parameters
    ----------
    case : dhfield.analysis.fields.FieldCase
        An analytic-versus-BEM case.
    r_max : float, optional
        Largest radius [m]; default 95 % of the smaller half-width of the grid.
    n_r, n_theta : int
        Number of radii in ``[0, r_max]`` and of angles in ``[0, pi/2]`` (the
        fields are even in x and y).

    Returns
    -------
    xarray.Dataset
        Analytic and numerical displacement and gap on ``(r, theta_p)``, CF metadata from
        :mod:`dhfield.core.schema`.
    """
    g = case.grid
    if r_max is None:
        r_max = 0.95 * min(g.x[-1], g.y[-1])
    r, theta = polar.polar_grid(r_max, n_r, n_theta)
    x = r[:, None] * np.cos(theta)[None, :]
    y = r[:, None] * np.sin(theta)[None, :]
    ana = fields.analytic_fields(case, x, y)
    nd = _nondim(case)
    dims = ("r", "theta_p")
    data = {}
    for qty in ("displacement", "gap"):
        num = polar.to_polar(getattr(case, f"{qty}_numerical"), g, r, theta)
        data[f"{qty}_analytic_polar"] = variable(f"{qty}_analytic_polar", dims, ana[qty], nondimensional=nd,
                                                 quantity=qty, qualifier=FIELD_VARIABLES[f"{qty}_analytic"][1])
        data[f"{qty}_numerical_polar"] = variable(
            f"{qty}_numerical_polar", dims, num, nondimensional=nd, quantity=qty,
            qualifier=FIELD_VARIABLES[f"{qty}_numerical"][1] + ", cubic-spline interpolated")
        data[f"{qty}_difference_polar"] = variable(f"{qty}_difference_polar", dims, ana[qty] - num,
                                                   nondimensional=nd, quantity=qty,
                                                   qualifier="analytic minus numerical")
    data["pressure_analytic_polar"] = variable("pressure_analytic_polar", dims, ana["pressure"], nondimensional=nd,
                                               quantity="pressure", qualifier="analytic (Eqs. 7/22)")
    if case.parameters.get("model") == "double_hertz":
        ident = field_metrics.annulus_identity(case, n_theta=n_theta)
        data["annulus_identity_error"] = variable("annulus_identity_error", "theta_p", ident["rel_error"])
    coords = {"r": coordinate("r", r, nondimensional=nd), "theta_p": coordinate("theta_p", theta)}
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs("dhfield polar resampling of the BEM cross-check",
                                     **case.parameters, **_scale_attrs(case)))
    return finalize(ds)


def field_dataset(case, *, polar=True, **polar_options) -> xr.Dataset:
    """The Dataset of one case (Cartesian maps, plus the polar resampling if ``polar``).

    Parameters
    ----------
    case : dhfield.analysis.fields.FieldCase
        An analytic-versus-BEM case.
    polar : bool, default True
        Include :func:`polar_dataset` of the case.
    **polar_options
        Passed to :func:`polar_dataset` (``r_max``, ``n_r``, ``n_theta``).

    Returns
    -------
    xarray.Dataset
        Pressure, displacement, gap and their errors on the grid, with provenance.
    """
    g = case.grid
    nd = _nondim(case)
    dims = ("y", "x")   # rows y, columns x: ds.gap.plot() draws x horizontally (the grid's arrays are (x, y))
    arrays = {
        "pressure": case.pressure,
        "pressure_analytic": case.pressure_exact,
        "displacement_analytic": case.displacement_analytic,
        "displacement_numerical": case.displacement_numerical,
        "displacement_difference": case.displacement_analytic - case.displacement_numerical,
        "gap_analytic": case.gap_analytic,
        "gap_numerical": case.gap_numerical,
        "gap_difference": case.gap_analytic - case.gap_numerical,
    }
    data = {name: variable(name, dims, np.asarray(arr).T, nondimensional=nd, quantity=FIELD_VARIABLES[name][0],
                           qualifier=FIELD_VARIABLES[name][1])
            for name, arr in arrays.items()}
    region = np.full(g.shape, 2, dtype=np.int8)
    region[case.masks["annulus"]] = 1
    region[case.masks["contact"]] = 0
    data["region"] = flag_variable("region", dims, region.T, REGIONS)
    # no axis="X"/"Y": the CF checker would read x and y as longitude and latitude
    coords = {"x": coordinate("x", g.x, nondimensional=nd), "y": coordinate("y", g.y, nondimensional=nd)}
    ds = xr.Dataset(data, coords=coords)
    if polar:
        pol = polar_dataset(case, **polar_options)
        ds = ds.assign_coords(pol.coords).assign(pol.data_vars)
    ds.attrs.update(provenance_attrs(
        "dhfield: analytic vs DC-FFT boundary-element displacement and gap of the "
        + ("extended double-Hertz" if case.parameters.get("model") == "double_hertz" else "Hertz")
        + " contact", **case.parameters, cell_size_x=g.dx, cell_size_y=g.dy, approach=case.approach,
        **_scale_attrs(case)))
    ds.attrs.update(_error_attrs(case))
    return finalize(ds)


def write_field(case, path, **options) -> Path:
    """Write :func:`field_dataset` of ``case`` to netCDF atomically; return the path.

    Parameters
    ----------
    case : dhfield.analysis.fields.FieldCase
        An analytic-versus-BEM case.
    path : path-like
        The netCDF file.
    **options
        Passed to :func:`field_dataset`.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    check_writable(path)
    return write_netcdf(field_dataset(case, **options), path)
