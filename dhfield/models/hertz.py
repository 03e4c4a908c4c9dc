"""Non-adhesive elliptical Hertz contact (Eqs. 7-15, Appendix 2).

Conventions
-----------
* x along the major semi-axis ``a`` (theta_p = 0), y along the minor semi-axis
  ``b = beta a`` (theta_p = pi/2); see :mod:`dhfield.core.geometry`.
* Pressure is positive in compression.  Surface displacement ``omega`` is the
  combined normal displacement of both surfaces, positive when the surfaces move
  towards each other's interior (the convention of Eq. 12), so that the gap is
  ``h = z - delta + omega``.
* SI units at the boundary; with R = E* = 1 every function is already
  nondimensional in the units of Eqs. (32)-(33).

Eqs. (8), (11) and (14)-(15) are evaluated through Carlson's symmetric integrals
(:mod:`dhfield.core.elliptic`).  They are algebraically identical to the Legendre forms
printed in the paper (tests compare both) and remain exact at the circle beta = 1,
where the printed forms are 0/0.

Paper notes
-----------
* Eq. (14a) writes ``L_in = delta = pi Po b K(k)``; dimensionally ``L_in`` is
  ``pi E* delta``, i.e. the approach is ``delta = Po b K(k)/E*`` (Eq. 13a at r = 0).
"""
from __future__ import annotations

import numpy as np
from scipy import special

from ..core.validation import check_ellipticity, check_finite, check_positive
from ..core.elliptic import complete_k, ellipsoid_integrals
from ..core.geometry import radius_ratio
from ..core._docstrings import fill_doc

__all__ = [
    "max_pressure",
    "load_factor",
    "load",
    "approach",
    "pressure",
    "ellipse_root",
    "displacement_coefficients",
    "surface_displacement",
    "surface_displacement_gradient",
    "gap",
    "principal_radii_from_ellipticity",
]


def _pressure_factor(beta):
    """kappa(beta) = Po_ab/a for R = E* = 1: 3/(2 beta sqrt(R_D(0,b^2,1) R_D(0,1,b^2)))."""
    b2 = np.asarray(beta, dtype=float) ** 2
    return 1.5 / (np.sqrt(b2) * np.sqrt(special.elliprd(0.0, b2, 1.0) * special.elliprd(0.0, 1.0, b2)))


def _check_contact(semi_major, beta, effective_radius, reduced_modulus):
    """Validated a [m], beta [-], R [m], E* [Pa] of a Hertz contact, as float arrays."""
    return (check_positive("semi_major", semi_major, "m"), check_ellipticity("beta", beta),
            check_positive("effective_radius", effective_radius, "m"),
            check_positive("reduced_modulus", reduced_modulus, "Pa"))


@fill_doc
def max_pressure(semi_major, beta, effective_radius=1.0, reduced_modulus=1.0, *, checked=True):
    """Maximum Hertz pressure Po_ab of the elliptical contact, Eq. (8).

    Parameters
    ----------
    %(hertz_contact)s
    checked : bool, default True
        Validate the inputs; False for internal callers that validated them once at their
        public entry and evaluate intermediate sizes (the closure solves).

    Returns
    -------
    ndarray
        Po_ab [Pa].

    Notes
    -----
    .. math::

        Po_{ab} = \\frac{E^*}{2R} \\frac{k^2 a}{\\beta\\{[\\mathbf{E}/\\beta^2-\\mathbf{K}]
                  [\\mathbf{K}-\\mathbf{E}]\\}^{1/2}}
                = \\frac{3 E^* a}{2 R \\beta \\sqrt{R_D(0,\\beta^2,1) R_D(0,1,\\beta^2)}}

    The second form follows from (K - E)/k^2 = R_D(0, beta^2, 1)/3 and
    (E/beta^2 - K)/k^2 = R_D(0, 1, beta^2)/3; it equals 2 E* a/(pi R) at beta = 1.
    """
    if checked:
        a, beta, r, e = _check_contact(semi_major, beta, effective_radius, reduced_modulus)
    else:
        a, beta, r, e = (np.asarray(x, dtype=float) for x in (semi_major, beta, effective_radius, reduced_modulus))
    return e / r * _pressure_factor(beta) * a  # Eq. (8)


@fill_doc
def load_factor(beta):
    """The factor F1 of Eq. (11); F1 = 1 at the circle.

    Parameters
    ----------
    %(ellipticity)s

    Returns
    -------
    ndarray
        F1 [-].

    Notes
    -----
    .. math::

        F_1^3 = \\frac{4}{\\pi k^2}\\beta^{3/2}\\{[\\mathbf{E}/\\beta^2-\\mathbf{K}][\\mathbf{K}-\\mathbf{E}]\\}^{1/2}
              = \\frac{4}{3\\pi}\\beta^{3/2}\\sqrt{R_D(0,\\beta^2,1)R_D(0,1,\\beta^2)}
    """
    beta = check_ellipticity("beta", beta)
    b2 = beta**2
    f13 = 4.0 / (3.0 * np.pi) * beta**1.5 * np.sqrt(
        special.elliprd(0.0, b2, 1.0) * special.elliprd(0.0, 1.0, b2))  # Eq. (11)
    return np.cbrt(f13)


@fill_doc
def load(semi_major, beta, effective_radius=1.0, reduced_modulus=1.0):
    """Hertz load W for contact semi-major axis a, Eq. (10).

    Parameters
    ----------
    %(hertz_contact)s

    Returns
    -------
    ndarray
        W, positive compressive [N].

    Notes
    -----
    .. math:: W = \\frac{4E^*}{3RF_1^3}(ab)^{3/2} = \\tfrac{2}{3}\\pi a b Po_{ab}
    """
    a, beta, r, e = _check_contact(semi_major, beta, effective_radius, reduced_modulus)
    return 4.0 * e / (3.0 * r * load_factor(beta) ** 3) * (a * a * beta) ** 1.5  # Eq. (10)


@fill_doc
def approach(semi_major, beta, effective_radius=1.0, reduced_modulus=1.0):
    """Hertz approach of distant points, delta = Po_ab b K(k)/E* (Eqs. 13a, 14a).

    Parameters
    ----------
    %(hertz_contact)s

    Returns
    -------
    ndarray
        The approach delta, positive into the bodies [m].

    Examples
    --------
    At the circle, delta = a^2/R (Hertz).

    >>> from dhfield.models import hertz
    >>> round(float(hertz.approach(0.5, 1.0, effective_radius=2.0)), 15)
    0.125
    """
    p0 = max_pressure(semi_major, beta, effective_radius, reduced_modulus)
    beta = np.asarray(beta, dtype=float)
    return p0 * beta * np.asarray(semi_major, dtype=float) * complete_k(beta) / reduced_modulus  # Eq. (14a)


@fill_doc
def pressure(x, y, semi_major, semi_minor, peak_pressure):
    """Semi-ellipsoidal Hertz pressure, Eq. (7); zero outside the ellipse.

    Parameters
    ----------
    %(surface_xy)s
    %(loaded_ellipse)s

    Returns
    -------
    ndarray
        Pressure, positive in compression [Pa].

    Examples
    --------
    >>> from dhfield.models import hertz
    >>> [float(hertz.pressure(x, 0.0, 2.0, 1.0, 3.0)) for x in (0.0, 2.0, 5.0)]
    [3.0, 0.0, 0.0]
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    q = 1.0 - (x / semi_major) ** 2 - (y / semi_minor) ** 2
    return peak_pressure * np.sqrt(np.maximum(q, 0.0))  # Eq. (7)


@fill_doc
def ellipse_root(x, y, semi_major, semi_minor):
    """The root l of x^2/(a^2+l) + y^2/(b^2+l) = 1 (below Eq. 12) [m^2].

    The positive (larger) root of the quadratic
    ``l^2 + (a^2 + b^2 - x^2 - y^2) l + (a^2 b^2 - x^2 b^2 - y^2 a^2) = 0``
    outside the ellipse, and 0 on and inside it.  Evaluated without
    cancellation: ``l = -2C/(B + sqrt(B^2 - 4C))`` when B > 0.

    Parameters
    ----------
    %(surface_xy)s
    semi_major, semi_minor : array_like
        Semi-axes a >= b of the ellipse [m].

    Returns
    -------
    ndarray
        The root l >= 0 [m^2].

    Examples
    --------
    On the major axis of a circle of radius 1, at x = 2: 4/(1 + l) = 1, so l = 3.

    >>> from dhfield.models import hertz
    >>> float(hertz.ellipse_root(2.0, 0.0, 1.0, 1.0))
    3.0
    """
    x2 = np.asarray(x, dtype=float) ** 2
    y2 = np.asarray(y, dtype=float) ** 2
    a2 = np.asarray(semi_major, dtype=float) ** 2
    b2 = np.asarray(semi_minor, dtype=float) ** 2
    bq = a2 + b2 - x2 - y2
    cq = a2 * b2 - x2 * b2 - y2 * a2
    # B^2 - 4C = (a^2 - b^2 - x^2 + y^2)^2 + 4 x^2 y^2 ... written to stay >= 0
    disc = np.sqrt((a2 - b2 - x2 + y2) ** 2 + 4.0 * x2 * y2)
    with np.errstate(divide="ignore", invalid="ignore"):
        l_pos = np.where(bq > 0, -2.0 * cq / (bq + disc), 0.5 * (disc - bq))
    return np.where(cq < 0, np.maximum(l_pos, 0.0), 0.0)


@fill_doc
def displacement_coefficients(x, y, semi_major, semi_minor, peak_pressure):
    """The coefficients L, M, N of Eqs. (13)-(15) / (B4)-(B6) at each point.

    ``omega = (L - M x^2 - N y^2)/(pi E*)``.  Inside the ellipse they are the
    constants of Eq. (14), outside the point-dependent values of Eq. (15).

    Parameters
    ----------
    %(surface_xy)s
    %(loaded_ellipse)s

    Returns
    -------
    L : ndarray
        Constant term [Pa m].
    M : ndarray
        Coefficient of x^2 [Pa m^-1].
    N : ndarray
        Coefficient of y^2 [Pa m^-1].
    """
    l = ellipse_root(x, y, semi_major, semi_minor)
    i1, i2, i3 = ellipsoid_integrals(l, semi_major, semi_minor)
    pref = 0.5 * np.pi * peak_pressure * semi_major * semi_minor
    return pref * i1, pref * i2, pref * i3  # Eq. (14), Eq. (15) via Eqs. (B4)-(B6)


@fill_doc
def surface_displacement(x, y, semi_major, semi_minor, peak_pressure, reduced_modulus=1.0):
    """Surface displacement of a semi-ellipsoidal pressure, Eqs. (12)-(15) [m].

    Valid everywhere on the surface: Eq. (13a) inside the ellipse (l = 0) and
    Eq. (13b) outside it.

    Parameters
    ----------
    %(surface_xy)s
    %(loaded_ellipse)s
    %(reduced_modulus_default)s

    Returns
    -------
    ndarray
        Displacement omega, positive into the bodies [m].

    Examples
    --------
    At the centre of a circular Hertz pressure, omega = pi a Po/(2 E*).

    >>> import numpy as np
    >>> from dhfield.models import hertz
    >>> bool(np.isclose(hertz.surface_displacement(0.0, 0.0, 1.0, 1.0, 1.0), np.pi / 2, rtol=1e-14))
    True
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    big_l, m, n = displacement_coefficients(x, y, semi_major, semi_minor, peak_pressure)
    return (big_l - m * x**2 - n * y**2) / (np.pi * reduced_modulus)  # Eq. (12) as Eq. (13)


@fill_doc
def surface_displacement_gradient(x, y, semi_major, semi_minor, peak_pressure, reduced_modulus=1.0):
    """Gradient (d omega/dx, d omega/dy) of Eq. (13).

    The integrand of Eq. (12b) vanishes at w = l, so the moving lower limit
    contributes nothing: d omega/dx = -2 x M/(pi E*), d omega/dy = -2 y N/(pi E*).

    Parameters
    ----------
    %(surface_xy)s
    %(loaded_ellipse)s
    %(reduced_modulus_default)s

    Returns
    -------
    d_omega_dx : ndarray
        Slope along x [-].
    d_omega_dy : ndarray
        Slope along y [-].
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    _, m, n = displacement_coefficients(x, y, semi_major, semi_minor, peak_pressure)
    return -2.0 * x * m / (np.pi * reduced_modulus), -2.0 * y * n / (np.pi * reduced_modulus)


@fill_doc
def principal_radii_from_ellipticity(beta, effective_radius=1.0):
    """Principal radii R', R'' that give Hertz ellipticity ``beta`` at equivalent radius R.

    Parameters
    ----------
    %(ellipticity)s
    %(effective_radius_default)s

    Returns
    -------
    r_major : ndarray
        R' = R sqrt(rho), rho = R'/R'' of :func:`dhfield.core.geometry.radius_ratio` [m].
    r_minor : ndarray
        R'' = R/sqrt(rho) [m].
    """
    rho = radius_ratio(beta)
    s = np.sqrt(rho)
    return effective_radius * s, effective_radius / s


@fill_doc
def gap(x, y, semi_major, beta, effective_radius=1.0, reduced_modulus=1.0):
    """Hertz gap h = z - delta + omega (Eqs. 2, 13, 14a); zero inside the contact.

    Parameters
    ----------
    %(surface_xy)s
    %(hertz_contact)s

    Returns
    -------
    ndarray
        Gap h >= 0 [m].
    """
    x = check_finite("x", x, "m")
    y = check_finite("y", y, "m")
    a = check_positive("semi_major", semi_major, "m")
    beta = check_ellipticity("beta", beta)
    r1, r2 = principal_radii_from_ellipticity(beta, effective_radius)
    p0 = max_pressure(a, beta, effective_radius, reduced_modulus)
    z = x**2 / (2.0 * r1) + y**2 / (2.0 * r2)  # Eq. (2)
    delta = approach(a, beta, effective_radius, reduced_modulus)
    return z - delta + surface_displacement(x, y, a, beta * a, p0, reduced_modulus)
