"""Maugis-Dugdale sphere out of contact: the Dugdale zone of a separated sphere.

The Dugdale law of Maugis (1992) acts wherever the gap is below its range
``h0 = dgamma/sigma0``, in contact or not.  A sphere approaching a flat therefore
feels a force before it touches: from the moment its central gap equals h0 until
contact forms at the centre, a uniform tension sigma0 acts over a disc of radius c
where the gap is below h0.  This module gives that separated branch; it joins the
MD contact curve (:mod:`dhfield.models.maugis_dugdale`) at its end point a = 0.

Source: the Dugdale assumption of D. Maugis, J. Colloid Interface Sci. 150 (1992)
243, doi:10.1016/0021-9797(92)90288-C (the MD equations, Eq. 6.17 there, as
reconstructed in the project's physics notes, Sec. 5); the surface displacement of
a uniform pressure p on a disc of radius c, ``2pc/E*`` at its centre and
``4pc/(pi E*)`` at its edge (K. L. Johnson, *Contact Mechanics*, CUP 1985,
Sec. 3.4, uniform pressure on a circular region).  The branch itself is derived
here.

Equations (derived here; the paper's units, Eqs. 32-35: R = E* = dgamma = 1, so
sigma0 = mu and h0 = 1/mu)
-------------------------------------------------------------------------------
With the approach delta (negative while separated), the gap is
``h(r) = r^2/(2R) - delta - u(r)``, u the displacement of the tension pulling the
surfaces together.  The zone edge r = c has h = h0:

.. math::

    W^* = -\\frac{\\mu c^2}{2}, \\qquad
    \\delta^* = \\frac{c^2}{2} - \\frac{4\\mu c}{\\pi} - \\frac{1}{\\mu}

(W = -pi sigma0 c^2 in units of 2 pi R dgamma, Eq. 34).  The branch starts at
c = 0 (delta* = -1/mu: the central gap is h0, no force) and ends when the central
gap closes, h(0) = 0:

.. math:: \\frac{c^2}{2} + \\left(2 - \\frac{4}{\\pi}\\right)\\mu c = \\frac{1}{\\mu}

where delta* = -2 mu c.  In Maugis' units (x = c/(pi dgamma R^2/K)^(1/3),
K = 4E*/3) this end point is ``P = -lambda pi x^2/2``, ``D = -4 lambda x/3`` with
``lambda pi x^2/4 + (4 lambda^2/3)(pi/2 - 1) x = 1``: the end point a = 0 of the
MD contact curve, which the tests check.
"""
from __future__ import annotations

import numpy as np

from ..core.validation import check_interval, check_positive

__all__ = ["separated_branch", "zone_radius_at_contact", "dugdale_range"]

_EDGE = 2.0 - 4.0 / np.pi  # (centre - edge) displacement of a uniform disc load, in units of sigma0 c/E*


def dugdale_range(mu):
    """Compute the range h0 = dgamma/sigma0 of the Dugdale law, in c_r^2/R (= 1/mu) [-].

    Parameters
    ----------
    mu : array_like
        Transition parameter of Eq. (35), > 0 [-] (the Dugdale stress in E* c_r/R).

    Returns
    -------
    ndarray
        The range h0 in c_r^2/R [-].
    """
    mu = check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless")
    return 1.0 / mu  # h0 = dgamma/sigma0 with dgamma = 1, sigma0 = mu (Eq. 35)


def zone_radius_at_contact(mu):
    """Dugdale-zone radius c* when the separated sphere touches (a = 0) [-].

    Parameters
    ----------
    mu : array_like
        Transition parameter of Eq. (35), > 0 [-].

    Returns
    -------
    ndarray
        The positive root of c^2/2 + (2 - 4/pi) mu c = 1/mu (module docstring), in c_r.
    """
    mu = check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless")
    # c^2 + 2 b c - 2/mu = 0, b = (2 - 4/pi) mu: c = (2/mu)/(b + sqrt(b^2 + 2/mu)) without cancellation
    b = _EDGE * mu
    return (2.0 / mu) / (b + np.sqrt(b * b + 2.0 / mu))


def separated_branch(c_star, mu):
    """Load and approach of the separated MD sphere with a Dugdale zone of radius c*.

    Parameters
    ----------
    c_star : array_like
        Dugdale-zone radius c/c_r, in [0, :func:`zone_radius_at_contact`] [-].
    mu : array_like
        Transition parameter of Eq. (35), > 0 [-]; broadcasts with ``c_star``.

    Returns
    -------
    dict
        ``W_star`` (W/(2 pi R dgamma), Eq. 34; tensile, negative), ``delta_star``
        (approach in c_r^2/R; negative) and ``c_star`` [-].

    Notes
    -----
    .. math::

        W^* = -\\frac{\\mu c^2}{2}, \\qquad
        \\delta^* = \\frac{c^2}{2} - \\frac{4\\mu c}{\\pi} - \\frac{1}{\\mu}

    (module docstring).  d(delta*)/dc < 0 for c < 4 mu/pi: the start of the branch
    is unstable under any machine, which is why a sphere approaching from
    separation jumps when its central gap reaches h0.
    """
    mu = check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless")
    c = check_interval("c_star", c_star, 0.0, np.inf, low_open=False, high_open=True,
                       what="Dugdale-zone radius in units of c_r")
    c, mu = np.broadcast_arrays(c, mu)
    if np.any(c > zone_radius_at_contact(mu) * (1.0 + 1e-12)):
        raise ValueError("c_star must be at most zone_radius_at_contact(mu) (the sphere touches there; "
                         "beyond it use the MD contact curve)")
    w = -0.5 * mu * c * c  # W = -pi sigma0 c^2 over 2 pi R dgamma (Eq. 34)
    d = 0.5 * c * c - 4.0 * mu * c / np.pi - 1.0 / mu  # h(c) = h0 with u(c) = 4 sigma0 c/(pi E*)
    return {"W_star": w, "delta_star": d, "c_star": c.copy()}
