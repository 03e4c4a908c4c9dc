"""xarray Dataset of a side-by-side model comparison (thin wrapper of :mod:`dhfield.compare`)."""
from __future__ import annotations

import numpy as np
import xarray as xr

from . import provenance_attrs

__all__ = ["comparison_dataset", "COMPARISON_VARIABLES"]

#: name -> (long_name, units) of the per-model pull-off variables (Eqs. 32-35)
COMPARISON_VARIABLES = {
    "W_star": ("pull-off load W sin(theta_skew)/(2 pi R dgamma) (Eq. 34)", "1"),
    "a_star": ("contact semi-major axis (radius for the circle) at pull-off, a/c_r (Eq. 32)", "1"),
    "c_star": ("outer adhesive semi-major axis at pull-off, c/c_r (NaN: none in the model)", "1"),
    "v": ("double-Hertz scaling factor v at pull-off (NaN: not a DH model)", "1"),
    "delta_star": ("approach at pull-off, delta R/c_r^2", "1"),
    "ellipticity": ("contact ellipticity b/a at pull-off", "1"),
    "sin_skew": ("sin(theta_skew) used in the load normalisation of Eq. (34)", "1"),
}


def comparison_dataset(records: dict, **extra_attrs) -> xr.Dataset:
    """Dataset on the dimension ``model`` from :func:`dhfield.compare.compare` (scalar mu, beta0)."""
    names = list(records)
    first = records[names[0]]
    data = {k: ("model", np.array([float(records[n][k]) for n in names]), {"long_name": ln, "units": u})
            for k, (ln, u) in COMPARISON_VARIABLES.items()}
    data["geometry"] = ("model", np.array([records[n]["geometry"] for n in names]),
                        {"long_name": "contact geometry of the model (circle or ellipse)"})
    ds = xr.Dataset(data, coords={"model": ("model", np.array(names), {"long_name": "comparison model"})})
    ds.attrs.update(provenance_attrs("Pull-off of the comparison models side by side (Zini et al. 2018, Fig. 9)",
                                     mu=float(first["mu"]), beta0=float(first["beta0"]),
                                     control=first["control"],
                                     mu_to_lambda="lambda = 2 (9/(16 pi))^(1/3) mu", **extra_attrs))
    return ds
