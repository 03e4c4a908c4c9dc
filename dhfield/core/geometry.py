"""Geometry of two equal elastic cylinders crossed at an angle (Eqs. 2-6).

Axis convention used throughout dhfield: x is the direction of the *larger*
principal relative radius R' (the major axis a of the contact ellipse, theta_p = 0)
and y the direction of R'' (minor axis b, theta_p = pi/2), so that the initial gap
is z = x^2/(2R') + y^2/(2R'') (Eq. 2) with R' >= R''.

The Hertz ellipticity beta = b/a belongs to the radius ratio R'/R'' through

.. math::

    \\frac{R'}{R''} = \\frac{\\mathbf{E}(k)/\\beta^2 - \\mathbf{K}(k)}{\\mathbf{K}(k) - \\mathbf{E}(k)}
                    = \\frac{R_D(0, 1, \\beta^2)}{R_D(0, \\beta^2, 1)},

the ratio of the two curvature conditions behind Eq. (8) (Eqs. 14b, 14c).  The
Carlson form on the right is exact at the circle (ratio 1).  With Eqs. (3)-(4),
cos(theta_skew) = (rho - 1)/(rho + 1), rho = R'/R''.
"""
from __future__ import annotations

import numpy as np
from scipy import special
from scipy.optimize import elementwise

from .validation import check_ellipticity, check_interval, check_positive

__all__ = [
    "principal_radii",
    "effective_radius",
    "reduced_modulus",
    "radius_ratio",
    "ellipticity_from_radius_ratio",
    "skew_angle",
    "ellipticity_from_skew_angle",
    "sin_skew_angle",
]


def principal_radii(cylinder_radius, skew_angle, *, checked=True):
    """Principal relative radii R', R'' of two crossed cylinders, Eqs. (3)-(4).

    Parameters
    ----------
    cylinder_radius : array_like
        Radius R_c of each of the two (equal) cylinders [m].
    skew_angle : array_like
        Crossing angle theta_skew between the cylinder axes, in (0, pi/2] [rad].
    checked : bool, default True
        Validate the inputs; False for internal callers that validated them once at their
        public entry (:mod:`dhfield.analysis.dimensional`).

    Returns
    -------
    r_major : ndarray
        R' = R_c/(1 - cos theta_skew) [m].
    r_minor : ndarray
        R'' = R_c/(1 + cos theta_skew) [m].

    Examples
    --------
    Perpendicular cylinders (theta_skew = pi/2) are a sphere of radius R_c: R' = R'' = R_c.

    >>> import numpy as np
    >>> from dhfield.core import geometry
    >>> [round(float(r), 12) for r in geometry.principal_radii(5e-3, np.pi / 2)]
    [0.005, 0.005]
    """
    if checked:
        rc = check_positive("cylinder_radius", cylinder_radius, "m")
        th = check_interval("skew_angle", skew_angle, 0.0, np.pi / 2, what="rad")
    else:
        rc, th = np.asarray(cylinder_radius, dtype=float), np.asarray(skew_angle, dtype=float)
    # 1 - cos = 2 sin^2(theta/2): no cancellation at small crossing angles.
    with np.errstate(over="ignore"):  # R' = inf for extreme inputs: the caller's range check names them
        return rc / (2.0 * np.sin(0.5 * th) ** 2), rc / (1.0 + np.cos(th))  # Eq. (3), Eq. (4)


def effective_radius(r_major, r_minor, *, checked=True):
    """Equivalent radius R = sqrt(R' R''), Eq. (5).

    Parameters
    ----------
    r_major, r_minor : array_like
        Principal relative radii R' and R'' > 0 [m].
    checked : bool, default True
        Validate the inputs; False for internal callers that validated them once at their
        public entry (:mod:`dhfield.analysis.dimensional`).

    Returns
    -------
    ndarray
        R [m].

    Examples
    --------
    >>> from dhfield.core import geometry
    >>> float(geometry.effective_radius(4.0, 1.0))
    2.0
    """
    if checked:
        r1 = check_positive("r_major", r_major, "m")
        r2 = check_positive("r_minor", r_minor, "m")
    else:
        r1, r2 = np.asarray(r_major, dtype=float), np.asarray(r_minor, dtype=float)
    return np.sqrt(r1 * r2)  # Eq. (5)


def reduced_modulus(e1, nu1, e2, nu2, *, checked=True):
    """Reduced Young's modulus E* of Eq. (6) [Pa].

    Parameters
    ----------
    e1 : array_like
        Young's modulus of body 1 [Pa].
    nu1 : array_like
        Poisson's ratio of body 1, in (-1, 0.5] [-].
    e2 : array_like
        Young's modulus of body 2 [Pa].
    nu2 : array_like
        Poisson's ratios, in (-1, 0.5] [-].
    checked : bool, default True
        Validate the inputs; False for internal callers that validated them once at their
        public entry (:mod:`dhfield.analysis.dimensional`).

    Returns
    -------
    ndarray
        E* = 1/((1 - nu1^2)/e1 + (1 - nu2^2)/e2) [Pa].

    Examples
    --------
    Two PDMS bodies, E = 2 MPa, nu = 0.5: E* = E/(2(1 - nu^2)).

    >>> from dhfield.core import geometry
    >>> float(geometry.reduced_modulus(2e6, 0.5, 2e6, 0.5)) / 1e6
    1.3333333333333333
    """
    if checked:
        e1 = check_positive("e1", e1, "Pa")
        e2 = check_positive("e2", e2, "Pa")
        nu1 = check_interval("nu1", nu1, -1.0, 0.5, what="Poisson's ratio")
        nu2 = check_interval("nu2", nu2, -1.0, 0.5, what="Poisson's ratio")
    else:
        e1, nu1, e2, nu2 = (np.asarray(x, dtype=float) for x in (e1, nu1, e2, nu2))
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)  # Eq. (6)


def _radius_ratio(beta):
    b2 = np.asarray(beta, dtype=float) ** 2
    with np.errstate(invalid="ignore", divide="ignore", under="ignore"):  # beta -> 0: inf/inf, rejected by callers
        return special.elliprd(0.0, 1.0, b2) / special.elliprd(0.0, b2, 1.0)


def radius_ratio(beta, *, checked=True):
    """The radius ratio R'/R'' that gives the Hertz ellipticity ``beta`` (Eqs. 8, 14).

    Parameters
    ----------
    beta : array_like
        Ellipticity ratio b/a in (0, 1] [-].
    checked : bool, default True
        Validate ``beta``; False for internal callers that validated their inputs once
        at their public entry and evaluate intermediate values (the closure solves).

    Returns
    -------
    ndarray
        R'/R'' >= 1 [-]; exactly 1 at beta = 1.

    Examples
    --------
    >>> from dhfield.core import geometry
    >>> float(geometry.radius_ratio(1.0))
    1.0
    """
    return _radius_ratio(check_ellipticity("beta", beta) if checked else beta)


def ellipticity_from_radius_ratio(ratio, *, checked=True):
    """Inverse of :func:`radius_ratio`: the Hertz beta for R'/R'' >= 1.

    Solved element-wise with a bracketing root finder in log(beta), to
    ~1e-15 relative.

    Parameters
    ----------
    ratio : array_like
        Radius ratio R'/R'' >= 1 [-].
    checked : bool, default True
        Validate ``ratio``; False for internal callers whose ratio is an intermediate
        value already known to be finite and >= 1 (the two-axis closure solve).

    Returns
    -------
    ndarray or float
        Ellipticity beta = b/a in (0, 1] [-]; exactly 1 at ratio = 1.

    Examples
    --------
    >>> from dhfield.core import geometry
    >>> round(float(geometry.ellipticity_from_radius_ratio(geometry.radius_ratio(0.8))), 12)
    0.8
    """
    if checked:
        ratio = check_interval("ratio", ratio, 1.0, np.inf, low_open=False, high_open=True,
                               what="R'/R'', dimensionless")
    rho = np.asarray(ratio, dtype=float)
    out = np.ones_like(rho)
    mask = rho > 1.0
    if np.any(mask):
        # log(rho) as a function of log(beta): decreasing; beta ~ rho^(-2/3) for large rho.
        target = np.log(rho[mask])

        def f(lb, t):
            return np.log(_radius_ratio(np.exp(lb))) - t

        lo = np.full_like(target, np.log(1e-12))
        res = elementwise.find_root(f, (lo, np.zeros_like(target)), args=(target,),
                                    tolerances=dict(xatol=1e-16, xrtol=1e-15))
        out[mask] = np.exp(res.x)
    return out if out.ndim else out[()]


def skew_angle(beta, *, checked=True):
    """Crossing angle theta_skew of equal cylinders giving Hertz ellipticity ``beta``.

    From Eqs. (3)-(4): cos(theta_skew) = (rho - 1)/(rho + 1), rho = R'/R''.

    Parameters
    ----------
    beta : array_like
        Ellipticity b/a in (0, 1] [-].
    checked : bool, default True
        Validate ``beta`` (:func:`radius_ratio`); False on inputs validated once already.

    Returns
    -------
    ndarray
        The crossing angle in (0, pi/2] [rad]; pi/2 (perpendicular cylinders) at beta = 1.

    Examples
    --------
    >>> import numpy as np
    >>> from dhfield.core import geometry
    >>> round(float(np.rad2deg(geometry.skew_angle(0.8))), 2)
    80.45
    """
    rho = radius_ratio(beta, checked=checked)
    return np.arccos((rho - 1.0) / (rho + 1.0))


def sin_skew_angle(beta, *, checked=True):
    """Sine of the crossing angle, sin(theta_skew), for Hertz ellipticity ``beta``.

    The factor of Eqs. (34) and (36), computed as 2 sqrt(rho)/(1 + rho), rho =
    R'/R'', which is exactly 1 at the circle.

    Parameters
    ----------
    beta : array_like
        Ellipticity b/a in (0, 1] [-].
    checked : bool, default True
        Validate ``beta`` (:func:`radius_ratio`); False on inputs validated once already.

    Returns
    -------
    ndarray
        The sine, in (0, 1] [-].
    """
    rho = radius_ratio(beta, checked=checked)
    return 2.0 * np.sqrt(rho) / (1.0 + rho)


def ellipticity_from_skew_angle(skew_angle):
    """Hertz ellipticity beta of equal cylinders crossed at ``skew_angle``.

    Parameters
    ----------
    skew_angle : array_like
        Crossing angle theta_skew in (0, pi/2] [rad].

    Returns
    -------
    ndarray or float
        The ellipticity b/a in (0, 1] [-] (Eqs. 3-4 and 8).

    Examples
    --------
    >>> import numpy as np
    >>> from dhfield.core import geometry
    >>> round(float(geometry.ellipticity_from_skew_angle(np.deg2rad(60))), 3)
    0.483
    """
    th = check_interval("skew_angle", skew_angle, 0.0, np.pi / 2, what="rad")
    cos = np.cos(th)
    rho = (1.0 + cos) / np.maximum(1.0 - cos, np.finfo(float).tiny)
    return ellipticity_from_radius_ratio(np.maximum(rho, 1.0))
