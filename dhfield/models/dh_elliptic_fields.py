"""The extended double-Hertz (DH) fields of an adhesive elliptical contact (Eqs. 16-27).

The adhesive pressure is the difference of two elliptical Hertz pressures with the
same ellipticity beta (Eq. 17): the contact ellipse (a, b = beta a) and the larger
adhesive ellipse (c, d = beta c), scaled by v (Eq. 22).  The total surface pressure
is therefore

    p = H_ab - v (H_cd - H_ab) = (1 + v) H_ab - v H_cd,

where H_ab, H_cd are the Hertz pressures of Eqs. (7)/(8) and (20).  Because both
Hertz fields are geometry-consistent (Eq. 20 has the same form as Eq. 8), each alone
makes omega = delta_i - z inside its own ellipse.  It follows that

* the contact condition h = 0 holds inside the contact ellipse with the total
  approach delta = (1 + v) delta_ab - v delta_cd;
* in the adhesive annulus the gap is h = (1 + v) h_H, h_H the plain Hertz gap of
  the contact ellipse, along every theta_p (the "annulus identity");
* the adhesive stress at the contact edge is sigma0 = v Po_cd sqrt(1 - a^2/c^2)
  all the way round (Eq. 24 holds for every theta_p, not only theta_p = 0).

Sign conventions are those of :mod:`dhfield.models.hertz`: pressure positive in
compression, displacement positive into the bodies, gap h = z - delta + omega.
The adhesive (tensile) stress sigma_ac of Eq. (23) is reported as a positive
number.

Paper notes
-----------
* Eq. (23)-(24) carry a minus sign (sigma = -P) while Fig. 3a and the text use the
  magnitude; here sigma_ac >= 0 is the tensile stress and sigma0 > 0.
* In Eq. (27) ``delta`` must be the Hertz approach of the contact ellipse,
  delta_ab (Eq. 14a), and omega_0ab the (constant) adhesive displacement inside
  the contact, v (delta_ab - delta_cd); with those readings Eq. (27) is
  h = (1 + v) h_H.  The approach of distant points of the adhesive contact is
  delta_ab + omega_0ab = (1 + v) delta_ab - v delta_cd.
* Eq. (21b) reads omega_in_ad; it is omega_in_cd.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import hertz
from ..core.validation import check_ellipticity, check_finite, check_positive
from ..core._docstrings import fill_doc

__all__ = [
    "pressure",
    "adhesive_stress",
    "max_adhesive_stress",
    "load",
    "approach",
    "surface_displacement",
    "gap",
    "check_parameters",
    "DoubleHertzParameters",
]


@fill_doc
class DoubleHertzParameters(NamedTuple):
    """Checked parameters of a DH state (float arrays), as returned by :func:`check_parameters`.

    Parameters
    ----------
    %(dh_parameters)s
    """

    semi_major: np.ndarray
    adhesive_semi_major: np.ndarray
    beta: np.ndarray
    scaling: np.ndarray
    effective_radius: np.ndarray
    reduced_modulus: np.ndarray


@fill_doc
def check_parameters(semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
                     reduced_modulus=1.0) -> DoubleHertzParameters:
    """Validate the parameters of a DH state; a ValueError names the first bad one.

    Parameters
    ----------
    %(dh_parameters)s

    Returns
    -------
    DoubleHertzParameters
        The parameters as float arrays.
    """
    a = check_positive("semi_major", semi_major, "contact semi-major axis a")
    c = check_positive("adhesive_semi_major", adhesive_semi_major, "adhesive semi-major axis c")
    if np.any(c < a):
        raise ValueError("adhesive_semi_major must be >= semi_major (c >= a)")
    beta = check_ellipticity("beta", beta)
    v = check_positive("scaling", scaling, "DH scaling factor v, dimensionless", allow_zero=True)
    r = check_positive("effective_radius", effective_radius, "m")
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    return DoubleHertzParameters(a, c, beta, v, r, e)


@fill_doc
def pressure(x, y, semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
             reduced_modulus=1.0):
    """Total surface pressure of the DH contact, Eqs. (7), (16), (22).

    Positive in compression inside the contact ellipse, negative (tensile) in the
    adhesive annulus, zero outside the adhesive ellipse.

    Parameters
    ----------
    %(surface_xy)s
    %(dh_parameters)s

    Returns
    -------
    ndarray
        Pressure, positive in compression [Pa].

    Examples
    --------
    With v = 0 the DH pressure is the Hertz pressure: at the centre Po_ab = 2 E* a/(pi R)
    for the circle.

    >>> import numpy as np
    >>> from dhfield.models import dh_elliptic_fields
    >>> bool(np.isclose(dh_elliptic_fields.pressure(0.0, 0.0, 1.0, 1.5, 1.0, 0.0), 2 / np.pi, rtol=1e-14))
    True
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    po_ab = hertz.max_pressure(a, beta, r, e)  # Eq. (8)
    po_cd = hertz.max_pressure(c, beta, r, e)  # Eq. (20)
    h_ab = hertz.pressure(x, y, a, beta * a, po_ab)  # Eq. (7)
    h_cd = hertz.pressure(x, y, c, beta * c, po_cd)  # Eq. (16)
    return (1.0 + v) * h_ab - v * h_cd  # Eq. (22): H_ab - v (H_cd - H_ab)


@fill_doc
def adhesive_stress(x, y, semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
                    reduced_modulus=1.0):
    """Tensile adhesive stress sigma_ac in the annulus, Eq. (23); 0 elsewhere.

    sigma_ac = v Po_cd sqrt(1 - (x/c)^2 - (y/d)^2) for points outside the contact
    ellipse and inside the adhesive ellipse.

    Parameters
    ----------
    %(surface_xy)s
    %(dh_parameters)s

    Returns
    -------
    ndarray
        The adhesive stress, a positive tensile magnitude [Pa].
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    po_cd = hertz.max_pressure(c, beta, r, e)  # Eq. (20)
    outside_ab = (x / a) ** 2 + (y / (beta * a)) ** 2 > 1.0
    return np.where(outside_ab, v * hertz.pressure(x, y, c, beta * c, po_cd), 0.0)  # Eq. (23)


@fill_doc
def max_adhesive_stress(semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
                        reduced_modulus=1.0):
    """Maximum adhesive stress sigma0 = v Po_cd sqrt(1 - a^2/c^2), Eq. (24).

    With equal ellipticities this is the stress at the contact edge for every
    theta_p (see module docstring).

    Parameters
    ----------
    %(dh_parameters)s

    Returns
    -------
    ndarray
        The maximum adhesive stress, a positive tensile magnitude [Pa].
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    po_cd = hertz.max_pressure(c, beta, r, e)  # Eq. (20)
    return v * po_cd * np.sqrt(1.0 - (a / c) ** 2)  # Eq. (24)


@fill_doc
def load(semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0, reduced_modulus=1.0):
    """Total load of the DH contact, Eq. (25).

    Parameters
    ----------
    %(dh_parameters)s

    Returns
    -------
    ndarray
        The load W, positive compressive [N].

    Notes
    -----
    .. math:: W = \\frac{4E^*}{3RF_1^3}\\{(ab)^{3/2} - v[(cd)^{3/2} - (ab)^{3/2}]\\}
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    f13 = hertz.load_factor(beta) ** 3  # Eq. (11)
    ab, cd = beta * a * a, beta * c * c
    return 4.0 * e / (3.0 * r * f13) * (ab**1.5 - v * (cd**1.5 - ab**1.5))  # Eq. (25)


@fill_doc
def approach(semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0, reduced_modulus=1.0):
    """Approach of distant points of the DH contact.

    delta = (1 + v) delta_ab - v delta_cd with delta_i = Po_i b_i K(k)/E* (Eq. 14a);
    the sum delta_ab + omega_0ab of Eqs. (26a)-(27).

    Parameters
    ----------
    %(dh_parameters)s

    Returns
    -------
    ndarray
        The approach delta, positive into the bodies [m].
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    d_ab = hertz.approach(a, beta, r, e)  # Eq. (14a)
    d_cd = hertz.approach(c, beta, r, e)  # Eq. (14a) for the adhesive ellipse
    return (1.0 + v) * d_ab - v * d_cd  # Eq. (26a): delta_ab + v (delta_ab - delta_cd)


@fill_doc
def surface_displacement(x, y, semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
                         reduced_modulus=1.0):
    """Total surface displacement of the DH pressure, Eqs. (13), (21), (26).

    omega = omega_ab + v (omega_ab - omega_cd), valid over the whole surface (inside
    the contact, in the annulus and outside the adhesive ellipse).

    Parameters
    ----------
    %(surface_xy)s
    %(dh_parameters)s

    Returns
    -------
    ndarray
        The displacement omega, positive into the bodies [m].
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    x = check_finite("x", x, "m")
    y = check_finite("y", y, "m")
    w_ab = hertz.surface_displacement(x, y, a, beta * a, hertz.max_pressure(a, beta, r, e), e)  # Eq. (13)
    w_cd = hertz.surface_displacement(x, y, c, beta * c, hertz.max_pressure(c, beta, r, e), e)  # Eq. (13) for cd
    return w_ab + v * (w_ab - w_cd)  # Eq. (21) scaled by v: Eq. (26)


@fill_doc
def gap(x, y, semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0, reduced_modulus=1.0):
    """Gap h of the DH contact, Eq. (27), over the whole surface.

    h = z + omega - delta with the total displacement and approach above; zero
    inside the contact ellipse, (1 + v) times the Hertz gap in the annulus.

    Parameters
    ----------
    %(surface_xy)s
    %(dh_parameters)s

    Returns
    -------
    ndarray
        The gap h >= 0 [m].
    """
    a, c, beta, v, r, e = check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                       effective_radius, reduced_modulus)
    x = check_finite("x", x, "m")
    y = check_finite("y", y, "m")
    r1, r2 = hertz.principal_radii_from_ellipticity(beta, r)
    z = x**2 / (2.0 * r1) + y**2 / (2.0 * r2)  # Eq. (2)
    omega = surface_displacement(x, y, a, c, beta, v, r, e)
    return z + omega - approach(a, c, beta, v, r, e)  # Eq. (27)
