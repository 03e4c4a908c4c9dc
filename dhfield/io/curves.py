"""xarray Datasets and files for load curves and pull-off tables (thin wrappers)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import xarray as xr

from . import atomic_path, provenance_attrs, write_netcdf

__all__ = ["load_curve_dataset", "pull_off_dataset", "write_load_curve", "CURVE_VARIABLES"]

#: name -> (long_name, units) of the nondimensional curve variables (Eqs. 32-36).
CURVE_VARIABLES = {
    "a_star": ("contact semi-major axis a/c_r (Eq. 32)", "1"),
    "b_star": ("contact semi-minor axis b/c_r (Eq. 32)", "1"),
    "c_star": ("adhesive semi-major axis c/c_r (Eq. 32)", "1"),
    "d_star": ("adhesive semi-minor axis d/c_r (Eq. 32)", "1"),
    "v": ("double-Hertz scaling factor v (Eq. 22)", "1"),
    "W_star": ("normalised load W sin(theta_skew)/(2 pi R dgamma) (Eq. 34)", "1"),
    "delta_star": ("normalised approach delta R/c_r^2", "1"),
}


def load_curve_dataset(curve, **extra_attrs) -> xr.Dataset:
    """Dataset of a :class:`dhfield.model.LoadCurve` on the dimension ``point``."""
    data = {}
    for name, (long_name, units) in CURVE_VARIABLES.items():
        data[name] = ("point", np.asarray(getattr(curve, name)), {"long_name": long_name, "units": units})
    ds = xr.Dataset(data, coords={"point": ("point", np.arange(len(curve.a_star)),
                                            {"long_name": "curve point index", "units": "1"})})
    ds.attrs.update(provenance_attrs("Elliptical double-Hertz load curve (Zini et al. 2018, Eqs. 31-36)",
                                     model="dh-elliptic", mu=curve.mu, beta0=curve.beta0,
                                     ellipticity=curve.ellipticity,
                                     length_unit="c_r = (R^2 dgamma/E*)^(1/3)", **extra_attrs))
    return ds


def pull_off_dataset(mu, beta0, results: dict, **extra_attrs) -> xr.Dataset:
    """Dataset of pull-off results on a (mu, beta0) grid.

    ``results`` maps variable name -> array of shape (len(mu), len(beta0)); names
    in :data:`CURVE_VARIABLES` get their metadata.
    """
    coords = {
        "mu": ("mu", np.asarray(mu, float), {"long_name": "Tabor parameter (Eq. 35)", "units": "1"}),
        "beta0": ("beta0", np.asarray(beta0, float), {"long_name": "initial ellipticity b/a (Eq. 9)", "units": "1"}),
    }
    data = {}
    for name, arr in results.items():
        long_name, units = CURVE_VARIABLES.get(name, (name, "1"))
        data[name] = (("mu", "beta0"), np.asarray(arr, float), {"long_name": f"{long_name} at pull-off",
                                                               "units": units})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs("Pull-off of the elliptical double-Hertz model", **extra_attrs))
    return ds


def write_load_curve(curve, path, **extra_attrs) -> Path:
    """Write a load curve to ``.nc`` (netCDF4 via xarray) or ``.csv``, atomically."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".nc":
        return write_netcdf(load_curve_dataset(curve, **extra_attrs), p)
    if suffix == ".csv":
        names = list(CURVE_VARIABLES)
        with atomic_path(p) as tmp:
            with open(tmp, "w", newline="") as fh:
                fh.write(f"# dhfield elliptical double-Hertz load curve; mu={curve.mu!r} beta0={curve.beta0!r} "
                         f"ellipticity={curve.ellipticity!r}; nondimensional (Eqs. 32-36)\n")
                w = csv.writer(fh)
                w.writerow(names)
                cols = [np.asarray(getattr(curve, n)) for n in names]
                for row in zip(*cols):
                    w.writerow([repr(float(x)) for x in row])
        return p
    raise ValueError(f"output file must end in .nc or .csv; got {str(p)!r}")
