"""Maugis-Dugdale (MD) adhesive sphere: the three coupled equations of Maugis (1992).

Source: D. Maugis, J. Colloid Interface Sci. 150 (1992) 243-269,
doi:10.1016/0021-9797(92)90288-C; the same equations in K. L. Johnson &
J. A. Greenwood, J. Colloid Interface Sci. 192 (1997) 326, doi:10.1006/jcis.1997.5010.

Maugis units
------------
With ``K = 4E*/3``: ``A = a/(pi dgamma R^2/K)^(1/3)``, ``P = W/(pi R dgamma)``,
``D = delta/(pi^2 dgamma^2 R/K^2)^(1/3)`` and
``lambda = 2 sigma0 (R/(pi dgamma K^2))^(1/3)`` (sigma0 the Dugdale stress).
With ``m = c/a`` (c the outer radius of the Dugdale zone) and ``M = sqrt(m^2 - 1)``:

.. math::

    \\frac{\\lambda A^2}{2}\\left[M + (m^2-2)\\arctan M\\right]
      + \\frac{4\\lambda^2 A}{3}\\left[M\\arctan M - m + 1\\right] = 1

    P = A^3 - \\lambda A^2\\left[M + m^2\\arctan M\\right]

    D = A^2 - \\tfrac43 A\\lambda M

Solution method (derived here)
------------------------------
The first equation is a quadratic in A for given m, with positive coefficients
(both brackets are > 0 for m > 1), so ``A(M) = 2/(c1 + sqrt(c1^2 + 4 c2))`` is
explicit and decreases monotonically from infinity (M -> 0, the JKR side) to 0
(M -> infinity, the DMT side).  The load curve is thus closed form in the
parameter M; a given A is reached with a bracketing root finder in log M, and the
pull-off is a bounded minimisation in log M.  The first bracket suffers
cancellation for small M (it behaves like 4M^3/3) and is evaluated there by its
series ``sum_n (-1)^(n-1) 4n/(4n^2-1) M^(2n+1)``.  At a = 0 (M -> infinity,
``A m -> x``) the curve ends at ``P = -lambda pi x^2/2``, ``D = -4 lambda x/3``
with ``lambda pi x^2/4 + (4 lambda^2/3)(pi/2 - 1) x = 1``.

Paper units
-----------
``a* = A (3 pi/4)^(1/3)``, ``W* = P/2``, ``delta* = D (9 pi^2/16)^(1/3)`` and
``lambda = 1.1272 mu`` (:mod:`dhfield.core.transition`).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.optimize import elementwise

from ..core.units import check_contact_size, si_circular_load_curve, si_pull_off
from ..core.validation import check_positive
from ..core.pull_off_search import scan_minimum
from ..core.records import pull_off_record
from ..core.transition import maugis_parameter
from ..core._docstrings import fill_doc

__all__ = ["load_curve", "pull_off", "pull_off_force", "LAMBDA_RANGE", "load_curve_nondimensional",
           "pull_off_nondimensional", "load_curve_maugis_units", "MaugisCurve"]

#: lambda range over which the solver is tested (DMT side, JKR side)
LAMBDA_RANGE = (1e-3, 1e3)

_A_UNIT = (3.0 * np.pi / 4.0) ** (1.0 / 3.0)  # a* per Maugis A
_D_UNIT = (9.0 * np.pi**2 / 16.0) ** (1.0 / 3.0)  # delta* per Maugis D
_LOG_M_RANGE = (-40.0, 40.0)  # ln M searched; A(M) spans ~1e-17 .. 1e26 there for lambda in LAMBDA_RANGE
_SERIES_M = 0.1
#: pull-off scan in Maugis A (descending), refined in ln M; pull-off A <= 1.145 (JKR)
_SCAN_A = np.geomspace(20.0, 1e-7, 110)
_SERIES_TERMS = 14


def _bracket_adhesion(mm):
    """M + (m^2 - 2) atan M, m^2 = 1 + M^2, without cancellation at small M."""
    direct = mm + (mm * mm - 1.0) * np.arctan(mm)
    n = np.arange(1, _SERIES_TERMS + 1)
    coef = (-1.0) ** (n - 1) * 4.0 * n / (4.0 * n * n - 1.0)
    ms = np.where(np.real(mm) < _SERIES_M, mm, _SERIES_M)  # complex-safe (complex-step derivative)
    series = ms**3 * np.polyval(coef[::-1], ms * ms)  # sum coef_n M^(2n+1) = M^3 * poly(M^2)
    return np.where(np.real(mm) < _SERIES_M, series, direct)


def _bracket_zone(mm):
    """M atan M - m + 1, with m - 1 = M^2/(1 + m)."""
    m = np.sqrt(1.0 + mm * mm)
    return mm * np.arctan(mm) - mm * mm / (1.0 + m)


def _state_maugis(log_m, lam):
    """(A, P, D, m) in Maugis units for the zone parameter ln M."""
    mm = np.exp(log_m)
    m = np.sqrt(1.0 + mm * mm)
    c2 = 0.5 * lam * _bracket_adhesion(mm)  # Maugis (1992), first MD equation
    c1 = 4.0 / 3.0 * lam**2 * _bracket_zone(mm)
    a = 2.0 / (c1 + np.sqrt(c1 * c1 + 4.0 * c2))  # positive root of c2 A^2 + c1 A - 1 = 0
    p = a**3 - lam * a * a * (mm + m * m * np.arctan(mm))  # Maugis (1992), second MD equation
    d = a * a - 4.0 / 3.0 * a * lam * mm  # Maugis (1992), third MD equation
    return a, p, d, m


def _zero_contact_zone(lam):
    """x = lim A m (the Dugdale-zone radius c in Maugis units) at A = 0."""
    qa = lam * np.pi / 4.0
    qb = 4.0 / 3.0 * lam**2 * (np.pi / 2.0 - 1.0)
    return 2.0 / (qb + np.sqrt(qb * qb + 4.0 * qa))  # root of qa x^2 + qb x - 1 = 0


def _zero_contact(lam):
    """(P, D) at A = 0, the end of the MD curve on the DMT side."""
    x = _zero_contact_zone(lam)
    return -0.5 * lam * np.pi * x * x, -4.0 / 3.0 * lam * x


def _log_m_at(a_maugis, lam):
    """ln M at which A(M) = a_maugis (> 0), by a bracketing root finder."""
    target = np.log(a_maugis)

    def f(t, tg, lm):
        return np.log(_state_maugis(t, lm)[0]) - tg

    lo = np.full_like(target, _LOG_M_RANGE[0])
    hi = np.full_like(target, _LOG_M_RANGE[1])
    res = elementwise.find_root(f, (lo, hi), args=(target, lam),
                                tolerances=dict(xatol=1e-15, xrtol=1e-15))
    return res.x


class MaugisCurve(NamedTuple):
    """MD states in Maugis units.

    Parameters
    ----------
    load : ndarray
        Load P = W/(pi R dgamma) [-].
    approach : ndarray
        Approach D [-].
    zone_ratio : ndarray
        Zone ratio m = c/a [-] (inf at A = 0).
    """

    load: np.ndarray
    approach: np.ndarray
    zone_ratio: np.ndarray


class _MaugisPullOff(NamedTuple):
    """MD pull-off in Maugis units: the solver's internal state (the model's pull-off records are
    :func:`pull_off_nondimensional`'s :class:`dhfield.core.records.PullOff` and :func:`pull_off`'s
    :class:`dhfield.core.records.PullOff` (its SI group)).

    Parameters
    ----------
    contact_radius : ndarray
        Contact radius A [-].
    load : ndarray
        Load P = W/(pi R dgamma) [-].
    approach : ndarray
        Approach D [-].
    zone_ratio : ndarray
        Zone ratio m = c/a [-].
    """

    contact_radius: np.ndarray
    load: np.ndarray
    approach: np.ndarray
    zone_ratio: np.ndarray


def load_curve_maugis_units(a_maugis, lam):
    """MD load and approach at contact radius A, in Maugis' own units, vectorised.

    Parameters
    ----------
    a_maugis : array_like
        Contact radius A = a/(pi dgamma R^2/K)^(1/3) >= 0, K = 4E*/3 [-].
    lam : array_like
        Maugis parameter lambda = 2 sigma0 (R/(pi dgamma K^2))^(1/3) > 0 [-]
        (tested over :data:`LAMBDA_RANGE`).

    Returns
    -------
    MaugisCurve
        P, D and m = c/a [-].

    Notes
    -----
    Maugis (1992), the three equations of the module docstring, solved for
    ln M at the given A; at A = 0 the closed-form end point.
    """
    check_contact_size("a_maugis", a_maugis)
    check_positive("lam", lam, "Maugis parameter lambda, dimensionless")
    return _load_curve_maugis_units(a_maugis, lam)


def _load_curve_maugis_units(a_maugis, lam):
    """:func:`load_curve_maugis_units` on validated inputs."""
    a_maugis, lam = np.broadcast_arrays(np.asarray(a_maugis, dtype=float),
                                        np.asarray(lam, dtype=float))
    p = np.empty(a_maugis.shape)
    d = np.empty(a_maugis.shape)
    m = np.full(a_maugis.shape, np.inf)
    zero = a_maugis == 0.0
    if np.any(zero):
        p[zero], d[zero] = _zero_contact(lam[zero])
    pos = ~zero
    if np.any(pos):
        t = _log_m_at(a_maugis[pos], lam[pos])
        _, p[pos], d[pos], m[pos] = _state_maugis(t, lam[pos])
    return MaugisCurve(p, d, m)


def load_curve_nondimensional(a_star, mu, *, checked=True):
    """MD state at contact radius a*, in the paper's units (Eqs. 32-35).

    The nondimensional core of :func:`load_curve` (R = E* = dgamma = 1,
    sigma0 = mu, lambda = 1.1272 mu of :mod:`dhfield.core.transition`).

    Parameters
    ----------
    a_star : array_like
        Contact radius a* = a/c_r >= 0, Eq. (32) [-].
    mu : array_like
        Transition parameter, Eq. (35), > 0 [-].
    checked : bool, default True
        Validate ``a_star`` and ``mu``; False for internal callers that validated them once
        at their public entry (:func:`load_curve`, :mod:`dhfield.models.md_elliptic`).

    Returns
    -------
    dict
        ``W_star`` = P/2 (Eq. 34), ``a_star``, ``c_star`` (Dugdale zone radius
        c/c_r) and ``delta_star`` [-].

    Notes
    -----
    ``a* = A (3 pi/4)^(1/3)``, ``W* = P/2``, ``delta* = D (9 pi^2/16)^(1/3)`` from
    :func:`load_curve_maugis_units`.
    """
    lam = maugis_parameter(mu, checked=checked)
    if checked:
        check_contact_size("a_star", a_star)
    a_star = np.asarray(a_star, dtype=float)
    p, d, m = _load_curve_maugis_units(a_star / _A_UNIT, lam)
    a_star = np.broadcast_to(a_star, p.shape)
    with np.errstate(invalid="ignore"):
        c_star = np.where(a_star > 0, m * a_star, _zero_contact_zone(lam) * _A_UNIT)
    return {"W_star": 0.5 * p, "a_star": a_star, "c_star": c_star, "delta_star": d * _D_UNIT}


def _pull_off_maugis_units(lam, control="load"):
    """MD pull-off in Maugis' own units, vectorised over lambda, on validated inputs.

    Parameters
    ----------
    lam : array_like
        Maugis parameter lambda > 0 [-] (tested over :data:`LAMBDA_RANGE`).
    control : {'load', 'displacement'}
        The first minimum of P (load) or D (displacement) on unloading; the end
        point A = 0 when the curve has no interior minimum.

    Returns
    -------
    _MaugisPullOff
        A, P, D and m = c/a (inf at A = 0) [-].
    """
    lam = np.asarray(lam, dtype=float)
    col = 1 if control == "load" else 2

    def f(t, lm):
        return _state_maugis(t, lm)[col]

    grid = _log_m_at(np.broadcast_to(_SCAN_A, lam.shape + _SCAN_A.shape), lam[..., None])
    t, _ = scan_minimum(f, grid, (lam,), xatol=1e-14)
    a, p, d, m = _state_maugis(t, lam)
    # the curve ends at A = 0 (M -> infinity); compare with that end point exactly
    p0, d0 = _zero_contact(lam)
    # (within rounding: the grid's last point already sits at A ~ 1e-17)
    end = (p0 <= p + 1e-12 * np.abs(p)) if control == "load" else (d0 <= d + 1e-12 * np.abs(d))
    a = np.where(end, 0.0, a)
    p = np.where(end, p0, p)
    d = np.where(end, d0, d)
    m = np.where(end, np.inf, m)
    return _MaugisPullOff(a, p, d, m)


def _pull_off_state(mu, control):
    """MD ``W_star``, ``a_star``, ``c_star``, ``delta_star`` [-] at pull-off (:func:`_pull_off_maugis_units`)."""
    lam = maugis_parameter(mu, checked=False)
    a, p, d, m = _pull_off_maugis_units(lam, control)
    with np.errstate(invalid="ignore"):
        c_star = np.where(a > 0, m * a, _zero_contact_zone(lam)) * _A_UNIT
    return {"W_star": 0.5 * p, "a_star": a * _A_UNIT, "c_star": c_star, "delta_star": d * _D_UNIT}


@fill_doc
def pull_off_nondimensional(beta0, mu, *, control="load"):
    """MD pull-off record in the paper's units (Eqs. 32-35), vectorised, at lambda = 1.1272 mu.

    The nondimensional core of :func:`pull_off`, solved in Maugis units (scan and complex-step
    refinement, :func:`dhfield.core.pull_off_search.scan_minimum`).  Inputs are not validated here
    (:func:`dhfield.analysis.compare.pull_off` and :func:`pull_off` do).

    Parameters
    ----------
    %(circle_beta0_mu)s
    %(control)s

    Returns
    -------
    %(pull_off_nondimensional_returns)s
    """
    mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))[1]
    return pull_off_record("md", beta0, mu, _pull_off_state(mu, control), control=control, sin_skew=1.0,
                           geometry="circle")


@fill_doc
def load_curve(contact_radius, effective_radius, reduced_modulus, work_of_adhesion,
               max_adhesive_stress):
    """Maugis-Dugdale load and approach at the given contact radius.

    Parameters
    ----------
    %(contact_radius)s
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    max_adhesive_stress : array_like
        Dugdale stress sigma0 [Pa].

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve (model ``md``, circle): ``semi_major`` = ``semi_minor`` = a [m],
        ``adhesive_semi_major`` = ``adhesive_semi_minor`` = c, the Dugdale zone's
        radius [m], ``force`` W [N] (positive compressive), ``approach`` delta [m].  The header's ``mu`` is the
        Tabor parameter of the inputs, Eq. (35).

    Notes
    -----
    Solves the three MD equations of the module docstring (Maugis 1992) with
    ``lambda = 2 sigma0 (R/(pi dgamma K^2))^(1/3)``, K = 4E*/3.

    References
    ----------
    .. [1] D. Maugis, J. Colloid Interface Sci. 150 (1992) 243,
       doi:10.1016/0021-9797(92)90288-C
    """
    return si_circular_load_curve("md", load_curve_nondimensional, contact_radius, effective_radius,
                                  reduced_modulus, work_of_adhesion, max_adhesive_stress, zone=True)


@fill_doc
def pull_off(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress, *,
             control="load"):
    """Maugis-Dugdale state at pull-off, vectorised.

    Parameters
    ----------
    %(material)s
    max_adhesive_stress : array_like
        Dugdale stress sigma0 [Pa].
    control : {'load', 'displacement'}
        Pull-off at the minimum load (load control) or at the minimum approach
        (displacement control); either may sit at the end a = 0 of the curve.

    Returns
    -------
    dhfield.core.records.PullOff
        ``force`` [N], ``semi_major`` = ``semi_minor`` (the contact radius) and the
        Dugdale-zone radius [m], ``approach`` [m], the SI inputs and the nondimensional
        record.
    """
    return si_pull_off(pull_off_nondimensional, effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress,
                       control=control)


@fill_doc
def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress, *,
                   control="load"):
    """Compute the Maugis-Dugdale pull-off force [N].

    Parameters
    ----------
    %(material)s
    max_adhesive_stress : array_like
        Dugdale stress sigma0 [Pa].
    %(control)s

    Returns
    -------
    %(pull_off_force_returns)s
    """
    return pull_off(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress,
                    control=control).force

