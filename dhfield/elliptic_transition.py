"""Candidate pull-off of the adhesive elliptical contact from DMT to JKR: the sphere's
Maugis-Dugdale transition laid between the elliptical DMT and GVG limits.

A candidate for the recommended model of issue 20, NOT a default and not registered in
:mod:`dhfield.compare`.  It is exact at both ends of the transition and on the circle:

* mu -> 0: DMT for the paraboloid, ``W = -2 pi dgamma sqrt(R'R'')`` (Derjaguin's
  approximation: the gap outside a rigid-like contact integrates to this for any
  paraboloid), i.e. ``W* = -sin(theta_skew)`` of Eq. (34);
* mu -> infinity: the energy-minimising elliptical JKR of Giudici, Vella & Griffiths
  (:mod:`dhfield.jkr_elliptic_energy`);
* beta0 = 1: Maugis-Dugdale on the sphere (:mod:`dhfield.maugis_dugdale`), exactly.

Model
-----
With the sphere's transition weight, from MD at the same mu (lambda = 1.1272 mu, R = sqrt(R'R''),
the mapping of :mod:`dhfield.transition`),

.. math::

    g(\\mu) = \\frac{W^*_{MD}(\\mu) - W^*_{DMT}}{W^*_{JKR} - W^*_{DMT}}, \\qquad
    W^* = W^*_{DMT,ell} + \\left(W^*_{GVG}(\\beta_0) - W^*_{DMT,ell}\\right) g(\\mu),

``W*_DMT = -1``, ``W*_JKR = -3/4`` (load control) or ``-5/12`` (displacement control) on the
sphere and ``W*_DMT,ell = -sin(theta_skew)``.  g runs from 0 (DMT) to 1 (JKR); the sphere's
identity ``W*_MD = -1 + (W*_JKR + 1) g`` makes beta0 = 1 exact.  The effective mu is mu
itself: against the stored BEM ground truth (beta0 0.5-1, mu 0.3-5, load control) the
largest deviation is 0.34 % (``python -m verification.elliptic_transition``), at the level of
the BEM's own distance from MD on the sphere, so no other definition was fitted.

Cost: one GVG pull-off per distinct beta0 and one MD pull-off per distinct mu (about
0.2 ms each, vectorised); a (beta0 x mu) map costs the sum, not the product.
"""
from __future__ import annotations

import numpy as np

from . import jkr_elliptic_energy, maugis_dugdale
from ._adhesion import check_material, load_unit, scalar_or_array, tabor_parameter
from ._validation import check_control, check_interval, check_tabor
from .geometry import sin_skew_angle
from .jkr_elliptic import check_geometry

__all__ = ["transition_weight", "pull_off_nondimensional", "pull_off_force"]

#: W* of the circular JKR pull-off for each control (JKR 1971): -(3/2) and -(5/6) pi R dgamma
_JKR_W_STAR = {"load": -0.75, "displacement": -5.0 / 12.0}


def _unique_eval(func, x):
    """func over the distinct values of x only, broadcast back to the shape of x."""
    u, inv = np.unique(np.ravel(x), return_inverse=True)
    return np.asarray(func(u), dtype=float)[inv].reshape(np.shape(x))


def transition_weight(mu, control="load"):
    """The sphere's DMT-to-JKR weight g = (W*_MD + 1)/(W*_JKR + 1) at mu [-], in [0, 1].

    Parameters
    ----------
    mu : array_like
        Tabor parameter of Eq. (35) with R = sqrt(R'R'') [-].
    control : {'load', 'displacement'}

    Returns
    -------
    ndarray
        0 at the DMT limit (mu -> 0), 1 at the JKR limit (mu -> infinity).
    """
    check_control(control)
    mu = check_tabor("mu", mu)
    w_md = _unique_eval(lambda m: maugis_dugdale.pull_off_nondimensional(1.0, m, control=control).W_star, mu)
    return (w_md + 1.0) / (_JKR_W_STAR[control] + 1.0)


def pull_off_nondimensional(mu, beta0, control="load"):
    """Pull-off of the candidate model in the paper's units (Eqs. 32-35), vectorised.

    Parameters
    ----------
    mu : array_like
        Tabor parameter of Eq. (35) [-].
    beta0 : array_like
        Hertz ellipticity in (0, 1] [-]; broadcasts with ``mu``.
    control : {'load', 'displacement'}

    Returns
    -------
    dict
        ``W_star`` = W sin(theta_skew)/(2 pi R dgamma) (Eq. 34), the limits ``W_star_dmt``
        (-sin(theta_skew)) and ``W_star_jkr`` (GVG), and the weight ``weight`` g [-].

    Notes
    -----
    .. math:: W^* = -\\sin\\theta_{skew} + \\left(W^*_{GVG} + \\sin\\theta_{skew}\\right) g(\\mu)
    """
    check_control(control)
    mu = check_tabor("mu", mu)
    beta0 = check_interval("beta0", beta0, 0.0, 1.0, what="Hertz ellipticity b/a, dimensionless")
    mu, beta0 = np.broadcast_arrays(mu, beta0)
    g = transition_weight(mu, control)
    w_jkr = _unique_eval(lambda b: jkr_elliptic_energy.pull_off_nondimensional(b, 1.0, control=control).W_star, beta0)
    w_dmt = -_unique_eval(sin_skew_angle, beta0)  # DMT: W = -2 pi dgamma sqrt(R'R''), Eq. (34)
    return {"W_star": w_dmt + (w_jkr - w_dmt) * g, "W_star_dmt": w_dmt, "W_star_jkr": w_jkr, "weight": g}


def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress, *,
                   radius_ratio=None, beta0=None, control="load"):
    """Pull-off force of the candidate model [N] (negative).

    Parameters
    ----------
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        R = sqrt(R'R'') [m], E* [Pa], dgamma [J/m^2].
    max_adhesive_stress : array_like
        Dugdale stress sigma0 [Pa]; mu of Eq. (35) follows.
    radius_ratio, beta0 : array_like
        R'/R'' >= 1, or its Hertz ellipticity in (0, 1] (give one) [-].
    control : {'load', 'displacement'}

    Returns
    -------
    ndarray
        W [N]: between -2 pi dgamma R (DMT) and the GVG pull-off (JKR).
    """
    b0 = check_geometry(radius_ratio, beta0)
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    mu = tabor_parameter(max_adhesive_stress, r, e, w)
    st = pull_off_nondimensional(mu, b0, control)
    return scalar_or_array(st["W_star"] / sin_skew_angle(b0) * load_unit(r, w))
