"""Circular double-Hertz (DH) model of Greenwood & Johnson (1998), in closed form.

Source: J. A. Greenwood & K. L. Johnson, J. Phys. D: Appl. Phys. 31 (1998) 3279,
doi:10.1088/0022-3727/31/22/017.  The adhesive stress is the difference of two Hertz
pressures (contact radius a, adhesive radius c), scaled by v; this is the circle
(beta = 1) of the extended model of the paper (Eqs. 16-31).

Equations (R = E* = dgamma = 1, the paper's units of Eqs. 32-35)
-----------------------------------------------------------------

.. math::

    \\sigma_0 = \\frac{2v}{\\pi}\\sqrt{c^2-a^2} = \\mu                  \\quad (Eq.\\ 24)

    \\Delta\\gamma = v(1+v)\\frac{2}{3\\pi}(c-a)^2(c+2a) = 1             \\quad (Eq.\\ 31)

    W^* = \\frac{2}{3\\pi}\\left[a^3 - v(c^3-a^3)\\right]                \\quad (Eq.\\ 36)

    \\delta^* = a^2 - v(c^2-a^2)

The work of adhesion (Eq. 31 at beta = 1, with the annulus gap h = (1+v) h_Hertz)
is checked against quadrature in the tests.

Closed form (derived here)
--------------------------
Take v as the curve parameter.  Eq. (24) fixes q = sqrt(c^2 - a^2) = pi mu/(2v)
and Eq. (31) fixes K = (c-a)^2 (c+2a) = 3 pi/(2 v (1+v)).  With s = c - a,
c + a = q^2/s and c + 2a = (3q^2/s - s)/2, so s solves the depressed cubic
s^3 - 3 q^2 s + 2K = 0.  Its root in (0, q] is

.. math::

    s = q\\,\\sigma, \\qquad \\sigma = 2\\sin\\left(\\tfrac13\\arcsin\\kappa\\right), \\qquad
    \\kappa = \\frac{K}{q^3} = \\frac{12 v^2}{(1+v)\\pi^2\\mu^3},

giving a = q(1/sigma - sigma)/2 and c = q(1/sigma + sigma)/2.  The curve runs from
a -> infinity (v -> 0, the JKR side) to a = 0 at kappa = 1, i.e.
v0 = [pi^2 mu^3 + sqrt(pi^4 mu^6 + 48 pi^2 mu^3)]/24, where W* = -1/(1+v0)
(-2/(1+v) in units of pi R dgamma).  A given a is reached by a bracketing root
finder in log v; the pull-off minimises W* (or delta*) over log v.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import elementwise

from ..core.units import check_contact_size, check_material, scalar_or_array, si_circular_load_curve, si_pull_off
from ..core.validation import check_positive
from ..core.pull_off_search import scan_minimum
from ..core.records import pull_off_record
from ..core._docstrings import fill_doc

__all__ = ["load_curve", "pull_off", "pull_off_force", "work_of_adhesion", "load_curve_nondimensional",
           "pull_off_nondimensional"]

_LOG_V_SPAN = 60.0  # root bracket below ln v0: a ~ pi^3 mu^4/(32 v^3) spans > e^150 there
#: pull-off scan in a* (descending, i.e. ascending v), then refined in ln v; the
#: JKR pull-off a* = 1.52 is the largest pull-off contact radius of the DH circle
_SCAN_A = np.concatenate([np.geomspace(8.0, 1e-4, 120), [0.0]])


def _v_zero_contact(mu):
    """v0 at which the DH circle reaches a = 0 (kappa = 1)."""
    g = np.pi**2 * np.asarray(mu, dtype=float) ** 3
    return (g + np.sqrt(g * g + 48.0 * g)) / 24.0


def _state(log_v, mu):
    """Closed-form DH state for parameter ln v (see the module docstring)."""
    v = np.exp(log_v)
    q = np.pi * mu / (2.0 * v)  # Eq. (24): sqrt(c^2 - a^2)
    kappa = 12.0 * v * v / ((1.0 + v) * np.pi**2 * mu**3)  # Eq. (31) over q^3
    kappa = np.where(np.real(kappa) > 1.0, 1.0, kappa)  # (complex-safe clamp for the derivative)
    sig = 2.0 * np.sin(np.arcsin(kappa) / 3.0)
    a = 0.5 * q * (1.0 / sig - sig)
    c = 0.5 * q * (1.0 / sig + sig)
    # c - a = q sig exactly and v q = pi mu/2 (Eq. 24): no cancellation in v (c^3 - a^3)
    # or v q^2 at large mu, where c - a is below the rounding of c.
    vq = 0.5 * np.pi * mu
    w_star = 2.0 / (3.0 * np.pi) * (a**3 - vq * sig * (c * c + c * a + a * a))  # Eq. (36) at beta = 1
    delta = a * a - vq * q  # approach (1+v) a^2 - v c^2
    return {"W_star": w_star, "a_star": a, "c_star": c, "v": v, "delta_star": delta}


def _log_v_at(a_star, mu):
    """ln v at which the contact radius equals a_star (>= 0)."""
    a_star, mu = np.broadcast_arrays(np.asarray(a_star, float), np.asarray(mu, float))
    top = np.log(_v_zero_contact(mu))
    out = top.copy()
    pos = a_star > 0
    if np.any(pos):
        def f(t, at, m):
            return np.log(_state(t, m)["a_star"]) - np.log(at)

        res = elementwise.find_root(f, (top[pos] - _LOG_V_SPAN, top[pos]), args=(a_star[pos], mu[pos]),
                                    tolerances=dict(xatol=1e-15, xrtol=1e-16))
        out[pos] = res.x
    return out


def load_curve_nondimensional(a_star, mu):
    """Circular DH state at contact radius a*, in the paper's units (Eqs. 32-35).

    The nondimensional core of :func:`load_curve` (R = E* = dgamma = 1).

    Parameters
    ----------
    a_star : array_like
        Contact radius a* = a/c_r >= 0, Eq. (32) [-].
    mu : array_like
        Transition parameter, Eq. (35), > 0 [-]; broadcasts with ``a_star``.

    Returns
    -------
    dict
        ``W_star`` (Eq. 36), ``a_star``, ``c_star`` (adhesive radius c/c_r),
        ``delta_star`` (delta R/c_r^2) and the scaling factor ``v`` [-].

    Notes
    -----
    The closed form of the module docstring: Eqs. (24) and (31) at beta = 1 fix
    c and v for each a, then

    .. math:: W^* = \\frac{2}{3\\pi}\\left[a^3 - v(c^3-a^3)\\right], \\qquad
              \\delta^* = a^2 - v(c^2-a^2)
    """
    check_contact_size("a_star", a_star)
    check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless")
    st = _state(_log_v_at(a_star, mu), np.asarray(mu, float))
    a_star = np.broadcast_to(np.asarray(a_star, float), st["a_star"].shape)
    st["a_star"] = a_star.copy()  # exact input (the solve reproduces it to ~1e-15)
    return st


def _pull_off_state(mu, control="load"):
    """Circular DH state at pull-off in the paper's units (Eqs. 32-35), vectorised over mu.

    Load control: the first minimum
    of W* (Eq. 36) met on unloading from high load (the end of the stable branch);
    displacement control: the same for delta*.  Either may be the end point a = 0
    (then W* = -1/(1 + v0)).

    Parameters
    ----------
    mu : array_like
        Transition parameter, Eq. (35), > 0 [-].
    control : {'load', 'displacement'}

    Returns
    -------
    dict
        ``W_star``, ``a_star``, ``c_star``, ``delta_star``, ``v`` as in
        :func:`load_curve_nondimensional`, and ``at_zero_contact`` (bool: the
        pull-off is the end point a = 0).
    """
    mu = np.asarray(mu, dtype=float)
    key = "W_star" if control == "load" else "delta_star"
    top = np.log(_v_zero_contact(mu))
    grid = _log_v_at(_SCAN_A, mu[..., None])
    grid[..., -1] = top  # a = 0 exactly

    def f(t, m):
        return _state(t, m)[key]

    t, _ = scan_minimum(f, grid, (mu,), xatol=1e-15)
    st = _state(np.minimum(t, top), mu)
    end = t >= top
    if np.any(end):  # a = 0 exactly: c = q = pi mu/(2 v0)
        c0 = np.pi * mu / (2.0 * st["v"])
        st["a_star"] = np.where(end, 0.0, st["a_star"])
        st["c_star"] = np.where(end, c0, st["c_star"])
        st["W_star"] = np.where(end, -2.0 / (3.0 * np.pi) * st["v"] * c0**3, st["W_star"])  # Eq. (36), a = 0
        st["delta_star"] = np.where(end, -st["v"] * c0**2, st["delta_star"])
    st["at_zero_contact"] = end
    return st


@fill_doc
def pull_off_nondimensional(beta0, mu, *, control="load"):
    """Compute the circular DH pull-off record (Greenwood & Johnson 1998) in the paper's units.

    The nondimensional core of :func:`pull_off`; inputs are not validated here
    (:func:`dhfield.analysis.compare.pull_off` does).

    Parameters
    ----------
    %(circle_beta0_mu)s
    %(control)s

    Returns
    -------
    %(pull_off_nondimensional_returns)s
    """
    mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))[1]
    return pull_off_record("dh-circular", beta0, mu, _pull_off_state(mu, control), control=control, sin_skew=1.0,
                           geometry="circle")


def work_of_adhesion(contact_radius, adhesive_radius, scaling, effective_radius, reduced_modulus):
    """Compute the work of adhesion of the circular DH stress field, closed form [J/m^2].

    Parameters
    ----------
    contact_radius : array_like
        Contact radius a [m].
    adhesive_radius : array_like
        Adhesive radius c >= a [m].
    scaling : array_like
        DH scaling factor v [-].
    effective_radius, reduced_modulus : array_like
        R [m], E* [Pa].

    Returns
    -------
    ndarray
        Delta gamma [J/m^2].

    Notes
    -----
    Eq. (31) at beta = 1 with the annulus gap h = (1+v) h_Hertz:

    .. math:: \\Delta\\gamma = v(1+v)\\frac{2E^*}{3\\pi R^2}(c-a)^2(c+2a)
    """
    a = check_contact_size("contact_radius", contact_radius)
    c = check_contact_size("adhesive_radius", adhesive_radius)
    if np.any(c < a):
        raise ValueError("adhesive_radius must be >= contact_radius (c >= a) [m]")
    v = check_contact_size("scaling", scaling)
    r, e, _ = check_material(effective_radius, reduced_modulus, 1.0)
    return scalar_or_array(v * (1 + v) * 2 * e / (3 * np.pi * r * r) * (c - a) ** 2 * (c + 2 * a))  # Eq. (31)


@fill_doc
def load_curve(contact_radius, effective_radius, reduced_modulus, work_of_adhesion,
               max_adhesive_stress):
    """Circular DH (Greenwood & Johnson 1998) load and approach at a contact radius.

    Parameters
    ----------
    %(contact_radius)s
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    max_adhesive_stress : array_like
        Peak adhesive stress sigma0 at the contact edge [Pa].

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve (model ``dh-circular``, circle): ``semi_major`` = ``semi_minor`` = a [m],
        ``adhesive_semi_major`` = ``adhesive_semi_minor`` = c [m], the DH factor ``v`` [-],
        ``force`` W [N] (positive compressive), ``approach`` delta [m].  The header's ``mu`` is the
        Tabor parameter of the inputs, Eq. (35).

    Notes
    -----
    .. math::

        W = \\frac{4E^*}{3R}\\left[a^3 - v(c^3 - a^3)\\right], \\qquad
        \\delta = \\frac{a^2 - v(c^2 - a^2)}{R}

    with c, v from Eqs. (24) and (31) at beta = 1 (closed form in the module
    docstring).

    References
    ----------
    .. [1] J. A. Greenwood, K. L. Johnson, J. Phys. D 31 (1998) 3279,
       doi:10.1088/0022-3727/31/22/017
    """
    return si_circular_load_curve("dh-circular", load_curve_nondimensional, contact_radius, effective_radius,
                                  reduced_modulus, work_of_adhesion, max_adhesive_stress, zone=True, dh_factor=True)


@fill_doc
def pull_off(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress, *,
             control="load"):
    """Circular DH state at pull-off.

    Parameters
    ----------
    %(material)s
    max_adhesive_stress : array_like
        Peak adhesive stress sigma0 [Pa].
    control : {'load', 'displacement'}
        Pull-off at the end of the stable branch of the load (load control) or of
        the approach (displacement control) on unloading.

    Returns
    -------
    dhfield.core.records.PullOff
        ``force`` [N], ``semi_major`` = ``semi_minor`` (the contact radius) and the
        adhesive radius [m], ``approach`` [m], the SI inputs and the nondimensional record.
    """
    return si_pull_off(pull_off_nondimensional, effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress,
                       control=control, check_mu=True)


@fill_doc
def pull_off_force(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress, *,
                   control="load"):
    """Compute the circular DH pull-off force [N].

    Parameters
    ----------
    %(material)s
    max_adhesive_stress : array_like
        Peak adhesive stress sigma0 [Pa].
    %(control)s

    Returns
    -------
    %(pull_off_force_returns)s
    """
    return pull_off(effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress,
                    control=control).force
