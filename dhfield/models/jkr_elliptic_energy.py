"""Energy-minimising JKR theory of an elliptical contact (Giudici, Vella & Griffiths 2025).

Source: A. Giudici, D. Vella & I. Griffiths, "Mechanics of elliptical JKR-type
adhesive contact", J. Phys. D: Appl. Phys. (2025), arXiv:2407.00378 ("GVG").
GVG keep Johnson & Greenwood's elliptical contact and pressure (:mod:`dhfield.models.jkr_elliptic`,
model ``jkr-elliptic``) but replace JG's Griffith criterion at the two axis ends by the
minimum of elastic plus surface energy over *both* semi-axes.  Every formula below
was derived here from that statement and checked independently (tests: the
energy is stationary in a and b by finite differences of a quadrature of the
energy; the circle is JKR).  The paper's own equation numbers could not be read
here; ``GVG`` in a comment marks a step of their model, ``(derived)`` our algebra.
Model name in :mod:`dhfield.analysis.compare`: ``jkr-elliptic-energy``.

Model
-----
Gap ``z = A x^2 + B y^2``, ``A = 1/(2R')``, ``B = 1/(2R'')``, R' >= R'' (x along R').
Contact ellipse with semi-axes a (along x) and b = beta a, ``X = x/a``, ``Y = y/b``;
pressure (Hertz-type plus elliptical flat punch, Boussinesq superposition)

.. math:: p = \\frac{\\alpha_0 + \\alpha_1 X^2 + \\alpha_2 Y^2}{\\sqrt{1 - X^2 - Y^2}} .

alpha1, alpha2 match the curvatures A, B inside the ellipse and alpha0 the
approach delta, exactly as in :mod:`dhfield.models.jkr_elliptic` (ellipsoidal-potential
integrals J; its helper ``shape_coefficients`` gives ``alpha_i = a g_i(beta)``).
The load is ``W = 2 pi a b [alpha0 + (alpha1 + alpha2)/3]`` and the approach
``delta = (ab/2E*)[2 alpha0 J0 + alpha1 b^2 J2 + alpha2 a^2 J1]``.

Energy (GVG).  At fixed approach the elastic energy ``U_E(a, b, delta)`` is
``(1/2) int p (delta - z) dA`` and the total energy is

.. math:: \\Pi(a, b, \\delta) = U_E(a, b, \\delta) - \\Delta\\gamma\\,\\pi a b .  \\qquad (G1)

GVG require ``dPi/da = dPi/db = 0`` at fixed delta (JG impose one condition
instead).  Under load control the equilibria are the same (Legendre transform).

Equilibrium in closed form (derived)
------------------------------------
By Irwin's relation the derivative of U_E at fixed delta is the energy release
rate integrated against the normal speed of the contact edge.  On the edge
``x = a cos(phi)``, ``y = b sin(phi)`` the stress intensity factor of the pressure
above is ``K_I = f(phi) sqrt(pi/h)`` with ``f = alpha0 + alpha1 cos^2 + alpha2 sin^2``
and ``h = sqrt(cos^2/a^2 + sin^2/b^2)``; ``G = K_I^2/(2E*)``; the normal speed
times the arc length is ``b cos^2(phi) dphi`` for ``da`` and ``a sin^2(phi) dphi``
for ``db``.  Eq. (G1) stationary in a and b is therefore

.. math:: \\oint G\\cos^2\\phi\\,d\\phi = \\oint G\\sin^2\\phi\\,d\\phi = \\pi\\Delta\\gamma ,
          \\qquad (G2)

Griffith's criterion on average with the weights cos^2 and sin^2 (JG: pointwise at
phi = 0 and pi/2).  Write ``f = s (1 + eps c)``, ``c = cos^2 phi``,
``s = alpha0 + alpha2``, ``eps = (alpha1 - alpha2)/s`` and (a = 1)
``I_j(m) = int_0^{pi/2} sin^{2j} t / sqrt(1 - m sin^2 t) dt``, m = k^2 = 1 - beta^2
(I0 = K, I1 = (K - E)/m, then ``(2j+1) m I_{j+1} = 2j(1+m) I_j - (2j-1) I_{j-1}``).
The difference of the two sides of Eq. (G2) is homogeneous in (s, alpha1 - alpha2):

.. math:: A_2 + 2A_1\\varepsilon + A_0\\varepsilon^2 = 0, \\quad
          A_2 = 2I_1 - I_0,\\; A_1 = 2I_2 - I_1,\\; A_0 = 2I_3 - I_2 ,  \\qquad (G3)

whose physical root (K_I of one sign all round the edge, eps in (-1, 0)) is
``eps = -A_2/(A_1 + sqrt(A_1^2 - A_0 A_2))``; it depends on beta only and vanishes at
the circle (A2 = 0).  The other root, eps -> -2 at the circle, changes the sign of
K_I along the edge.  The cos^2-side of Eq. (G2) then fixes the size:

.. math:: a\\,s^2 = \\frac{E^*\\Delta\\gamma}{2\\beta\\,(I_1 + 2\\varepsilon I_2 + \\varepsilon^2 I_3)},
          \\qquad s = \\frac{\\alpha_1 - \\alpha_2}{\\varepsilon} = \\frac{a\\,(g_1 - g_2)}{\\varepsilon}
          \\;\\Rightarrow\\;
          a^3 = \\frac{E^*\\Delta\\gamma\\,\\varepsilon^2}{2\\beta\\,(I_1 + 2\\varepsilon I_2 + \\varepsilon^2 I_3)\\,(g_1 - g_2)^2}. \\qquad (G4)

So the load curve is closed form in beta, which runs from the Hertz ellipticity
beta0 (g1 = g2: a -> infinity, high load) to 1 (eps = 0: a -> 0), as in JG; the
contact becomes rounder on unloading.  The A_j are summed from their power series
in m below m = 1/4 (they cancel at the circle), from Carlson's R_F, R_D and the
recurrence above.  beta0 = 1 is circular JKR exactly (not a limit).  Equation labels
(G1)-(G4) are this module's.

Stability (checked, tests): at fixed delta the Hessian of Eq. (G1) in (a, b) is positive
definite on the branch from high load down to the displacement-control pull-off (the
first minimum of delta) and has one negative eigenvalue beyond it, so the states up to
there are true minima over both semi-axes; the load-control pull-off is the first
minimum of W met on unloading, as for JKR and JG.

Normalisation
-------------
As :mod:`dhfield.models.jkr_elliptic`: ``W* = W sin(theta_skew)/(2 pi R dgamma)`` (Eq. 34),
sin(theta_skew) of beta0, R = sqrt(R'R''); lengths in ``c_r = (R^2 dgamma/E*)^(1/3)``
(Eq. 33); approaches in ``c_r^2/R``.  :func:`pull_off_force_ratio` gives the pull-off
in units of the circular JKR value 1.5 pi R dgamma instead (no sin(theta_skew)).
"""
from __future__ import annotations

import numpy as np
from scipy import special

from .jkr_elliptic import EllipticJKR

__all__ = [
    "load_curve",
    "pull_off",
    "pull_off_force",
    "pull_off_force_ratio",
    "pull_off_ellipticity",
    "load_curve_nondimensional",
    "pull_off_nondimensional",
    "state_at_ellipticity",
]

_SERIES_M = 0.25  # below this m = 1 - beta^2 the A_j of Eq. (G3) are summed from their series
_SERIES_TERMS = 32  # 0.25^32 ~ 5e-20

_n = np.arange(_SERIES_TERMS + 3, dtype=float)
#: c_n = (1/2)_n / n!, so that I_j(m) = (pi/2) sum_n c_n c_{n+j} m^n
_C = np.concatenate([[1.0], np.cumprod((_n[:-1] + 0.5) / (_n[:-1] + 1.0))])
_N = _n[:_SERIES_TERMS]
_COEF_A2 = 0.5 * np.pi * _C[:-3] * _C[:-3] * _N / (_N + 1.0)  # 2 I1 - I0 (derived)
_COEF_A1 = 0.5 * np.pi * _C[:-3] * _C[1:-2] * (_N + 1.0) / (_N + 2.0)  # 2 I2 - I1
_COEF_A0 = 0.5 * np.pi * _C[:-3] * _C[2:-1] * (_N + 2.0) / (_N + 3.0)  # 2 I3 - I2
_COEF_I = [0.5 * np.pi * _C[:-3] * _C[j:j + _SERIES_TERMS] for j in range(4)]


def _edge_moments(m):
    """I_1, I_2, I_3 and A_2, A_1, A_0 of Eq. (G3) at m = 1 - beta^2 (complex-safe).

    Series below m = 1/4 (A_2 cancels there: (pi/16) m against I_0 ~ pi/2), Carlson's
    R_F, R_D and the recurrence above it (A_2 then loses at most ~1.5 digits).
    """
    m = np.asarray(m)
    small = np.real(m) < _SERIES_M
    out = [np.empty(m.shape, dtype=m.dtype) for _ in range(6)]
    if np.any(small):
        ms = m[small]
        for o, c in zip(out, _COEF_I[1:] + [_COEF_A2, _COEF_A1, _COEF_A0]):
            o[small] = np.polyval(c[::-1], ms)
    if not np.all(small):
        ml = m[~small]
        i0 = special.elliprf(0.0, 1.0 - ml, 1.0)  # K(m)
        i1 = special.elliprd(0.0, 1.0 - ml, 1.0) / 3.0  # (K - E)/m
        i2 = (2.0 * (1.0 + ml) * i1 - i0) / (3.0 * ml)  # recurrence (derived)
        i3 = (4.0 * (1.0 + ml) * i2 - 3.0 * i1) / (5.0 * ml)
        for o, v in zip(out, (i1, i2, i3, 2.0 * i1 - i0, 2.0 * i2 - i1, 2.0 * i3 - i2)):
            o[~small] = v
    return out


def _energy_stationary(one_m_beta, beta, k2, g1, g2, dg):
    """GVG's condition: the size a and alpha0 at ellipticity beta, Eqs. (G3)-(G4) (R = E* = dgamma = 1)."""
    i1, i2, i3, a2, a1, a0 = _edge_moments(k2)
    eps = -a2 / (a1 + np.sqrt(a1 * a1 - a0 * a2))  # Eq. (G3), the root with K_I of one sign
    a3 = eps * eps / (2.0 * beta * (i1 + 2.0 * eps * i2 + eps * eps * i3) * dg * dg)  # Eq. (G4)
    a = a3 ** (1.0 / 3.0)
    a = np.where(np.isnan(np.real(a)), np.inf, a)
    return a, a * dg / eps - a * g2  # s = alpha0 + alpha2 = (alpha1 - alpha2)/eps, Eq. (G3)


#: Giudici, Vella & Griffiths (2025): the energy stationary in both semi-axes.
GVG = EllipticJKR("jkr-elliptic-energy", _energy_stationary)


def state_at_ellipticity(beta, beta0):
    """GVG state whose contact ellipse has ellipticity beta (closed form, paper units).

    Parameters
    ----------
    beta, beta0 : array_like
        The contact's ellipticity b/a in (beta0, 1) and the geometry's Hertz one in (0, 1)
        [-], as for :func:`dhfield.models.jkr_elliptic.state_at_ellipticity`.

    Returns
    -------
    dict
        The state's W* (Eq. 34), a*, b*, delta*, beta and the pressure coefficients alpha,
        with GVG's size at that ellipticity.

    Notes
    -----
    Eq. (G4) of the module docstring, with eps the root of Eq. (G3):

    .. math:: a^3 = \\frac{\\varepsilon^2}{2\\beta\\,(I_1 + 2\\varepsilon I_2 + \\varepsilon^2 I_3)
              \\,(g_1 - g_2)^2}
    """
    return GVG.state_at_ellipticity(beta, beta0)


def load_curve_nondimensional(a_star, beta0):
    """GVG state at contact semi-major axis a*, in the paper's units (Eqs. 32-35).

    The nondimensional core of :func:`load_curve`, on the family's machinery
    (:meth:`dhfield.models.jkr_elliptic.EllipticJKR.load_curve_nondimensional`).

    Parameters
    ----------
    a_star, beta0 : array_like
        Contact semi-major axis a* > 0 (Eq. 32) and the Hertz ellipticity in (0, 1] [-],
        broadcast together.

    Returns
    -------
    dict
        W*, a*, b*, delta* and the contact ellipticity beta [-] (keys as in
        :func:`dhfield.models.jkr_elliptic.load_curve_nondimensional`).
    """
    return GVG.load_curve_nondimensional(a_star, beta0)


def pull_off_nondimensional(beta0, mu, *, control="load"):
    """GVG pull-off record in the paper's units, Eqs. (32)-(35).

    The nondimensional core of :func:`pull_off`; inputs are not validated here
    (:func:`dhfield.analysis.compare.pull_off` does).  The first minimum of W* (load control) or
    delta* (displacement control) met on unloading, refined on the complex-step derivative
    of the closed-form curve (:meth:`dhfield.models.jkr_elliptic.EllipticJKR.pull_off_state`).

    Parameters
    ----------
    beta0, mu : array_like
        The grid point [-]; GVG has no mu (it sets the record's shape only).
    control : {'load', 'displacement'}
        The minimum of W* (load) or of delta* (displacement) met on unloading.

    Returns
    -------
    dhfield.core.records.PullOff
        Model ``jkr-elliptic-energy``; ``ellipticity`` is b/a at pull-off.
    """
    return GVG.pull_off_nondimensional(beta0, mu, control=control)


def load_curve(semi_major, effective_radius, reduced_modulus, work_of_adhesion, *,
               radius_ratio=None, beta0=None):
    """Energy-minimising elliptical JKR (Giudici, Vella & Griffiths 2025) states at contact semi-axis a.

    In SI units, on the family's machinery (:meth:`dhfield.models.jkr_elliptic.EllipticJKR.load_curve`).

    Parameters
    ----------
    semi_major : array_like
        Contact semi-axis a > 0 along the larger principal radius R' [m].
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        R = sqrt(R' R''), Eq. (5) [m]; E*, Eq. (6) [Pa]; dgamma [J/m^2].
    radius_ratio, beta0 : array_like, optional
        R'/R'' >= 1, or the Hertz ellipticity of that geometry in (0, 1] [-] (give one).

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve (model ``jkr-elliptic-energy``): ``semi_major``, ``semi_minor`` [m], ``force`` W [N] (compressive
        positive), ``approach`` [m] (no adhesive zone: NaN), and ``ellipticity``, b/a along
        the curve [-].

    Notes
    -----
    Closed form in the ellipticity beta (module docstring, Eqs. G1-G4): the total
    energy ``U_E - dgamma pi a b`` is stationary in both semi-axes.

    References
    ----------
    .. [1] A. Giudici, D. Vella, I. Griffiths, J. Phys. D (2025), arXiv:2407.00378
    """
    return GVG.load_curve(semi_major, effective_radius, reduced_modulus, work_of_adhesion,
                          radius_ratio=radius_ratio, beta0=beta0)


def pull_off(effective_radius, reduced_modulus, work_of_adhesion, *, radius_ratio=None, beta0=None,
             control="load"):
    """Energy-minimising elliptical JKR state at pull-off, in SI units.

    The GVG pull-off (:func:`pull_off_nondimensional`) converted by
    :func:`dhfield.core.units.pull_off_si`.

    Parameters
    ----------
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        The contact's R = sqrt(R'R'') [m], E* [Pa] and dgamma [J/m^2].
    radius_ratio, beta0 : array_like
        The geometry, by R'/R'' >= 1 or by beta0 in (0, 1] (one of the two) [-].
    control : {'load', 'displacement'}
        The loading mode: the first minimum of W or of delta on unloading; states up to
        the displacement-control pull-off are energy minima over both semi-axes.

    Returns
    -------
    dhfield.core.records.PullOff
        The one SI pull-off record (its ``ellipticity``: b/a at pull-off).
    """
    return GVG.pull_off(effective_radius, reduced_modulus, work_of_adhesion, radius_ratio=radius_ratio,
                        beta0=beta0, control=control)


def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, *, radius_ratio=None,
                   beta0=None, control="load"):
    """Compute the energy-minimising elliptical JKR pull-off force W [N] (negative: tensile).

    The ``force`` of the SI record of :func:`pull_off`.

    Parameters
    ----------
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        As in :func:`pull_off` [m, Pa, J/m^2].
    radius_ratio, beta0 : array_like
        As in :func:`pull_off` [-].
    control : {'load', 'displacement'}
        As in :func:`pull_off`.

    Returns
    -------
    ndarray
        :func:`pull_off`'s ``force`` [N].
    """
    return pull_off(effective_radius, reduced_modulus, work_of_adhesion, radius_ratio=radius_ratio, beta0=beta0,
                    control=control).force


def pull_off_force_ratio(*, radius_ratio=None, beta0=None, control="load"):
    """Compute the GVG pull-off force in units of the circular JKR one, W/(-1.5 pi R dgamma) [-].

    Parameters
    ----------
    radius_ratio, beta0 : array_like
        As in :func:`pull_off` [-]; the ratio depends on the shape R'/R'' only (R = sqrt(R'R'')).
    control : {'load', 'displacement'}
        As in :func:`pull_off`.

    Returns
    -------
    ndarray
        The ratio [-]: 1 at the circle (5/9 under displacement control).
    """
    return GVG.pull_off_force_ratio(radius_ratio=radius_ratio, beta0=beta0, control=control)


def pull_off_ellipticity(*, radius_ratio=None, beta0=None, control="load"):
    """Compute the contact ellipticity b/a at the GVG pull-off [-].

    Parameters
    ----------
    radius_ratio, beta0 : array_like
        As in :func:`pull_off` [-].
    control : {'load', 'displacement'}
        As in :func:`pull_off`.

    Returns
    -------
    ndarray
        In [beta0, 1] [-]; 1 at the circle.
    """
    return GVG.pull_off_ellipticity(radius_ratio=radius_ratio, beta0=beta0, control=control)
