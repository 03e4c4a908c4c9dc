"""Mapping between the paper's transition parameter mu (Eq. 35) and Maugis' lambda.

Definitions
-----------
* The paper (Eq. 35, after Tabor 1977): ``mu = sigma0 (R/(E*^2 dgamma))^(1/3)``.
* Maugis (1992), doi:10.1016/0021-9797(92)90288-C; Johnson & Greenwood
  (1997) doi:10.1006/jcis.1997.5010: ``lambda = 2 sigma0 (R/(pi dgamma K^2))^(1/3)``
  with ``K = 4E*/3``.

With the *same* sigma0 (the maximum adhesive stress: the Dugdale stress of MD, the
peak stress of the DH models) the two differ by a constant:

.. math::

    \\lambda = 2\\sigma_0\\left(\\frac{R}{\\pi\\Delta\\gamma (4E^*/3)^2}\\right)^{1/3}
             = 2\\left(\\frac{9}{16\\pi}\\right)^{1/3}\\mu \\approx 1.12725\\,\\mu .

This is the mapping used by :mod:`dhfield.analysis.compare` whenever MD is put on the
axes of the DH models: both are evaluated with the same sigma0 and dgamma.

Note: Johnson & Greenwood (1997) also quote ``lambda = 1.16 mu``; there ``mu`` is
Tabor's parameter of a Lennard-Jones law, whose peak stress (1.03 sigma_th) is
matched to a Dugdale stress of equal range.  That is a *different* sigma0 and is
not used here.
"""
from __future__ import annotations

import numpy as np

from .validation import check_positive

__all__ = ["MAUGIS_PER_TABOR", "maugis_parameter", "tabor_from_maugis"]

#: lambda/mu for equal sigma0: 2 (9/(16 pi))^(1/3) = 1.1272...
MAUGIS_PER_TABOR = 2.0 * (9.0 / (16.0 * np.pi)) ** (1.0 / 3.0)


def maugis_parameter(mu, *, checked=True):
    """Convert the paper's transition parameter mu of Eq. (35) to Maugis' lambda [-].

    Parameters
    ----------
    mu : array_like
        Tabor parameter mu = sigma0 (R/(E*^2 dgamma))^(1/3) > 0, Eq. (35) [-].
    checked : bool, default True
        Validate ``mu``; False for internal callers that validated it once at their public
        entry (the MD solves of :mod:`dhfield.models.maugis_dugdale`).

    Returns
    -------
    ndarray
        Maugis' lambda = 2 sigma0 (R/(pi dgamma K^2))^(1/3), K = 4E*/3 [-].

    Notes
    -----
    .. math:: \\lambda = 2\\left(\\frac{9}{16\\pi}\\right)^{1/3}\\mu
    """
    if checked:
        mu = check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless")
    else:
        mu = np.asarray(mu, dtype=float)
    out = MAUGIS_PER_TABOR * mu  # Eq. (35) with Maugis (1992) lambda, same sigma0
    return out[()] if out.ndim == 0 else out


def tabor_from_maugis(lam):
    """Convert Maugis' lambda to the paper's mu (the inverse of :func:`maugis_parameter`) [-].

    Parameters
    ----------
    lam : array_like
        Maugis' transition parameter lambda > 0 [-].

    Returns
    -------
    ndarray
        The Tabor parameter mu = lambda/(2 (9/(16 pi))^(1/3)) of Eq. (35) [-].
    """
    lam = check_positive("lam", lam, "Maugis transition parameter, dimensionless")
    out = lam / MAUGIS_PER_TABOR
    return out[()] if out.ndim == 0 else out
