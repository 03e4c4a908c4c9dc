"""xarray Datasets for the theta_p dependence, Eq. (30) and the equal-beta test.

Thin wrappers around the numpy results of :mod:`dhfield.models.dh_elliptic_periphery`,
:mod:`dhfield.analysis.eq30` and :mod:`dhfield.models.dh_elliptic_closure`.  Every variable and coordinate
carries ``long_name`` and ``units`` from :mod:`dhfield.core.schema` (CF; ``"1"`` for
dimensionless, the paper's scale named in ``long_name``), the global attributes
carry the provenance (:func:`dhfield.io.provenance_attrs`) and every input
parameter.  All quantities are nondimensional in the paper's units
(R = E* = Delta gamma = 1, Eqs. 32-35).  Grids are on ``(beta0, mu)`` and every
Dataset goes through :func:`dhfield.io.cf.finalize` (canonical dimension order,
no fill value on coordinates).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from . import provenance_attrs, write_netcdf
from .cf import coordinate, finalize, label_coordinate, variable

__all__ = [
    "PROFILE_VARIABLES",
    "pull_off_periphery_dataset",
    "equal_beta_dataset",
    "eq30_dataset",
    "grid_periphery_dataset",
    "load_curve_periphery_dataset",
    "write_dataset",
]

#: Ray quantities of dhfield.models.dh_elliptic_periphery.PeripheryProfile (schema names; nondimensional).
PROFILE_VARIABLES = ("contact_radius", "adhesive_radius", "zone_width", "max_adhesive_stress", "edge_separation",
                     "work_of_adhesion", "contact_edge_gap")
_LENGTH_UNIT = "c_r = (R^2 dgamma/E*)^(1/3) (Eq. 33)"


def _coords(mu, beta0, theta=None):
    c = {"beta0": coordinate("beta0", beta0), "mu": coordinate("mu", mu)}
    if theta is not None:
        c["theta"] = coordinate("theta", theta)
    return c


def _var(dims, arr, quantity, qualifier=None):
    """A nondimensional variable of the schema quantity ``quantity``."""
    return variable(quantity, dims, arr, nondimensional=True, qualifier=qualifier)


def pull_off_periphery_dataset(pull_off, profile, law=None, *, beta0, mu, control="load") -> xr.Dataset:
    """Dataset of the ray quantities at pull-off on a (beta0, mu) grid.

    Parameters
    ----------
    pull_off : dhfield.core.records.PullOff
        The pull-off points.
    profile : dhfield.models.dh_elliptic_periphery.PeripheryProfile
        Shape (len(beta0), len(mu), len(theta)).
    law : dhfield.models.dh_elliptic_periphery.CohesiveLaw, optional
        The sigma-h curves, shape (len(beta0), len(mu), n_law_theta, n_sample).
    beta0, mu : array_like
        1-D grids [-]; ``pull_off`` and ``profile`` have shape (len(beta0), len(mu)).
    control : str
        Pull-off control mode (recorded).

    Returns
    -------
    xarray.Dataset
        CF metadata from :mod:`dhfield.core.schema`, on the grid dims ``(beta0, mu)``.
    """
    theta = np.asarray(profile.theta)[0, 0]
    data = {name: _var(("beta0", "mu", "theta"), getattr(profile, name), name, "on the ray theta_p")
            for name in PROFILE_VARIABLES}
    for name in ("W_star", "a_star", "c_star", "v"):
        data[name] = _var(("beta0", "mu"), getattr(pull_off, name), name, "at pull-off")
    w = np.asarray(profile.work_of_adhesion)
    data["work_ratio"] = _var(("beta0", "mu"), w[..., -1] / w[..., 0], "work_ratio")
    coords = _coords(mu, beta0, theta)
    if law is not None:
        coords["law_theta"] = coordinate("law_theta", np.asarray(law.theta)[0, 0, :, 0])
        coords["sample"] = coordinate("sample", np.arange(np.shape(law.separation)[-1]))
        dims = ("beta0", "mu", "law_theta", "sample")
        data["law_separation"] = _var(dims, law.separation, "gap", "along the ray")
        data["law_stress"] = _var(dims, law.stress, "adhesive_stress", "along the ray")
        data["law_radius"] = _var(dims, law.radius, "r", "along the ray")
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        "Elliptical double-Hertz model: quantities along every ray theta_p at pull-off (Zini et al. 2018)",
        model="dh-elliptic", control=control, mu=np.asarray(mu, float), beta0=np.asarray(beta0, float),
        n_theta=int(theta.size), length_unit=_LENGTH_UNIT))
    return finalize(ds)


def equal_beta_dataset(spread, closures: dict, *, beta0, mu, control="load") -> xr.Dataset:
    """Dataset of the equal-beta test and of the closures' pull-off points.

    Parameters
    ----------
    spread : dhfield.models.dh_elliptic_closure.EqualBetaSpread
        The equal-beta test at pull-off.
    closures : dict
        Name -> dhfield.models.dh_elliptic_closure.ClosureState at pull-off (e.g. "paper",
        "ray_average", "two_axis").
    beta0, mu : array_like
        1-D grids [-]; arrays have shape (len(beta0), len(mu)).
    control : str
        Pull-off control mode (recorded).

    Returns
    -------
    xarray.Dataset
        CF metadata from :mod:`dhfield.core.schema`, on the grid dims ``(beta0, mu)``.
    """
    names = list(closures)
    grid = ("beta0", "mu")
    data = {name: _var(grid, getattr(spread, name), name, "at pull-off, paper's model")
            for name in ("work_ratio", "work_spread", "mean_work", "law_spread", "law_sup_spread",
                         "separation_ratio", "width_ratio")}
    #: closure field -> (schema quantity, qualifier)
    fields = {
        "W_star": ("W_star", None),
        "a_star": ("a_star", None),
        "c_star": ("c_star", None),
        "beta_contact": ("ellipticity", None),
        "beta_adhesive": ("adhesive_ellipticity", None),
        "work_major": ("work_major", None),
        "work_minor": ("work_minor", None),
        "sigma0_minor": ("max_adhesive_stress", "on the minor axis"),
    }
    for key, (quantity, qual) in fields.items():
        arr = np.stack([np.asarray(getattr(closures[n], key), float) for n in names], axis=0)
        data[f"closure_{key}"] = _var(("closure", "beta0", "mu"), arr, quantity,
                                      "at pull-off" + (f", {qual}" if qual else ""))
    coords = _coords(mu, beta0)
    coords["closure"] = label_coordinate("closure", names)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        "Equal-beta test and alternative closures of the elliptical double-Hertz model",
        control=control, mu=np.asarray(mu, float), beta0=np.asarray(beta0, float),
        closures=",".join(names), length_unit=_LENGTH_UNIT))
    return finalize(ds)


def eq30_dataset(area, boundary, work_major, work_minor, mean_work, *, beta0, mu) -> xr.Dataset:
    """Dataset of Eq. (30) (area and Green's forms) next to the ray works, at pull-off.

    Parameters
    ----------
    area : array_like
        Eq. (30) as an area integral (:func:`dhfield.analysis.eq30.eq30_area`).
    boundary : array_like
        Its Green's form (:func:`dhfield.analysis.eq30.eq30_boundary`, ``total``).
    work_major, work_minor : array_like
        Delta gamma(0) and Delta gamma(pi/2).
    mean_work : array_like
        The periphery average of Delta gamma (:func:`dhfield.analysis.eq30.periphery_work_of_adhesion`).
    beta0, mu : array_like
        1-D grids [-]; the other arrays have shape (len(beta0), len(mu)).

    Returns
    -------
    xarray.Dataset
        CF metadata from :mod:`dhfield.core.schema`, on the grid dims ``(beta0, mu)``.
    """
    grid = ("beta0", "mu")
    data = {
        "eq30_area": _var(grid, area, "eq30", "as printed, area integral on the polar grid"),
        "eq30_boundary": _var(grid, boundary, "eq30", "by Green's theorem (boundary integral)"),
        "work_major": _var(grid, work_major, "work_major", "at pull-off"),
        "work_minor": _var(grid, work_minor, "work_minor", "at pull-off"),
        "mean_work": _var(grid, mean_work, "mean_work", "weights r_ab^2 (erratum form), at pull-off"),
    }
    ds = xr.Dataset(data, coords=_coords(mu, beta0))
    ds.attrs.update(provenance_attrs(
        "Eq. (30) of Zini et al. (2018): area vs boundary evaluation; it equals 4[dgamma(0) - dgamma(pi/2)]",
        mu=np.asarray(mu, float), beta0=np.asarray(beta0, float), length_unit=_LENGTH_UNIT))
    return finalize(ds)


def grid_periphery_dataset(theta, analytic, numerical: dict, **parameters) -> xr.Dataset:
    """Dataset comparing analytic and gridded (BEM) ray quantities for one state.

    Parameters
    ----------
    theta : array_like
        Ray angles [rad].
    analytic : dhfield.models.dh_elliptic_periphery.PeripheryProfile
        The analytic ray quantities.
    numerical : dict
        Label -> PeripheryProfile from :func:`dhfield.models.dh_elliptic_periphery.periphery_from_gap_grid`.
    **parameters
        Recorded as attributes (state, grid size, ...).

    Returns
    -------
    xarray.Dataset
        Analytic and numerical quantities on ``theta``, CF metadata from :mod:`dhfield.core.schema`.
    """
    data = {"work_analytic": _var("theta", analytic.work_of_adhesion, "work_of_adhesion", "analytic (Eq. 31)"),
            "edge_separation_analytic": _var("theta", analytic.edge_separation, "edge_separation", "analytic")}
    for label, prof in numerical.items():
        data[f"work_{label}"] = _var("theta", prof.work_of_adhesion, "work_of_adhesion",
                                     f"from the gridded gap ({label})")
        data[f"edge_separation_{label}"] = _var("theta", prof.edge_separation, "edge_separation",
                                                f"from the gridded gap ({label})")
        data[f"contact_edge_gap_{label}"] = _var("theta", prof.contact_edge_gap, "contact_edge_gap",
                                                 f"residual of the contact condition ({label})")
    ds = xr.Dataset(data, coords={"theta": coordinate("theta", theta)})
    ds.attrs.update(provenance_attrs("Ray work of adhesion: analytic vs gridded (BEM) gap", **parameters))
    return finalize(ds)


def load_curve_periphery_dataset(curves: dict, profiles: dict, *, beta0, mu) -> xr.Dataset:
    """Dataset of the ray quantities along load curves.

    Parameters
    ----------
    curves : dict
        (beta0, mu) -> dhfield.core.records.LoadCurve, all on the same a* points.
    profiles : dict
        (beta0, mu) -> dhfield.models.dh_elliptic_periphery.PeripheryProfile of shape (len(a_star), len(theta)).
    beta0, mu : array_like
        1-D grids [-].

    Returns
    -------
    xarray.Dataset
        CF metadata from :mod:`dhfield.core.schema`, on the grid dims ``(beta0, mu)``.
    """
    mu, beta0 = np.asarray(mu, float), np.asarray(beta0, float)
    first = next(iter(profiles.values()))
    theta = np.asarray(first.theta)[0]
    a_star = np.asarray(next(iter(curves.values())).a_star)
    shape = (beta0.size, mu.size, a_star.size)
    data = {}
    for name in ("W_star", "c_star", "v", "delta_star"):
        arr = np.full(shape, np.nan)
        for (b, m), cur in curves.items():
            arr[list(beta0).index(b), list(mu).index(m)] = getattr(cur, name)
        data[name] = _var(("beta0", "mu", "a_star"), arr, name)
    for name in PROFILE_VARIABLES:
        arr = np.full(shape + (theta.size,), np.nan)
        for (b, m), prof in profiles.items():
            arr[list(beta0).index(b), list(mu).index(m)] = getattr(prof, name)
        data[name] = _var(("beta0", "mu", "a_star", "theta"), arr, name, "on the ray theta_p")
    coords = _coords(mu, beta0, theta)
    coords["a_star"] = coordinate("a_star", a_star, nondimensional=True)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        "Elliptical double-Hertz model: quantities along every ray theta_p along load curves",
        model="dh-elliptic", mu=mu, beta0=beta0, n_theta=int(theta.size), length_unit=_LENGTH_UNIT))
    return finalize(ds)


def write_dataset(ds, path) -> Path:
    """Write one of the datasets above atomically (netCDF4).

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset of this module.
    path : path-like
        The netCDF file.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return write_netcdf(ds, path)
