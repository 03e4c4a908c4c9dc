"""Resampling of a cell-centred Cartesian field onto polar points (r, theta_p).

The paper's fields are written along rays theta_p from the major axis (Eqs. A1, A2);
the BEM gives them on a Cartesian grid.  :func:`polar_grid` makes the rays,
:func:`to_polar` interpolates a grid field onto them (cubic splines).
"""
from __future__ import annotations

import numpy as np
from scipy import ndimage

from .. import bem
from ..core.validation import check_positive

__all__ = ["polar_grid", "to_polar"]


def polar_grid(r_max, n_r=200, n_theta=91, theta_max=0.5 * np.pi):
    """Return radii ``[0, r_max]`` [m] and angles ``theta_p in [0, theta_max]`` [rad].

    Parameters
    ----------
    r_max : float
        Largest radius [m].
    n_r : int, default 200
        Number of radii.
    n_theta : int, default 91
        Number of angles.
    theta_max : float, default pi/2
        Largest angle [rad].

    Returns
    -------
    r : ndarray
        1-D radii [m].
    theta_p : ndarray
        1-D angles [rad].
    """
    r_max = float(check_positive("r_max", r_max, "m"))
    return np.linspace(0.0, r_max, int(n_r)), np.linspace(0.0, float(theta_max), int(n_theta))


def to_polar(field, grid: bem.Grid, r, theta_p, order=3):
    """Interpolate a cell-centred Cartesian field onto polar points ``(r, theta_p)``.

    Parameters
    ----------
    field : array_like
        Shape ``grid.shape``.
    grid : dhfield.bem.Grid
        The grid the field lives on.
    r, theta_p : array_like
        1-D radii [m] and polar angles from the x axis [rad]; the result has
        shape ``(len(r), len(theta_p))``.
    order : int, default 3
        Spline order of :func:`scipy.ndimage.map_coordinates`.

    Returns
    -------
    ndarray
        The field at ``x = r cos theta_p, y = r sin theta_p``; NaN outside the
        hull of the cell centres.

    Notes
    -----
    The spline's boundary condition (``mode="reflect"``) perturbs it near the
    domain edge by an amount that decays like 0.27^k at k cells from the edge.
    """
    f = np.asarray(field, dtype=float)
    if f.shape != grid.shape:
        raise ValueError(f"field must have the grid shape {grid.shape}; got {f.shape}")
    r = np.asarray(r, dtype=float)
    t = np.asarray(theta_p, dtype=float)
    x = r[:, None] * np.cos(t)[None, :]
    y = r[:, None] * np.sin(t)[None, :]
    fi = (x - grid.x[0]) / grid.dx
    fj = (y - grid.y[0]) / grid.dy
    out = ndimage.map_coordinates(f, [fi, fj], order=order, mode="reflect")
    inside = (fi >= 0) & (fi <= grid.nx - 1) & (fj >= 0) & (fj <= grid.ny - 1)
    return np.where(inside, out, np.nan)
