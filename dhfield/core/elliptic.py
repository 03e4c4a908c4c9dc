"""Elliptic integrals in the forms the elliptical Hertz problem needs.

Conventions
-----------
scipy's Legendre functions ``ellipk(m)``, ``ellipe(m)``, ``ellipkinc(phi, m)`` and
``ellipeinc(phi, m)`` take the *parameter* ``m = k**2 = 1 - beta**2``, not the
modulus ``k``.  They are wrapped here, once, with the modulus spelled out.

The ellipsoidal potential integrals of Appendix 2 (Eqs. B1-B3) are evaluated in
Carlson's symmetric form.  With ``w = l + t``,

.. math::

    I_1 = \\int_l^\\infty \\frac{dw}{\\sqrt{(a^2+w)(b^2+w)w}} = 2 R_F(l, b^2+l, a^2+l)

    I_2 = \\int_l^\\infty \\frac{dw}{\\sqrt{(a^2+w)^3(b^2+w)w}} = \\tfrac23 R_D(l, b^2+l, a^2+l)

    I_3 = \\int_l^\\infty \\frac{dw}{\\sqrt{(a^2+w)(b^2+w)^3w}} = \\tfrac23 R_D(l, a^2+l, b^2+l)

These are the same incomplete elliptic integrals as the Legendre forms printed in
the paper, ``2F(phi, k)/a`` etc. with ``phi = asin(a/sqrt(a^2+l))``, but they have
no 0/0 at the circle ``a = b`` (k = 0) and no cancellation near it, and ``l = 0``
gives the complete integrals used inside the ellipse.  The Legendre forms are
kept in :func:`ellipsoid_integrals_legendre` so that the paper's printed
expressions are tested against the Carlson forms and against quadrature.
"""
from __future__ import annotations

import numpy as np
from scipy import special
from ._docstrings import fill_doc

__all__ = [
    "complete_k",
    "ellipsoid_integrals",
    "ellipsoid_integrals_legendre",
]


@fill_doc
def complete_k(beta):
    """Complete elliptic integral of the first kind K(k), k**2 = 1 - beta**2.

    Parameters
    ----------
    %(ellipticity)s

    Returns
    -------
    ndarray
        K(k) [-]; pi/2 at the circle (beta = 1).

    Examples
    --------
    >>> import numpy as np
    >>> from dhfield.core import elliptic
    >>> bool(np.isclose(elliptic.complete_k(1.0), np.pi / 2, rtol=1e-15))
    True
    """
    beta = np.asarray(beta, dtype=float)
    return special.elliprf(0.0, beta**2, 1.0)  # K(k) = R_F(0, 1 - k^2, 1)


@fill_doc
def ellipsoid_integrals(l, a, b):
    """Ellipsoidal potential integrals I1, I2, I3 of Eqs. (B1)-(B3), Carlson form.

    Parameters
    ----------
    %(ellipsoid_lower_limit)s
    a, b : array_like
        Semi-axes of the ellipse, ``a`` along x [m].

    Returns
    -------
    %(ellipsoid_integrals_returns)s

    Examples
    --------
    At the centre of a circle of radius a (l = 0): I1 = pi/a and I2 = I3 = pi/(2 a^3), since
    R_F(0, a^2, a^2) = pi/(2a) and R_D(0, a^2, a^2) = 3 pi/(4 a^3) (DLMF 19.20.1, 19.20.4).

    >>> import numpy as np
    >>> from dhfield.core import elliptic
    >>> i1, i2, i3 = elliptic.ellipsoid_integrals(0.0, 1.0, 1.0)
    >>> bool(np.allclose([i1, i2, i3], [np.pi, np.pi / 2, np.pi / 2], rtol=1e-14))
    True
    """
    l = np.asarray(l, dtype=float)
    a2 = np.asarray(a, dtype=float) ** 2 + l
    b2 = np.asarray(b, dtype=float) ** 2 + l
    i1 = 2.0 * special.elliprf(l, b2, a2)  # Eq. (B1)
    i2 = (2.0 / 3.0) * special.elliprd(l, b2, a2)  # Eq. (B2)
    i3 = (2.0 / 3.0) * special.elliprd(l, a2, b2)  # Eq. (B3)
    return i1, i2, i3


@fill_doc
def ellipsoid_integrals_legendre(l, a, b):
    """Eqs. (B1)-(B3) exactly as printed, with Legendre incomplete integrals.

    Only defined for ``b < a`` (k > 0); the circle is a 0/0 limit here, which is
    why the library evaluates :func:`ellipsoid_integrals` instead.  Kept as the
    paper's reference form for tests.

    Parameters
    ----------
    %(ellipsoid_lower_limit)s
    a : array_like
        Semi-major axis, along x [m].
    b : array_like
        Semi-minor axis, ``b < a`` [m].

    Returns
    -------
    %(ellipsoid_integrals_returns)s

    Examples
    --------
    >>> import numpy as np
    >>> from dhfield.core import elliptic
    >>> carlson = elliptic.ellipsoid_integrals(0.3, 1.0, 0.6)
    >>> bool(np.allclose(elliptic.ellipsoid_integrals_legendre(0.3, 1.0, 0.6), carlson, rtol=1e-12))
    True
    """
    l = np.asarray(l, dtype=float)
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    k2 = 1.0 - (b / a) ** 2
    kp2 = 1.0 - k2
    phi = np.arcsin(a / np.sqrt(a**2 + l))
    F = special.ellipkinc(phi, k2)
    E = special.ellipeinc(phi, k2)
    s, c = np.sin(phi), np.cos(phi)
    i1 = 2.0 * F / a  # Eq. (B1)
    i2 = 2.0 * (F - E) / (k2 * a**3)  # Eq. (B2)
    i3 = 2.0 / (k2 * kp2 * a**3) * (E - kp2 * F - k2 * s * c / np.sqrt(1.0 - k2 * s**2))  # Eq. (B3)
    return i1, i2, i3
