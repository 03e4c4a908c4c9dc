"""Work of adhesion of the DH adhesive annulus along a ray theta_p (Eqs. 28-31).

Eq. (31) is the one-dimensional work of adhesion along theta_p = 0,

.. math:: \\Delta\\gamma = \\int_{r_{ab}}^{r_{cd}} \\sigma_{ac}(r)\\,\\frac{dh}{dr}\\,dr,

and :func:`work_of_adhesion` evaluates the same integral along any ray theta_p.

Quadrature
----------
The integrand behaves like sqrt(r - r_ab) at the contact edge (the Hertz gap
slope) and like sqrt(r_cd - r) at the adhesive edge (sigma_ac).  Both are removed
exactly by integrating in the ellipsoidal coordinate l of the contact ellipse
(the root of Eq. 12; r_ab <-> l = 0), with l = l_cd sin^2 t, t in [0, pi/2]:
sqrt(l) = sqrt(l_cd) sin t is analytic in t and sigma_ac ~ cos t.  The remaining
integrand is analytic; its nearest complex singularities sit at
sin t = +/- i b/sqrt(l_cd) (from the b^2 + l factor of Eq. B3), close to t = 0
when the annulus is wide compared with the contact.  Gauss-Legendre panels graded
geometrically towards t = 0 from t1 = asin(b/sqrt(l_cd)) keep the convergence
exponential for every ratio; 1e-13 relative with the default rule (see tests).

Along the ray the slope of the Hertz gap is, with the gradient of Eq. (13) and
the contact conditions 1/R' = Po ab I2(0)/E*, 1/R'' = Po ab I3(0)/E*,

    dh_H/dr = r [cos^2 theta_p Po ab (I2(0) - I2(l))
                 + sin^2 theta_p Po ab (I3(0) - I3(l))] / E*,

and dh/dr = (1 + v) dh_H/dr in the annulus (module :mod:`dhfield.models.dh_elliptic_fields`).
"""
from __future__ import annotations

import functools

import numpy as np
from scipy.special import roots_legendre

from . import dh_elliptic_fields, hertz
from ..core.validation import check_finite
from ..core.elliptic import ellipsoid_integrals
from ..core._docstrings import fill_doc

__all__ = ["work_of_adhesion", "graded_rule", "graded_panel_counts", "ragged_graded_rule"]

#: Gauss-Legendre nodes per panel of the graded rule.
NODES_PER_PANEL = 16
#: Geometric ratio of successive panels; 2/(q-1) = 1 keeps the Bernstein-ellipse
#: parameter of each panel at 1 + sqrt(2), i.e. ~1e-12 error with 16 nodes.
PANEL_RATIO = 3.0
#: Smallest first-panel end t1: the near-singularity scale b/sqrt(l_cd) reaches ~1e-20
#: over the accepted model domain (beta0 >= 1e-4, a* >= 1e-6, mu >= 1e-6); the rule
#: then has at most 64 panels.
T1_MIN = 1e-30


@functools.lru_cache(maxsize=8)
def _legendre(n):
    x, w = roots_legendre(n)
    return x, w


def graded_rule(t1, n_panels=None, nodes=NODES_PER_PANEL, t_end=np.pi / 2):
    """Composite Gauss-Legendre rule on [0, t_end], graded geometrically towards 0.

    Panels are [0, t1] and P geometric panels from t1 to t_end.  ``t1`` may be an
    array: every element gets its own panels but the same number of them, so the
    rule has a fixed shape ``t1.shape + (nodes * (P + 1),)`` and vectorises.

    Parameters
    ----------
    t1 : array_like
        End of the first panel, the scale of the near singularity [rad].
    n_panels : int, optional
        P; by default just enough for the smallest t1 at ratio :data:`PANEL_RATIO`.
    nodes : int, default NODES_PER_PANEL
        Gauss-Legendre nodes per panel.
    t_end : float, default pi/2
        End of the interval [rad].

    Returns
    -------
    t : ndarray
        Nodes, shape ``t1.shape + (nodes * (P + 1),)`` [rad].
    w : ndarray
        Weights, same shape [rad].

    Examples
    --------
    The rule integrates cos exactly enough: the integral over [0, pi/2] is 1.

    >>> import numpy as np
    >>> from dhfield.models import dh_elliptic_adhesion
    >>> t, w = dh_elliptic_adhesion.graded_rule(1e-3)
    >>> round(float(np.sum(w * np.cos(t))), 14)
    1.0
    """
    t1 = np.clip(np.asarray(t1, dtype=float), T1_MIN, t_end)
    if n_panels is None:
        n_panels = int(graded_panel_counts(t1.min(), t_end)) if t1.size else 0
    x, w = _legendre(nodes)
    ratio = (t_end / t1) ** (1.0 / max(n_panels, 1))
    j = np.arange(n_panels + 1)
    edges = t1[..., None] * ratio[..., None] ** j  # t1 ... t_end
    edges = np.concatenate([np.zeros(t1.shape + (1,)), edges], axis=-1)
    if n_panels == 0:
        edges = np.stack([np.zeros_like(t1), np.full_like(t1, t_end)], axis=-1)
    lo, hi = edges[..., :-1], edges[..., 1:]
    half = 0.5 * (hi - lo)
    mid = 0.5 * (hi + lo)
    t = (mid[..., None] + half[..., None] * x).reshape(t1.shape + (-1,))
    wt = (half[..., None] * w).reshape(t1.shape + (-1,))
    return t, wt


def graded_panel_counts(t1, t_end=np.pi / 2):
    """Geometric panels P of :func:`graded_rule` for each first-panel end ``t1``.

    Just enough panels from ``t1`` to ``t_end`` at ratio :data:`PANEL_RATIO`:
    P = ceil(log(t_end/t1)/log(PANEL_RATIO)), with t1 clipped to [T1_MIN, t_end].

    Parameters
    ----------
    t1 : array_like
        End of the first panel [rad].
    t_end : float, default pi/2
        End of the interval [rad].

    Returns
    -------
    ndarray of int
        P for each ``t1`` (0 when ``t1 = t_end``).
    """
    t1 = np.clip(np.asarray(t1, dtype=float), T1_MIN, t_end)
    return np.ceil(np.log(t_end / t1) / np.log(PANEL_RATIO)).astype(int)


def ragged_graded_rule(t1, nodes=NODES_PER_PANEL, t_end=np.pi / 2):
    """:func:`graded_rule` for many ``t1``, each with its own panel count, as flat panels.

    Element i gets the P_i + 1 panels [0, t1], [t1 r], ..., [t1 r^(P_i - 1), t_end]
    with r = (t_end/t1)^(1/P_i) and P_i = :func:`graded_panel_counts` (t1_i), the
    rule ``graded_rule(t1_i)`` gives it alone; so a result does not depend on the
    other elements of a batch.

    Parameters
    ----------
    t1 : array_like
        End of the first panel of each element [rad].
    nodes : int, default NODES_PER_PANEL
        Gauss-Legendre nodes per panel.
    t_end : float, default pi/2
        End of the interval [rad].

    Returns
    -------
    t : ndarray, shape (panels, nodes)
        Nodes of every panel [rad].
    w : ndarray, shape (panels, nodes)
        Weights of every panel [rad].
    first : ndarray of int
        Index of the first panel of each element (for ``np.add.reduceat``).
    owner : ndarray of int
        Element of each panel.
    """
    t1 = np.clip(np.asarray(t1, dtype=float), T1_MIN, t_end)
    n_panels = graded_panel_counts(t1, t_end)
    count = n_panels + 1
    first = np.cumsum(count) - count
    owner = np.repeat(np.arange(t1.size), count)
    j = np.arange(owner.size) - first[owner]  # panel index within its element
    ratio = (t_end / t1) ** (1.0 / np.maximum(n_panels, 1))
    hi = t1[owner] * ratio[owner] ** j
    lo = np.where(j == 0, 0.0, hi / ratio[owner])
    x, w = _legendre(nodes)
    half = 0.5 * (hi - lo)
    t = (0.5 * (hi + lo))[:, None] + half[:, None] * x
    return t, half[:, None] * w, first, owner


@fill_doc
def work_of_adhesion(semi_major, adhesive_semi_major, beta, scaling, theta=0.0, effective_radius=1.0,
                     reduced_modulus=1.0):
    """Work of adhesion along the ray ``theta`` of the DH annulus, Eq. (31) [J m^-2].

    Parameters
    ----------
    %(dh_state)s
    theta : array_like, default 0
        Polar angle theta_p of the ray; 0 is the major axis (Eq. 31) [rad].
    %(dh_material)s

    Returns
    -------
    ndarray
        Delta gamma(theta_p) = int_{r_ab}^{r_cd} sigma_ac (dh/dr) dr [J m^-2].

    Notes
    -----
    .. math::

        \\Delta\\gamma(\\theta_p) = \\int_{r_{ab}}^{r_{cd}} \\sigma_{ac}\\frac{dh}{dr}dr
        = \\int_0^{\\pi/2} \\sigma_{ac}\\,(1+v)\\frac{dh_H}{dl}\\,2 l_{cd}\\sin t\\cos t\\,dt

    At theta_p = 0 this is Eq. (31).  For beta = 1 it equals the closed form of
    Greenwood & Johnson (1998), v (1+v) 2E*/(3 pi R^2) (c-a)^2 (c+2a).
    """
    a, c, beta, v, r_eff, e = dh_elliptic_fields.check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                            effective_radius, reduced_modulus)
    theta = check_finite("theta", theta, "rad")
    a, c, beta, v, theta, r_eff, e = np.broadcast_arrays(a, c, beta, v, theta, r_eff, e)
    b, d = beta * a, beta * c
    cos2, sin2 = np.cos(theta) ** 2, np.sin(theta) ** 2
    r_cd = c * d / np.sqrt(d**2 * cos2 + c**2 * sin2)  # Eq. (A2)
    l_cd = hertz.ellipse_root(r_cd * np.cos(theta), r_cd * np.sin(theta), a, b)
    t1 = np.arcsin(np.minimum(1.0, b / np.sqrt(np.maximum(l_cd, 1e-300))))
    t, w = graded_rule(t1)
    ex = (lambda q: q[..., None])
    l = ex(l_cd) * np.sin(t) ** 2
    a2l, b2l = ex(a) ** 2 + l, ex(b) ** 2 + l
    r2 = 1.0 / (ex(cos2) / a2l + ex(sin2) / b2l)
    dr2_dl = r2**2 * (ex(cos2) / a2l**2 + ex(sin2) / b2l**2)
    po_ab = hertz.max_pressure(a, beta, r_eff, e)  # Eq. (8)
    po_cd = hertz.max_pressure(c, beta, r_eff, e)  # Eq. (20)
    _, i2, i3 = ellipsoid_integrals(l, ex(a), ex(b))
    _, i20, i30 = ellipsoid_integrals(0.0, a, b)
    k = po_ab * a * b / e
    slope = 0.5 * dr2_dl * ex(k) * (ex(cos2) * (ex(i20) - i2) + ex(sin2) * (ex(i30) - i3))  # dh_H/dl
    sigma = ex(v * po_cd) * np.sqrt(np.maximum(1.0 - r2 / ex(r_cd) ** 2, 0.0))  # Eq. (23)
    jac = 2.0 * ex(l_cd) * np.sin(t) * np.cos(t)
    out = (1.0 + v) * np.sum(w * sigma * slope * jac, axis=-1)  # Eq. (31)
    return out if out.ndim else out[()]
