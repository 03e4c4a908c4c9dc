"""The recommended model of the adhesive elliptical contact, ``md-elliptic``: the sphere's
Maugis-Dugdale transition carried over to the ellipse, between the elliptical DMT and the
exact-energy elliptical JKR limits.

Registered in :mod:`dhfield.compare` as ``md-elliptic`` (:data:`MODEL_NAME`), the default
model of the library, the command line, the SI API and the sweeps.  The name says what it
approximates: the elliptical contact with a Dugdale (Maugis-Dugdale) adhesive law, which
the BEM of :mod:`dhfield.bem` solves exactly; it is not a closed-form solution of that
problem but an interpolation between three exact results:

* mu -> 0: DMT for the paraboloid, ``W = -2 pi dgamma sqrt(R'R'')`` (Derjaguin's
  approximation: the gap outside a rigid-like contact integrates to this for any
  paraboloid), i.e. ``W* = -sin(theta_skew)`` of Eq. (34), with the Hertz ellipse as
  load curve;
* mu -> infinity: the energy-minimising elliptical JKR of Giudici, Vella & Griffiths
  (:mod:`dhfield.jkr_elliptic_energy`, GVG), pull-off and load curve;
* beta0 = 1: Maugis-Dugdale on the sphere (:mod:`dhfield.maugis_dugdale`), pull-off and
  load curve, exactly.

Error against the ground truth: the largest deviation of the load-control pull-off from
the 30 stored BEM cases (``data/adhesive_ground_truth.nc``, beta0 0.5-1, mu 0.3-5) is
0.34 % (``python -m verification.elliptic_transition``), at the level of the BEM's own
distance from MD on the sphere.  Elsewhere in the accepted domain (crossing angles down to
10 deg, mu from 1e-6 to 1e12) it rests on the three exact limits above and the smooth
interpolation between them.

Pull-off
--------
With the sphere's transition weight, from MD at the same mu (lambda = 1.1272 mu,
R = sqrt(R'R''), the mapping of :mod:`dhfield.transition`),

.. math::

    g(\\mu) = \\frac{W^*_{MD}(\\mu) - W^*_{DMT}}{W^*_{JKR} - W^*_{DMT}}, \\qquad
    W^* = W^*_{DMT,ell} + \\left(W^*_{GVG}(\\beta_0) - W^*_{DMT,ell}\\right) g(\\mu),
    \\qquad (T1)

``W*_DMT = -1``, ``W*_JKR = -3/4`` (load control) or ``-5/12`` (displacement control) on the
sphere and ``W*_DMT,ell = -sin(theta_skew)``.  g runs from 0 (DMT) to 1 (JKR); the sphere's
identity ``W*_MD = -1 + (W*_JKR + 1) g`` makes beta0 = 1 exact.  The effective mu is mu
itself: no parameter was fitted to the ground truth.

Load curve
----------
The ellipse's curve is built from the limits' curves, each taken at the same position
relative to its own pull-off (load control; a_MD, a_JKR, a_GVG the pull-off contact sizes
of MD on the sphere, JKR and GVG; DMT has its pull-off at a = 0).  Above the pull-off, with
the shift x >= 0,

.. math::

    W^* &= (1 - g)\\,(C_{ell}\\,x^3 - \\sin\\theta_{skew}) + g\\,W^*_{GVG}(a_{GVG} + x)
           + \\sin\\theta_{skew}\\,\\epsilon(x),  \\qquad (T2)

    \\epsilon(x) &= W^*_{MD}(a_{MD} + x) - (1 - g)\\,(C_{sph}\\,x^3 - 1) - g\\,W^*_{JKR}(a_{JKR} + x),

    \\delta^* &= \\delta^*_{MD}(a_{MD} + x) + g\\,[\\delta^*_{GVG}(a_{GVG} + x)
           - \\delta^*_{JKR}(a_{JKR} + x)] + (1 - g)(D_{ell} - 1)\\,x^2,  \\qquad (T3)

    a^* &= a_p + x, \\quad a_p = a_{MD} + g\\,(a_{GVG} - a_{JKR}), \\qquad
    b^* = a^*\\,[(1 - g)\\,\\beta_0 + g\\,\\beta_{GVG}],  \\qquad (T4)

where ``C_sph = 2/(3 pi)`` and ``C_ell`` are the Hertz loads per a*^3 of the sphere and the
ellipse (Eq. 10 with sin(theta_skew), Eq. 34), ``D_ell`` the ellipse's Hertz approach per
a*^2 (Eq. 14a; 1 for the sphere) and beta_GVG GVG's contact ellipticity at its argument.
Eq. (T2) is the blend of the elliptical DMT and GVG curves with the weight g of Eq. (T1),
plus epsilon, the sphere's departure of MD from the same blend of its own limits, scaled
by the ellipse's adhesive load sin(theta_skew); epsilon and its slope vanish at x = 0.
Below the pull-off (a* < a_p, the unstable branch under load control) the shift becomes
a scale, ``t = a*/a_p`` in [0, 1): every curve is taken at t times its pull-off size and

.. math::

    W^* = -\\sin\\theta_{skew} + (W^*_{GVG,po} + \\sin\\theta_{skew})\\,g\\,R_{MD}
          \\left(R_{GVG}/R_{JKR}\\right)^{g^2},  \\qquad (T5)

with ``R_MD = (W*_MD + 1)/(W*_MD,po + 1)``, ``R_JKR = (W*_JKR + 1)/(W*_JKR,po + 1)``,
``R_GVG = (W*_GVG + sin)/(W*_GVG,po + sin)`` the growths of the three loads above their
pull-offs (all >= 1, 1 at t = 1; the exponent g^2 keeps W* above the pull-off load on this
branch, checked on a grid by the tests); the approach is Eq. (T3) at the scaled sizes
(the DMT bracket 0) plus ``m a_p (t - 1) t^2`` (Eq. T6), with m the difference of the two
forms' slopes d(delta*)/da* at a_p, so that delta* is continuously differentiable there.
The curve runs down to a* = 0, where W* = sin(theta_skew) W*_MD(0), and covers the JKR
and GVG curves entirely.  At a* = a_p both forms of W* agree with zero slope, since every
curve is at its pull-off.

Limits, exact: mu -> 0 (g -> 0, a_MD -> 0, MD -> DMT) gives the Hertz ellipse minus
sin(theta_skew), the elliptical DMT; mu -> infinity (g -> 1, MD -> JKR, a_MD -> a_JKR)
gives GVG's curve; beta0 = 1 (GVG = JKR, C_ell = C_sph, D_ell = 1) gives MD.  At high load
the curve tends to the Hertz ellipse to leading order in a*.

**One model.** Every curve of Eq. (T2) is stationary at its own pull-off (x = 0), so the
load curve is stationary at x = 0 with the value of Eq. (T1): under load control the
pull-off of :func:`pull_off_nondimensional` is the minimum of :func:`load_curve_nondimensional`
(tests check it).  Under displacement control the record is Eqs. (T1)-(T4) aligned at the
minima of delta* of MD, JKR and GVG instead (the minimum of delta* of that
displacement-aligned curve); the load curve here is the load-aligned one, whose own minimum
of delta* differs from the displacement-control record (``python -m
verification.bench_recommended`` prints by how much).

The model defines no adhesive zone (``c_star``, ``d_star``: NaN) and no double-Hertz factor
(``v``: NaN).  The contact ellipticity b*/a* of Eq. (T4) is the interpolation of the two
limits' (Hertz's beta0 and GVG's), a model quantity, not a solved one.

Cost: one GVG pull-off per distinct beta0 and one MD pull-off per distinct mu (about
0.2 ms each, vectorised); a (beta0 x mu) map costs the sum, not the product.  Equation
labels (T1)-(T6) are this module's.
"""
from __future__ import annotations

import numpy as np
from scipy import special

from . import jkr, jkr_elliptic_energy, maugis_dugdale
from ._adhesion import check_material, load_unit, scalar_or_array, tabor_parameter
from ._validation import check_control, check_interval, check_tabor
from .elliptic import complete_k
from .geometry import sin_skew_angle
from .jkr_elliptic import check_geometry
from .records import pull_off_record

__all__ = ["MODEL_NAME", "transition_weight", "pull_off_nondimensional", "load_curve_nondimensional",
           "pull_off_force"]

#: The model's name in :mod:`dhfield.compare`.
MODEL_NAME = "md-elliptic"
_NAN = float("nan")
#: W* of the circular JKR pull-off for each control (JKR 1971): -(3/2) and -(5/6) pi R dgamma
_JKR_W_STAR = {"load": -0.75, "displacement": -5.0 / 12.0}
#: Hertz load per a*^3 of the sphere, W* = 2 a*^3/(3 pi) (Eq. 10 at beta = 1, Eq. 34)
_C_SPHERE = 2.0 / (3.0 * np.pi)
#: Smallest GVG contact size evaluated (GVG at a* -> 0 is the circle, W* -> 0)
_A_MIN = 1e-12


def _unique_eval(func, x):
    """func over the distinct values of x only, broadcast back to the shape of x."""
    u, inv = np.unique(np.ravel(x), return_inverse=True)
    return np.asarray(func(u), dtype=float)[inv].reshape(np.shape(x))


def transition_weight(mu, control="load"):
    """Compute the sphere's DMT-to-JKR weight g = (W*_MD + 1)/(W*_JKR + 1) at mu, in [0, 1].

    Parameters
    ----------
    mu : array_like
        Tabor parameter of Eq. (35) with R = sqrt(R'R'') [-].
    control : {'load', 'displacement'}
        Loading mode of the MD and JKR pull-offs.

    Returns
    -------
    ndarray
        The weight g [-]: 0 at the DMT limit (mu -> 0), 1 at the JKR limit (mu -> infinity).
    """
    check_control(control)
    mu = check_tabor("mu", mu)
    w_md = _unique_eval(lambda m: maugis_dugdale.pull_off_nondimensional(1.0, m, control=control).W_star, mu)
    return (w_md + 1.0) / (_JKR_W_STAR[control] + 1.0)


def _hertz_constants(beta0):
    """C_ell (Hertz W* per a*^3) and D_ell (Hertz delta* per a*^2) of the ellipse (R = E* = 1).

    Eq. (10) with Eq. (11)'s Carlson form, ``W = pi a^3/sqrt(R_D(0, beta^2, 1) R_D(0, 1, beta^2))``,
    times sin(theta_skew)/(2 pi) (Eq. 34); Eq. (14a), ``delta = Po b K(k) = 3 W K(k)/(2 pi a)``.
    Both are those of :mod:`dhfield.hertz` (1 and 2/(3 pi) at the circle), restated here to keep this
    module on the comparison layer.
    """
    beta0 = np.asarray(beta0, float)
    b2 = beta0 * beta0
    w1 = np.pi / np.sqrt(special.elliprd(0.0, b2, 1.0) * special.elliprd(0.0, 1.0, b2))  # Eqs. (10), (11)
    c_ell = sin_skew_angle(beta0) * w1 / (2.0 * np.pi)  # Eq. (34)
    return c_ell, 3.0 * w1 * complete_k(beta0) / (2.0 * np.pi)  # Eq. (14a)


def _sphere(mu, control):
    """MD pull-off state and the weight g per mu (distinct values evaluated once)."""
    u, inv = np.unique(np.ravel(mu), return_inverse=True)
    rec = maugis_dugdale.pull_off_nondimensional(1.0, u, control=control)
    g = (np.asarray(rec.W_star, float) + 1.0) / (_JKR_W_STAR[control] + 1.0)
    out = {"g": g, "W": rec.W_star, "a": rec.a_star, "delta": rec.delta_star}
    return {k: np.asarray(v, float)[inv].reshape(np.shape(mu)) for k, v in out.items()}


def _ellipse(beta0, control):
    """GVG pull-off state, sin(theta_skew) and the Hertz constants per beta0 (distinct values once)."""
    u, inv = np.unique(np.ravel(beta0), return_inverse=True)
    rec = jkr_elliptic_energy.pull_off_nondimensional(u, 1.0, control=control)
    c_ell, d_ell = _hertz_constants(u)
    out = {"W": rec.W_star, "a": rec.a_star, "delta": rec.delta_star, "beta": rec.ellipticity,
           "sin": sin_skew_angle(u), "c_ell": c_ell, "d_ell": d_ell}
    return {k: np.asarray(v, float)[inv].reshape(np.shape(beta0)) for k, v in out.items()}


def _jkr_state(control):
    rec = jkr.pull_off_nondimensional(1.0, 1.0, control=control)
    return {"W": float(rec.W_star), "a": float(rec.a_star), "delta": float(rec.delta_star)}


def pull_off_nondimensional(beta0, mu, *, control="load"):
    """Pull-off record of the recommended model in the paper's units (Eqs. 32-35), vectorised.

    Inputs are not validated here (:func:`dhfield.compare.pull_off` does).

    Parameters
    ----------
    beta0 : array_like
        Hertz ellipticity b/a of the geometry, in (0, 1] [-].
    mu : array_like
        Tabor parameter of Eq. (35) [-]; broadcasts with ``beta0``.
    control : {'load', 'displacement'}
        Loading mode: the minimum of W* (load) or of delta* (displacement) of the curve of
        Eqs. (T2)-(T4) aligned at the pull-offs of that mode.

    Returns
    -------
    dhfield.records.PullOff
        ``W_star`` of Eq. (T1); ``a_star``, ``b_star``, ``delta_star`` and ``ellipticity``
        of Eqs. (T3)-(T4) at x = 0; ``c_star``, ``d_star``, ``v`` and
        ``adhesive_ellipticity`` are NaN (the model defines no adhesive zone);
        ``at_zero_contact`` where a* = 0 (beta0 = 1 with MD's pull-off at zero contact).

    Notes
    -----
    .. math:: W^* = -\\sin\\theta_{skew} + \\left(W^*_{GVG} + \\sin\\theta_{skew}\\right) g(\\mu)

    (Eq. T1 of the module docstring; Eq. T2 at x = 0 is the same sum.)
    """
    beta0, mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))
    sph, ell, jk = _sphere(mu, control), _ellipse(beta0, control), _jkr_state(control)
    g = sph["g"]
    w = -ell["sin"] + (ell["W"] + ell["sin"]) * g  # Eq. (T1)
    a = sph["a"] + g * (ell["a"] - jk["a"])  # Eq. (T4), x = 0
    d = sph["delta"] + g * (ell["delta"] - jk["delta"])  # Eq. (T3), x = 0
    beta = (1.0 - g) * beta0 + g * ell["beta"]  # Eq. (T4)
    st = {"W_star": w, "a_star": a, "b_star": beta * a, "delta_star": d, "c_star": _NAN, "d_star": _NAN,
          "ellipticity": beta, "at_zero_contact": a == 0.0}
    return pull_off_record(MODEL_NAME, beta0, mu, st, control=control, sin_skew=ell["sin"], geometry="ellipse")


def _limit_curves(a_md, a_jkr, a_gvg, beta0, mu):
    """MD (sphere), JKR (sphere) and GVG (ellipse) states at the given contact sizes."""
    md_c = maugis_dugdale.load_curve_nondimensional(a_md, mu)
    jk_c = jkr.load_curve_nondimensional(a_jkr)
    if beta0 == 1.0:  # GVG is JKR at the circle: the corrections vanish identically
        gv_c = {**jkr.load_curve_nondimensional(a_gvg), "beta": np.ones(np.shape(a_gvg))}
    else:
        gv_c = jkr_elliptic_energy.load_curve_nondimensional(np.maximum(a_gvg, _A_MIN), beta0)
    return md_c, jk_c, gv_c


def _slope_mismatch(sph, jk, ell, g, a_p, beta0, mu):
    """d(delta*)/da* at a_p of the shifted form (T3) minus that of the scaled form (T6) [-].

    Central differences (relative step 1e-6) of the three limit curves at their pull-off sizes.
    """
    if a_p <= 0.0:
        return 0.0
    sizes = np.array([sph["a"], jk["a"], ell["a"]])
    h = 1e-6 * np.maximum(sizes, 1e-3)
    lo = _limit_curves(*(sizes - h), beta0, mu)
    hi = _limit_curves(*(sizes + h), beta0, mu)
    dd = [(float(hi[i]["delta_star"]) - float(lo[i]["delta_star"])) / (2.0 * h[i]) for i in range(3)]
    shifted = dd[0] + g * (dd[2] - dd[1])
    scaled = (sizes[0] * dd[0] + g * (sizes[2] * dd[2] - sizes[1] * dd[1])) / a_p
    return shifted - scaled


def load_curve_nondimensional(a_star, beta0, mu, *, control="load"):
    """State of the recommended model at contact semi-major axis a*, in the paper's units.

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axis a* = a/c_r >= 0, Eq. (32) [-].
    beta0 : float
        Hertz ellipticity b/a of the geometry, in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35) [-].
    control : {'load', 'displacement'}
        The pull-offs the curve is aligned at (module docstring); 'load', the default, is
        the model's load curve, whose minimum of W* is the load-control pull-off record.

    Returns
    -------
    dict
        ``W_star`` (Eq. 34), ``a_star``, ``b_star``, ``delta_star`` (approach in c_r^2/R) and
        the contact ellipticity ``beta`` = b*/a* [-], arrays of the shape of ``a_star``.

    Notes
    -----
    Eqs. (T2)-(T4) of the module docstring above the pull-off size a_p, the scaled form
    below it.  Each point costs one MD and one GVG state at a given contact size
    (bracketing root finders).
    """
    check_control(control)
    a_in = np.asarray(check_interval("a_star", a_star, 0.0, np.inf, low_open=False,
                                     what="contact semi-major axis a/c_r, dimensionless"), float)
    a_e = np.atleast_1d(a_in)
    beta0 = float(check_interval("beta0", beta0, 0.0, 1.0, what="Hertz ellipticity b/a, dimensionless"))
    mu = float(check_tabor("mu", mu))
    sph = {k: float(v) for k, v in _sphere(np.asarray(mu), control).items()}
    ell = {k: float(v) for k, v in _ellipse(np.asarray(beta0), control).items()}
    jk = _jkr_state(control)
    g = sph["g"]
    a_p = sph["a"] + g * (ell["a"] - jk["a"])  # Eq. (T4), the pull-off size
    above = a_e >= a_p
    x = np.where(above, a_e - a_p, 0.0)  # shift above the pull-off
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(above, 1.0, a_e / a_p)  # scale below it (a_p > 0 there)
    md_c, jk_c, gv_c = _limit_curves(t * sph["a"] + x, t * jk["a"] + x, t * ell["a"] + x, beta0, mu)
    # above: Eqs. (T2), (T3)
    # the sphere's MD minus its shift-aligned DMT-JKR blend: 0 with zero slope at x = 0
    resid = md_c["W_star"] - (1.0 - g) * (_C_SPHERE * x**3 - 1.0) - g * jk_c["W_star"]
    w = np.array((1.0 - g) * (ell["c_ell"] * x**3 - ell["sin"]) + g * gv_c["W_star"]
                 + ell["sin"] * resid)  # Eq. (T2)
    dmt_d = (ell["d_ell"] - 1.0) * x**2
    d = np.array(md_c["delta_star"] + g * (gv_c["delta_star"] - jk_c["delta_star"])
                 + (1.0 - g) * dmt_d)  # Eq. (T3)
    below = ~above
    if np.any(below):
        # Eq. (T5): relative growths of the three loads above their pull-offs, all 1 at t = 1
        r_md = (md_c["W_star"][below] + 1.0) / (sph["W"] + 1.0)
        r_gvg = (gv_c["W_star"][below] + ell["sin"]) / (ell["W"] + ell["sin"])
        r_jkr = (jk_c["W_star"][below] + 1.0) / (jk["W"] + 1.0)
        w[below] = -ell["sin"] + (ell["W"] + ell["sin"]) * g * r_md * (r_gvg / r_jkr) ** (g * g)  # Eq. (T5)
        # Eq. (T6): the approach, C1 at a_p through the slope term m a_p (t - 1) t^2
        tb = t[below]
        d[below] += _slope_mismatch(sph, jk, ell, g, a_p, beta0, mu) * a_p * (tb - 1.0) * tb * tb
    beta = (1.0 - g) * beta0 + g * gv_c["beta"]  # Eq. (T4)
    out = {"W_star": w, "a_star": a_e, "b_star": beta * a_e, "delta_star": d, "beta": beta}
    return {k: np.reshape(v, a_in.shape) for k, v in out.items()}


def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress, *,
                   radius_ratio=None, beta0=None, control="load"):
    """Compute the pull-off force of the recommended model [N] (negative).

    Parameters
    ----------
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        R = sqrt(R'R'') [m], E* [Pa], dgamma [J/m^2].
    max_adhesive_stress : array_like
        Dugdale stress sigma0 [Pa]; mu of Eq. (35) follows.
    radius_ratio, beta0 : array_like, optional
        R'/R'' >= 1, or its Hertz ellipticity in (0, 1] (give one) [-].
    control : {'load', 'displacement'}
        Loading mode.

    Returns
    -------
    ndarray
        W [N]: between -2 pi dgamma R (DMT) and the GVG pull-off (JKR).
    """
    check_control(control)
    b0 = check_geometry(radius_ratio, beta0)
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    mu = check_tabor("mu", tabor_parameter(max_adhesive_stress, r, e, w))
    st = pull_off_nondimensional(b0, mu, control=control)
    return scalar_or_array(st.W_star / sin_skew_angle(b0) * load_unit(r, w))
