"""xarray Datasets for the theta_p dependence, Eq. (30) and the equal-beta test.

Thin wrappers around the numpy results of :mod:`dhfield.periphery`,
:mod:`dhfield.eq30` and :mod:`dhfield.closure`.  Every variable and coordinate
carries ``long_name`` and ``units`` (CF; ``"1"`` for dimensionless), the global
attributes carry the provenance (:func:`dhfield.io.provenance_attrs`) and every
input parameter.  All quantities are nondimensional in the paper's units
(R = E* = Delta gamma = 1, Eqs. 32-35) unless a ``units`` attribute says otherwise.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from . import provenance_attrs, write_netcdf

__all__ = [
    "PROFILE_VARIABLES",
    "pull_off_periphery_dataset",
    "equal_beta_dataset",
    "eq30_dataset",
    "grid_periphery_dataset",
    "load_curve_periphery_dataset",
    "write_dataset",
]

#: name -> (long_name, units) of the ray quantities of dhfield.periphery.PeripheryProfile.
PROFILE_VARIABLES = {
    "contact_radius": ("contact-ellipse radius r_ab on the ray (Eq. A1), in c_r", "1"),
    "adhesive_radius": ("adhesive-ellipse radius r_cd on the ray (Eq. A2), in c_r", "1"),
    "zone_width": ("adhesive-zone width r_cd - r_ab on the ray, in c_r", "1"),
    "max_adhesive_stress": ("adhesive stress at the contact edge sigma0(theta_p) (Eq. 24), in E* c_r/R", "1"),
    "edge_separation": ("gap at the adhesive edge h(r_cd, theta_p) (Eq. 27), in c_r^2/R", "1"),
    "work_of_adhesion": ("work of adhesion along the ray int sigma dh (Eq. 31 on every ray), in dgamma", "1"),
    "contact_edge_gap": ("gap at the contact edge h(r_ab, theta_p), in c_r^2/R", "1"),
}

_THETA_ATTRS = {"long_name": "polar angle theta_p of the ray, 0 on the major axis (Eqs. A3-A4)",
                "units": "rad"}
_MU_ATTRS = {"long_name": "Tabor parameter mu (Eq. 35)", "units": "1"}
_BETA0_ATTRS = {"long_name": "initial (Hertz) ellipticity beta0 = b/a (Eq. 19)", "units": "1"}
_LENGTH_UNIT = "c_r = (R^2 dgamma/E*)^(1/3) (Eq. 33)"


def _coords(mu, beta0, theta=None):
    c = {"beta0": ("beta0", np.asarray(beta0, float), dict(_BETA0_ATTRS)),
         "mu": ("mu", np.asarray(mu, float), dict(_MU_ATTRS))}
    if theta is not None:
        c["theta"] = ("theta", np.asarray(theta, float), dict(_THETA_ATTRS))
    return c


def _var(dims, arr, long_name, units="1"):
    return (dims, np.asarray(arr, float), {"long_name": long_name, "units": units})


def pull_off_periphery_dataset(mu, beta0, pull_off, profile, law=None, *, control="load") -> xr.Dataset:
    """Dataset of the ray quantities at pull-off on a (beta0, mu) grid.

    Parameters
    ----------
    mu, beta0 : array_like
        1-D grids [-]; ``pull_off`` and ``profile`` have shape (len(beta0), len(mu)).
    pull_off : dhfield.model.PullOff
    profile : dhfield.periphery.PeripheryProfile
        Shape (len(beta0), len(mu), len(theta)).
    law : dhfield.periphery.CohesiveLaw, optional
        sigma-h curves, shape (len(beta0), len(mu), n_law_theta, n_sample).
    control : str
        Pull-off control mode (recorded).
    """
    theta = np.asarray(profile.theta)[0, 0]
    data = {name: _var(("beta0", "mu", "theta"), getattr(profile, name), ln, u)
            for name, (ln, u) in PROFILE_VARIABLES.items()}
    data["W_star"] = _var(("beta0", "mu"), pull_off.W_star,
                          "pull-off load W sin(theta_skew)/(2 pi R dgamma) (Eq. 34)")
    data["a_star"] = _var(("beta0", "mu"), pull_off.a_star, "contact semi-major axis at pull-off, in c_r")
    data["c_star"] = _var(("beta0", "mu"), pull_off.c_star, "adhesive semi-major axis at pull-off, in c_r")
    data["v"] = _var(("beta0", "mu"), pull_off.v, "double-Hertz scaling factor v at pull-off (Eq. 22)")
    w = np.asarray(profile.work_of_adhesion)
    data["work_ratio"] = _var(("beta0", "mu"), w[..., -1] / w[..., 0],
                              "work of adhesion ratio dgamma(pi/2)/dgamma(0) at pull-off")
    coords = _coords(mu, beta0, theta)
    if law is not None:
        lt = np.asarray(law.theta)[0, 0, :, 0]
        coords["law_theta"] = ("law_theta", lt, {"long_name": "ray angle of the sigma-h curves",
                                                 "units": "rad"})
        coords["sample"] = ("sample", np.arange(np.shape(law.separation)[-1]),
                            {"long_name": "sample index along the ray, contact edge to adhesive edge",
                             "units": "1"})
        dims = ("beta0", "mu", "law_theta", "sample")
        data["law_separation"] = _var(dims, law.separation, "gap h along the ray (Eq. 27), in c_r^2/R")
        data["law_stress"] = _var(dims, law.stress, "tensile adhesive stress along the ray (Eq. 23), in E* c_r/R")
        data["law_radius"] = _var(dims, law.radius, "radius r along the ray, in c_r")
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        "Elliptical double-Hertz model: quantities along every ray theta_p at pull-off (Zini et al. 2018)",
        model="dh-elliptic", control=control, mu=np.asarray(mu, float), beta0=np.asarray(beta0, float),
        n_theta=int(theta.size), length_unit=_LENGTH_UNIT))
    return ds


def equal_beta_dataset(mu, beta0, spread, closures: dict, *, control="load") -> xr.Dataset:
    """Dataset of the equal-beta test and of the closures' pull-off points.

    Parameters
    ----------
    mu, beta0 : array_like
        1-D grids; arrays have shape (len(beta0), len(mu)).
    spread : dhfield.closure.EqualBetaSpread
    closures : dict
        name -> dhfield.closure.ClosureState at pull-off (e.g. "paper",
        "ray_average", "two_axis").
    """
    names = list(closures)
    data = {
        "work_ratio": _var(("beta0", "mu"), spread.work_ratio, "dgamma(pi/2)/dgamma(0) at pull-off, paper's model"),
        "work_spread": _var(("beta0", "mu"), spread.work_spread, "(max - min)/mean of dgamma(theta_p) at pull-off"),
        "mean_work": _var(("beta0", "mu"), spread.mean_work,
                          "periphery average of dgamma(theta_p), weights r_ab^2, in dgamma"),
        "law_spread": _var(("beta0", "mu"), spread.law_spread,
                           "max over theta_p of int |sigma_theta(h) - sigma_0(h)| dh / dgamma(0)"),
        "law_sup_spread": _var(("beta0", "mu"), spread.law_sup_spread,
                               "max over theta_p, h of |sigma_theta(h) - sigma_0(h)| / sigma0"),
        "separation_ratio": _var(("beta0", "mu"), spread.separation_ratio,
                                 "edge separation h(r_cd) minor axis / major axis"),
        "width_ratio": _var(("beta0", "mu"), spread.width_ratio, "zone width minor axis / major axis"),
    }
    fields = {
        "W_star": "pull-off load W sin(theta_skew(beta0))/(2 pi R dgamma) (Eq. 34)",
        "a_star": "contact semi-major axis at pull-off, in c_r",
        "c_star": "adhesive semi-major axis at pull-off, in c_r",
        "beta_contact": "contact ellipticity b/a at pull-off",
        "beta_adhesive": "adhesive ellipticity d/c at pull-off",
        "work_major": "dgamma(0) at pull-off, in dgamma",
        "work_minor": "dgamma(pi/2) at pull-off, in dgamma",
        "sigma0_minor": "adhesive stress at the contact edge on the minor axis, in E* c_r/R",
    }
    for key, ln in fields.items():
        arr = np.stack([np.asarray(getattr(closures[n], key), float) for n in names], axis=0)
        data[f"closure_{key}"] = _var(("closure", "beta0", "mu"), arr, ln)
    coords = _coords(mu, beta0)
    coords["closure"] = ("closure", np.array(names, dtype=str),
                         {"long_name": "closure: paper = Eqs. 17-19, 31; ray_average = mean dgamma = 1; "
                                       "two_axis = dgamma = 1 on both axes, beta_cd != beta_ab"})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        "Equal-beta test and alternative closures of the elliptical double-Hertz model",
        control=control, mu=np.asarray(mu, float), beta0=np.asarray(beta0, float),
        closures=",".join(names), length_unit=_LENGTH_UNIT))
    return ds


def eq30_dataset(mu, beta0, area, boundary, work_major, work_minor, mean_work) -> xr.Dataset:
    """Dataset of Eq. (30) (area and Green's forms) next to the ray works, at pull-off."""
    data = {
        "eq30_area": _var(("beta0", "mu"), area, "Eq. (30) as printed, area integral on the polar grid"),
        "eq30_boundary": _var(("beta0", "mu"), boundary, "Eq. (30) by Green's theorem (boundary integral)"),
        "work_major": _var(("beta0", "mu"), work_major, "dgamma(0), Eq. (31), in dgamma"),
        "work_minor": _var(("beta0", "mu"), work_minor, "dgamma(pi/2), Eq. (31) on the minor axis, in dgamma"),
        "mean_work": _var(("beta0", "mu"), mean_work,
                          "periphery average of dgamma(theta_p), weights r_ab^2 (erratum form), in dgamma"),
    }
    ds = xr.Dataset(data, coords=_coords(mu, beta0))
    ds.attrs.update(provenance_attrs(
        "Eq. (30) of Zini et al. (2018): area vs boundary evaluation; it equals 4[dgamma(0) - dgamma(pi/2)]",
        mu=np.asarray(mu, float), beta0=np.asarray(beta0, float), length_unit=_LENGTH_UNIT))
    return ds


def grid_periphery_dataset(theta, analytic, numerical: dict, **parameters) -> xr.Dataset:
    """Dataset comparing analytic and gridded (BEM) ray quantities for one state.

    Parameters
    ----------
    theta : array_like
        Ray angles [rad].
    analytic : dhfield.periphery.PeripheryProfile
    numerical : dict
        label -> PeripheryProfile from :func:`dhfield.periphery.periphery_from_gap_grid`.
    **parameters
        Recorded as attributes (state, grid size, ...).
    """
    data = {"work_analytic": _var("theta", analytic.work_of_adhesion, "dgamma(theta_p), analytic (Eq. 31)"),
            "edge_separation_analytic": _var("theta", analytic.edge_separation, "h(r_cd), analytic (Eq. 27)")}
    for label, prof in numerical.items():
        data[f"work_{label}"] = _var("theta", prof.work_of_adhesion, f"dgamma(theta_p) from the gridded gap ({label})")
        data[f"edge_separation_{label}"] = _var("theta", prof.edge_separation,
                                                f"h(r_cd) from the gridded gap ({label})")
        data[f"contact_edge_gap_{label}"] = _var("theta", prof.contact_edge_gap,
                                                 f"h(r_ab), residual of the contact condition ({label})")
    ds = xr.Dataset(data, coords={"theta": ("theta", np.asarray(theta, float), dict(_THETA_ATTRS))})
    ds.attrs.update(provenance_attrs("Ray work of adhesion: analytic vs gridded (BEM) gap", **parameters))
    return ds


def load_curve_periphery_dataset(mu, beta0, curves: dict, profiles: dict) -> xr.Dataset:
    """Dataset of the ray quantities along load curves.

    Parameters
    ----------
    mu, beta0 : array_like
        1-D grids.
    curves : dict
        (beta0, mu) -> dhfield.model.LoadCurve, all on the same a* points.
    profiles : dict
        (beta0, mu) -> dhfield.periphery.PeripheryProfile of shape (len(a_star), len(theta)).
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
        data[name] = _var(("beta0", "mu", "a_star"), arr, {
            "W_star": "load W sin(theta_skew)/(2 pi R dgamma) (Eq. 34)",
            "c_star": "adhesive semi-major axis, in c_r", "v": "double-Hertz scaling factor v (Eq. 22)",
            "delta_star": "approach, in c_r^2/R"}[name])
    for name, (ln, u) in PROFILE_VARIABLES.items():
        arr = np.full(shape + (theta.size,), np.nan)
        for (b, m), prof in profiles.items():
            arr[list(beta0).index(b), list(mu).index(m)] = getattr(prof, name)
        data[name] = _var(("beta0", "mu", "a_star", "theta"), arr, ln, u)
    coords = _coords(mu, beta0, theta)
    coords["a_star"] = ("a_star", a_star, {"long_name": "contact semi-major axis a/c_r (Eq. 32)", "units": "1"})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        "Elliptical double-Hertz model: quantities along every ray theta_p along load curves",
        model="dh-elliptic", mu=mu, beta0=beta0, n_theta=int(theta.size), length_unit=_LENGTH_UNIT))
    return ds


def write_dataset(ds, path) -> Path:
    """Write one of the datasets above atomically (netCDF4)."""
    return write_netcdf(ds, path)
