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
  direct evaluation of Eq. 31 in :mod:`dhfield.models.dh_elliptic_adhesion` and against the circular
  closed form).  With w = S^2 sin^2 t it is evaluated by the graded Gauss rule of
  :func:`dhfield.models.dh_elliptic_adhesion.graded_rule`, with analytic derivatives in S and a.

At a given a* the equation for S is solved by a vectorised, bracketed Newton
iteration in log S (monotone: d log(Delta gamma)/d log S lies between 1 and 3).
The load-controlled pull-off is the largest a* where dW*/da* = 0 (the end of the
stable branch, reached from high load), the displacement-controlled pull-off the
largest a* where d delta*/da* = 0; both derivatives are analytic (implicit
function theorem).  The pull-off search runs in the ratio x = a/S instead of a*
(:func:`_state_at_ratio`): T0 scales as a^-4 at fixed x, so Eqs. (24), (31)
become a quadratic in v with a closed-form root, each state costs one quadrature
and no iteration, and a*(x) is increasing (d log a/d log x >= 1).  The roots are
found with Chandrupatla's bracketing method to 1e-13 in x.  When the
derivative is positive all the way down to a* -> 0 (the DMT side), the pull-off
is the zero-contact limit, which has a closed form (a quadratic in S).

Accepted domain (issue 9): mu in :data:`TABOR_RANGE`, beta0 in
:data:`ELLIPTICITY_RANGE`, a* in :data:`CONTACT_SIZE_RANGE`; anything else is a
ValueError naming the parameter and its range.  The solve works in u = log S and
forms v S^2 = mu S/kappa and c^3 - a^3 = S^2 (c^2 + ca + a^2)/(c + a) directly, so
there is no cancellation as the annulus narrows (c - a ~ mu^-2): the pull-off
tends to the model's own JKR limit (:func:`jkr_limit_pull_off`) as 1/mu^2 and
equals it to ~1e-14 from mu ~ 1e7 up.  The pull-off scan is scaled with the shape
and extended where needed (:func:`dhfield.core.pull_off_search.stable_branch_end`);
states are evaluated in bounded chunks.
"""
from __future__ import annotations

from dataclasses import astuple, dataclass

import numpy as np
from scipy import special

from ..core.validation import (CONTACT_SIZE_RANGE, ELLIPTICITY_RANGE, TABOR_RANGE, check_contact_size_star,
                               check_control, check_count, check_model_ellipticity, check_tabor)
from .dh_elliptic_adhesion import NODES_PER_PANEL, graded_panel_counts, ragged_graded_rule
from ..core.geometry import sin_skew_angle
from ..core.pull_off_search import stable_branch_end
from ..core.records import LoadCurve, PullOff, load_curve_record, pull_off_record

__all__ = ["solve_adhesive_axis", "adhesive_axis_state", "load_curve", "load_curve_nondimensional", "pull_off", "pull_off_nondimensional",
           "jkr_limit_pull_off", "LoadCurve",
           "PullOff", "DEFAULT_A_STAR", "MAX_CURVE_POINTS", "TABOR_RANGE", "ELLIPTICITY_RANGE",
           "CONTACT_SIZE_RANGE"]

#: Default contact semi-major axes of a load curve: covers pull-off (a* <~ 2 for
#: mu <= 20) up to W* ~ 10 at every beta0 in (0.3, 1].
DEFAULT_A_STAR = (0.02, 3.0)
#: Relative tolerance of the Newton solve for S (Delta gamma = 1 to this accuracy).
SOLVE_RTOL = 1e-14
_MAX_NEWTON = 60
#: Contact sizes of the ends of the pull-off scan, relative (they only bound the scan).
_RATIO_RTOL = 1e-6
#: Largest number of points of one load curve (the output alone is ~80 bytes a point).
MAX_CURVE_POINTS = 1_000_000
#: Points per chunk of state evaluations by Newton in S (load curves; the quadrature
#: bounds its own memory, :data:`_NODES_PER_SLICE`).
CHUNK_POINTS = 1024
#: Noise floor of the pull-off derivative, relative to |W*| (|delta*|) at zero contact:
#: the analytic derivative carries ~1e-12 relative rounding noise at a* ~ 1e-5.
DERIVATIVE_FLOOR = 1e-9
#: Pull-off scan: from a* = _SCAN_LOW (times max(1, a_JKR)) to _SCAN_TOP_FACTOR times
#: the JKR-limit pull-off contact a_JKR (see :func:`_pull_off_scan`), geometric in the
#: ratio x = a/S between those ends (:func:`_pull_off_ratio_scan`).
_SCAN_LOW, _SCAN_TOP_FACTOR, _SCAN_POINTS = 1e-4, 8.0, 48
#: Quadrature nodes (states x nodes) per slice of :func:`_axis_integrals`: ~12 work
#: arrays of this size (~6 MB) bound its memory whatever the number of states.
_NODES_PER_SLICE = 1 << 16
#: Working memory of one state of the pull-off search outside the quadrature (~40
#: per-state arrays): sizes its chunks.
_BYTES_PER_STATE = 40 * 8


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


def _slices_by_nodes(t1):
    """Element slices whose graded rules have at most :data:`_NODES_PER_SLICE` nodes together."""
    nodes = np.cumsum((graded_panel_counts(t1) + 1) * NODES_PER_PANEL)  # nodes up to each element
    start = 0
    while start < t1.size:
        before = nodes[start - 1] if start else 0
        stop = max(start + 1, int(np.searchsorted(nodes, before + _NODES_PER_SLICE, side="right")))
        yield slice(start, stop)
        start = stop


def _axis_integrals(a, b, s, with_a=True):
    """T0, T1, Ta of the exchanged Eq. (31) for contact (a, b) and S.

    With w = S^2 sin^2 t and q = (a^2 + S^2 sin^2 t)^{3/2} (b^2 + S^2 sin^2 t)^{1/2}:
    T0 = int cos^4 t / q dt, T1 = int cos^2 t / q dt and
    Ta = d T0/da at fixed S and beta (b = beta a).  S may underflow to 0 (the
    narrow-annulus limit, T0 = 3 pi/(16 a^3 b)).

    Every element gets the panels its own near-singularity scale needs
    (:func:`dhfield.models.dh_elliptic_adhesion.ragged_graded_rule`), so a result does not depend on the other
    elements of the batch; memory is bounded by :data:`_NODES_PER_SLICE`.
    """
    a, b, s = np.broadcast_arrays(*(np.asarray(q, dtype=float) for q in (a, b, s)))
    out_shape = a.shape
    a, b, s = (q.ravel() for q in (a, b, s))
    with np.errstate(divide="ignore"):
        t1 = np.arcsin(np.minimum(1.0, b / s))
    t0, t1_sum = np.empty(a.size), np.empty(a.size)
    ta = np.empty(a.size) if with_a else None
    for sl in _slices_by_nodes(t1):
        t, w, first, owner = ragged_graded_rule(t1[sl])
        ai, bi, si = a[sl][owner, None], b[sl][owner, None], s[sl][owner, None]
        sin2 = np.sin(t) ** 2
        s2 = (si * si) * sin2
        a2s, b2s = ai * ai + s2, bi * bi + s2
        c2 = 1.0 - sin2
        wc2q = w * c2 / (a2s * np.sqrt(a2s * b2s))  # w cos^2 t / q
        t0[sl] = np.add.reduceat(np.einsum("pi,pi->p", wc2q, c2), first)
        t1_sum[sl] = np.add.reduceat(np.sum(wc2q, axis=-1), first)
        if with_a:
            beta2 = (bi / ai) ** 2
            ta[sl] = np.add.reduceat(np.sum(wc2q * c2 * (-3.0 * ai / a2s - (beta2 * ai) / b2s), axis=-1), first)
    t0, t1_sum = t0.reshape(out_shape), t1_sum.reshape(out_shape)
    return t0, t1_sum, (ta.reshape(out_shape) if with_a else None)


def _log_adhesion_terms(a, u, shape, with_a=True):
    """log J (Delta gamma = v (1 + v) J), S dJ/dS / J and dJ/da / J, in log S = u (R = E* = 1).

    J = (Po_cd/c)(Po_ab ab)/(3E*) 2 S^4 T0 (Eq. 31, exchanged order) is formed in logs
    so that neither S^4 nor a^3 under- or overflows.
    """
    kappa, beta = shape.kappa, shape.beta
    t0, t1, ta = _axis_integrals(a, beta * a, np.exp(u), with_a)
    log_j = np.log(2.0 / 3.0 * kappa**2 * beta) + 3.0 * np.log(a) + 4.0 * u + np.log(t0)  # Eq. (31)
    s_js_j = 3.0 * t1 / t0
    ja_j = 3.0 / a + ta / t0 if with_a else None
    return log_j, s_js_j, ja_j


def _zero_contact_log_s(mu, shape):
    """log S, S = c at a = 0: mu S^2 + mu^2 S/kappa - 3 R' = 0 (Eqs. 24, 31 with a -> 0)."""
    p = mu**2 / shape.kappa
    return np.log(6.0 * shape.r_major) - np.log(p + np.sqrt(p * p + 12.0 * mu * shape.r_major))


def _zero_contact_s(mu, shape):
    return np.exp(_zero_contact_log_s(mu, shape))


def _log_residual(a, u, log_mu, shape):
    """log Delta gamma (target 0) and its u-derivative, with log v of Eq. (24)."""
    log_v = log_mu - np.log(shape.kappa) - u  # Eq. (24) with sigma0 = mu
    log_j, s_js_j, _ = _log_adhesion_terms(a, u, shape, with_a=False)
    g = log_v + np.logaddexp(0.0, log_v) + log_j  # log[v (1 + v) J]
    dg = -1.0 - special.expit(log_v) + s_js_j
    scale = np.abs(log_v) + np.abs(log_j) + 1.0
    return g, dg, scale


def _solve_log_s(a, mu, shape):
    """Solve Delta gamma(a, S) = 1 for u = log S, element-wise (bracketed Newton in u)."""
    fields = astuple(shape)
    a, mu, *fields = np.broadcast_arrays(np.asarray(a, float), np.asarray(mu, float), *fields)
    out_shape = a.shape
    a, mu, *fields = (f.ravel() for f in (a, mu, *fields))
    shape = _Shape(*fields)
    log_mu = np.log(mu)
    # Start between the small-contact limit (closed form) and the narrow-annulus
    # estimate S^2 ~ 8a/(pi mu^2); the bracket below makes any start safe.
    u0 = _zero_contact_log_s(mu, shape)
    u1 = 0.5 * np.log(8.0 * a / np.pi) - log_mu
    u = -0.5 * np.logaddexp(-2.0 * u0, -2.0 * u1)  # S^-2 = S0^-2 + S1^-2
    lo = np.full(a.shape, -np.inf)
    hi = np.full(a.shape, np.inf)
    active = np.ones(a.shape, bool)
    eps = np.finfo(float).eps
    for _ in range(_MAX_NEWTON):
        idx = np.nonzero(active)
        sh = _Shape(*(f[idx] for f in fields))
        ui = u[idx]
        g, dg, scale = _log_residual(a[idx], ui, log_mu[idx], sh)
        lo_i = np.where(g < 0, ui, lo[idx])
        hi_i = np.where(g > 0, ui, hi[idx])
        # Converged: residual at the solve tolerance, or at the rounding level of its terms.
        done = (np.abs(g) < SOLVE_RTOL) | (np.abs(g) < 8.0 * eps * scale)
        new = ui + np.clip(-g / dg, -20.0, 20.0)
        # Newton step leaving the bracket: bisect instead.
        bad = ((new <= lo_i) | (new >= hi_i)) & np.isfinite(lo_i) & np.isfinite(hi_i)
        with np.errstate(invalid="ignore"):
            new = np.where(bad, 0.5 * (lo_i + hi_i), new)
        # A bracket collapsed to rounding is converged too.
        done |= (hi_i - lo_i) <= 4.0 * eps * np.maximum(1.0, np.abs(ui))
        lo[idx], hi[idx], u[idx] = lo_i, hi_i, np.where(done, ui, new)
        active[idx] = ~done
        if not active.any():
            break
    else:
        raise RuntimeError("adhesive-axis solve did not converge; please report the inputs")
    return u.reshape(out_shape)


def _solve_s(a, mu, shape):
    """S = sqrt(c^2 - a^2) solving Delta gamma(a, S) = 1 (see :func:`_solve_log_s`)."""
    return np.exp(_solve_log_s(a, mu, shape))


def _state(a, mu, shape, derivatives=False):
    """Full state at contact semi-major axis a (arrays broadcast): S from the Newton solve."""
    u = _solve_log_s(a, mu, shape)
    a, mu = np.broadcast_arrays(np.asarray(a, float), np.asarray(mu, float))
    log_v = np.log(mu) - np.log(shape.kappa) - u  # Eq. (24) with sigma0 = mu
    out = _state_from_solution(a, u, log_v, mu, shape)
    if derivatives:
        _, s_js_j, ja_j = _log_adhesion_terms(a, u, shape)
        g_u = -1.0 - special.expit(log_v) + s_js_j
        u_a = -ja_j / g_u  # implicit function theorem, d(log S)/da
        out.update(_derivatives(a, out, u_a, 1.0, shape))
    return out


def _state_from_solution(a, u, log_v, mu, shape):
    """W*, delta*, c, v of a solved state (a, u = log S, log v).

    Written without cancellation or overflow at large mu: with m = v S^2 = mu S/kappa
    (Eq. 24) and c^3 - a^3 = S^2 (c^2 + ca + a^2)/(c + a), Eq. (36) is
    W* = sin/3 kappa beta [a^3 - m r], r = (c^2 + ca + a^2)/(c + a), and the approach
    (1+v) delta_ab - v delta_cd = kappa beta K (a^2 - m).
    """
    kappa, beta, kk, sn = shape.kappa, shape.beta, shape.k_complete, shape.sin_skew
    s = np.exp(u)
    with np.errstate(over="ignore"):
        v = np.exp(log_v)  # Eq. (24)
    m = np.exp(np.log(mu) + u) / kappa  # v S^2
    c = np.hypot(a, s)
    r = (c * c + c * a + a * a) / (c + a)  # (c^3 - a^3)/S^2
    w_star = sn / 3.0 * kappa * beta * (a**3 - m * r)  # Eq. (36): (1+v) a^3 - v c^3
    delta = kappa * beta * kk * (a * a - m)  # (1+v) delta_ab - v delta_cd, Eq. (14a)
    return dict(a=a, s=s, c=c, v=v, W=w_star, delta=delta, _m=m, _r=r)


def _derivatives(a, st, u_p, a_p, shape):
    """dW*/da and d delta*/da from the derivatives of log S (u_p) and a (a_p) in one parameter p."""
    kappa, beta, kk, sn = shape.kappa, shape.beta, shape.k_complete, shape.sin_skew
    s, c, m, r = st["s"], st["c"], st["_m"], st["_r"]
    m_p = m * u_p
    c_p = (a * a_p + s * s * u_p) / c
    cpa2 = (c + a) ** 2
    r_p = (c * c + 2.0 * c * a) / cpa2 * c_p + (2.0 * c * a + a * a) / cpa2 * a_p
    w_p = sn / 3.0 * kappa * beta * (3.0 * a * a * a_p - m_p * r - m * r_p)  # d/dp of Eq. (36)
    delta_p = kappa * beta * kk * (2.0 * a * a_p - m_p)
    return dict(dW=w_p / a_p, ddelta=delta_p / a_p)


def _state_at_ratio(x, mu, shape, derivatives=False):
    """Full state at the ratio x = a/S of contact semi-axis to S = sqrt(c^2 - a^2), no iteration.

    At fixed x, T0(a, beta a, S) = a^-4 T0(1, beta, 1/x) and Eqs. (24), (31) with
    Delta gamma = 1 become v (1 + v) A a^3 = 1 with v = mu x/(kappa a) and
    A = (2/3) kappa^2 beta x^-4 T0(1, beta, 1/x): in v, Q v^2 = 1 + v with
    Q = (kappa/(mu x))^3 / A, solved in closed form (positive root) and in logs, so
    one quadrature gives the state.  a(x) is increasing (d log a/d log x >= 1,
    because T1 >= T0), so the search for the pull-off can run in x.
    """
    x, mu = np.broadcast_arrays(np.asarray(x, float), np.asarray(mu, float))
    kappa, beta = shape.kappa, shape.beta
    log_x = np.log(x)
    log_mu = np.log(mu)
    t0, t1, _ = _axis_integrals(1.0, beta, np.exp(-log_x), with_a=False)
    log_big_a = np.log(2.0 / 3.0 * kappa**2 * beta) - 4.0 * log_x + np.log(t0)  # log A, Eq. (31)
    log_q = 3.0 * (np.log(kappa) - log_mu - log_x) - log_big_a
    # Positive root of Q v^2 - v - 1 = 0 in logs: v = y (y + sqrt(y^2 + 4))/2 with y = Q^-1/2
    # for Q >= 1, v = (1 + sqrt(1 + 4Q))/(2Q) for Q < 1.
    big = log_q >= 0.0
    y = np.exp(-0.5 * np.where(big, log_q, 0.0))
    q = np.exp(np.where(big, 0.0, log_q))
    log_v = np.where(big, np.log(y) + np.log(0.5 * (y + np.sqrt(y * y + 4.0))),
                     -log_q + np.log(0.5 * (1.0 + np.sqrt(1.0 + 4.0 * q))))
    u = log_mu - np.log(kappa) - log_v  # log S, Eq. (24) with sigma0 = mu
    a = np.exp(u + log_x)
    out = _state_from_solution(a, u, log_v, mu, shape)
    if derivatives:
        # d/d log x: d log A = -3 T1/T0 (S dJ/dS = 3 J T1/T0, see _log_adhesion_terms),
        # d log Q = -3 - d log A >= 0 (T1 >= T0), d log v = -(1 + v)/(2 + v) d log Q;
        # then u = log S = log(mu/kappa) - log v and log a = u + log x.
        dlog_q = -3.0 + 3.0 * t1 / t0
        frac = 1.0 - special.expit(-np.logaddexp(0.0, log_v))  # (1 + v)/(2 + v)
        u_x = frac * dlog_q
        out.update(_derivatives(a, out, u_x, a * (u_x + 1.0), shape))
        out["_dlog_a"] = u_x + 1.0  # d log a/d log x >= 1
    return out


def _check_inputs(mu, beta0, ellipticity):
    mu = check_tabor("mu", mu)
    beta0 = check_model_ellipticity("beta0", beta0)
    if ellipticity is None:
        ell = beta0  # Eq. (9), Eq. (19): beta = beta_(pull-off) = beta0
    else:
        ell = check_model_ellipticity("ellipticity", ellipticity)
    return mu, beta0, ell


def _state_chunked(a, mu, shape, derivatives=False):
    """:func:`_state` over broadcast inputs, evaluated in chunks of :data:`CHUNK_POINTS`.

    Each state carries a quadrature axis of up to ~1000 nodes: chunks bound the
    working memory (~100 MB) whatever the number of points.
    """
    fields = astuple(shape)
    a, mu, *fields = np.broadcast_arrays(np.asarray(a, float), np.asarray(mu, float), *fields)
    out_shape = a.shape
    a, mu, *fields = (np.ravel(f) for f in (a, mu, *fields))
    keys = ("a", "s", "c", "v", "W", "delta") + (("dW", "ddelta") if derivatives else ())
    out = {k: np.empty(a.size) for k in keys}
    for i in range(0, a.size, CHUNK_POINTS):
        sl = slice(i, i + CHUNK_POINTS)
        st = _state(a[sl], mu[sl], _Shape(*(f[sl] for f in fields)), derivatives)
        for k in keys:
            out[k][sl] = st[k]
    return {k: v.reshape(out_shape) for k, v in out.items()}


def solve_adhesive_axis(a_star, *, beta0, mu, ellipticity=None):
    """Solve Eqs. (24), (31), (35) for the adhesive semi-axis c* and the factor v.

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axis a* = a/c_r in :data:`CONTACT_SIZE_RANGE` [-].
    beta0 : array_like
        Initial (Hertz) ellipticity in :data:`ELLIPTICITY_RANGE` [-].
    mu : array_like
        Tabor parameter, Eq. (35), in :data:`TABOR_RANGE` [-].
    ellipticity : array_like, optional
        Ellipticity of both ellipses if different from beta0 (see :func:`pull_off`).

    Returns
    -------
    c_star : ndarray
        Adhesive semi-major axis [-].  Empty inputs give empty outputs; masked
        arrays are rejected.
    v : ndarray
        DH scaling factor [-].
    """
    a = check_contact_size_star("a_star", a_star)
    mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
    return adhesive_axis_state(a, beta0, mu, ellipticity=ell)


def adhesive_axis_state(a_star, beta0, mu, *, ellipticity=None):
    """Solve for (c*, v) like :func:`solve_adhesive_axis`, inputs not validated.

    For callers that validated ``a_star``, ``beta0``, ``mu`` (float arrays) once and solve
    many states (the closures' pull-off searches).

    Parameters
    ----------
    a_star : ndarray
        Contact semi-major axis a* = a/c_r [-].
    beta0 : ndarray
        Initial (Hertz) ellipticity [-].
    mu : ndarray
        Tabor parameter, Eq. (35) [-].
    ellipticity : ndarray, optional
        Ellipticity of both ellipses if different from beta0.

    Returns
    -------
    c_star : ndarray
        Adhesive semi-major axis [-].
    v : ndarray
        DH scaling factor [-].
    """
    ell = beta0 if ellipticity is None else ellipticity
    st = _state_chunked(a_star, mu, _shape(ell, sin_skew_angle(beta0, checked=False)))
    return _scalar(st["c"]), _scalar(st["v"])


def _scalar(x):
    x = np.asarray(x)
    return x[()] if x.ndim == 0 else x


def load_curve(*, beta0, mu, a_star=None, ellipticity=None, n=200, checked=True):
    """Load curve of the elliptical DH model at Tabor parameter ``mu`` and ellipticity ``beta0``.

    Parameters
    ----------
    beta0 : float
        Initial ellipticity beta0 = b/a (Eq. 9) in :data:`ELLIPTICITY_RANGE` [-].
    mu : float
        Tabor parameter, Eq. (35), in :data:`TABOR_RANGE` [-].
    a_star : array_like, optional
        Contact semi-major axes a* in :data:`CONTACT_SIZE_RANGE` [-], at most
        :data:`MAX_CURVE_POINTS` of them; default ``n`` points evenly spaced over
        :data:`DEFAULT_A_STAR`.  An empty array gives an empty curve; masked
        arrays are rejected (the mask would be lost).
    ellipticity : float, optional
        Ellipticity of both ellipses if it differs from beta0; the normalisation of
        Eq. (34) keeps sin(theta_skew) of beta0.
    n : int
        Number of points of the default a* grid, an integer in [2, :data:`MAX_CURVE_POINTS`].
    checked : bool, default True
        Validate ``beta0``, ``mu`` and ``a_star``; False for a caller that validated them
        once at its public entry (:func:`dhfield.analysis.compare.load_curve`: scalars, ``a_star`` given).

    Returns
    -------
    dhfield.core.records.LoadCurve
        The curve, nondimensional (Eqs. 32-36): model ``dh-elliptic``, and ``ellipticity``,
        the ellipticity of both ellipses (beta0 unless given), after the arrays.
    """
    if not checked:
        a = np.asarray(a_star, dtype=float)
        ell = beta0 if ellipticity is None else ellipticity
    else:
        mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
        for name, val in (("mu", mu), ("beta0", beta0), ("ellipticity", ell)):
            if np.ndim(val) != 0:
                raise ValueError(f"{name} must be a scalar for a load curve; got an array of shape {np.shape(val)}")
        if a_star is None:
            n = check_count("n", n, 2, MAX_CURVE_POINTS, "number of curve points")
            a_star = np.linspace(*DEFAULT_A_STAR, n)
        a = check_contact_size_star("a_star", a_star)
        if a.size > MAX_CURVE_POINTS:
            raise ValueError(f"a_star must have at most {MAX_CURVE_POINTS} points (MAX_CURVE_POINTS); "
                             f"got {a.size}")
    sin_skew = sin_skew_angle(beta0, checked=False)
    st = _state_chunked(a, mu, _shape(ell, sin_skew))
    arrays = {"a_star": st["a"], "b_star": ell * st["a"], "c_star": st["c"], "d_star": ell * st["c"], "v": st["v"],
              "W_star": st["W"], "delta_star": st["delta"]}
    return load_curve_record("dh-elliptic", beta0, mu, arrays, sin_skew=sin_skew, geometry="ellipse",
                             ellipticity=ell)


def load_curve_nondimensional(a_star, *, beta0, mu, ellipticity=None, derivatives=False):
    """Elliptical DH states at contact semi-major axes a*, vectorised, with their slopes.

    The nondimensional core of :func:`load_curve` (paper units, R = E* = dgamma = 1):
    unlike it, ``mu`` and ``beta0`` broadcast with ``a_star``, and the exact
    derivatives along the curve are available.

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axes a* in :data:`CONTACT_SIZE_RANGE` [-].
    beta0 : array_like
        Initial ellipticity (Eq. 9) in :data:`ELLIPTICITY_RANGE` [-].
    mu : array_like
        Tabor parameter, Eq. (35), in :data:`TABOR_RANGE` [-].
    ellipticity : array_like, optional
        Ellipticity of both ellipses if it differs from beta0 (Eq. 34 keeps
        sin(theta_skew) of beta0).
    derivatives : bool, default False
        Also return ``dW`` = dW*/da* and ``ddelta`` = d delta*/da* (implicit
        differentiation of Eq. 31 at fixed mu) as ``dW_star``, ``ddelta_star``.

    Returns
    -------
    dict
        ``a_star``, ``c_star``, ``v`` (scaling, Eq. 24), ``W_star`` (Eq. 36),
        ``delta_star`` [-], and with ``derivatives`` ``dW_star`` and
        ``ddelta_star``; arrays of the broadcast shape.

    Notes
    -----
    S = sqrt(c^2 - a^2) solves Delta gamma(a, S) = 1 (Eq. 31 with v of Eq. 24 at
    sigma0 = mu) by a bracketed Newton iteration in log S; W* from Eq. (36).
    """
    mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
    a = check_contact_size_star("a_star", a_star)
    a, mu, beta0, ell = np.broadcast_arrays(a, mu, beta0, ell)
    st = _state_chunked(a, mu, _shape(ell, sin_skew_angle(beta0, checked=False)), derivatives)
    names = dict(a="a_star", c="c_star", v="v", W="W_star", delta="delta_star", dW="dW_star", ddelta="ddelta_star")
    return {names[k]: val for k, val in st.items() if k in names}


def _zero_contact_state(mu, shape):
    s = _zero_contact_s(mu, shape)
    v = mu / (shape.kappa * s)  # Eq. (24) at a = 0
    m = mu * s / shape.kappa  # v S^2
    w_star = -shape.sin_skew / 3.0 * shape.kappa * shape.beta * m * s  # Eq. (36) at a = 0
    delta = -shape.kappa * shape.beta * shape.k_complete * m
    return dict(a=np.zeros_like(s), c=s, v=v, W=w_star, delta=delta)


def jkr_limit_pull_off(beta0, *, control="load", ellipticity=None):
    """Compute the pull-off of the elliptical DH model in its JKR limit mu -> infinity (derived here).

    Parameters
    ----------
    beta0 : array_like
        Initial ellipticity in :data:`ELLIPTICITY_RANGE` [-].
    control : {"load", "displacement"}
        Loading mode of the pull-off.
    ellipticity : array_like, optional
        Ellipticity of both ellipses if different from beta0 (as in :func:`pull_off`).

    Returns
    -------
    W_star : ndarray
        Pull-off load W* (Eq. 34) [-].
    a_star : ndarray
        Contact semi-major axis a* at pull-off [-].

    Notes
    -----
    As mu -> infinity the annulus narrows, S^2 = c^2 - a^2 -> 8a/(pi mu^2) (Eqs. 24,
    31 with T0 -> 3 pi/(16 a^3 b)), and v S^2 = mu S/kappa -> sqrt(8a/pi)/kappa, so
    Eq. (36) tends to

    .. math::

        W^*_\\infty(a) = \\beta\\sin\\theta_{skew}\\left[\\frac{\\kappa a^3}{3}
                         - \\sqrt{\\frac{2}{\\pi}}\\,a^{3/2}\\right],
        \\qquad \\kappa = Po_{ab}/a \\ \\text{(Eq. 8)},

    with minimum W* = -3 beta sin(theta_skew)/(2 pi kappa) at
    a^{3/2} = (3/(2 kappa)) sqrt(2/pi) (load control), and the approach
    delta_inf = beta K(k) (kappa a^2 - sqrt(8a/pi)) with minimum at a third of that
    a^{3/2}, W* = -5 beta sin(theta_skew)/(6 pi kappa) (displacement control).  At
    beta = 1 (kappa = 2/pi) these are JKR's -3/4 and -5/12.  For beta < 1 this is
    *not* elliptical JKR (Johnson & Greenwood 2005): the DH ellipses keep beta0 and
    the Griffith condition holds on the major axis only.  The finite-mu pull-off
    approaches it as 1/mu^2 (relative 1.4e-5 at mu = 100, beta0 = 1).
    """
    check_control(control)
    beta0 = check_model_ellipticity("beta0", beta0)
    ell = beta0 if ellipticity is None else check_model_ellipticity("ellipticity", ellipticity)
    sh = _shape(ell, sin_skew_angle(beta0))
    k = 3.0 if control == "load" else 1.0
    a32 = k / (2.0 * sh.kappa) * np.sqrt(2.0 / np.pi)
    w_star = sh.sin_skew * sh.beta * (sh.kappa * a32**2 / 3.0 - np.sqrt(2.0 / np.pi) * a32)
    return _scalar(w_star), _scalar(np.cbrt(a32 * a32))


def _pull_off_scan(shape):
    """Per-problem scan of a* for the pull-off search, scaled with the ellipse shape.

    From a* = :data:`_SCAN_LOW` to :data:`_SCAN_TOP_FACTOR` times the JKR-limit
    pull-off contact (3 sqrt(2/pi)/(2 kappa))^(2/3); the search extends it where the
    derivative is still negative at the top (small beta0 at mu ~ 1-100 pulls off
    at up to ~6 times the JKR-limit contact).
    """
    a_jkr = np.cbrt((1.5 / shape.kappa * np.sqrt(2.0 / np.pi)) ** 2)
    unit = np.geomspace(1.0, _SCAN_TOP_FACTOR / _SCAN_LOW, _SCAN_POINTS)
    return _SCAN_LOW * np.maximum(a_jkr, 1.0)[..., None] * unit


def _ratio_at(a, mu, shape):
    """The ratio x = a/S of the state of contact size a: Newton in log x on log a(x).

    Starts from the larger of the zero-contact S and the narrow-annulus estimate
    S^2 = 8a/(pi mu^2) (about 2 steps on average over the accepted domain, 5 at
    most) and uses d log a/d log x >= 1 of :func:`_state_at_ratio` (one quadrature
    a step); a(x) matches a to :data:`_RATIO_RTOL`.
    """
    log_a = np.log(a)
    u0 = _zero_contact_log_s(mu, shape)
    u1 = 0.5 * np.log(8.0 * a / np.pi) - np.log(mu)
    log_x = log_a - np.maximum(u0, u1)
    active = np.ones(log_x.shape, bool)
    for _ in range(_MAX_NEWTON):
        idx = np.nonzero(active)
        st = _state_at_ratio(np.exp(log_x[idx]), mu[idx], _Shape(*(f[idx] for f in astuple(shape))),
                             derivatives=True)
        err = np.log(st["a"]) - log_a[idx]
        log_x[idx] -= err / st["_dlog_a"]
        active[idx] = np.abs(err) > _RATIO_RTOL
        if not active.any():
            return np.exp(log_x)
    raise RuntimeError("pull-off scan: the contact size did not converge in the ratio; please report the inputs")


def _pull_off_ratio_scan(mu, shape):
    """The scan of :func:`_pull_off_scan` in the ratio x = a/S (geometric between its ends).

    Only the two ends are solved for x (:func:`_ratio_at`); x(a) is increasing, so the
    scan covers the same contact sizes and the search can run in x, where a state
    needs one quadrature and no iteration (:func:`_state_at_ratio`).
    """
    ends = _pull_off_scan(shape)[..., [0, -1]]
    x_ends = _ratio_at(ends, np.broadcast_to(mu[..., None], ends.shape),
                       _Shape(*(np.broadcast_to(f[..., None], ends.shape) for f in astuple(shape))))
    unit = np.linspace(0.0, 1.0, _SCAN_POINTS)
    return x_ends[..., :1] * (x_ends[..., 1:] / x_ends[..., :1]) ** unit


def pull_off(*, beta0, mu, control="load", ellipticity=None):
    """Pull-off point of the elliptical DH model, vectorised over ``mu`` and ``beta0``.

    Parameters
    ----------
    beta0 : array_like
        Initial ellipticity in :data:`ELLIPTICITY_RANGE` [-].
    mu : array_like
        Tabor parameter, Eq. (35), in :data:`TABOR_RANGE` [-].
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
        The record of every analytic model (:class:`dhfield.core.records.PullOff`, model
        ``"dh-elliptic"``): W_star is W*max of Eq. (34) (negative: tensile), with a*, b*,
        c*, d*, v, delta* there; ``ellipticity`` is that of both ellipses; ``warning`` is
        empty (the validity policy is :func:`dhfield.analysis.compare.pull_off`'s).  Empty inputs
        give empty results; masked arrays are rejected.

    Notes
    -----
    The end of the stable branch is found by :func:`dhfield.core.pull_off_search.stable_branch_end`
    (a scan covering a* from 1e-4 max(1, a_JKR) to 8 a_JKR, walked from its top,
    then Chandrupatla's method on the analytic derivative), in the ratio
    x = a/S of the contact semi-axis to S = sqrt(c^2 - a^2), where a state needs
    one quadrature and no Newton solve.  Every problem has its own quadrature
    panels, scan and root, so a result does not depend on the other inputs of the
    call (bit for bit); memory stays bounded (a 200 x 200 map takes < 1 GiB).
    Where the load-controlled minimum is very flat (the DMT side, mu <~ 0.1,
    |W*|/(W*'' a*^2) up to ~1e11) a* is fixed only to the derivative's rounding
    noise over the curvature, ~1e-4 relative, while W* holds to ~1e-13.  The derivative is trusted only above a noise floor
    :data:`DERIVATIVE_FLOOR` times |W*(a* = 0)| (for delta*: |delta*(0)|): below it,
    W* is flat to ~1e-15 and the pull-off is the zero-contact limit.
    """
    check_control(control)
    mu, beta0, ell = _check_inputs(mu, beta0, ellipticity)
    return pull_off_nondimensional(beta0, mu, control=control, ellipticity=ell)


def pull_off_nondimensional(beta0, mu, *, control="load", ellipticity=None):
    """The core of :func:`pull_off`, inputs not validated (:func:`dhfield.analysis.compare.pull_off` does).

    Parameters
    ----------
    beta0, mu : array_like
        Initial ellipticity and Tabor parameter (Eq. 35) [-], float arrays.
    control : {"load", "displacement"}
    ellipticity : array_like, optional
        As in :func:`pull_off` (default beta0).

    Returns
    -------
    PullOff
        As :func:`pull_off`.
    """
    ell = beta0 if ellipticity is None else ellipticity
    mu, beta0, ell = np.broadcast_arrays(mu, beta0, ell)
    out_shape = mu.shape
    mu, beta0, ell = (np.ravel(q) for q in (mu, beta0, ell))
    shape = _shape(ell, sin_skew_angle(beta0, checked=False))
    key = "dW" if control == "load" else "ddelta"
    fields = astuple(shape)  # in _Shape's field order
    zero = _zero_contact_state(mu, shape)
    floor = DERIVATIVE_FLOOR * np.abs(zero["W"] if control == "load" else zero["delta"])

    def deriv(x, mu_, *fields_):
        return _state_at_ratio(x, mu_, _Shape(*fields_), derivatives=True)[key]

    end = stable_branch_end(deriv, _pull_off_ratio_scan(mu, shape), (mu, *fields), floor=floor,
                            bytes_per_state=_BYTES_PER_STATE)
    has = end.found
    res = {k: np.array(v, dtype=float) for k, v in zero.items()}
    if has.any():
        sub = _state_at_ratio(end.x[has], mu[has], _Shape(*(f[has] for f in fields)))
        for k in res:
            res[k][has] = sub[k]

    def out(x):
        return _scalar(np.reshape(x, out_shape))

    a, c = out(res["a"]), out(res["c"])
    state = {"W_star": out(res["W"]), "a_star": a, "b_star": a * out(ell), "c_star": c, "d_star": c * out(ell),
             "v": out(res["v"]), "delta_star": out(res["delta"]), "ellipticity": out(ell), "at_zero_contact": out(~has)}
    return pull_off_record("dh-elliptic", out(beta0), out(mu), state, control=control,
                           sin_skew=out(shape.sin_skew), geometry="ellipse")
