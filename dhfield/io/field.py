"""netCDF output of one field case: Cartesian and polar maps of the BEM cross-check.

One :class:`xarray.Dataset` per case (:class:`dhfield.fields.FieldCase`):

* coordinates ``x``, ``y`` (cell centres) and, for the polar resampling, ``r``
  and ``theta_p``;
* on (x, y): the gridded pressure fed to the BEM, the analytic pressure, the
  analytic and numerical displacement and gap, their differences (analytic minus
  numerical) and a region flag (contact / annulus / outside);
* on (r, theta_p): the same displacement and gap variables, numerical ones
  interpolated from the grid (cubic splines), analytic ones evaluated directly,
  and, for DH cases, the annulus-identity error along each ray theta_p;
* CF-style ``units`` and ``long_name`` on every variable, and the global
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

from .. import fields
from . import check_writable, provenance_attrs, write_netcdf

__all__ = ["field_dataset", "polar_dataset", "write_field", "compute_and_write_case", "FIELD_VARIABLES"]

#: name -> (long_name, kind) of the Cartesian variables; kind selects the unit.
FIELD_VARIABLES = {
    "pressure": ("cell pressure fed to the BEM (cell averages of Eqs. 7/22, compressive positive)", "pressure"),
    "pressure_analytic": ("analytic pressure at the cell centres (Eqs. 7/22, compressive positive)", "pressure"),
    "displacement_analytic": ("analytic combined surface displacement (Eqs. 13/26, into the bodies)", "length"),
    "displacement_numerical": ("DC-FFT BEM combined surface displacement (Love coefficients)", "length"),
    "displacement_difference": ("analytic minus numerical displacement", "length"),
    "gap_analytic": ("analytic gap h = z - delta + omega (Eq. 27)", "length"),
    "gap_numerical": ("gap from the BEM displacement, h = z - delta + omega_BEM", "length"),
    "gap_difference": ("analytic minus numerical gap", "length"),
}

_NONDIM = "nondimensional"


def _units(case) -> dict:
    if "a_star" in case.parameters:
        return {"length": "1", "pressure": "1"}
    return {"length": "m", "pressure": "Pa"}


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
    case : dhfield.fields.FieldCase
    r_max : float, optional
        Largest radius [m]; default 95 % of the smaller half-width of the grid.
    n_r, n_theta : int
        Number of radii in ``[0, r_max]`` and of angles in ``[0, pi/2]`` (the
        fields are even in x and y).
    """
    g = case.grid
    if r_max is None:
        r_max = 0.95 * min(g.x[-1], g.y[-1])
    r, theta = fields.polar_grid(r_max, n_r, n_theta)
    x = r[:, None] * np.cos(theta)[None, :]
    y = r[:, None] * np.sin(theta)[None, :]
    ana = fields.analytic_fields(case, x, y)
    u = _units(case)
    dims = ("r", "theta_p")
    data = {}
    for qty in ("displacement", "gap"):
        num = fields.to_polar(getattr(case, f"{qty}_numerical"), g, r, theta)
        data[f"{qty}_analytic_polar"] = (dims, ana[qty], {"long_name": FIELD_VARIABLES[f"{qty}_analytic"][0],
                                                           "units": u["length"]})
        data[f"{qty}_numerical_polar"] = (dims, num, {"long_name": FIELD_VARIABLES[f"{qty}_numerical"][0]
                                                      + ", cubic-spline interpolated", "units": u["length"]})
        data[f"{qty}_difference_polar"] = (dims, ana[qty] - num, {"long_name": f"analytic minus numerical {qty}",
                                                                  "units": u["length"]})
    data["pressure_analytic_polar"] = (dims, ana["pressure"], {
        "long_name": "analytic pressure (Eqs. 7/22, compressive positive)", "units": u["pressure"]})
    if case.parameters.get("model") == "double_hertz":
        ident = fields.annulus_identity(case, n_theta=n_theta)
        data["annulus_identity_error"] = ("theta_p", ident["rel_error"], {
            "long_name": "max over the annulus ray of |h_BEM - (1+v) h_Hertz| / max (1+v) h_Hertz",
            "units": "1"})
    coords = {"r": ("r", r, {"long_name": "radial coordinate r (Eq. A3)", "units": u["length"]}),
              "theta_p": ("theta_p", theta, {"long_name": "polar angle theta_p from the major axis (Eq. A3)",
                                             "units": "radian"})}
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs("dhfield polar resampling of the BEM cross-check",
                                     **case.parameters, **_scale_attrs(case)))
    return ds


def field_dataset(case, *, polar=True, **polar_options) -> xr.Dataset:
    """The Dataset of one case (Cartesian maps, plus the polar resampling if ``polar``)."""
    g = case.grid
    u = _units(case)
    dims = ("x", "y")
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
    data = {name: (dims, np.asarray(arr, dtype=float), {"long_name": FIELD_VARIABLES[name][0],
                                                        "units": u[FIELD_VARIABLES[name][1]]})
            for name, arr in arrays.items()}
    region = np.full(g.shape, 2, dtype=np.int8)
    region[case.masks["annulus"]] = 1
    region[case.masks["contact"]] = 0
    data["region"] = (dims, region, {"long_name": "region of the surface", "flag_values": np.array([0, 1, 2], np.int8),
                                     "flag_meanings": "contact_ellipse adhesive_annulus outside"})
    coords = {
        "x": ("x", g.x, {"long_name": "cell-centre x, along the major axis a", "units": u["length"], "axis": "X"}),
        "y": ("y", g.y, {"long_name": "cell-centre y, along the minor axis b", "units": u["length"], "axis": "Y"}),
    }
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
    return ds


def write_field(case, path, **options) -> Path:
    """Write :func:`field_dataset` of ``case`` to netCDF atomically; return the path."""
    check_writable(path)
    return write_netcdf(field_dataset(case, **options), path)


def compute_and_write_case(beta0, mu, a_star, n, out, *, half_width=None, sampling="average", threads=None,
                           polar=True) -> Path:
    """Compute one nondimensional DH case on an ``n`` x ``n`` grid and write it to ``out``.

    Parameters
    ----------
    beta0 : float
        Ellipticity of both ellipses, (0, 1] [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    a_star : float
        Contact semi-major axis a/c_r [-].
    n : int
        Cells per axis (>= 8; even uses the symmetry mode) [-].
    out : path-like
        Output netCDF file; its directory must exist and be writable.  Checked
        before anything is computed; the write is atomic.
    half_width : float, optional
        Half-width of the square domain [-]; default 1.5 c*.
    sampling : {"average", "centre"}
    threads : int, optional
        FFTW threads.
    polar : bool, default True
        Include the polar resampling.

    Returns
    -------
    pathlib.Path
    """
    check_writable(out)
    case = fields.model_case(n, beta0, mu, a_star, half_width=half_width, sampling=sampling, threads=threads)
    return write_field(case, out, polar=polar)
