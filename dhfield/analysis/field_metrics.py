"""Error metrics of a BEM field against the analytic one: regions, statistics, the annulus identity.

Regions of the contact (:func:`region_masks`), error statistics of a numerical field
against its analytic value per region (:func:`compare`), and the double-Hertz check
h = (1 + v) h_Hertz in the adhesive annulus along every ray (:func:`annulus_identity`,
Eq. 27 with Eqs. A1, A2).
"""
from __future__ import annotations

import numpy as np
from scipy import ndimage

from ..models import hertz

__all__ = ["region_masks", "compare", "annulus_identity"]


def region_masks(x, y, semi_major, beta, adhesive_semi_major=None):
    """Compute boolean masks of the contact ellipse, the adhesive annulus and the outside.

    Parameters
    ----------
    x, y : array_like
        Points [m] (e.g. ``grid.mesh()``).
    semi_major : float
        Contact semi-major axis a [m].
    beta : float
        Common ellipticity [-].
    adhesive_semi_major : float, optional
        Adhesive semi-major axis c [m]; without it the annulus is empty.

    Returns
    -------
    dict
        ``{"contact": ..., "annulus": ..., "outside": ...}``; points on an ellipse
        belong to the inner region.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    rho_ab = (x / semi_major) ** 2 + (y / (beta * semi_major)) ** 2
    contact = rho_ab <= 1.0
    if adhesive_semi_major is None:
        return {"contact": contact, "annulus": np.zeros_like(contact), "outside": ~contact}
    c = adhesive_semi_major
    inside_cd = (x / c) ** 2 + (y / (beta * c)) ** 2 <= 1.0
    return {"contact": contact, "annulus": inside_cd & ~contact, "outside": ~inside_cd}


def compare(numerical, analytic, masks=None, scale=None) -> dict:
    """Compute error statistics of ``numerical - analytic``, overall and per region.

    Parameters
    ----------
    numerical, analytic : array_like
        Same shape.
    masks : dict of str -> bool array, optional
        Regions (e.g. from :func:`region_masks`); "all" is always added.
    scale : float, optional
        Normalisation of the relative errors; default ``max|analytic|``.

    Returns
    -------
    dict
        ``{region: {"max": max|e|, "rms": sqrt(mean e^2), "rel_max": max|e|/scale,
        "rel_rms": rms/scale, "count": n}}``; NaN entries for empty regions.
    """
    num = np.asarray(numerical, dtype=float)
    ana = np.asarray(analytic, dtype=float)
    if num.shape != ana.shape:
        raise ValueError(f"numerical and analytic must have the same shape; got {num.shape} and {ana.shape}")
    err = num - ana
    if scale is None:
        scale = float(np.max(np.abs(ana)))
    regions = {"all": np.ones(err.shape, dtype=bool)}
    regions.update(masks or {})
    out = {}
    for name, m in regions.items():
        m = np.asarray(m, dtype=bool)
        if m.shape != err.shape:
            raise ValueError(f"mask {name!r} must have shape {err.shape}; got {m.shape}")
        e = err[m]
        if e.size == 0:
            mx = rms = float("nan")
        else:
            mx = float(np.max(np.abs(e)))
            rms = float(np.sqrt(np.mean(e * e)))
        out[name] = {"max": mx, "rms": rms, "rel_max": mx / scale, "rel_rms": rms / scale,
                     "count": int(e.size)}
    return out


def annulus_identity(case, n_theta=91, n_r=64):
    """Check h_BEM = (1 + v) h_Hertz in the adhesive annulus along every theta_p.

    The numerical gap is interpolated (cubic splines) onto rays
    ``theta_p in [0, pi/2]`` at ``n_r`` radii strictly between ``r_ab(theta_p)``
    and ``r_cd(theta_p)`` (Eqs. A1, A2), and compared with ``(1 + v)`` times the
    analytic Hertz gap of the contact ellipse (:func:`dhfield.models.hertz.gap`).

    Parameters
    ----------
    case : dhfield.analysis.fields.FieldCase
        A DH case (:func:`dhfield.analysis.fields.dh_case` or :func:`dhfield.analysis.fields.model_case`).
    n_theta : int, default 91
        Number of rays [-].
    n_r : int, default 64
        Radii per ray [-].

    Returns
    -------
    dict
        ``theta_p`` [rad]; ``max_error`` per ray [m]; ``rel_error`` per ray
        (divided by the largest ``(1 + v) h_H`` in the annulus); ``worst``.
    """
    prm = case.parameters
    a, c, beta, v = prm["semi_major"], prm["adhesive_semi_major"], prm["beta"], prm["scaling"]
    r_, e_ = prm["effective_radius"], prm["reduced_modulus"]
    theta = np.linspace(0.0, 0.5 * np.pi, int(n_theta))
    ct, st = np.cos(theta), np.sin(theta)
    b, d = beta * a, beta * c
    r_ab = a * b / np.sqrt((b * ct) ** 2 + (a * st) ** 2)  # Eq. (A1)
    r_cd = c * d / np.sqrt((d * ct) ** 2 + (c * st) ** 2)  # Eq. (A2)
    s = (np.arange(n_r) + 0.5) / n_r
    rr = r_ab[None, :] + s[:, None] * (r_cd - r_ab)[None, :]
    x, y = rr * ct[None, :], rr * st[None, :]
    g = case.grid
    fi = (x - g.x[0]) / g.dx
    fj = (y - g.y[0]) / g.dy
    h_num = ndimage.map_coordinates(case.gap_numerical, [fi, fj], order=3, mode="reflect")
    h_ref = (1.0 + v) * hertz.gap(x, y, a, beta, r_, e_)
    err = np.max(np.abs(h_num - h_ref), axis=0)
    scale = float(np.max(np.abs(h_ref)))
    return {"theta_p": theta, "max_error": err, "rel_error": err / scale, "worst": float(np.max(err / scale)),
            "scale": scale}
