"""Approximate JKR theory of an elliptical contact (Johnson & Greenwood 2005).

Source: K. L. Johnson & J. A. Greenwood, "An approximate JKR theory for elliptical
contacts", J. Phys. D: Appl. Phys. 38 (2005) 1042-1046, doi:10.1088/0022-3727/38/7/012.
The model is reconstructed here from its assumptions (physics notes, Sec. 6) and
every step below was derived and checked independently (tests: quadrature, the
Hertz and JKR limits).

Model
-----
Gap ``z = A x^2 + B y^2`` with ``A = 1/(2R')``, ``B = 1/(2R'')``, R' >= R''
(x along R', as everywhere in dhfield).  The contact is an ellipse with semi-axes
a (along x) and b = beta a (along y); its pressure is

.. math:: p = \\frac{\\alpha_0 + \\alpha_1 X^2 + \\alpha_2 Y^2}{\\sqrt{1 - X^2 - Y^2}},
          \\qquad X = x/a, \\; Y = y/b .

The surface displacement inside the ellipse is quadratic in x, y.  Matching its
curvatures to A and B gives two linear equations for alpha1, alpha2 (the flat-punch
term alpha0 only shifts the approach):

.. math::

    A = \\frac{ab}{2E^*}\\left[\\alpha_1(b^2J_{12} - 2J_1) + \\alpha_2(J_1 - b^2J_{12})\\right]

    B = \\frac{ab}{2E^*}\\left[\\alpha_1(J_2 - a^2J_{12}) + \\alpha_2(a^2J_{12} - 2J_2)\\right]

    \\delta = \\frac{ab}{2E^*}\\left[2\\alpha_0 J_0 + \\alpha_1 b^2 J_2 + \\alpha_2 a^2 J_1\\right]

with the ellipsoidal-potential integrals (Delta(s) = sqrt(s (a^2+s)(b^2+s)))

.. math::

    J_0 = \\int_0^\\infty\\frac{ds}{\\Delta} = 2R_F(0,b^2,a^2), \\quad
    J_1 = \\int_0^\\infty\\frac{ds}{(a^2+s)\\Delta} = \\tfrac23 R_D(0,b^2,a^2), \\quad
    J_2 = \\tfrac23 R_D(0,a^2,b^2),

    J_{12} = \\int_0^\\infty\\frac{ds}{(a^2+s)(b^2+s)\\Delta} = \\frac{J_2 - J_1}{a^2 - b^2}
           = \\frac{1}{a^5}\\sum_{n\\ge0}\\frac{(3/2)_n}{n!}B(\\tfrac12, n+\\tfrac52)\\,k^{2n}.

(The displacements of X^2/sqrt(Q) and Y^2/sqrt(Q) are 2a^2 d/d(a^2) and
2b^2 d/d(b^2) of the Hertz displacement, Eq. 12a; the identities
a^2 J_1 + b^2 J_2 = J_0 and 3a^2 J_11 + b^2 J_12 = 3 J_1 remove J_11 and J_22.
The series, with k^2 = 1 - beta^2, is used for k^2 < 1/4, where the divided
difference would lose digits; it is exact at the circle.)

Griffith's criterion at the ends of both axes only: the stress intensity factors
``K_I = -(alpha0 + alpha1) sqrt(pi a)`` and ``-(alpha0 + alpha2) sqrt(pi b)`` both
equal sqrt(2 E* dgamma).  The load is ``W = 2 pi a b [alpha0 + (alpha1 + alpha2)/3]``.

Closed-form parametrisation (derived here)
------------------------------------------
alpha1 and alpha2 are linear in a at fixed beta: alpha_i = a g_i(beta, R'/R'').
Subtracting the two Griffith conditions gives the contact size explicitly,

.. math:: a^{3/2} = \\sqrt{\\frac{2\\Delta\\gamma}{\\pi E^*}}\\,
          \\frac{\\beta^{-1/2} - 1}{g_1(\\beta) - g_2(\\beta)} ,

so the load curve is closed form in beta, which runs from the Hertz ellipticity
beta0 (g1 = g2: a -> infinity, high load) to 1 (a -> 0): the contact becomes
rounder on unloading.  At beta0 = 1 the model is JKR exactly (handled as the
circle, not as a limit).

Normalisation
-------------
Loads are reported as in the paper, ``W* = W sin(theta_skew)/(2 pi R dgamma)``
(Eq. 34) with sin(theta_skew) of beta0 and R = sqrt(R'R''), so that elliptical
JKR shares the axes of Figs. 8-9 with the DH models; lengths in
c_r = (R^2 dgamma/E*)^(1/3).  The Hertz load and a* follow the same units.
:func:`pull_off_force_ratio` gives the pull-off in units of the circular JKR
value 1.5 pi R dgamma instead (no sin(theta_skew)).
"""
from __future__ import annotations

import numpy as np
from scipy import special
from scipy.optimize import elementwise

from ..core.units import (approach_unit, check_material, length_unit, load_unit, scalar_or_array, si_curve,
                          si_pull_off)
from ..core.validation import as_circle, check_control, check_ellipticity, check_finite, check_interval
from ..core.geometry import ellipticity_from_radius_ratio, sin_skew_angle
from ..core.pull_off_search import scan_minimum
from ..core.records import pull_off_record
from ..core._docstrings import fill_doc

__all__ = [
    "EllipticJKR",
    "load_curve",
    "pull_off",
    "pull_off_force",
    "pull_off_force_ratio",
    "pull_off_ellipticity",
    "ellipticity_at_load",
    "load_curve_nondimensional",
    "pull_off_nondimensional",
    "state_at_ellipticity",
]

_SERIES_K2 = 0.25  # below this k^2 = 1 - beta^2, J12 from its series (terms ~ k^(2n))
_SERIES_TERMS = 64  # 0.25^64 ~ 1e-39
_U_EDGE = 1e-12  # parameter u in (0, 1) kept this far from the ends (a -> inf, a -> 0)
_SCAN_U = 0.5 * (1.0 - np.cos(np.pi * np.linspace(0.0, 1.0, 80)))  # dense at both ends
_SCAN_U = np.clip(_SCAN_U, 1e-9, 1.0 - 1e-9)

_N = np.arange(_SERIES_TERMS)
_SERIES_COEF = np.cumprod(np.concatenate([[1.0], (1.5 + _N[:-1]) / (_N[:-1] + 1.0)])) * \
    np.cumprod(np.concatenate([[3.0 * np.pi / 8.0], (_N[:-1] + 2.5) / (_N[:-1] + 3.0)]))


def _integrals(beta, k2):
    """J0, J1, J2, J12 for a = 1, b = beta, k2 = 1 - beta^2 given accurately.

    Complex-safe (the pull-off uses a complex-step derivative).
    """
    b2 = beta * beta
    j0 = 2.0 * special.elliprf(0.0, b2, 1.0)
    j1 = 2.0 / 3.0 * special.elliprd(0.0, b2, 1.0)
    j2 = 2.0 / 3.0 * special.elliprd(0.0, 1.0, b2)
    small = np.real(k2) < _SERIES_K2
    ks = np.where(small, k2, 0.0)
    series = np.polyval(_SERIES_COEF[::-1], ks)  # sum_n (3/2)_n/n! B(1/2, n+5/2) k^(2n)
    kd = np.where(small, 1.0, k2)
    return j0, j1, j2, np.where(small, series, (j2 - j1) / kd)


def _radius_ratio_m1(beta0):
    """R'/R'' - 1 of the Hertz ellipticity beta0, without cancellation: (1 - b^2) J12/J1."""
    beta0 = np.asarray(beta0, dtype=float)
    k2 = (1.0 - beta0) * (1.0 + beta0)
    _, j1, _, j12 = _integrals(beta0, k2)
    return k2 * j12 / j1  # J2/J1 - 1, since J2 - J1 = k^2 J12


def shape_coefficients(beta, k2, rho_m1):
    """g1, g2 with alpha_i = a g_i (R = E* = 1) and the integrals.

    ``rho_m1`` = R'/R'' - 1.  g1 - g2 is formed directly: with the curvature
    rows summed, g1 - g2 = beta J1 [(rho - 1) - k^2 J12/J1]/(4 sqrt(rho) det), which
    vanishes at the Hertz ellipticity (rho = J2/J1) without cancellation.
    """
    j0, j1, j2, j12 = _integrals(beta, k2)
    b2 = beta * beta
    rho = 1.0 + rho_m1
    gap_a = 0.5 / np.sqrt(rho)  # A = 1/(2R'), R' = sqrt(rho)
    gap_b = 0.5 * np.sqrt(rho)  # B = 1/(2R'')
    m11 = 0.5 * beta * (b2 * j12 - 2.0 * j1)  # JG (2005): curvature match along x (derived form)
    m12 = 0.5 * beta * (j1 - b2 * j12)
    m21 = 0.5 * beta * (j2 - j12)  # JG (2005): curvature match along y (derived form)
    m22 = 0.5 * beta * (j12 - 2.0 * j2)
    det = m11 * m22 - m12 * m21
    g2 = (gap_b * m11 - gap_a * m21) / det
    dg = beta * j1 * (rho_m1 - k2 * j12 / j1) / (4.0 * np.sqrt(rho) * det)
    return g2 + dg, g2, dg, j0, j1, j2


def _griffith_at_axis_ends(one_m_beta, beta, k2, g1, g2, dg):
    """JG's condition: the size a and alpha0 at ellipticity beta (K_I = sqrt(2 E* dgamma) at both axis ends)."""
    root = np.expm1(-0.5 * np.log1p(-one_m_beta))  # beta^(-1/2) - 1
    a = (np.sqrt(2.0 / np.pi) * root / dg) ** (2.0 / 3.0)  # JG (2005): K_I equal at both axis ends
    a = np.where(np.isnan(np.real(a)), np.inf, a)
    return a, -(a * g1) - np.sqrt(2.0 / (np.pi * a))  # JG (2005): K_I = sqrt(2 E* dgamma) at the end of a


def _state_u(u, beta0, rho_m1, sin_skew):
    """Closed-form elliptical JKR state at beta = beta0 + (1 - beta0) u (paper units)."""
    return JG.state_u(u, beta0, rho_m1, sin_skew)


def circle_state(a_star, sin_skew=1.0):
    a = np.asarray(a_star, dtype=float)
    w = (4.0 / 3.0 * a**3 - np.sqrt(8.0 * np.pi * a**3)) / (2.0 * np.pi)  # JKR (1971)
    d = a**2 - np.sqrt(2.0 * np.pi * a)
    return {"W_star": w * sin_skew, "a_star": a, "b_star": a, "delta_star": d,
            "beta": np.ones_like(a)}


def geometry_terms(beta0):
    """beta0, R'/R'' - 1 and sin(theta_skew) of Eq. (34)."""
    beta0 = np.asarray(beta0, dtype=float)
    rho_m1 = _radius_ratio_m1(beta0)
    return beta0, rho_m1, 2.0 * np.sqrt(1.0 + rho_m1) / (2.0 + rho_m1)

def _state_si(model, state, beta0, effective_radius, reduced_modulus, work_of_adhesion):
    """Convert nondimensional elliptical-JKR states (Eqs. 32-34) to an SI load curve.

    Parameters
    ----------
    model : str
        The model's name (:attr:`EllipticJKR.model`).
    state : dict
        ``W_star``, ``a_star``, ``b_star``, ``delta_star``, ``beta`` [-] in the paper's units.
    beta0 : array_like
        Hertz ellipticity of the geometry [-] (sin(theta_skew) of Eq. 34).
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        R [m], E* [Pa] and dgamma [J/m^2], validated.

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve: semi-axes [m], force [N], approach [m], and ``ellipticity`` b/a [-].
    """
    r, e, w = effective_radius, reduced_modulus, work_of_adhesion
    cr = length_unit(r, e, w, checked=False)
    sn = geometry_terms(beta0)[2]
    arrays = {"semi_major": state["a_star"] * cr, "semi_minor": state["b_star"] * cr,
              "force": state["W_star"] / sn * load_unit(r, w, checked=False),  # Eq. (34)
              "approach": state["delta_star"] * approach_unit(r, e, w, checked=False)}
    return si_curve(model, arrays, beta0=scalar_or_array(beta0), sin_skew=scalar_or_array(sn), geometry="ellipse",
                    ellipticity=scalar_or_array(state["beta"]))


def _u_at_contact(state_u, a_star, beta0, rho_m1, sin_skew):
    def f(u, at, b0, r, s):
        with np.errstate(divide="ignore"):  # a = 0 at u -> 1; arctan keeps f finite
            return np.arctan(np.log(state_u(u, b0, r, s)["a_star"] / at))

    lo = np.full(np.shape(a_star), _U_EDGE)
    res = elementwise.find_root(f, (lo, 1.0 - lo), args=(a_star, beta0, rho_m1, sin_skew),
                                tolerances=dict(xatol=1e-16, xrtol=1e-15))
    return res.x


class EllipticJKR:
    """Elliptical JKR with the contact shape fixed by one condition: the family of JG 2005 and GVG 2025.

    Both keep Johnson & Greenwood's elliptical contact and pressure and have the state in
    closed form along the ellipticity, beta = beta0 + (1 - beta0) u, u in (0, 1): beta0
    (a -> infinity, high load) to 1 (a -> 0).  They differ only in the condition that
    fixes the size at each ellipticity: Griffith's criterion at both axis ends (JG,
    :mod:`dhfield.models.jkr_elliptic`) or the energy stationary in both semi-axes (GVG,
    :mod:`dhfield.models.jkr_elliptic_energy`), the ``state_u`` of the family.  The load curve,
    the pull-off search and the SI conversions are this class's, once for both models;
    beta0 = 1 is circular JKR (:func:`circle_state`).

    Parameters
    ----------
    model : str
        The model's name in :mod:`dhfield.analysis.compare` (``jkr-elliptic`` or
        ``jkr-elliptic-energy``).
    condition : callable
        ``condition(one_m_beta, beta, k2, g1, g2, dg)`` -> ``(a, alpha0)``: the contact
        size a (inf where it diverges) and the pressure's alpha0 at ellipticity beta,
        from 1 - beta, k^2 = 1 - beta^2 and the shape coefficients g1, g2 and
        dg = g1 - g2 of :func:`shape_coefficients` (dg NaN where rounding leaves it <= 0);
        complex-safe (the pull-off uses the complex-step derivative of the state).
    """

    def __init__(self, model, condition):
        self.model = model
        self.condition = condition

    def state_u(self, u, beta0, rho_m1, sin_skew):
        """Compute the closed-form state at beta = beta0 + (1 - beta0) u (paper units, R = E* = dgamma = 1).

        Parameters
        ----------
        u : array_like
            Path parameter in (0, 1) (complex allowed) [-].
        beta0, rho_m1, sin_skew : array_like
            The geometry: Hertz ellipticity, R'/R'' - 1 and sin(theta_skew) (:func:`geometry_terms`).

        Returns
        -------
        dict
            ``W_star`` (Eq. 34), ``a_star``, ``b_star``, ``delta_star``, ``beta`` and
            ``alpha`` = (alpha0, alpha1, alpha2), alpha1,2 = a g1,2 from the curvatures.
        """
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):  # a = inf at u -> 0
            one_m_beta = (1.0 - beta0) * (1.0 - u)
            beta = 1.0 - one_m_beta
            k2 = one_m_beta * (1.0 + beta)
            g1, g2, dg, j0, j1, j2 = shape_coefficients(beta, k2, rho_m1)
            # at u -> 0 (beta -> beta0, a -> infinity) rounding can leave dg <= 0: a = infinity
            dg = np.where(np.real(dg) > 0.0, dg, np.nan)
            a, al0 = self.condition(one_m_beta, beta, k2, g1, g2, dg)
            al1, al2 = a * g1, a * g2
            load = 2.0 * np.pi * a * a * beta * (al0 + (al1 + al2) / 3.0)  # JG (2005): W = 2 pi a b [a0 + (a1+a2)/3]
            delta = 0.5 * a * beta * (2.0 * al0 * j0 + al1 * beta * beta * j2 + al2 * j1)  # approach (derived)
        return {"W_star": load * sin_skew / (2.0 * np.pi), "a_star": a, "b_star": beta * a,
                "delta_star": delta, "beta": beta,  # Eq. (34)
                "alpha": (al0, al1, al2)}

    def state_at_ellipticity(self, beta, beta0):
        """Compute the state whose contact ellipse has ellipticity beta (closed form, paper units).

        Parameters
        ----------
        beta : array_like
            Contact ellipticity b/a in (beta0, 1) [-].
        beta0 : array_like
            Hertz ellipticity of the geometry, in (0, 1) [-].

        Returns
        -------
        dict
            ``W_star`` (Eq. 34), ``a_star``, ``b_star``, ``delta_star``, ``beta`` [-] and
            ``alpha``, the coefficients (alpha0, alpha1, alpha2) of the pressure [E* = 1].
        """
        b0 = check_interval("beta0", beta0, 0.0, 1.0, high_open=True, what="Hertz ellipticity, dimensionless")
        b = np.asarray(check_finite("beta", beta, "contact ellipticity b/a, dimensionless"), dtype=float)
        if np.any((b <= b0) | (b >= 1.0)):
            raise ValueError("beta must lie in (beta0, 1) (contact ellipticity b/a, dimensionless)")
        b0, rho_m1, sn = geometry_terms(b0)
        return self.state_u((b - b0) / (1.0 - b0), b0, rho_m1, sn)

    def load_curve_nondimensional(self, a_star, beta0):
        """Compute the state at contact semi-major axis a*, in the paper's units (Eqs. 32-35).

        Parameters
        ----------
        a_star, beta0 : array_like
            The contact semi-major axis a* > 0 (Eq. 32) and the geometry's Hertz
            ellipticity in (0, 1], broadcast together [-].

        Returns
        -------
        dict
            ``W_star`` (Eq. 34), ``a_star``, ``b_star``, ``delta_star`` and the contact
            ellipticity ``beta`` [-]: a* decreases monotonically along the closed-form
            curve, so its ellipticity is found by a bracketing root finder.
        """
        beta0, rho_m1, sn = geometry_terms(beta0)
        a_star, beta0, rho_m1, sn = np.broadcast_arrays(np.asarray(a_star, float), beta0, rho_m1, sn)
        circ = beta0 == 1.0
        out = circle_state(a_star, sn)
        if np.any(~circ):
            sel = ~circ
            u = _u_at_contact(self.state_u, a_star[sel], beta0[sel], rho_m1[sel], sn[sel])
            st = self.state_u(u, beta0[sel], rho_m1[sel], sn[sel])
            for k in out:
                out[k] = np.array(out[k], dtype=float)
                out[k][sel] = st[k]
            out["a_star"][sel] = a_star[sel]
            out["b_star"][sel] = st["beta"] * a_star[sel]
        return out

    def pull_off_state(self, beta0, control="load"):
        """Compute the state at pull-off in the paper's units (Eqs. 32-35), vectorised over beta0.

        Parameters
        ----------
        beta0 : array_like
            Hertz ellipticity of the geometry in (0, 1] [-].
        control : {'load', 'displacement'}
            The first minimum of W* (load control) or delta* (displacement control) met
            on unloading from high load, beta = beta0 towards 1.

        Returns
        -------
        dict
            ``W_star``, ``a_star``, ``b_star``, ``delta_star``, ``beta`` [-] as in
            :meth:`load_curve_nondimensional`.

        Notes
        -----
        :func:`dhfield.core.pull_off_search.scan_minimum` on the closed-form curve, refined on its
        complex-step derivative (~1e-15 in beta).  beta0 = 1: JKR, W* = -3/4 (load control,
        a*^3 = 9 pi/8) and -5/12 (displacement control, a*^3 = pi/8).
        """
        beta0, rho_m1, sn = geometry_terms(beta0)
        a3 = 9.0 * np.pi / 8.0 if control == "load" else np.pi / 8.0  # JKR (1971), circle
        out = circle_state(np.full(beta0.shape, np.cbrt(a3)), sn)
        circ = beta0 == 1.0
        if np.any(~circ):
            sel = ~circ
            key = "W_star" if control == "load" else "delta_star"
            state_u = self.state_u

            def f(u, b0, r, s):
                return state_u(u, b0, r, s)[key]

            u, _ = scan_minimum(f, _SCAN_U, (beta0[sel], rho_m1[sel], sn[sel]), xatol=1e-15)
            st = state_u(u, beta0[sel], rho_m1[sel], sn[sel])
            for k in out:
                out[k] = np.array(out[k], dtype=float)
                out[k][sel] = st[k]
        return out

    def pull_off_nondimensional(self, beta0, mu, *, control="load"):
        """Compute the pull-off record in the paper's units, Eqs. (32)-(35); inputs not validated.

        Parameters
        ----------
        beta0, mu : array_like
            The grid point [-] (mu only sets the record's shape: the family has no mu).
        control : {'load', 'displacement'}
            The minimum of W* or of delta* (:meth:`pull_off_state`).

        Returns
        -------
        dhfield.core.records.PullOff
            Model :attr:`model`, ``ellipticity`` b/a at pull-off.
        """
        beta0 = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))[0]
        st = self.pull_off_state(beta0, control)
        return pull_off_record(self.model, beta0, mu, {**st, "ellipticity": st["beta"]}, control=control,
                               sin_skew=sin_skew_angle(beta0, checked=False), geometry="ellipse")

    @fill_doc
    def load_curve(self, semi_major, effective_radius, reduced_modulus, work_of_adhesion, *, radius_ratio=None,
                   beta0=None):
        """Compute the states at contact semi-axis a, in SI units (inputs validated here).

        Parameters
        ----------
        semi_major : array_like
            Contact semi-axis a > 0 along the larger principal radius R' [m].
        %(material)s
        %(elliptic_geometry)s

        Returns
        -------
        dhfield.core.records.LoadCurve
            Model :attr:`model`: ``semi_major``, ``semi_minor`` [m], ``force`` [N],
            ``approach`` [m], and ``ellipticity`` b/a along the curve [-].
        """
        b0 = check_geometry(radius_ratio, beta0)
        a = check_interval("semi_major", semi_major, 0.0, np.inf, high_open=True, what="m, > 0")
        r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
        return _state_si(self.model, self.load_curve_nondimensional(a / length_unit(r, e, w, checked=False), b0),
                         b0, r, e, w)

    @fill_doc
    def pull_off(self, effective_radius, reduced_modulus, work_of_adhesion, *, radius_ratio=None, beta0=None,
                 control="load"):
        """Compute the pull-off in SI units (inputs validated here).

        Parameters
        ----------
        %(material)s
        %(elliptic_geometry)s
        %(control)s

        Returns
        -------
        dhfield.core.records.PullOff
            With R' = R sqrt(rho), R'' = R/sqrt(rho) and ``max_adhesive_stress`` NaN.
        """
        b0 = check_geometry(radius_ratio, beta0)
        return si_pull_off(self.pull_off_nondimensional, effective_radius, reduced_modulus, work_of_adhesion,
                           control=control, radius_ratio=1.0 + geometry_terms(b0)[1], beta0=b0)  # R'/R''

    @fill_doc
    def pull_off_force_ratio(self, *, radius_ratio=None, beta0=None, control="load"):
        """Compute the pull-off force over the circular JKR value, W_pull-off/(-1.5 pi R dgamma) [-].

        Parameters
        ----------
        %(elliptic_geometry)s
        %(control)s

        Returns
        -------
        ndarray
            The ratio [-]: 1 at the circle (5/9 under displacement control).
        """
        b0 = check_geometry(radius_ratio, beta0)
        check_control(control)
        st = self.pull_off_state(b0, control)
        return scalar_or_array(st["W_star"] / geometry_terms(b0)[2] / -0.75)

    def pull_off_ellipticity(self, *, radius_ratio=None, beta0=None, control="load"):
        """Compute the contact ellipticity b/a at pull-off [-].

        Parameters
        ----------
        radius_ratio, beta0 : array_like, optional
            The geometry, as in :meth:`pull_off_force_ratio` [-].
        control : {'load', 'displacement'}
            As in :meth:`pull_off_force_ratio`.

        Returns
        -------
        ndarray
            The ellipticity, in [beta0, 1] [-]; 1 at the circle.
        """
        b0 = check_geometry(radius_ratio, beta0)
        check_control(control)
        return scalar_or_array(self.pull_off_state(b0, control)["beta"])

    def beta_at_load(self, w_star, beta0):
        """Compute beta on the stable (load-controlled) branch at load W* >= W*_pull-off (not validated).

        Parameters
        ----------
        w_star : array_like
            Load W* of Eq. (34) [-].
        beta0 : array_like
            Hertz ellipticity of the geometry in (0, 1] [-].

        Returns
        -------
        ndarray
            The contact ellipticity [-].
        """
        beta0, rho_m1, sn = geometry_terms(beta0)
        w_star, beta0, rho_m1, sn = np.broadcast_arrays(np.asarray(w_star, float), beta0, rho_m1, sn)
        out = np.ones(w_star.shape)
        sel = beta0 < 1.0
        if np.any(sel):
            po = self.pull_off_state(beta0[sel])
            u_po = (po["beta"] - beta0[sel]) / (1.0 - beta0[sel])
            state_u = self.state_u

            def f(u, w, b0, r, s):
                return state_u(u, b0, r, s)["W_star"] - w

            res = elementwise.find_root(f, (np.full(u_po.shape, _U_EDGE), u_po),
                                        args=(w_star[sel], beta0[sel], rho_m1[sel], sn[sel]),
                                        tolerances=dict(xatol=1e-16, xrtol=1e-15))
            out[sel] = beta0[sel] + (1.0 - beta0[sel]) * res.x
        return out


def check_geometry(radius_ratio_, beta0):
    """Validate one of R'/R'' >= 1 and its Hertz ellipticity beta0 in (0, 1]; return beta0.

    Parameters
    ----------
    radius_ratio_ : array_like or None
        R'/R'' >= 1 [-].
    beta0 : array_like or None
        Hertz ellipticity in (0, 1] [-] (give exactly one of the two).

    Returns
    -------
    ndarray
        beta0, exactly 1 within :data:`dhfield.core.validation.CIRCLE_TOLERANCE` of the circle.
    """
    if (radius_ratio_ is None) == (beta0 is None):
        raise ValueError("give exactly one of radius_ratio (R'/R'' >= 1) and beta0 (Hertz b/a in (0, 1])")
    if beta0 is not None:
        return as_circle(check_ellipticity("beta0", beta0))
    rho = check_interval("radius_ratio", radius_ratio_, 1.0, np.inf, low_open=False, high_open=True,
                         what="R'/R'' >= 1, dimensionless")
    return as_circle(ellipticity_from_radius_ratio(rho))


#: Johnson & Greenwood (2005): Griffith's criterion at both axis ends.
JG = EllipticJKR("jkr-elliptic", _griffith_at_axis_ends)


def state_at_ellipticity(beta, beta0):
    """Elliptical JKR state whose contact ellipse has ellipticity beta (closed form, paper units).

    Parameters
    ----------
    beta : array_like
        Contact ellipticity b/a in (beta0, 1) [-]: beta runs from beta0 (a -> infinity,
        high load) to 1 (a -> 0) on unloading.
    beta0 : array_like
        Hertz ellipticity of the geometry, in (0, 1) [-] (beta0 = 1 is circular
        JKR, :func:`dhfield.models.jkr.load_curve_nondimensional`).

    Returns
    -------
    dict
        ``W_star`` (W sin(theta_skew)/(2 pi R dgamma), Eq. 34), ``a_star``, ``b_star``
        (semi-axes / c_r), ``delta_star``, ``beta`` [-] and ``alpha``, the
        coefficients (alpha0, alpha1, alpha2) of the pressure
        ``(alpha0 + alpha1 X^2 + alpha2 Y^2)/sqrt(1 - X^2 - Y^2)`` [E* = 1].

    Notes
    -----
    The closed-form parametrisation of the module docstring (Johnson & Greenwood
    2005, Griffith's criterion at both axis ends):

    .. math:: a^{3/2} = \\sqrt{\\frac{2\\Delta\\gamma}{\\pi E^*}}\\,
              \\frac{\\beta^{-1/2} - 1}{g_1(\\beta) - g_2(\\beta)}
    """
    return JG.state_at_ellipticity(beta, beta0)


def load_curve_nondimensional(a_star, beta0):
    """Elliptical JKR state at contact semi-major axis a*, in the paper's units (Eqs. 32-35).

    The nondimensional core of :func:`load_curve` (:meth:`EllipticJKR.load_curve_nondimensional`).

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axis a* = a/c_r > 0, Eq. (32) [-].
    beta0 : array_like
        Hertz ellipticity of the geometry in (0, 1] [-]; broadcasts with ``a_star``.

    Returns
    -------
    dict
        ``W_star`` (Eq. 34, with sin(theta_skew) of beta0), ``a_star``, ``b_star``,
        ``delta_star`` and the contact ellipticity ``beta`` [-].
    """
    return JG.load_curve_nondimensional(a_star, beta0)


@fill_doc
def pull_off_nondimensional(beta0, mu, *, control="load"):
    """Elliptical JKR pull-off record (Johnson & Greenwood 2005) in the paper's units, Eqs. (32)-(35).

    The nondimensional core of :func:`pull_off`; inputs are not validated here
    (:func:`dhfield.analysis.compare.pull_off` does).

    Parameters
    ----------
    beta0, mu : array_like
        Hertz ellipticity and Tabor parameter (Eq. 35) [-]; JKR does not depend on mu, the
        record has their broadcast shape.
    %(control)s

    Returns
    -------
    dhfield.core.records.PullOff
        ``ellipticity`` is beta_JKR(pull-off).
    """
    return JG.pull_off_nondimensional(beta0, mu, control=control)


@fill_doc
def load_curve(semi_major, effective_radius, reduced_modulus, work_of_adhesion, *,
               radius_ratio=None, beta0=None):
    """Elliptical JKR (Johnson & Greenwood 2005) states at contact semi-major axis a.

    Parameters
    ----------
    semi_major : array_like
        Contact semi-axis a > 0 along the larger principal radius R' [m].
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    radius_ratio : array_like, optional
        R'/R'' >= 1 [-].
    beta0 : array_like, optional
        The Hertz ellipticity of that geometry in (0, 1] [-] (give one of the two).

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve: ``semi_major``, ``semi_minor`` [m], ``force`` W [N] (compressive
        positive), ``approach`` [m] (no adhesive zone: NaN), and ``ellipticity``, b/a along
        the curve [-].

    Notes
    -----
    Closed form in the ellipticity beta (module docstring):

    .. math:: a^{3/2} = \\sqrt{2\\Delta\\gamma/(\\pi E^*)}\\,(\\beta^{-1/2}-1)/(g_1 - g_2),
              \\quad W = 2\\pi ab\\left[\\alpha_0 + (\\alpha_1+\\alpha_2)/3\\right]

    References
    ----------
    .. [1] K. L. Johnson, J. A. Greenwood, J. Phys. D 38 (2005) 1042,
       doi:10.1088/0022-3727/38/7/012
    """
    return JG.load_curve(semi_major, effective_radius, reduced_modulus, work_of_adhesion,
                         radius_ratio=radius_ratio, beta0=beta0)


@fill_doc
def pull_off(effective_radius, reduced_modulus, work_of_adhesion, *, radius_ratio=None, beta0=None,
             control="load"):
    """Elliptical JKR state at pull-off, in SI units.

    Parameters
    ----------
    %(material)s
    radius_ratio, beta0 : array_like
        R'/R'' >= 1, or its Hertz ellipticity in (0, 1] (give one) [-].
    control : {'load', 'displacement'}
        First minimum of the load (load control) or of the approach
        (displacement control) met on unloading.

    Returns
    -------
    dhfield.core.records.PullOff
        ``force`` [N], ``semi_major``, ``semi_minor`` [m], ``approach`` [m], the SI inputs
        and the nondimensional record (``ellipticity`` beta_JKR(pull-off)).
    """
    return JG.pull_off(effective_radius, reduced_modulus, work_of_adhesion, radius_ratio=radius_ratio,
                       beta0=beta0, control=control)


@fill_doc
def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, *, radius_ratio=None,
                   beta0=None, control="load"):
    """Compute the elliptical JKR pull-off force [N] (negative).

    Parameters
    ----------
    %(material)s
    %(elliptic_geometry)s
    %(control)s

    Returns
    -------
    %(pull_off_force_returns)s
    """
    return JG.pull_off(effective_radius, reduced_modulus, work_of_adhesion, radius_ratio=radius_ratio,
                       beta0=beta0, control=control).force


@fill_doc
def pull_off_force_ratio(*, radius_ratio=None, beta0=None, control="load"):
    """Compute the pull-off force over the circular JKR value, W_pull-off/(-1.5 pi R dgamma) [-].

    R = sqrt(R'R''); depends on R'/R'' only.

    Parameters
    ----------
    %(elliptic_geometry)s
    %(control)s

    Returns
    -------
    ndarray
        The ratio [-]: 1 at the circle (and 5/9 under displacement control, the
        circular fixed-grips value).
    """
    return JG.pull_off_force_ratio(radius_ratio=radius_ratio, beta0=beta0, control=control)


@fill_doc
def pull_off_ellipticity(*, radius_ratio=None, beta0=None, control="load"):
    """Compute beta_JKR(pull-off), the contact ellipticity b/a at pull-off [-].

    Parameters
    ----------
    %(elliptic_geometry)s
    %(control)s

    Returns
    -------
    ndarray
        The ellipticity at pull-off, in [beta0, 1] [-]; 1 at the circle.
    """
    return JG.pull_off_ellipticity(radius_ratio=radius_ratio, beta0=beta0, control=control)


@fill_doc
def ellipticity_at_load(load_star, *, radius_ratio=None, beta0=None):
    """Compute the contact ellipticity b/a on the stable branch at load W* of Eq. (34) [-].

    Parameters
    ----------
    load_star : array_like
        Load W* of Eq. (34), >= the load-controlled pull-off W* [-].
    %(elliptic_geometry)s

    Returns
    -------
    ndarray
        The ellipticity beta [-]; beta -> beta0 (the Hertz ellipticity) as W* -> infinity.
    """
    b0 = check_geometry(radius_ratio, beta0)
    w = check_interval("load_star", load_star, -1.0, np.inf, high_open=True,
                       what="W* of Eq. (34), above the pull-off load")
    po = JG.pull_off_state(b0)["W_star"]
    if np.any(w < po):
        raise ValueError(f"load_star must be >= the pull-off load W* = {np.min(po):.6g}; "
                         f"got {np.min(w)!r}")
    return scalar_or_array(JG.beta_at_load(w, b0))
