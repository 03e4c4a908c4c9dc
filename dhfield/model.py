"""The nondimensional elliptical DH model: load curves and pull-off (Eqs. 31-36).

Units (Eqs. 32-35): R = E* = Delta gamma = 1, so lengths are in
c_r = (R^2 Delta gamma/E*)^(1/3), the approach in c_r^2/R, stresses in
E* c_r/R (so sigma0 = mu, Eq. 35) and loads are reported as
W* = W sin(theta_skew)/(2 pi R Delta gamma) (Eq. 34).

At a given contact semi-major axis a* the unknowns are c* and v (Eqs. 24, 31):

* Eq. (24) with sigma0 = mu gives v explicitly, v = mu/(kappa S), where
  S = sqrt(c^2 - a^2) and kappa = Po_ab/a (Eq. 8).
* Eq. (31) with Delta gamma = 1 leaves one equation for S.  Writing the Hertz gap
  slope as an integral over the ellipsoidal coordinate and exchanging the order of
  integration turns Eq. (31) into a single integral of algebraic functions:

  .. math::

      \\Delta\\gamma = v(1+v)\\,\\frac{Po_{cd}}{c}\\frac{Po_{ab}\\,ab}{3E^*}
          \\int_0^{S^2} \\frac{(S^2-w)^{3/2}\\,dw}{\\sqrt{(a^2+w)^3(b^2+w)w}}

  (no elliptic integrals are needed in the solve; the tests check it against the
  direct evaluation of Eq. 31 in :mod:`dhfield.adhesion` and against the circular
  closed form).  With w = S^2 sin^2 t it is evaluated by the graded Gauss rule of
  :func:`dhfield.adhesion.graded_rule`, with analytic derivatives in S and a.

The equation for S is solved by a vectorised, bracketed Newton iteration in log S
(monotone: d log(Delta gamma)/d log S lies between 1 and 3).  The load-controlled
pull-off is the largest a* where dW*/da* = 0 (the end of the stable branch, reached
from high load), the displacement-controlled pull-off the largest a* where
d delta*/da* = 0; both derivatives are analytic (implicit function theorem), the
roots are found with Chandrupatla's bracketing method to 1e-12 in a*.  When the
derivative is positive all the way down to a* -> 0 (the DMT side), the pull-off
is the zero-contact limit, which has a closed form (a quadratic in S).
"""
from __future__ import annotations

from dataclasses import asdict, astuple, dataclass, field

import numpy as np
from scipy import special
from scipy.optimize import elementwise

from ._validation import check_ellipticity, check_positive
from .adhesion import graded_rule
from .geometry import sin_skew_angle

__all__ = ["solve_adhesive_axis", "load_curve", "pull_off", "LoadCurve", "PullOff",
           "DEFAULT_A_STAR"]

#: Default contact semi-major axes of a load curve: covers pull-off (a* <~ 2 for
#: mu <= 20) up to W* ~ 10 at every beta0 in (0.3, 1].
DEFAULT_A_STAR = (0.02, 3.0)
#: Relative tolerance of the Newton solve for S (Delta gamma = 1 to this accuracy).
SOLVE_RTOL = 1e-14
_MAX_NEWTON = 60
#: Scan used to bracket the pull-off: geometric grid in a* (the minimum is refined after).
_SCAN = np.geomspace(1e-3, 4.0, 48)


@dataclass(frozen=True)
class _Shape:
    """Constants of one ellipse shape (R = E* = 1), shared by both ellipses (Eq. (17))."""
    beta: np.ndarray        # ellipticity of both ellipses
    kappa: np.ndarray       # Po_ab / a, Eq. (8)
    k_complete: np.ndarray  # K(k)
    r_major: np.ndarray     # R' of the shape-consistent geometry
    sin_skew: np.ndarray    # normalisation of Eq. (34)


def _shape(beta, sin_skew=None):
    beta = np.asarray(beta, dtype=float)
    b2 = beta**2
    rd_a = special.elliprd(0.0, b2, 1.0)
    rd_b = special.elliprd(0.0, 1.0, b2)
    kappa = 1.5 / (beta * np.sqrt(rd_a * rd_b))  # Eq. (8) with R = E* = 1
    rho = rd_b / rd_a
    if sin_skew is None:
        sin_skew = 2.0 * np.sqrt(rho) / (1.0 + rho)
    return _Shape(beta, kappa, special.elliprf(0.0, b2, 1.0), np.sqrt(rho), np.asarray(sin_skew, float))


def _axis_integrals(a, b, s, with_a=True):
    """T0, T1, Ta of the exchanged Eq. (31) for contact (a, b) and S.

    With w = S^2 sin^2 t and q = (a^2 + S^2 sin^2 t)^{3/2} (b^2 + S^2 sin^2 t)^{1/2}:
    T0 = int cos^4 t / q dt, T1 = int cos^2 t / q dt and
    Ta = d T0/da at fixed S and beta (b = beta a).
    """
    scale = np.minimum(1.0, b / s)
    t, w = graded_rule(np.arcsin(scale))
    ex = (lambda q: q[..., None])
    s2 = (ex(s) * np.sin(t)) ** 2
    a2s, b2s = ex(a) ** 2 + s2, ex(b) ** 2 + s2
    inv_q = 1.0 / (a2s * np.sqrt(a2s * b2s))
    c2 = np.cos(t) ** 2
    t0 = np.sum(w * c2 * c2 * inv_q, axis=-1)
    t1 = np.sum(w * c2 * inv_q, axis=-1)
    if not with_a:
        return t0, t1, None
    beta2 = (b / a) ** 2
    ta = np.sum(w * c2 * c2 * inv_q * (-3.0 * ex(a) / a2s - ex(beta2 * a) / b2s), axis=-1)
    return t0, t1, ta


def _adhesion_terms(a, s, shape, with_a=True):
    """J with Delta gamma = v (1 + v) J, and dJ/dS, dJ/da (None unless ``with_a``) (R = E* = 1)."""
    kappa, beta = shape.kappa, shape.beta
    c_pref = kappa**2 * beta * a**3 / 3.0  # (Po_cd/c)(Po_ab ab)/(3E*)
    t0, t1, ta = _axis_integrals(a, beta * a, s, with_a)
    s4 = s**4
    j = c_pref * 2.0 * s4 * t0  # Eq. (31), exchanged order
    j_s = 6.0 * c_pref * s**3 * t1
    j_a = 3.0 * j / a + c_pref * 2.0 * s4 * ta if with_a else None
    return j, j_s, j_a


def _zero_contact_s(mu, shape):
    """S = c at a = 0: mu S^2 + mu^2 S/kappa - 3 R' = 0 (Eqs. 24, 31 with a -> 0)."""
    p = mu**2 / shape.kappa
    return 2.0 * 3.0 * shape.r_major / (p + np.sqrt(p * p + 12.0 * mu * shape.r_major))


def _solve_s(a, mu, shape):
    """Solve Delta gamma(a, S) = 1 for S, element-wise (bracketed Newton in log S)."""
    fields = astuple(shape)
    a, mu, *fields = np.broadcast_arrays(np.asarray(a, float), np.asarray(mu, float), *fields)
    out_shape = a.shape
    a, mu, *fields = (f.ravel() for f in (a, mu, *fields))
    shape = _Shape(*fields)
    # Start between the small-contact limit (closed form) and the narrow-annulus
    # estimate S^2 ~ 8a/(pi mu^2); the bracket below makes any start safe.
    s0 = _zero_contact_s(mu, shape)
    s1 = np.sqrt(8.0 * a / (np.pi * mu**2))
    u = np.log(np.minimum(s0, np.maximum(s1, 1e-3 * s0)))
    lo = np.full(a.shape, -np.inf)
    hi = np.full(a.shape, np.inf)
    active = np.ones(a.shape, bool)
    for _ in range(_MAX_NEWTON):
        idx = np.nonzero(active)
        s = np.exp(u[idx])
        sh = _Shape(*(f[idx] for f in fields))
        v = mu[idx] / (sh.kappa * s)  # Eq. (24) with sigma0 = mu
        j, j_s, _ = _adhesion_terms(a[idx], s, sh, with_a=False)
        g = np.log(v) + np.log1p(v) + np.log(j)  # log Delta gamma, target 0
        dg = -1.0 - v / (1.0 + v) + s * j_s / j
        ui = u[idx]
        lo_i = np.where(g < 0, ui, lo[idx])
        hi_i = np.where(g > 0, ui, hi[idx])
        done = np.abs(g) < SOLVE_RTOL
        new = ui + np.clip(-g / dg, -2.0, 2.0)
        # Newton step leaving the bracket: bisect instead.
        bad = ((new <= lo_i) | (new >= hi_i)) & np.isfinite(lo_i) & np.isfinite(hi_i)
        new = np.where(bad, 0.5 * (lo_i + hi_i), new)
        lo[idx], hi[idx], u[idx] = lo_i, hi_i, np.where(done, ui, new)
        active[idx] = ~done
        if not active.any():
            break
    else:
        raise RuntimeError("adhesive-axis solve did not converge; please report the inputs")
    return np.exp(u).reshape(out_shape)


def _state(a, mu, shape, derivatives=False):
    """Full state at contact semi-major axis a (arrays broadcast)."""
    s = _solve_s(a, mu, shape)
    a, mu = np.broadcast_arrays(np.asarray(a, float), np.asarray(mu, float))
    kappa, beta, kk, sn = shape.kappa, shape.beta, shape.k_complete, shape.sin_skew
    v = mu / (kappa * s)  # Eq. (24)
    c = np.sqrt(a * a + s * s)
    w_star = sn / 3.0 * kappa * beta * ((1.0 + v) * a**3 - v * c**3)  # Eq. (36)
    delta = kappa * beta * kk * ((1.0 + v) * a**2 - v * c**2)  # (1+v) delta_ab - v delta_cd, Eq. (14a)
    out = dict(a=a, s=s, c=c, v=v, W=w_star, delta=delta)
    if derivatives:
        j, j_s, j_a = _adhesion_terms(a, s, shape)
        g_s = (-1.0 - v / (1.0 + v)) / s + j_s / j
        g_a = j_a / j
        s_a = -g_a / g_s  # implicit function theorem
        v_a = -v * s_a / s
        c_a = (a + s * s_a) / c
        out["dW"] = sn / 3.0 * kappa * beta * (3.0 * (1.0 + v) * a**2 + v_a * (a**3 - c**3)
                                               - 3.0 * v * c**2 * c_a)
        out["ddelta"] = kappa * beta * kk * (2.0 * a - v_a * s * s - 2.0 * v * s * s_a)
    return out


def _check_inputs(mu, beta0, ellipticity):
    mu = check_positive("mu", mu, "Tabor parameter, Eq. (35)")
    beta0 = check_ellipticity("beta0", beta0)
    if ellipticity is None:
        ell = beta0  # Eq. (9), Eq. (19): beta = beta_(pull-off) = beta0
    else:
        ell = check_ellipticity("ellipticity", ellipticity)
    return mu, beta0, ell


def solve_adhesive_axis(a_star, mu, beta0, *, ellipticity=None):
    """Solve Eqs. (24), (31), (35) for the adhesive semi-axis c* and the factor v.

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axis a* = a/c_r > 0 [-].
    mu : array_like
        Tabor parameter, Eq. (35), > 0 [-].
    beta0 : array_like
        Initial (Hertz) ellipticity in (0, 1] [-].
    ellipticity : array_like, optional
        Ellipticity of both ellipses if different from beta0 (see :func:`pull_off`).

    Returns
    -------
    c_star, v : ndarray
        Adhesive semi-major axis [-] and DH scaling factor [-].
    """
    a = check_positive("a_star", a_star, "contact semi-major axis a/c_r")
    mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
    st = _state(a, mu, _shape(ell, sin_skew_angle(beta0)))
    return _scalar(st["c"]), _scalar(st["v"])


def _scalar(x):
    x = np.asarray(x)
    return x[()] if x.ndim == 0 else x


@dataclass(frozen=True)
class LoadCurve:
    """A nondimensional load curve of the elliptical DH model (Eqs. 32-36).

    Attributes (arrays over the contact size)
    -----------------------------------------
    a_star, b_star : contact semi-axes a/c_r, b/c_r
    c_star, d_star : adhesive semi-axes c/c_r, d/c_r
    v : DH scaling factor
    W_star : load W sin(theta_skew)/(2 pi R Delta gamma), Eq. (34)
    delta_star : approach delta/(c_r^2/R)
    """
    mu: float
    beta0: float
    ellipticity: float
    a_star: np.ndarray
    b_star: np.ndarray
    c_star: np.ndarray
    d_star: np.ndarray
    v: np.ndarray
    W_star: np.ndarray
    delta_star: np.ndarray

    def as_dict(self):
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in asdict(self).items()}


@dataclass(frozen=True)
class PullOff:
    """Pull-off point of the elliptical DH model (nondimensional, Eqs. 32-36).

    ``at_zero_contact`` is True where the pull-off is the a* -> 0 limit (the load
    or approach increases monotonically with a*, as on the DMT side).
    """
    mu: np.ndarray
    beta0: np.ndarray
    ellipticity: np.ndarray
    control: str
    W_star: np.ndarray
    a_star: np.ndarray
    c_star: np.ndarray
    v: np.ndarray
    delta_star: np.ndarray
    at_zero_contact: np.ndarray = field(default=None)

    def as_dict(self):
        out = {}
        for k, v in asdict(self).items():
            v = np.asarray(v) if not isinstance(v, str) else v
            out[k] = v.tolist() if isinstance(v, np.ndarray) else v
        return out


def load_curve(mu, beta0, a_star=None, *, ellipticity=None, n=200):
    """Load curve of the elliptical DH model at Tabor parameter ``mu`` and ellipticity ``beta0``.

    Parameters
    ----------
    mu : float
        Tabor parameter, Eq. (35), > 0 [-].
    beta0 : float
        Initial ellipticity beta0 = b/a in (0, 1] (Eq. 9) [-].
    a_star : array_like, optional
        Contact semi-major axes a* > 0 [-]; default ``n`` points evenly spaced over
        :data:`DEFAULT_A_STAR`.
    ellipticity : float, optional
        Ellipticity of both ellipses if it differs from beta0; the normalisation of
        Eq. (34) keeps sin(theta_skew) of beta0.
    n : int
        Number of points of the default a* grid.

    Returns
    -------
    LoadCurve
    """
    mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
    if a_star is None:
        if int(n) < 2:
            raise ValueError(f"n must be an integer >= 2 (number of curve points); got {n!r}")
        a_star = np.linspace(*DEFAULT_A_STAR, int(n))
    a = check_positive("a_star", a_star, "contact semi-major axis a/c_r")
    st = _state(a, mu, _shape(ell, sin_skew_angle(beta0)))
    return LoadCurve(float(mu), float(beta0), float(ell), st["a"], ell * st["a"], st["c"], ell * st["c"],
                     st["v"], st["W"], st["delta"])


def _zero_contact_state(mu, shape):
    s = _zero_contact_s(mu, shape)
    v = mu / (shape.kappa * s)
    w_star = -shape.sin_skew / 3.0 * shape.kappa * shape.beta * v * s**3  # Eq. (36) at a = 0
    delta = -shape.kappa * shape.beta * shape.k_complete * v * s**2
    return dict(a=np.zeros_like(s), c=s, v=v, W=w_star, delta=delta)


def pull_off(mu, beta0, *, control="load", ellipticity=None):
    """Pull-off point of the elliptical DH model, vectorised over ``mu`` and ``beta0``.

    Parameters
    ----------
    mu : array_like
        Tabor parameter, Eq. (35), > 0 [-].
    beta0 : array_like
        Initial ellipticity in (0, 1] [-].
    control : {"load", "displacement"}
        Load control: the minimum of W*(a*) at the end of the stable branch.
        Displacement control: the minimum of delta*(a*).
    ellipticity : array_like, optional
        Ellipticity of both ellipses at pull-off if different from beta0 (the
        paper's beta_(pull-off) = beta_JKR(pull-off) variant); Eq. (34) keeps
        sin(theta_skew) of beta0.

    Returns
    -------
    PullOff
        W_star is W*max of Eq. (34) (negative: tensile), with a*, c*, v, delta* there.
    """
    if control not in ("load", "displacement"):
        raise ValueError(f"control must be 'load' or 'displacement'; got {control!r}")
    mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
    mu, beta0, ell = np.broadcast_arrays(mu, beta0, ell)
    shape = _shape(ell, sin_skew_angle(beta0))
    key = "dW" if control == "load" else "ddelta"
    ex = (lambda q: q[..., None])
    fields = astuple(shape)  # in _Shape's field order
    scan = _state(_SCAN, ex(mu), _Shape(*(ex(f) for f in fields)), derivatives=True)[key]
    # Largest a* where the derivative crosses from negative to positive.
    up = (scan[..., :-1] < 0) & (scan[..., 1:] >= 0)
    has = up.any(axis=-1)
    last = np.where(has, up.shape[-1] - 1 - np.argmax(up[..., ::-1], axis=-1), 0)
    lo, hi = _SCAN[last], _SCAN[last + 1]

    def f(a, mu_, *fields_):
        return _state(a, mu_, _Shape(*fields_), derivatives=True)[key]

    res = {k: np.array(v, dtype=float) for k, v in _zero_contact_state(mu, shape).items()}
    if has.any():
        args = tuple(np.broadcast_to(q, mu.shape)[has] for q in (mu, *fields))
        root = elementwise.find_root(f, (lo[has], hi[has]), args=args,
                                     tolerances=dict(xatol=1e-13, xrtol=1e-13))
        sub = _state(root.x, args[0], _Shape(*args[1:]))
        for k in res:
            res[k][has] = sub[k]
    return PullOff(_scalar(mu), _scalar(beta0), _scalar(ell), control, _scalar(res["W"]),
                   _scalar(res["a"]), _scalar(res["c"]), _scalar(res["v"]), _scalar(res["delta"]),
                   _scalar(~has))
