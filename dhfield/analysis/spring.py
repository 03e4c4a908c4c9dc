"""Compliant loading: an adhesive contact in series with a machine spring.

Real rigs and AFM cantilevers are springs.  The machine controls the position of
the far end of a spring of stiffness K, and the contact sees the load W that
spring transmits.  This module gives, for every model with a load-approach curve
(:data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`), the pull-off under that spring and
the loading-unloading cycle: the jump into contact on approach, the jump out on
retraction and the energy lost per cycle.

Units
-----
The paper's (Eqs. 32-35): loads ``W* = W sin(theta_skew)/(2 pi R dgamma)``
(Eq. 34, sin(theta_skew) = 1 for the circular models), approaches
``delta* = delta R/c_r^2`` with ``c_r = (R^2 dgamma/E*)^(1/3)`` (Eq. 33), and so
stiffnesses in the ratio of the two units and energies in their product:

.. math::

    K^* = K\\,\\frac{c_r^2/R}{2\\pi R\\Delta\\gamma/\\sin\\theta_{skew}}, \\qquad
    U^* = \\frac{U}{(2\\pi R\\Delta\\gamma/\\sin\\theta_{skew})\\,(c_r^2/R)} .

With R = E* = dgamma = 1 and a circular model, K* = K/(2 pi).

The spring (derived here)
-------------------------
Loads positive compressive, approaches positive into the contact.  The machine
controls the displacement of the spring's far end,

.. math:: \\Delta = \\delta + W/K ,

and at fixed Delta the potential energy of contact plus spring has second
derivative ``dW/d(delta) + K`` along the curve of equilibria: a state is stable
while ``dW/d(delta) > -K``.  Unloading from high load along the stable branch,
the contact jumps out where the curve's stiffness meets -K,

.. math:: \\frac{dW}{d\\delta} = -K
          \\iff \\frac{d}{dt}\\left[s\\,\\delta + (1-s)\\,W\\right] = 0,
          \\qquad s = \\frac{K}{1+K},

for any curve parameter t: the jump is the first minimum of the machine
position ``F_s = s delta + (1 - s) W = s Delta`` (scaled) met on unloading.  K -> 0
(s = 0) is load control, the minimum of W; K -> infinity (s = 1) is displacement
control, the minimum of delta, or the end of the curve.  In between the jump lies
between the two (dW/d(delta) runs from 0 at the minimum of W to -infinity at the
minimum of delta), which is where it is searched.  The contact lands, at the same
Delta, on the force-free separated state ``W = 0, delta = Delta``.

The cycle (derived here)
------------------------
Approaching from separation at W = 0, the force-free state ends at approach
delta_s; there the contact jumps, at fixed Delta = delta_s, along the line
``W = K (delta_s - delta)`` (slope -K in the W-delta plane) to the state of the
stable branch with the same machine position: the root of
``F_s(t) = s delta_s`` above the jump-out point.  Where the force-free approach
ends depends on the model (:data:`JUMP_IN_RULES`):

* ``jkr``, ``jkr-elliptic``: at contact, delta_s = 0, where the curve starts
  (a -> 0: W -> 0, delta -> 0) -- exact, the JKR models have no force out of
  contact.  Load control lands at W = 0 (a*^3 = 9 pi/2 for the sphere),
  displacement control at delta = 0 (a*^3 = 2 pi, W* = -2/3).
* ``md``: where the gap at the centre reaches the Dugdale range h0 = dgamma/sigma0,
  delta_s = -1/mu: the force-free branch ends there and the separated branch of
  :mod:`dhfield.models.maugis_dugdale_separated` leaves it unstable (d delta/dc < 0 at c = 0);
  the contact lands on that separated branch (a stiff machine, small lambda) or on
  the contact curve, which the separated branch joins at a = 0 (Maugis 1992).
  The jump-out is searched along both.
* the DH models, ``md-elliptic`` and ``dmt`` define no force out of contact: the
  approach is taken as force-free until the contact curve's end,
  delta_s = delta(a = 0), and the record carries a warning that says so.  That
  end is a convention, not physics: the Dugdale law that MD and the BEM use
  would end it where the central gap reaches the range h0, delta_s = -1/mu.
  The energy lost is computed with both ends, and their difference is stated
  as ``energy_lost_convention`` (0 for the three models above, whose jump-in
  is physical); ``energy_lost_uncertainty`` = ``energy_lost_error`` (the
  quadrature's) + ``energy_lost_convention`` is the uncertainty to which
  ``dhfield cycle`` prints the energy.

The energy lost per cycle is the work the machine does, ``U = oint W dDelta``.
The force-free branch and the jumps (Delta fixed) do no work, so with the curve
parameter t running from the jump-out point t_o up to the landing point t_i,

.. math:: U = -\\int_{t_o}^{t_i} W \\frac{d\\delta}{dt}\\,dt
              + \\frac{W_o^2 - W_i^2}{2K},

the area the cycle encloses in the W-delta plane with the jumps drawn as lines
of slope -K.  It is infinite under load control (K = 0, a nonzero pull-off
load): the spring releases W_o^2/(2K).  The integral is a Chebyshev quadrature of
the public load curve (two orders; the difference is reported as
``energy_lost_error``); on the MD separated branch it is closed form.

The BEM under a spring and its cycle are :mod:`dhfield.analysis.bem_spring` (the same
jump conditions on the BEM's branch sampled by adhesive force).

References
----------
.. [1] D. Maugis, J. Colloid Interface Sci. 150 (1992) 243,
   doi:10.1016/0021-9797(92)90288-C (the MD model; Eq. 6.17, as reconstructed in
   the project's physics notes, Sec. 5)
.. [2] K. L. Johnson, K. Kendall, A. D. Roberts, Proc. R. Soc. Lond. A 324 (1971)
   301, doi:10.1098/rspa.1971.0141 (the JKR curve)
.. [3] D. Maugis, M. Barquins, J. Phys. D 11 (1978) 1989,
   doi:10.1088/0022-3727/11/14/011 (JKR contacts under a machine of finite
   stiffness: the stability condition dW/d(delta) = -K)
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import elementwise

from . import compare
from ..core.validation import check_interval
from ..models.maugis_dugdale_separated import dugdale_range, separated_branch, zone_radius_at_contact
from ..core.pull_off_search import stable_minimum_index
from ..core.records import PullOff, broadcast_field
from ..core.schema import PULL_OFF_SPRING_KEYS

__all__ = ["stiffness_star", "check_machine_stiffness", "add_machine_displacement", "pull_off_under_spring", "spring_pull_off_record",
           "pull_off_force_under_spring", "loading_cycle", "loading_cycle_si", "cycle_si_values", "cycle_path",
           "JUMP_IN_RULES", "CYCLE_UNITS", "spring_weight"]

#: How each model's force-free approach ends (module docstring).
JUMP_IN_RULES = {
    "jkr": "contact (a = 0: W = 0, delta = 0)",
    "jkr-elliptic": "contact (a = 0: W = 0, delta = 0)",
    "md": "Dugdale range (central gap = dgamma/sigma0, delta* = -1/mu)",
}
_CONTACT_END = "contact-curve end (a = 0); the model defines no force out of contact"
_NO_FORCE_WARNING = ("{model} defines no force out of contact: the approach is taken as force-free until "
                     "the contact curve's end (a = 0), so its jump-in is a convention")
_JKR_TYPE = ("jkr", "jkr-elliptic")
_A_MIN = 1e-6  # smallest a* the public curves accept (CONTACT_SIZE_RANGE); a = 0 is the end state
_SCAN = 33  # first scan of the jump-out bracket
_ZOOM = 17  # points per zoom step (the bracket shrinks 8x per step)
_ZOOM_STEPS = 14  # 8^14 ~ 4e12: bracket width ~1e-12 of the first one
_QUAD_NODES = (48, 96)  # Chebyshev orders of the energy integral; their difference is the error estimate

#: Units of the cycle record (nondimensional keys '1'; SI keys of :func:`loading_cycle_si`).
CYCLE_UNITS = {
    "machine_stiffness_star": "1", "energy_lost_star": "1", "energy_lost_error_star": "1",
    "energy_lost_convention_star": "1", "energy_lost_uncertainty_star": "1",
    "machine_stiffness": "N m-1", "energy_lost": "J", "energy_lost_error": "J", "energy_lost_convention": "J",
    "energy_lost_uncertainty": "J",
    "jump_in_start_approach": "m", "jump_in_force": "N", "jump_in_approach": "m", "jump_in_semi_major": "m",
    "jump_out_force": "N", "jump_out_approach": "m", "jump_out_semi_major": "m",
    "separation_approach": "m", "max_tension_force": "N",
}


def check_machine_stiffness(name, value):
    """Validate a machine stiffness: finite and >= 0 (0 is load control).

    Parameters
    ----------
    name : str
        The parameter's name, used in the error message.
    value : array_like
        The machine stiffness, K [N/m] or K* [-].

    Returns
    -------
    ndarray
        ``value`` as a float array, unchanged.

    Raises
    ------
    ValueError
        Naming ``name`` and the accepted range.
    """
    return check_interval(name, value, 0.0, np.inf, low_open=False, high_open=True,
                          what="machine stiffness, >= 0 and finite; 0 is load control")


def stiffness_star(machine_stiffness, effective_radius, reduced_modulus, work_of_adhesion, sin_skew=1.0):
    """Convert a machine stiffness to the paper's units, K* = K (c_r^2/R)/(2 pi R dgamma/sin(theta_skew)) [-].

    Parameters
    ----------
    machine_stiffness : array_like
        K >= 0, finite [N/m].
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        R [m], E* [Pa], dgamma [J/m^2].
    sin_skew : array_like, default 1.0
        The sine of the skew angle, sin(theta_skew), of the load normalisation,
        Eq. (34): 1 for the circular models, that of beta0 for the elliptical
        ones [-].

    Returns
    -------
    ndarray
        K* [-], broadcast over the inputs.

    Raises
    ------
    ValueError
        If ``machine_stiffness`` is negative or not finite.

    Notes
    -----
    dW*/d(delta*) = -K* is then the jump condition in the paper's units: the load
    unit is 2 pi R dgamma/sin(theta_skew) (Eq. 34), the approach unit c_r^2/R with
    c_r of Eq. (33).
    """
    from ..core.units import approach_unit, load_unit

    k = check_machine_stiffness("machine_stiffness", machine_stiffness)
    return k * approach_unit(effective_radius, reduced_modulus, work_of_adhesion) / load_unit(
        effective_radius, work_of_adhesion, sin_skew)  # Eqs. (33), (34)


def add_machine_displacement(curve, machine_stiffness):
    """A load curve with the column ``machine_displacement``: Delta = delta + W/K.

    Parameters
    ----------
    curve : dict
        A load-curve record of :func:`dhfield.analysis.compare.load_curve` (``W_star``,
        ``delta_star``; K in the paper's units, :func:`stiffness_star`) or of
        :func:`dhfield.analysis.dimensional.load_curve_si` (``force`` [N], ``approach`` [m];
        K in N/m).
    machine_stiffness : float
        K > 0, finite [N/m or -].

    Returns
    -------
    dict
        The record with ``machine_displacement`` after the approach column [m or c_r^2/R]:
        the position of the spring's far end, whose first minimum on unloading is
        the jump out (module docstring).
    """
    k = float(check_interval("machine_stiffness", machine_stiffness, 0.0, np.inf, high_open=True,
                             what="machine stiffness, > 0 and finite"))
    si = "force" in curve
    load, approach = (curve["force"], curve["approach"]) if si else (curve["W_star"], curve["delta_star"])
    out = {}
    for key, v in curve.items():
        out[key] = v
        if key == ("approach" if si else "delta_star"):
            with np.errstate(over="ignore"):
                delta = np.asarray(approach, float) + np.asarray(load, float) / k  # Delta
            if not np.all(np.isfinite(delta)):  # W/K overflows: K is too small to be told from load control
                raise ValueError(f"machine_stiffness = {k:g} is too small: the machine displacement W/K "
                                 "overflows (a machine this soft is load control: leave the stiffness out)")
            out["machine_displacement"] = delta
    return out


# --------------------------------------------------------------------------- one model's curve, by parameter t
class _Curve:
    """A model's curve of equilibria by one parameter t: the contact size a* = t for t >= 0 and,
    for MD only, the separated branch c* = c_end + t for t in [-c_end, 0]."""

    def __init__(self, model, mu, beta0):
        compare.load_curve(model, mu=mu, beta0=beta0, a_star=[1.0])  # validates model, mu, beta0 (scalars)
        self.model, self.mu, self.beta0 = model, float(mu), float(beta0)
        self.load = compare.pull_off(model, mu=mu, beta0=beta0, control="load", check_closure=False, warn=False)
        self.disp = compare.pull_off(model, mu=mu, beta0=beta0, control="displacement", check_closure=False, warn=False)
        self.separated = model == "md"
        self.c_end = float(zone_radius_at_contact(mu)) if self.separated else 0.0
        if bool(self.disp["at_zero_contact"]):
            self.end = (float(self.disp["W_star"]), float(self.disp["delta_star"]))
        elif model in _JKR_TYPE:
            self.end = (0.0, 0.0)  # JKR (1971): W and delta -> 0 as a -> 0
        else:  # error O(a^2) ~ 1e-12 (checked against the exact a = 0 of dh-circular and md)
            c = compare.load_curve(model, mu=mu, beta0=beta0, a_star=[_A_MIN])
            self.end = (float(c["W_star"][0]), float(c["delta_star"][0]))
        self.t_start = -self.c_end  # where the curve leaves the force-free state (MD) or starts (others)
        if self.separated:
            self.start_delta = float(-dugdale_range(mu))
        elif model in _JKR_TYPE:
            self.start_delta = 0.0
        else:
            self.start_delta = self.end[1]
        a_w = float(self.load["a_star"]) if not bool(self.load["at_zero_contact"]) else 0.0
        self.t_hi = a_w
        self.t_lo = float(self.disp["a_star"]) if not bool(self.disp["at_zero_contact"]) else self.t_start
        self.t_lo = min(self.t_lo, self.t_hi)

    def states(self, t):
        """W*, delta* at parameter t (any shape)."""
        t = np.asarray(t, dtype=float)
        w = np.empty(t.shape)
        d = np.empty(t.shape)
        pos = t > 0
        if np.any(pos):
            c = compare.load_curve(self.model, mu=self.mu, beta0=self.beta0, a_star=np.maximum(t[pos], _A_MIN))
            w[pos], d[pos] = c["W_star"], c["delta_star"]
            small = t[pos] < _A_MIN
            if np.any(small):  # below the smallest size the curves accept: the end state
                ws, ds = w[pos], d[pos]
                ws[small], ds[small] = self.end
                w[pos], d[pos] = ws, ds
        neg = ~pos
        if np.any(neg):
            if self.separated:
                st = separated_branch(np.clip(self.c_end + t[neg], 0.0, self.c_end), self.mu)
                w[neg], d[neg] = st["W_star"], st["delta_star"]
            else:
                w[neg], d[neg] = self.end
        return w, d

    def machine(self, t, s):
        """F_s = s delta + (1 - s) W (the machine position s Delta)."""
        w, d = self.states(t)
        return s * d + (1.0 - s) * w


def _jump_out(curve, s):
    """Parameter t of the jump out (first minimum of F_s from high load), vectorised over s."""
    hi = np.full(s.shape, curve.t_hi)
    lo = np.full(s.shape, curve.t_lo)
    if curve.t_hi <= curve.t_lo:
        return lo
    if not bool(curve.disp["at_zero_contact"]) and np.all(s == 1.0):
        return lo  # the rigid machine: the displacement-controlled pull-off of the model itself
    for n in [_SCAN] + [_ZOOM] * _ZOOM_STEPS:
        frac = np.linspace(0.0, 1.0, n)
        t = hi[:, None] + (lo - hi)[:, None] * frac  # descending from the high-load end
        f = curve.machine(t, s[:, None])
        i = stable_minimum_index(f)  # the one rule: the first local minimum from the high-load end
        j = np.arange(s.size)
        new_hi = t[j, np.maximum(i - 1, 0)]
        new_lo = t[j, np.minimum(i + 1, n - 1)]
        hi, lo = new_hi, new_lo
        if np.all(np.abs(hi - lo) < 1e-13 * np.maximum(1.0, np.abs(hi))):
            break
    i_end = np.abs(lo - curve.t_lo) < 1e-15  # bracket shrank onto the low end
    t = np.where(i_end, curve.t_lo, 0.5 * (hi + lo))
    t = _polish(curve, s, t, ~i_end)
    # below the smallest a* the curves accept the state is the end state a = 0: say so
    return np.where((t > 0) & (t <= 2.0 * _A_MIN), 0.0, t)


def _polish(curve, s, t, interior):
    """The zoom locates a flat minimum to ~sqrt(eps); polish it as the root of dF_s/dt (5-point
    differences, h = 1e-4: truncation ~h^4, rounding ~eps/h) where the curve is smooth around it."""
    h = 1e-4 * np.maximum(1.0, np.abs(t))
    w = 1e-6 * np.maximum(1.0, np.abs(t))
    room = t - w - 2 * h > (curve.t_start if curve.separated else _A_MIN)  # the curve goes on below t_lo
    if curve.separated:  # the branches meet at t = 0 with a kink in the parameter
        room &= (t - w - 2 * h > 0.0) | (t + w + 2 * h < 0.0)
    ok = interior & room
    if not np.any(ok):
        return t

    def slope(x, ss, hh):
        f = curve.machine(x[..., None] + hh[..., None] * np.array([-2.0, -1.0, 1.0, 2.0]), ss[..., None])
        return (f[..., 0] - 8.0 * f[..., 1] + 8.0 * f[..., 2] - f[..., 3]) / (12.0 * hh)

    lo, hi = t[ok] - w[ok], t[ok] + w[ok]
    sl, sh = slope(lo, s[ok], h[ok]), slope(hi, s[ok], h[ok])
    bracketed = (sl < 0) & (sh > 0)
    if np.any(bracketed):
        res = elementwise.find_root(slope, (lo[bracketed], hi[bracketed]),
                                    args=(s[ok][bracketed], h[ok][bracketed]),
                                    tolerances=dict(xatol=1e-15, xrtol=1e-15))
        sub = t[ok]
        sub[bracketed] = np.where(res.success, res.x, sub[bracketed])
        t = t.copy()
        t[ok] = sub
    return t


def _landing(curve, s, t_out, f_start):
    """Parameter t > t_out where F_s = f_start (the jump-in lands there), vectorised over s."""
    f_out = curve.machine(t_out, s)
    top = np.full(s.shape, max(curve.t_hi, 1.0) * 1.5)
    for _ in range(60):
        low = curve.machine(top, s) < f_start
        if not np.any(low):
            break
        top = np.where(low, 2.0 * top, top)
    else:
        raise RuntimeError(f"{curve.model}: no stable state reached on loading (the curve never rises to the "
                           "machine position of the jump-in)")
    land = np.array(t_out, dtype=float)
    need = f_out < f_start
    if np.any(need):
        def g(t, ss, fs):
            return curve.machine(t, ss) - fs

        res = elementwise.find_root(g, (t_out[need], top[need]), args=(s[need], f_start[need]),
                                    tolerances=dict(xatol=1e-14, xrtol=1e-14))
        land[need] = res.x
    return land


def _jump_in_convention_spread(curve, s, k, t_out, w_out, energy):
    """|U*(delta_s = -1/mu) - U*| for a model without a force out of contact (module docstring), else 0.

    The energy of the cycle whose force-free approach ends where the central gap reaches the
    Dugdale range (delta_s = -h0 = -1/mu, the rule of MD and the BEM) instead of at the contact
    curve's end; NaN where no state of the loading branch reaches that machine position.
    """
    if curve.model in JUMP_IN_RULES:
        return np.zeros(s.shape)
    try:
        t_alt = _landing(curve, s, t_out, s * float(-dugdale_range(curve.mu)))
    except RuntimeError:
        return np.full(s.shape, np.nan)
    w_alt, _ = curve.states(t_alt)
    alt = -_contact_integral(curve, np.maximum(t_out, 0.0), np.maximum(t_alt, 0.0), _QUAD_NODES[-1])
    with np.errstate(divide="ignore", invalid="ignore"):
        alt = alt + np.where(np.isinf(k), 0.0, (w_out**2 - w_alt**2) / (2.0 * k))
        spread = np.abs(alt - energy)
    return np.where(alt == energy, 0.0, spread)  # equal (also both infinite, load control): no spread


def _contact_integral(curve, a1, a2, n):
    """int_{a1}^{a2} W d(delta) along the contact curve, Chebyshev of order n (vectorised by loop)."""
    out = np.zeros(a1.shape)
    x = np.cos(np.pi * (np.arange(n) + 0.5) / n)  # Chebyshev nodes of the first kind
    todo = a2 > a1
    if not np.any(todo):
        return out
    t = 0.5 * (a1[todo, None] + a2[todo, None]) + 0.5 * (a2 - a1)[todo, None] * x
    w, d = curve.states(t)
    for k, (lo, hi) in enumerate(zip(a1[todo], a2[todo])):
        cw = np.polynomial.Chebyshev.fit(t[k], w[k], n - 1, domain=[lo, hi])
        cd = np.polynomial.Chebyshev.fit(t[k], d[k], n - 1, domain=[lo, hi])
        prod = (cw * cd.deriv()).integ(lbnd=lo)
        out[np.flatnonzero(todo)[k]] = prod(hi)
    return out


def _separated_integral(mu, c1, c2):
    """int_{c1}^{c2} W d(delta) on the MD separated branch, closed form."""
    def prim(c):  # W = -mu c^2/2, d(delta)/dc = c - 4 mu/pi (dhfield.models.maugis_dugdale_separated)
        return -0.5 * mu * (c**4 / 4.0 - 4.0 * mu / np.pi * c**3 / 3.0)
    return prim(c2) - prim(c1)


def spring_weight(machine_stiffness):
    """Return the weight s = K*/(1 + K*) of the machine position F_s = s delta* + (1 - s) W*, and K*.

    Parameters
    ----------
    machine_stiffness : array_like or None
        K* >= 0 and finite; None is the rigid machine (s = 1, K* = inf) [-].

    Returns
    -------
    (ndarray, ndarray)
        The weight s and K* (validated), both [-].
        Used by :mod:`dhfield.analysis.bem_spring`, the BEM under a spring.

    Raises
    ------
    ValueError
        If ``machine_stiffness`` is negative or not finite (the message names it).
    """
    return _as_weight(machine_stiffness)


def _as_weight(k):
    """s = K/(1 + K), with K = None or inf the rigid machine (s = 1)."""
    if k is None:
        return np.ones(()), np.full((), np.inf)
    k = check_machine_stiffness("machine_stiffness", k)
    return k / (1.0 + k), k


def _state_record(curve, t):
    """a*, b*, c*, d*, v of the states at t (W, delta from :meth:`_Curve.states`)."""
    t = np.atleast_1d(t)
    nan = np.full(t.shape, np.nan)
    out = {"a_star": np.zeros(t.shape), "b_star": np.zeros(t.shape), "c_star": nan.copy(),
           "d_star": nan.copy(), "v": nan.copy()}
    pos = t >= _A_MIN
    if np.any(pos):
        c = compare.load_curve(curve.model, mu=curve.mu, beta0=curve.beta0, a_star=t[pos])
        for k in out:
            out[k][pos] = c[k]
    end = ~pos
    if np.any(end):
        if curve.separated:
            out["c_star"][end] = np.clip(curve.c_end + t[end], 0.0, curve.c_end)
        elif bool(curve.disp["at_zero_contact"]):
            for k in ("c_star", "d_star", "v"):
                out[k][end] = curve.disp[k]
    return out


def pull_off_under_spring(model, *, beta0, mu, machine_stiffness):
    """Pull-off of a model under a machine spring of stiffness K*, vectorised over K*.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`.
    beta0, mu : float
        Hertz ellipticity of the geometry and transition parameter (Eq. 35) [-], keyword-only.
    machine_stiffness : array_like
        K* >= 0, finite, in the paper's units (:func:`stiffness_star`) [-]; 0 is
        load control.

    Returns
    -------
    dhfield.core.records.PullOff
        ``control = 'spring'``, the spring group filled; arrays of the shape of K* (read as
        attributes or as a mapping): the record's fields at the jump out and
        ``machine_stiffness_star``, ``W_star`` (load at
        the jump out, Eq. 34), ``delta_star``, ``a_star``, ``b_star``, ``c_star``,
        ``d_star``, ``v`` at the jump, ``separation_delta_star`` (the approach
        after the jump, W = 0: the machine position Delta* = delta* + W*/K*),
        ``max_tension_W_star`` (the smallest W* met from high load to the jump:
        the largest tensile force a recording shows), ``at_zero_contact`` (the jump
        starts at or beyond the loss of contact, a = 0) and ``on_separated_branch``
        (MD only: the jump starts out of contact, :mod:`dhfield.models.maugis_dugdale_separated`).

    Notes
    -----
    The first minimum of ``s delta* + (1 - s) W*``, s = K*/(1 + K*), met on
    unloading (module docstring): where dW*/d(delta*) = -K*.  It is bracketed by
    the load- and displacement-controlled pull-offs of
    :func:`dhfield.analysis.compare.pull_off` and located by a vectorised zoom search to a
    bracket of ~1e-12 (the load at the jump is then exact to rounding: the
    machine position is stationary there).  For MD the search continues on the
    separated branch, so for a stiff machine and small lambda the jump out can
    start out of contact, beyond the a = 0 end point that
    :func:`dhfield.models.maugis_dugdale.pull_off` reports under displacement control.
    """
    s, k = _as_weight(machine_stiffness)
    curve = _Curve(model, mu, beta0)
    out = _pull_off(curve, s, k)
    return _spring_record(curve.load, out)


def _spring_record(load, out):
    """The :class:`dhfield.core.records.PullOff` (spring group filled) of the jump out ``out`` (arrays over K*);
    the model, geometry, inputs and warning are those of the load-control record ``load``."""
    shape = np.shape(out["W_star"])
    a, b, c, d = (np.asarray(out[x], float) for x in ("a_star", "b_star", "c_star", "d_star"))
    zero = np.asarray(out["at_zero_contact"], bool)
    with np.errstate(invalid="ignore", divide="ignore"):
        ell = np.where(a > 0, b / np.where(a > 0, a, 1.0), np.where(zero, float(load.ellipticity), 1.0))
        ok = np.isfinite(c) & (c > 0) & np.isfinite(d)
        adh = np.where(ok, d / np.where(ok, c, 1.0), np.nan)

    def full(x, dtype=float):
        return broadcast_field(x, shape, dtype)

    return PullOff(model=load.model, control="spring", geometry=load.geometry, beta0=full(load.beta0),
                   mu=full(load.mu), sin_skew=full(load.sin_skew), W_star=out["W_star"], a_star=out["a_star"],
                   b_star=out["b_star"], c_star=out["c_star"], d_star=out["d_star"], v=out["v"],
                   delta_star=out["delta_star"], ellipticity=full(ell), adhesive_ellipticity=full(adh),
                   at_zero_contact=out["at_zero_contact"], warning=full(load.warning, object),
                   machine_stiffness_star=out["machine_stiffness_star"],
                   separation_delta_star=out["separation_delta_star"],
                   max_tension_W_star=out["max_tension_W_star"], on_separated_branch=out["on_separated_branch"])


def _pull_off(curve, s, k):
    shape = s.shape
    s1 = np.atleast_1d(s).astype(float)
    k1 = np.broadcast_to(np.atleast_1d(k), s1.shape)
    t = _jump_out(curve, s1)
    w, d = curve.states(t)
    with np.errstate(divide="ignore", invalid="ignore"):
        sep = np.where(k1 > 0, d + w / k1, -np.inf)  # Delta = delta + W/K
    sep = np.where(np.isinf(k1), d, sep)
    w_min = np.where(t < curve.t_hi, float(curve.load["W_star"]), w)  # min W on [t, inf): W(a_W) if passed
    w_min = np.minimum(w_min, w)
    rec = {"machine_stiffness_star": k1.astype(float), "W_star": w, "delta_star": d,
           **_state_record(curve, t), "separation_delta_star": sep, "max_tension_W_star": w_min,
           "at_zero_contact": t < _A_MIN, "on_separated_branch": t < 0.0, "_t": t}
    return {key: (v.reshape(shape)[()] if key != "_t" else v) for key, v in rec.items()}


def spring_pull_off_record(model, *, beta0, mu, machine_stiffness):
    """Build a pull-off record (keys of :data:`dhfield.core.schema.PULL_OFF_KEYS`) under a spring of stiffness K*.

    ``control`` is ``'spring'``; the state is the one at the jump out
    (:func:`pull_off_under_spring`), scalar K* only.  The ``warning`` is that of
    :func:`dhfield.analysis.compare.pull_off` (the model's validated range).

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`.
    beta0, mu : float
        Hertz ellipticity of the geometry and transition parameter (Eq. 35) [-], keyword-only.
    machine_stiffness : float
        K* >= 0 in the paper's units (:func:`stiffness_star`) [-]; a scalar.

    Returns
    -------
    dhfield.core.records.PullOff
        The record: ``control = 'spring'``, W*, a*, b*, c*, d*, v and delta* at
        the jump out, the ellipticities b/a and d/c, ``at_zero_contact``, and the
        other fields of :func:`dhfield.analysis.compare.pull_off`'s record (load control).

    Raises
    ------
    ValueError
        If ``machine_stiffness`` is not a scalar, or out of range.
    """
    if np.ndim(machine_stiffness):
        raise ValueError("machine_stiffness of a pull-off record must be a scalar")
    po = pull_off_under_spring(model, mu=mu, beta0=beta0, machine_stiffness=machine_stiffness)
    return po.replace(**{key: None for key in PULL_OFF_SPRING_KEYS})


def pull_off_force_under_spring(params, machine_stiffness, model=compare.DEFAULT_MODEL):
    """Pull-off in SI units under a machine spring of stiffness K [N/m].

    Parameters
    ----------
    params : ContactParameters
        From :func:`dhfield.analysis.dimensional.contact_parameters` (scalars).
    machine_stiffness : float
        K >= 0, finite [N/m]; 0 is load control.
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`.

    Returns
    -------
    dict
        The keys of :data:`dhfield.core.schema.PULL_OFF_SI_KEYS` (``control`` =
        'spring'): ``force`` [N] at the jump out, the contact size and approach
        there [m], and the nondimensional record.
    """
    from .dimensional import pull_off_record_si

    k_star = _si_stiffness_star(params, machine_stiffness, model)
    return pull_off_record_si(spring_pull_off_record(model, mu=params.mu, beta0=params.beta0, machine_stiffness=k_star), params)


def _sin_skew(model, params):
    return 1.0 if model in compare.CIRCULAR_MODEL_NAMES else float(params.sin_skew)


def _si_stiffness_star(params, machine_stiffness, model):
    return stiffness_star(machine_stiffness, params.effective_radius, params.reduced_modulus,
                          params.work_of_adhesion, _sin_skew(model, params))


def loading_cycle(model, *, beta0, mu, machine_stiffness=None, with_path=False):
    """Loading-unloading cycle of a model under a machine spring: both jumps and the energy lost.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`.
    beta0, mu : float
        Hertz ellipticity of the geometry and transition parameter (Eq. 35) [-], keyword-only.
    machine_stiffness : array_like or None
        K* >= 0 in the paper's units (:func:`stiffness_star`) [-]; None: a rigid
        machine (displacement control); 0: load control (infinite energy lost).

    Returns
    -------
    dict
        ``model``, ``geometry``, ``beta0``, ``mu``, ``sin_skew``,
        ``machine_stiffness_star`` (inf for the rigid machine), ``jump_in_rule``;
        ``jump_in_start_delta_star`` (where the force-free approach ends, W = 0),
        ``jump_in_W_star``, ``jump_in_delta_star``, ``jump_in_a_star`` (where it
        lands); ``jump_out_W_star``, ``jump_out_delta_star``, ``jump_out_a_star``,
        ``jump_out_c_star`` (where the jump out starts), ``separation_delta_star``
        (where it lands, W = 0), ``max_tension_W_star``; ``energy_lost_star``
        (per cycle, in (2 pi R dgamma/sin(theta_skew)) c_r^2/R) and
        ``energy_lost_error_star`` (its quadrature error estimate); ``warning``.
        Scalars for a scalar K*, else arrays.

    Other Parameters
    ----------------
    with_path : bool
        Also return ``_curve`` and ``_t`` (the curve and the jump parameters) for
        :func:`cycle_path`.

    Notes
    -----
    Module docstring: the jump out at the first minimum of s delta* + (1-s) W*,
    the jump in at fixed machine position from the end of the force-free
    approach, and

    .. math:: U^* = -\\int_{t_o}^{t_i} W^* \\frac{d\\delta^*}{dt}\\,dt
                    + \\frac{W_o^{*2} - W_i^{*2}}{2K^*}.
    """
    curve = _Curve(model, mu, beta0)
    s, k = _as_weight(machine_stiffness)
    shape = s.shape
    s1 = np.atleast_1d(s).astype(float)
    k1 = np.broadcast_to(np.atleast_1d(k), s1.shape).astype(float)
    out = _pull_off(curve, s1, k1)
    t_out = out["_t"]
    f_start = s1 * curve.start_delta  # machine position at the end of the force-free approach (W = 0)
    t_in = _landing(curve, s1, t_out, f_start)
    w_in, d_in = curve.states(t_in)
    w_out, d_out = out["W_star"], out["delta_star"]
    # energy: -int W d(delta) from the jump out up to the landing, by branch
    integ = {}
    for n in _QUAD_NODES:
        total = _contact_integral(curve, np.maximum(t_out, 0.0), np.maximum(t_in, 0.0), n)
        if curve.separated:
            c1 = np.clip(curve.c_end + np.minimum(t_out, 0.0), 0.0, curve.c_end)
            c2 = np.clip(curve.c_end + np.minimum(t_in, 0.0), 0.0, curve.c_end)
            total = total + _separated_integral(curve.mu, c1, c2)
        integ[n] = -total
    with np.errstate(divide="ignore", invalid="ignore"):
        spring = np.where(np.isinf(k1), 0.0, (w_out**2 - w_in**2) / (2.0 * k1))
    spring = np.where((k1 == 0) & (w_out**2 == w_in**2), 0.0, spring)
    energy = integ[_QUAD_NODES[-1]] + spring
    err = np.abs(integ[_QUAD_NODES[-1]] - integ[_QUAD_NODES[0]])
    convention = _jump_in_convention_spread(curve, s1, k1, t_out, w_out, energy)
    warning = str(compare.validity_message(model, mu, beta0))
    rule = JUMP_IN_RULES.get(model, _CONTACT_END)
    if model not in JUMP_IN_RULES:
        warning = "; ".join(x for x in (_NO_FORCE_WARNING.format(model=model), warning) if x)
    land_state = _state_record(curve, t_in)
    circle = model in compare.CIRCULAR_MODEL_NAMES
    rec = {
        "model": model, "geometry": "circle" if circle else "ellipse", "beta0": float(beta0),
        "mu": float(mu), "sin_skew": float(compare.load_curve(model, mu=mu, beta0=beta0, a_star=[1.0])["sin_skew"]),
        "machine_stiffness_star": k1, "jump_in_rule": rule,
        "jump_in_start_delta_star": np.full(s1.shape, curve.start_delta),
        "jump_in_W_star": w_in, "jump_in_delta_star": d_in, "jump_in_a_star": land_state["a_star"],
        "jump_out_W_star": w_out, "jump_out_delta_star": d_out, "jump_out_a_star": out["a_star"],
        "jump_out_c_star": out["c_star"], "separation_delta_star": out["separation_delta_star"],
        "max_tension_W_star": out["max_tension_W_star"], "energy_lost_star": energy,
        "energy_lost_error_star": err, "energy_lost_convention_star": convention,
        "energy_lost_uncertainty_star": err + convention, "warning": warning,
    }
    for key, v in rec.items():
        if isinstance(v, np.ndarray):
            rec[key] = v.reshape(shape)[()] if v.ndim else v
            if isinstance(rec[key], np.generic):
                rec[key] = rec[key].item()
    if with_path:
        rec["_curve"], rec["_t"] = curve, (t_out.reshape(shape), t_in.reshape(shape))
    return rec


#: The SI entries of a cycle record, in order: (SI key, nondimensional key, unit of :func:`cycle_si_values`).
_CYCLE_SI_ENTRIES = (
    ("jump_in_start_approach", "jump_in_start_delta_star", "approach"),
    ("jump_in_force", "jump_in_W_star", "force"),
    ("jump_in_force_error", "jump_in_W_star_error", "force"),
    ("jump_in_approach", "jump_in_delta_star", "approach"),
    ("jump_in_semi_major", "jump_in_a_star", "length"),
    ("jump_out_force", "jump_out_W_star", "force"),
    ("jump_out_force_error", "jump_out_W_star_error", "force"),
    ("jump_out_approach", "jump_out_delta_star", "approach"),
    ("jump_out_semi_major", "jump_out_a_star", "length"),
    ("separation_approach", "separation_delta_star", "approach"),
    ("max_tension_force", "max_tension_W_star", "force"),
    ("energy_lost", "energy_lost_star", "energy"),
    ("energy_lost_error", "energy_lost_error_star", "energy"),
    ("energy_lost_convention", "energy_lost_convention_star", "energy"),
    ("energy_lost_uncertainty", "energy_lost_uncertainty_star", "energy"),
)


def cycle_si_values(rec, *, force, approach, length=None):
    """SI values of the nondimensional entries of a cycle record (analytic or BEM), Eqs. (32)-(34) inverted.

    Parameters
    ----------
    rec : dict
        A record of :func:`loading_cycle` (or the BEM's cycle record of ``dhfield cycle``).
    force : float
        Load unit 2 pi R dgamma/sin(theta_skew) [N] (Eq. 34).
    approach : float
        Approach unit c_r^2/R [m] (Eq. 33).
    length : float, optional
        Length unit c_r [m] (Eq. 32); needed where ``rec`` has semi-axes (``jump_in_a_star``).

    Returns
    -------
    dict
        Each SI key whose nondimensional key is in ``rec``, in a fixed order: forces (and their
        error estimates) x ``force``, approaches x ``approach``, semi-axes x ``length``,
        energies x ``force`` x ``approach`` [N, m, J].
    """
    out = {}
    for key, star, unit in _CYCLE_SI_ENTRIES:
        if star in rec:
            v = rec[star]
            out[key] = (v * force * approach if unit == "energy" else
                        v * {"force": force, "approach": approach, "length": length}[unit])
    return out


def loading_cycle_si(params, machine_stiffness=None, model=compare.DEFAULT_MODEL):
    """Loading-unloading cycle in SI units under a machine spring of stiffness K [N/m].

    Parameters
    ----------
    params : ContactParameters
        From :func:`dhfield.analysis.dimensional.contact_parameters` (scalars).
    machine_stiffness : float or None
        K >= 0, finite [N/m]; None: a rigid machine (displacement control).
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`.

    Returns
    -------
    dict
        The record of :func:`loading_cycle` and its SI values (:data:`CYCLE_UNITS`):
        ``machine_stiffness`` [N/m], ``jump_in_start_approach``, ``jump_in_force``,
        ``jump_in_approach``, ``jump_in_semi_major``, ``jump_out_force``,
        ``jump_out_approach``, ``jump_out_semi_major``, ``separation_approach``,
        ``max_tension_force``, ``energy_lost``, ``energy_lost_error`` [J].

    Notes
    -----
    Inverts Eqs. (32)-(34): W = W* 2 pi R dgamma/sin(theta_skew), a = a* c_r,
    delta = delta* c_r^2/R, U = U* (2 pi R dgamma/sin(theta_skew)) c_r^2/R.
    """
    from ..core.units import load_unit

    if np.ndim(params.mu) or np.ndim(params.beta0):
        raise ValueError("params of a cycle must be scalars; got array-valued ContactParameters")
    k_star = None if machine_stiffness is None else _si_stiffness_star(params, machine_stiffness, model)
    rec = loading_cycle(model, mu=params.mu, beta0=params.beta0, machine_stiffness=k_star)
    force = float(load_unit(params.effective_radius, params.work_of_adhesion, rec["sin_skew"]))  # Eq. (34)
    length, approach = float(params.length_unit), float(params.approach_unit)  # Eqs. (32), (33)
    si = {"machine_stiffness": float("inf") if machine_stiffness is None else float(machine_stiffness),
          **cycle_si_values(rec, force=force, approach=approach, length=length)}
    warning = rec.pop("warning")
    return {**rec, **si, "warning": warning}


def cycle_path(model, *, beta0, mu, machine_stiffness=None, n=200, overshoot=0.3):
    """Trace the closed cycle as polylines in the (delta*, W*) plane, for plotting.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`.
    beta0, mu : float
        Hertz ellipticity of the geometry and transition parameter (Eq. 35) [-], keyword-only.
    machine_stiffness : float or None
        K* >= 0 in the paper's units [-], a scalar; None: a rigid machine
        (as :func:`loading_cycle`).
    n : int, default 200
        Points on the equilibrium curve between the jumps.
    overshoot : float, default 0.3
        Fraction of the curve's parameter range drawn above the landing point
        (loading beyond the jump-in, then unloading along the same branch).

    Returns
    -------
    dict
        ``record`` (:func:`loading_cycle`), ``branch`` (delta*, W* arrays of the
        stable branch from the jump out to above the landing), ``approach``
        ((delta*, W*) of the force-free approach, W = 0), ``jump_in`` and
        ``jump_out`` (two-point segments of slope -K*), ``loop`` (delta*, W*: the
        closed boundary of the energy lost).
    """
    rec = loading_cycle(model, mu=mu, beta0=beta0, machine_stiffness=machine_stiffness, with_path=True)
    curve = rec.pop("_curve")
    t_out, t_in = (float(x) for x in rec.pop("_t"))
    t = np.linspace(t_out, t_in + overshoot * max(t_in - t_out, 0.5), n)
    w, d = curve.states(t)
    loop_t = np.linspace(t_out, t_in, n)
    lw, ld = curve.states(loop_t)
    ds, dsep = rec["jump_in_start_delta_star"], rec["separation_delta_star"]
    jin = (np.array([ds, rec["jump_in_delta_star"]]), np.array([0.0, rec["jump_in_W_star"]]))
    jout = (np.array([rec["jump_out_delta_star"], dsep]), np.array([rec["jump_out_W_star"], 0.0]))
    loop_d = np.concatenate([ld, [ds, dsep, rec["jump_out_delta_star"]]])
    loop_w = np.concatenate([lw, [0.0, 0.0, rec["jump_out_W_star"]]])
    lo = min(dsep, ds, float(np.min(d))) if np.isfinite(dsep) else min(ds, float(np.min(d)))
    return {"record": rec, "branch": (d, w), "approach": (np.array([lo - 0.2, ds]), np.zeros(2)),
            "jump_in": jin, "jump_out": jout, "loop": (loop_d, loop_w)}
