"""Derjaguin-Muller-Toporov (DMT) / Bradley limit of the adhesive sphere.

Sources: B. V. Derjaguin, V. M. Muller, Yu. P. Toporov, J. Colloid Interface Sci. 53
(1975) 314, doi:10.1016/0021-9797(75)90018-1; R. S. Bradley, Phil. Mag. 13 (1932)
853 (rigid spheres); the Hertzian DMT form used as the lambda -> 0 limit of the
Maugis-Dugdale model (Maugis 1992, doi:10.1016/0021-9797(92)90288-C).

The contact is Hertzian and the adhesive force -2 pi R dgamma acts outside it:

.. math::

    W = \\frac{4E^*a^3}{3R} - 2\\pi R\\Delta\\gamma, \\qquad \\delta = \\frac{a^2}{R},

i.e. ``W* = 2 a*^3/(3 pi) - 1`` and ``delta* = a*^2`` in the paper's units
(Eqs. 32-35, :mod:`dhfield.core.units`).  The approach is monotone in a, so under
both load and displacement control the pull-off is W* = -1 at a = 0.
"""
from __future__ import annotations

import numpy as np

from ..core.units import (check_material, length_unit, load_unit, scalar_or_array, si_circular_load_curve,
                          si_pull_off)
from ..core.validation import check_finite
from ..core.records import pull_off_record
from ..core._docstrings import fill_doc

__all__ = ["load_curve", "contact_radius", "pull_off", "pull_off_force", "load_curve_nondimensional",
           "pull_off_nondimensional"]


def load_curve_nondimensional(a_star):
    """DMT load and approach at contact radius a*, in the paper's units (Eqs. 32-35).

    The nondimensional core of :func:`load_curve`.

    Parameters
    ----------
    a_star : array_like
        Contact radius a* = a/c_r >= 0, Eq. (32) [-].

    Returns
    -------
    dict
        ``W_star`` (W/(2 pi R dgamma), Eq. 34), ``a_star``, ``delta_star``
        (delta R/c_r^2, Eq. 33) [-].

    Notes
    -----
    .. math:: W^* = \\frac{2 a^{*3}}{3\\pi} - 1, \\qquad \\delta^* = a^{*2}

    (Hertz load minus 2 pi R dgamma; Hertz approach.)
    """
    a = np.asarray(a_star, dtype=float)
    w = 2.0 * a**3 / (3.0 * np.pi) - 1.0  # DMT: Hertz load - 2 pi R dgamma
    return {"W_star": w, "a_star": a, "delta_star": a**2}  # Hertz approach


def _pull_off_state(control):  # noqa: ARG001 - the same state for both controls
    """``W_star``, ``a_star``, ``delta_star`` [-] at pull-off (:func:`load_curve_nondimensional`)."""
    return load_curve_nondimensional(0.0)


@fill_doc
def pull_off_nondimensional(beta0, mu, *, control="load"):
    """DMT pull-off record in the paper's units: W* = -1 at a* = 0 for either control.

    The nondimensional core of :func:`pull_off`; inputs are not validated here
    (:func:`dhfield.analysis.compare.pull_off` does).

    Parameters
    ----------
    %(circle_beta0_mu_unused)s
    control : {'load', 'displacement'}
        Both give the same state (the approach is monotone in a).

    Returns
    -------
    %(pull_off_nondimensional_returns)s
    """
    return pull_off_record("dmt", beta0, mu, _pull_off_state(control), control=control, sin_skew=1.0,
                           geometry="circle")


@fill_doc
def load_curve(contact_radius, effective_radius, reduced_modulus, work_of_adhesion):
    """DMT load and approach at the given contact radius.

    Parameters
    ----------
    %(contact_radius)s
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve (model ``dmt``, circle): ``semi_major`` = ``semi_minor`` = a [m],
        ``force`` W [N] (positive compressive), ``approach`` delta [m].

    Notes
    -----
    .. math:: W = \\frac{4E^*a^3}{3R} - 2\\pi R\\Delta\\gamma, \\qquad \\delta = a^2/R
    """
    return si_circular_load_curve("dmt", load_curve_nondimensional, contact_radius, effective_radius, reduced_modulus,
                                  work_of_adhesion)


@fill_doc
def contact_radius(load, effective_radius, reduced_modulus, work_of_adhesion):
    """Compute the DMT contact radius: a^3 = 3R(W + 2 pi R dgamma)/(4E*) [m].

    Parameters
    ----------
    load : array_like
        Load W >= -2 pi R dgamma [N].
    %(material)s

    Returns
    -------
    ndarray
        The contact radius a [m].
    """
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    p = check_finite("load", load, "N")
    ws = p / load_unit(r, w, checked=False)
    if np.any(ws < -1.0):
        raise ValueError(f"load must be >= -2 pi R dgamma (the DMT pull-off force) [N]; "
                         f"got {p[ws < -1.0].flat[0]!r}")
    return scalar_or_array(np.cbrt(1.5 * np.pi * (ws + 1.0)) * length_unit(r, e, w, checked=False))


@fill_doc
def pull_off(effective_radius, reduced_modulus, work_of_adhesion, *, control="load"):
    """DMT state at pull-off: W = -2 pi R dgamma at a = 0, delta = 0, for both controls.

    Parameters
    ----------
    %(material)s
    control : {'load', 'displacement'}
        Loading mode (the same result for DMT).

    Returns
    -------
    dhfield.core.records.PullOff
        ``force`` [N], ``semi_major`` = ``semi_minor`` = 0, ``approach`` = 0 [m], the SI
        inputs (``max_adhesive_stress`` NaN) and the nondimensional record (``mu`` NaN).
    """
    return si_pull_off(pull_off_nondimensional, effective_radius, reduced_modulus, work_of_adhesion, control=control)


@fill_doc
def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, *, control="load"):
    """Compute the DMT pull-off force -2 pi R dgamma [N].

    Parameters
    ----------
    %(material)s
    %(control)s

    Returns
    -------
    %(pull_off_force_returns)s
    """
    return pull_off(effective_radius, reduced_modulus, work_of_adhesion, control=control).force
