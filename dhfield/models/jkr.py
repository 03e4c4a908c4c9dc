"""Johnson-Kendall-Roberts (JKR) adhesive contact of a sphere (circular contact).

Source: K. L. Johnson, K. Kendall & A. D. Roberts, Proc. R. Soc. Lond. A 324 (1971)
301-313, doi:10.1098/rspa.1971.0141; in the form of K. L. Johnson, *Contact
Mechanics* (CUP 1985), Sec. 5.5.

Nondimensionalisation: the paper's units (Eqs. 32-35, see :mod:`dhfield.core.units`),
``a* = a/c_r``, ``W* = W/(2 pi R dgamma)``, ``delta* = delta R/c_r^2``.  In these
units the JKR curve is

.. math::

    W^* = \\frac{1}{2\\pi}\\left(\\tfrac43 a^{*3} - \\sqrt{8\\pi a^{*3}}\\right), \\qquad
    \\delta^* = a^{*2} - \\sqrt{2\\pi a^*}.

Pull-off: W* = -3/4 at a*^3 = 9 pi/8 under load control, W* = -5/12 at
a*^3 = pi/8 under displacement control (fixed grips).
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

#: a*^3 at pull-off for each control mode (dW/da = 0 and d(delta)/da = 0)
_PULL_OFF_A3 = {"load": 9.0 * np.pi / 8.0, "displacement": np.pi / 8.0}


def load_curve_nondimensional(a_star):
    """JKR load and approach at contact radius a*, in the paper's units (Eqs. 32-35).

    The nondimensional core of :func:`load_curve`.

    Parameters
    ----------
    a_star : array_like
        Contact radius a* = a/c_r >= 0, Eq. (32) [-].

    Returns
    -------
    dict
        ``W_star`` (load W/(2 pi R dgamma), Eq. 34), ``a_star``, ``delta_star``
        (approach delta R/c_r^2, Eq. 33) [-], arrays of the shape of ``a_star``.

    Notes
    -----
    .. math::

        W^* = \\frac{1}{2\\pi}\\left(\\tfrac43 a^{*3} - \\sqrt{8\\pi a^{*3}}\\right), \\qquad
        \\delta^* = a^{*2} - \\sqrt{2\\pi a^*}

    (Johnson, Kendall & Roberts 1971: Hertz minus the flat-punch term.)
    """
    a = np.asarray(a_star, dtype=float)
    w = (4.0 / 3.0 * a**3 - np.sqrt(8.0 * np.pi * a**3)) / (2.0 * np.pi)  # JKR (1971): Hertz load minus flat-punch term
    d = a**2 - np.sqrt(2.0 * np.pi * a)  # JKR (1971): Hertz approach minus flat-punch term
    return {"W_star": w, "a_star": a, "delta_star": d}


def _contact_radius(w_star):
    """a* for load W* >= -3/4 on the stable (load-controlled) branch."""
    p = 2.0 * np.pi * np.asarray(w_star, dtype=float)  # P in units of R dgamma
    # a^3 = (3R/4E*)[P + 3 pi dgamma R + sqrt(6 pi dgamma R P + (3 pi dgamma R)^2)]
    disc = np.maximum(6.0 * np.pi * p + (3.0 * np.pi) ** 2, 0.0)
    return np.cbrt(0.75 * (p + 3.0 * np.pi + np.sqrt(disc)))  # JKR (1971): inverse of the load curve


def _pull_off_state(control):
    """``W_star``, ``a_star``, ``delta_star`` [-] at pull-off (:func:`load_curve_nondimensional`)."""
    return load_curve_nondimensional(np.cbrt(_PULL_OFF_A3[control]))


@fill_doc
def pull_off_nondimensional(beta0, mu, *, control="load"):
    """JKR pull-off record in the paper's units (Eqs. 32-35); the core of :func:`pull_off`.

    Inputs are not validated here (:func:`dhfield.analysis.compare.pull_off` does).

    Parameters
    ----------
    %(circle_beta0_mu_unused)s
    control : {'load', 'displacement'}
        Load control: the minimum of W* (a*^3 = 9 pi/8, W* = -3/4); displacement
        control: the minimum of delta* (a*^3 = pi/8, W* = -5/12).

    Returns
    -------
    %(pull_off_nondimensional_returns)s
    """
    return pull_off_record("jkr", beta0, mu, _pull_off_state(control), control=control, sin_skew=1.0,
                           geometry="circle")


@fill_doc
def load_curve(contact_radius, effective_radius, reduced_modulus, work_of_adhesion):
    """JKR load and approach at the given contact radius.

    Parameters
    ----------
    %(contact_radius)s
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve (model ``jkr``, circle): ``semi_major`` = ``semi_minor`` = a [m],
        ``force`` W [N] (positive compressive), ``approach`` delta [m].

    Notes
    -----
    .. math::

        W = \\frac{4E^*a^3}{3R} - \\sqrt{8\\pi\\Delta\\gamma E^* a^3}, \\qquad
        \\delta = \\frac{a^2}{R} - \\sqrt{\\frac{2\\pi a\\Delta\\gamma}{E^*}}

    References
    ----------
    .. [1] K. L. Johnson, K. Kendall, A. D. Roberts, Proc. R. Soc. Lond. A 324 (1971)
       301, doi:10.1098/rspa.1971.0141
    """
    return si_circular_load_curve("jkr", load_curve_nondimensional, contact_radius, effective_radius, reduced_modulus,
                                  work_of_adhesion)


@fill_doc
def contact_radius(load, effective_radius, reduced_modulus, work_of_adhesion):
    """Compute the JKR contact radius on the stable branch [m].

    Parameters
    ----------
    load : array_like
        Load W >= -(3/2) pi R dgamma [N].
    %(material)s

    Returns
    -------
    ndarray
        The contact radius a [m].

    Notes
    -----
    .. math:: a^3 = \\frac{3R}{4E^*}\\left[W + 3\\pi\\Delta\\gamma R
              + \\sqrt{6\\pi\\Delta\\gamma R W + (3\\pi\\Delta\\gamma R)^2}\\right]
    """
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    p = check_finite("load", load, "N")
    ws = p / load_unit(r, w, checked=False)
    if np.any(ws < -0.75):
        raise ValueError(f"load must be >= -(3/2) pi R dgamma (the JKR pull-off force) [N]; "
                         f"got {p[ws < -0.75].flat[0]!r}")
    return scalar_or_array(_contact_radius(ws) * length_unit(r, e, w, checked=False))


@fill_doc
def pull_off(effective_radius, reduced_modulus, work_of_adhesion, *, control="load"):
    """JKR state at pull-off.

    Parameters
    ----------
    %(material)s
    control : {'load', 'displacement'}
        Loading mode: pull-off is the minimum load (load control) or the load
        where the approach is minimum, d(delta)/da = 0 (displacement control).

    Returns
    -------
    dhfield.core.records.PullOff
        ``force`` [N], ``semi_major`` = ``semi_minor`` (the contact radius) [m],
        ``approach`` [m], the SI inputs (``max_adhesive_stress`` NaN) and the
        nondimensional record (``mu`` NaN: JKR has none).

    Notes
    -----
    Load control: :math:`W = -\\tfrac32\\pi R\\Delta\\gamma`, :math:`a^3 = 9\\pi\\Delta\\gamma R^2/(8E^*)`.
    Displacement control: :math:`W = -\\tfrac56\\pi R\\Delta\\gamma`, :math:`a^3 = \\pi\\Delta\\gamma R^2/(8E^*)`.
    """
    return si_pull_off(pull_off_nondimensional, effective_radius, reduced_modulus, work_of_adhesion, control=control)


@fill_doc
def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, *, control="load"):
    """Compute the JKR pull-off force [N] (negative, tensile).

    Parameters
    ----------
    %(material)s
    %(control)s

    Returns
    -------
    %(pull_off_force_returns)s
    """
    return pull_off(effective_radius, reduced_modulus, work_of_adhesion, control=control).force
