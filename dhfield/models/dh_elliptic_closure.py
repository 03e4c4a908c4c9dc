"""The equal-beta test and alternative closures of the elliptical DH model.

The paper closes the model with two assumptions: both ellipses share one fixed
ellipticity (Eqs. 17-19), and the work of adhesion is imposed on the major axis
only (Eq. 31).  With equal ellipticity the maximum adhesive stress is the same on
every ray, but the work of adhesion along a ray, Delta gamma(theta_p), is not
(:mod:`dhfield.models.dh_elliptic_periphery`): the fields do not realise one cohesive law.

This module

* quantifies the spread across theta_p of Delta gamma and of the sigma-h curves,
  as a function of beta0 and mu (:func:`equal_beta_spread`, :func:`law_spread`);
* implements two alternative closures and their pull-off points:

  - **ray average** (:func:`solve_ray_average`, :func:`pull_off_ray_average`):
    equal ellipticity as in the paper, but Delta gamma = 1 imposed on the
    periphery average (weights r_ab^2 d theta_p by default, see
    :func:`dhfield.models.dh_elliptic_periphery.ray_average`) instead of on theta_p = 0;
  - **two axes** (:func:`solve_two_axis`, :func:`pull_off_two_axis`): Delta
    gamma = 1 on both axes, theta_p = 0 and pi/2, with beta_cd != beta_ab and the
    contact condition kept exactly.

Two-axis closure: what the contact condition requires
-------------------------------------------------------
The pressure is p = A S_ab - B S_cd, S the unit semi-ellipsoids on the contact
ellipse (a, b) and the adhesive ellipse (c, d).  Inside the contact ellipse each
S gives a displacement L - M x^2 - N y^2 (Eqs. 13-14, B4-B6), so h = 0 there
(h = z - delta + omega, Eq. 27) holds for all x, y iff the curvatures match
Eq. (2):

.. math::

    A\\,ab\\,I_2^{ab}(0) - B\\,cd\\,I_2^{cd}(0) = E^*/R', \\qquad
    A\\,ab\\,I_3^{ab}(0) - B\\,cd\\,I_3^{cd}(0) = E^*/R'',

and delta = (A ab I1_ab(0) - B cd I1_cd(0))/(2E*).  A single Hertz field has
I3/I2 = rho(beta), the curvature ratio of its own ellipticity (Eqs. 8, 14), so the
two conditions say

.. math::

    A\\,ab\\,I_2^{ab}\\,[\\rho(\\beta_{ab}) - \\rho_0] = B\\,cd\\,I_2^{cd}\\,[\\rho(\\beta_{cd}) - \\rho_0],
    \\qquad \\rho_0 = R'/R'' = \\rho(\\beta_0).

With equal ellipticities the two rows are dependent (both fields have ratio
rho0 iff beta = beta0) and v = B/Po_cd is free, to be fixed by sigma0; that is
the paper's model.  With beta_cd != beta_ab they fix A and B, and since
A ab I2_ab > B cd I2_cd > 0, beta_ab and beta_cd lie on the *same* side of beta0,
the adhesive ellipse further from it: the contact ellipse is no longer the Hertz
ellipse of the geometry.  Here (B, c, d) are the unknowns; the ratio condition
gives beta_ab = rho^{-1}[(E*/R'' + B cd I3_cd)/(E*/R' + B cd I2_cd)], the first
condition A.  Then sigma0 = B sqrt(1 - a^2/c^2) = mu on the major axis (Eq. 24)
and Delta gamma(0) = Delta gamma(pi/2) = 1 (Eq. 31 on both axes) close the model
at each a.  The gap in the annulus is (A/E*) g(x, y; a, b) and the adhesive stress
B sqrt(1 - x^2/c^2 - y^2/d^2) (:mod:`dhfield.models.dh_elliptic_periphery`).  The load is
W = (2 pi/3)(A ab - B cd) (Eq. 25), reported as W* = W sin(theta_skew)/(2 pi R Delta gamma)
with theta_skew of beta0 (Eq. 34).

Units: nondimensional throughout, R = E* = Delta gamma = 1 (Eqs. 32-35), so
sigma0 = mu, R' = sqrt(rho0), R'' = 1/sqrt(rho0).
"""
from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
from scipy.optimize import elementwise

from . import hertz, dh_elliptic, dh_elliptic_periphery
from ..core.validation import as_circle, check_contact_size_star, check_control, check_interval
from ..core.elliptic import ellipsoid_integrals
from ..core.geometry import ellipticity_from_radius_ratio, radius_ratio, sin_skew_angle
from ..core.pull_off_search import last_local_minimum
from ..core.records import pull_off_record

__all__ = [
    "CLOSURES",
    "CLOSURE_MU_RANGE",
    "CLOSURE_BETA0_RANGE",
    "EqualBetaSpread",
    "ClosureState",
    "law_spread",
    "rays_for",
    "equal_beta_spread",
    "solve_ray_average",
    "solve_two_axis",
    "pull_off_ray_average",
    "pull_off_two_axis",
    "pull_off_closure",
    "state_at_pull_off",
    "MODEL_NAMES",
]

CLOSURES = ("paper", "ray_average", "two_axis")
#: Accepted Tabor parameter of the closures.  Above mu ~ 50 the two-axis Newton solve
#: in (log c, log d) fails (the annulus, ~mu^-2 wide, is below its finite-difference
#: step); 30 is the largest value verified for beta0 in {0.3, 0.35, 0.48, 0.6, 0.8, 0.9,
#: 0.99, 1} and both controls (two-axis and ray-average; the solves also converge at 50).
#: It covers the PDMS example of the README (mu = 21.65).  At mu = 30 the closures are
#: within ~1e-4 of their JKR limits.
CLOSURE_MU_RANGE = (1e-6, 30.0)
#: Accepted beta0 of the closures: the periphery averages need 1 + 4 ceil(3/beta0) rays
#: (120 001 at 1e-4, out of memory), and the ray-average load-control search returns
#: a spurious zero-contact minimum at beta0 <= 0.1 (mu = 50); verified down to 0.3.
CLOSURE_BETA0_RANGE = (0.3, 1.0)
#: Rays for spreads and averages (uniform; trapezoid is spectral for these even integrands).
N_THETA = 31
#: Relative tolerance of the closure solves (log Delta gamma residual).
SOLVE_TOL = 1e-12
#: Contact sizes scanned to bracket the load-controlled pull-off (minimum of W*).
_SCAN = np.geomspace(2e-3, 4.0, 40)
#: Contact size that stands for the zero-contact limit a* -> 0 (DMT side): the
#: closures' W*, delta* differ from their a* = 0 limits by O(a*^2) ~ 1e-12 there.
A_ZERO = 1e-6
#: Relative step of the finite-difference Jacobian of the two-axis Newton solve.
_FD_STEP = 1e-7
_MAX_NEWTON = 40


# --------------------------------------------------------------------------- containers
@dataclass(frozen=True)
class EqualBetaSpread:
    """How far the equal-beta DH fields are from one cohesive law around the periphery.

    Every field is an array over the broadcast inputs.

    Parameters
    ----------
    work_ratio : ndarray
        Delta gamma(pi/2)/Delta gamma(0) [-].
    work_spread : ndarray
        (max - min)/mean of Delta gamma(theta_p) over theta_p [-].
    mean_work : ndarray
        Periphery average of Delta gamma, weights r_ab^2 [units of Delta gamma].
    law_spread : ndarray
        Max over theta_p of int |sigma_theta(h) - sigma_0(h)| dh / Delta gamma(0) [-].
    law_sup_spread : ndarray
        Max over theta_p and h of |sigma_theta(h) - sigma_0(h)| / sigma0 [-].
    separation_ratio : ndarray
        Edge separation h(r_cd) on the minor axis / on the major axis [-].
    width_ratio : ndarray
        (r_cd - r_ab) on the minor axis / on the major axis [-].
    """

    work_ratio: np.ndarray
    work_spread: np.ndarray
    mean_work: np.ndarray
    law_spread: np.ndarray
    law_sup_spread: np.ndarray
    separation_ratio: np.ndarray
    width_ratio: np.ndarray

    def as_dict(self):
        """Return the fields as a dict.

        Returns
        -------
        dict
            ``{field name: array}``.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class ClosureState:
    """An equilibrium state of a closure (nondimensional, R = E* = Delta gamma = 1).

    Parameters
    ----------
    closure : str
        "paper", "ray_average" or "two_axis".
    mu, beta0 : ndarray
        Tabor parameter (Eq. 35) and the geometry's Hertz ellipticity [-].
    a_star, b_star, c_star, d_star : ndarray
        Semi-axes of the contact and adhesive ellipses, in c_r (Eq. 33) [-].
    contact_amplitude, adhesive_amplitude : ndarray
        A and B of p = A S_ab - B S_cd, in E* c_r/R [-].
    W_star : ndarray
        Load W sin(theta_skew)/(2 pi R Delta gamma) (Eq. 34) [-].
    delta_star : ndarray
        Approach, in c_r^2/R [-].
    work_major, work_minor : ndarray
        Delta gamma(0) and Delta gamma(pi/2), in Delta gamma [-].
    sigma0_major, sigma0_minor : ndarray
        Adhesive stress at the contact edge on the two axes, in E* c_r/R [-].

    Notes
    -----
    The state type of the closure solves (:func:`solve_two_axis`, :func:`solve_ray_average`,
    :func:`state_at_pull_off`), not a pull-off record: the pull-off is
    :func:`pull_off_closure`'s :class:`dhfield.core.records.PullOff`.
    """

    closure: str
    mu: np.ndarray
    beta0: np.ndarray
    a_star: np.ndarray
    b_star: np.ndarray
    c_star: np.ndarray
    d_star: np.ndarray
    contact_amplitude: np.ndarray
    adhesive_amplitude: np.ndarray
    W_star: np.ndarray
    delta_star: np.ndarray
    work_major: np.ndarray
    work_minor: np.ndarray
    sigma0_major: np.ndarray
    sigma0_minor: np.ndarray

    @property
    def beta_contact(self):
        """Ellipticity of the contact ellipse b/a [-]."""
        return self.b_star / self.a_star

    @property
    def beta_adhesive(self):
        """Ellipticity of the adhesive ellipse d/c [-]."""
        return self.d_star / self.c_star

    def as_dict(self):
        """Return the fields and the two ellipticities as a dict.

        Returns
        -------
        dict
            ``{name: array}``, with ``beta_contact`` and ``beta_adhesive`` added.
        """
        out = {f.name: getattr(self, f.name) for f in fields(self)}
        out["beta_contact"] = self.beta_contact
        out["beta_adhesive"] = self.beta_adhesive
        return out


# --------------------------------------------------------------------------- the equal-beta test
def law_spread(law, norm="l1"):
    """Measure the distance between the sigma-h curves of all rays and that of the first ray.

    Parameters
    ----------
    law : dhfield.models.dh_elliptic_periphery.CohesiveLaw
        Curves with the theta axis second-to-last; the first ray is the reference
        (theta_p = 0 by convention).  sigma = 0 beyond each ray's edge separation.
    norm : {"l1", "sup"}
        ``"l1"``: max over rays of int |sigma_theta(h) - sigma_0(h)| dh, relative to
        the reference's area int sigma_0 dh = Delta gamma(0).  ``"sup"``: max over
        rays and h of |sigma_theta(h) - sigma_0(h)|, relative to sigma_0(h = 0);
        dominated by the square-root drop of sigma near the edge separation, where
        a relative shift eps of the edge separation costs ~sqrt(eps).

    Returns
    -------
    ndarray
        The relative distance, shape of the state [-].
    """
    if norm not in ("l1", "sup"):
        raise ValueError(f"norm must be 'l1' or 'sup'; got {norm!r}")
    h, s = np.asarray(law.separation), np.asarray(law.stress)
    lead = h.shape[:-2]
    hf = h.reshape((-1,) + h.shape[-2:])
    sf = s.reshape((-1,) + s.shape[-2:])
    out = np.empty(hf.shape[0])
    for k in range(hf.shape[0]):
        grid = np.unique(np.concatenate([hf[k].ravel(), np.linspace(0.0, hf[k].max(), 4001)]))
        ref = np.interp(grid, hf[k, 0], sf[k, 0], right=0.0)
        dev = 0.0
        for j in range(1, hf.shape[1]):
            diff = np.abs(np.interp(grid, hf[k, j], sf[k, j], right=0.0) - ref)
            dev = max(dev, float(np.max(diff) if norm == "sup" else np.trapezoid(diff, grid)))
        out[k] = dev / (sf[k, 0, 0] if norm == "sup" else np.trapezoid(ref, grid))
    return out.reshape(lead) if lead else out[0]


def rays_for(beta):
    """Return the number of uniform rays on [0, pi/2] for periphery averages: 1 + 4 ceil(3/beta).

    The integrands are even about both axes, so the trapezoidal rule converges
    geometrically, more slowly as beta falls (17 rays: 1e-14 at beta = 0.8; 41 rays:
    ~1e-9 at beta = 0.3 with a wide zone, ~1e-6 with a very narrow one).

    Parameters
    ----------
    beta : array_like
        Ellipticities [-]; the smallest one sets the count.

    Returns
    -------
    int
        The number of rays.
    """
    return int(1 + 4 * np.ceil(3.0 / np.min(np.asarray(beta, float))))


def _spread_from_state(a, c, beta, v, n_theta=N_THETA, n_law=129):
    th = np.linspace(0.0, 0.5 * np.pi, int(n_theta))
    prof = dh_elliptic_periphery.periphery(a, c, beta, v, th)
    w = prof.work_of_adhesion
    law = dh_elliptic_periphery.cohesive_law(a, c, beta, v, th, n_points=n_law)
    return EqualBetaSpread(
        work_ratio=w[..., -1] / w[..., 0],
        work_spread=(w.max(axis=-1) - w.min(axis=-1)) / np.mean(w, axis=-1),
        mean_work=dh_elliptic_periphery.ray_average(w, th, prof.contact_radius, "area"),
        law_spread=law_spread(law),
        law_sup_spread=law_spread(law, "sup"),
        separation_ratio=prof.edge_separation[..., -1] / prof.edge_separation[..., 0],
        width_ratio=prof.zone_width[..., -1] / prof.zone_width[..., 0],
    )


def equal_beta_spread(*, beta0, mu, control="load", n_theta=N_THETA):
    """Run the equal-beta test at the pull-off point of the paper's model.

    Parameters
    ----------
    beta0 : array_like
        Ellipticity (Eqs. 17-19) [-]; broadcast against ``mu``.
    mu : array_like
        Tabor parameter, Eq. (35) [-].
    control : {"load", "displacement"}
        Pull-off control mode.
    n_theta : int
        Rays on [0, pi/2].

    Returns
    -------
    EqualBetaSpread
        With Delta gamma(0) = 1 (Eq. 31) at pull-off, ``work_ratio`` is
        Delta gamma(pi/2) itself.
    """
    po = dh_elliptic.pull_off(mu=mu, beta0=beta0, control=control)
    a = np.where(np.asarray(po.a_star) > 0, po.a_star, 1e-9 * np.asarray(po.c_star))
    return _spread_from_state(a, po.c_star, po.ellipticity, po.v, n_theta)


# --------------------------------------------------------------------------- shared pieces
def _geometry(beta0):
    """R', R'' (R = 1) and the Eq. (34) factor of a validated beta0 (not checked again: the solves call it often)."""
    rho0 = radius_ratio(beta0, checked=False)
    return np.sqrt(rho0), 1.0 / np.sqrt(rho0), sin_skew_angle(beta0, checked=False)


def _two_field_state(closure, mu, beta0, a, b, c, d, amp_a, amp_b):
    """ClosureState from the two-ellipse field (R = E* = 1)."""
    _, _, sn = _geometry(beta0)
    j1a = ellipsoid_integrals(0.0, a, b)[0]
    j1c = ellipsoid_integrals(0.0, c, d)[0]
    w_star = sn / 3.0 * (amp_a * a * b - amp_b * c * d)  # Eq. (25) -> Eq. (36)
    delta = 0.5 * (amp_a * a * b * j1a - amp_b * c * d * j1c)  # Eq. (14a) for both fields
    prof = dh_elliptic_periphery.periphery_two_ellipses(a, b, c, d, amp_a, amp_b, np.array([0.0, 0.5 * np.pi]))
    return ClosureState(closure, *np.broadcast_arrays(mu, beta0, a, b, c, d, amp_a, amp_b, w_star, delta,
                                                      prof.work_of_adhesion[..., 0],
                                                      prof.work_of_adhesion[..., 1],
                                                      prof.max_adhesive_stress[..., 0],
                                                      prof.max_adhesive_stress[..., 1]))


def _check_domain(mu, beta0):
    """Validate (mu, beta0) against the closures' accepted domain (see :data:`CLOSURE_MU_RANGE`)."""
    mu = check_interval("mu", mu, *CLOSURE_MU_RANGE, low_open=False,
                        what="Tabor parameter of Eq. (35) for the closures")
    beta0 = as_circle(check_interval("beta0", beta0, *CLOSURE_BETA0_RANGE, low_open=False,
                                     what="ellipticity ratio b/a for the closures"))
    return mu, beta0


def _check(a_star, mu, beta0):
    a = check_contact_size_star("a_star", a_star)
    mu, beta0 = _check_domain(mu, beta0)
    return np.broadcast_arrays(a, mu, beta0)


# --------------------------------------------------------------------------- closure 1: ray average
def _ray_average_log_residual(log_s, a, mu, beta, weight, n_theta):
    s = np.exp(log_s)
    c = np.sqrt(a * a + s * s)
    po_ab = hertz.max_pressure(a, beta, checked=False)  # Eq. (8)
    po_cd = hertz.max_pressure(c, beta, checked=False)  # Eq. (20)
    v = mu / (po_cd * s / c)  # Eq. (24) with sigma0 = mu: mu = v Po_cd sqrt(1 - a^2/c^2)
    th = np.linspace(0.0, 0.5 * np.pi, n_theta)
    prof = dh_elliptic_periphery.periphery_two_ellipses(a, beta * a, c, beta * c, po_ab, po_cd, th)  # v-free J(theta)
    mean = dh_elliptic_periphery.ray_average(prof.work_of_adhesion, th, prof.contact_radius, weight)
    return np.log(v) + np.log1p(v) + np.log(mean)  # log of the mean Delta gamma, target 0


def solve_ray_average(a_star, *, beta0, mu, weight="area", n_theta=None):
    """Solve the ray-average closure: equal beta (Eq. 17), sigma0 = mu, mean Delta gamma = 1.

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axis a* [-].
    beta0 : array_like
        Ellipticity of both ellipses (Eq. 19) [-].
    mu : array_like
        Tabor parameter, Eq. (35) [-].
    weight : {"area", "angle"}
        Periphery average (:func:`dhfield.models.dh_elliptic_periphery.ray_average`).
    n_theta : int, optional
        Rays of the average; default :func:`rays_for` (beta0).

    Returns
    -------
    ClosureState
        The equilibrium state at ``a_star``.

    Notes
    -----
    .. math::

        \\sigma_0 = vPo_{cd}\\sqrt{1 - a^2/c^2} = \\mu \\quad (\\text{Eq. 24}),\\qquad
        \\frac{\\int_0^{\\pi/2}\\Delta\\gamma(\\theta_p)\\,r_{ab}^2\\,d\\theta_p}{\\int_0^{\\pi/2}r_{ab}^2\\,d\\theta_p} = 1

    Since Delta gamma(theta_p) = v(1+v) J(theta_p; a, c), the second equation is
    one equation for S = sqrt(c^2 - a^2), solved by Chandrupatla's method in log S
    from a bracket around the paper's solution (Delta gamma(0) = 1).
    """
    a, mu, beta0 = _check(a_star, mu, beta0)
    if weight not in ("area", "angle"):
        raise ValueError(f"weight must be 'area' or 'angle'; got {weight!r}")
    return _solve_ray_average(a, mu, beta0, weight=weight, n_theta=n_theta)


def _solve_ray_average(a, mu, beta0, *, weight="area", n_theta=None):
    """:func:`solve_ray_average` on validated, broadcast inputs."""
    n_theta = rays_for(beta0) if n_theta is None else int(n_theta)
    c0, _ = dh_elliptic.adhesive_axis_state(a, beta0, mu)
    log_s0 = np.log(np.sqrt(np.asarray(c0) ** 2 - a * a))
    args = (a, mu, beta0)

    def f(u, a_, mu_, b_):
        return _ray_average_log_residual(u, a_, mu_, b_, weight, n_theta)

    br = elementwise.bracket_root(f, log_s0, log_s0 + 0.5, args=args)
    res = elementwise.find_root(f, (br.bracket[0], br.bracket[1]), args=args,
                                tolerances=dict(xatol=1e-14, xrtol=1e-14, fatol=SOLVE_TOL))
    if not np.all(res.success):
        raise RuntimeError("ray-average closure solve failed; please report the inputs")
    s = np.exp(res.x)
    c = np.sqrt(a * a + s * s)
    po_ab, po_cd = hertz.max_pressure(a, beta0, checked=False), hertz.max_pressure(c, beta0, checked=False)
    v = mu / (po_cd * s / c)  # Eq. (24)
    return _two_field_state("ray_average", mu, beta0, a, beta0 * a, c, beta0 * c, (1 + v) * po_ab,
                            v * po_cd)  # Eq. (22)


# --------------------------------------------------------------------------- closure 2: two axes
def _two_axis_fields(a, log_c, log_d, mu, r1, r2):
    """(b, c, d, A, B) from the unknowns (log c, log d) for principal radii R', R''; NaN where inadmissible."""
    c, d = np.exp(log_c), np.exp(log_d)
    ok = (c > a) & (d <= c)
    c = np.where(ok, c, np.nan)
    amp_b = mu / np.sqrt(1.0 - (a / c) ** 2)  # Eq. (24) on the major axis: sigma0 = mu
    _, k2, k3 = ellipsoid_integrals(0.0, c, d)
    top = 1.0 / r2 + amp_b * c * d * k3
    bottom = 1.0 / r1 + amp_b * c * d * k2
    rho_ab = top / bottom  # curvature ratio the contact ellipse must have
    ok = ok & np.isfinite(rho_ab) & (rho_ab >= 1.0)
    beta_ab = np.full(np.shape(rho_ab), np.nan)
    if np.any(ok):
        # an intermediate value, finite and >= 1 by ``ok``: not validated again (issue 16, validate once)
        beta_ab[ok] = ellipticity_from_radius_ratio(np.asarray(rho_ab)[ok], checked=False)
    b = beta_ab * a
    _, j2, _ = ellipsoid_integrals(0.0, a, b)
    amp_a = bottom / (a * b * j2)  # first curvature condition
    ok = ok & (d > b)
    nan = (lambda q: np.where(ok, q, np.nan))
    return nan(b), nan(c), nan(d), nan(amp_a), nan(amp_b)


def _two_axis_residual(a, log_c, log_d, mu, r1, r2):
    b, c, d, amp_a, amp_b = _two_axis_fields(a, log_c, log_d, mu, r1, r2)
    safe = np.isfinite(b)
    fill = (lambda q, f: np.where(safe, q, f))
    prof = dh_elliptic_periphery.periphery_two_ellipses(fill(a, 1.0), fill(b, 0.5), fill(c, 2.0), fill(d, 1.5),
                                            fill(amp_a, 1.0), fill(amp_b, 1.0), np.array([0.0, 0.5 * np.pi]))
    w = prof.work_of_adhesion
    r = np.log(np.where(safe[..., None], w, np.nan))
    return r[..., 0], r[..., 1]  # log Delta gamma on the two axes (Eq. 31 on both)


def solve_two_axis(a_star, *, beta0, mu):
    """Solve the two-axis closure: Delta gamma = 1 on both axes, beta_cd != beta_ab, contact exact.

    Parameters
    ----------
    a_star : array_like
        Contact semi-major axis a* [-].
    beta0 : array_like
        Hertz ellipticity of the geometry, fixing R'/R'' [-].
    mu : array_like
        Tabor parameter; sigma0 = mu on the major axis (Eqs. 24, 35) [-].

    Returns
    -------
    ClosureState
        The equilibrium state; b* and d* are outputs: beta_contact and beta_adhesive differ from each
        other and from beta0 (module docstring).

    Notes
    -----
    Unknowns (c, d) at given a; B from sigma0, beta_ab and A from the curvature
    conditions.  Damped Newton in (log c, log d) with a forward-difference
    Jacobian (relative step :data:`_FD_STEP`), started from the paper's solution
    (d = beta0 c); converged when both log Delta gamma are below :data:`SOLVE_TOL`.
    """
    return _solve_two_axis(*_check(a_star, mu, beta0))


def _solve_two_axis(a, mu, beta0):
    """:func:`solve_two_axis` on validated, broadcast inputs."""
    shape = a.shape
    a, mu, beta0 = (np.atleast_1d(q).ravel() for q in (a, mu, beta0))
    c0, _ = dh_elliptic.adhesive_axis_state(a, beta0, mu)
    r1, r2, _ = _geometry(beta0)  # once per solve: the residual is evaluated ~10 times per Newton step
    u = np.stack([np.log(c0), np.log(beta0 * c0)], axis=-1).astype(float)
    u = np.array(np.broadcast_to(u, a.shape + (2,)))
    active = np.ones(a.shape, bool)
    for _ in range(_MAX_NEWTON):
        idx = np.nonzero(active)
        ai, mi, ui, r1i, r2i = a[idx], mu[idx], u[idx], r1[idx], r2[idx]
        f0 = np.stack(_two_axis_residual(ai, ui[:, 0], ui[:, 1], mi, r1i, r2i), axis=-1)
        done = np.all(np.abs(f0) < SOLVE_TOL, axis=-1)
        jac = np.empty(f0.shape + (2,))
        for k in range(2):
            up = ui.copy()
            up[:, k] += _FD_STEP
            jac[..., k] = (np.stack(_two_axis_residual(ai, up[:, 0], up[:, 1], mi, r1i, r2i), axis=-1) - f0) / _FD_STEP
            back = ~np.isfinite(jac[..., k]).all(axis=-1)
            if back.any():
                # Within _FD_STEP of the circle (d = c, rho_ab = 1) the forward step leaves the admissible
                # states (d > c): difference backwards there (issue 18, item 12).
                dn = ui[back].copy()
                dn[:, k] -= _FD_STEP
                jac[back, :, k] = (f0[back] - np.stack(_two_axis_residual(ai[back], dn[:, 0], dn[:, 1], mi[back],
                                                                          r1i[back], r2i[back]), axis=-1)) / _FD_STEP
        step = -np.linalg.solve(jac, f0[..., None])[..., 0]
        # damping: halve until the residual decreases and stays admissible
        lam = np.ones(ai.shape)
        norm0 = np.max(np.abs(f0), axis=-1)
        for _ in range(20):
            trial = ui + np.clip(lam[:, None] * step, -0.5, 0.5)
            ft = np.stack(_two_axis_residual(ai, trial[:, 0], trial[:, 1], mi, r1i, r2i), axis=-1)
            good = np.isfinite(ft).all(axis=-1) & (np.max(np.abs(ft), axis=-1) < norm0)
            if np.all(good | done):
                break
            lam = np.where(good | done, lam, 0.5 * lam)
        new = ui + np.clip(lam[:, None] * step, -0.5, 0.5)
        u[idx] = np.where(done[:, None], ui, new)
        active[idx] = ~done
        if not active.any():
            break
    else:
        raise RuntimeError("two-axis closure solve did not converge; please report the inputs")
    out = _two_axis_fields(a, u[..., 0], u[..., 1], mu, r1, r2)
    mu, beta0, a, b, c, d, amp_a, amp_b = (np.reshape(q, shape) for q in (mu, beta0, a, *out))
    return _two_field_state("two_axis", mu, beta0, a, b, c, d, amp_a, amp_b)


# --------------------------------------------------------------------------- pull-off
def _paper_state(a_star, mu, beta0):
    a, mu, beta0 = np.broadcast_arrays(a_star, mu, beta0)
    c, v = dh_elliptic.adhesive_axis_state(a, beta0, mu)
    c = np.asarray(c, float)
    v = np.asarray(v, float)
    return _two_field_state("paper", mu, beta0, a, beta0 * a, c, beta0 * c,
                            (1 + v) * hertz.max_pressure(a, beta0, checked=False),
                            v * hertz.max_pressure(c, beta0, checked=False))  # Eq. (22)


#: closure -> its state on validated inputs ``f(a_star, mu, beta0)`` (the pull-off search evaluates it
#: hundreds of times: the inputs are checked once, by :func:`pull_off_closure`).
_SOLVERS = {
    "paper": _paper_state,
    "ray_average": lambda a, mu, beta0: _solve_ray_average(*np.broadcast_arrays(a, mu, beta0)),
    "two_axis": lambda a, mu, beta0: _solve_two_axis(*np.broadcast_arrays(a, mu, beta0)),
}


#: closure -> the model name of its pull-off record (``paper``: the paper's model, Eqs. 17-19, 31).
MODEL_NAMES = {"paper": "dh-elliptic", "ray_average": "dh-elliptic-ray-average", "two_axis": "dh-elliptic-two-axis"}


def _check_pull_off(mu, beta0, closure, control):
    if closure not in CLOSURES:
        raise ValueError(f"closure must be one of {CLOSURES}; got {closure!r}")
    check_control(control)
    return np.broadcast_arrays(*_check_domain(mu, beta0))


def _pull_off_state(mu, beta0, closure, control):
    """The closure's state at its pull-off and where that is the zero-contact limit (validated inputs)."""
    solver = _SOLVERS[closure]
    key = "W_star" if control == "load" else "delta_star"

    def objective(a, m, b):
        return getattr(solver(a, m, b), key)

    end = last_local_minimum(objective, _SCAN, (np.ravel(mu), np.ravel(beta0)))
    has = end.found.reshape(mu.shape)
    a_best = np.where(has, end.x.reshape(mu.shape), A_ZERO)
    return solver(a_best, mu, beta0), ~has


def pull_off_closure(*, beta0, mu, closure="two_axis", control="load"):
    """Find the pull-off point of a closure: the minimum of W* (load) or delta* (displacement).

    Parameters
    ----------
    beta0 : array_like
        Hertz ellipticity of the geometry [-]; broadcast against ``mu``.
    mu : array_like
        Tabor parameter (Eq. 35) [-].
    closure : {"paper", "ray_average", "two_axis"}
        "paper" is Eqs. (17)-(19), (24), (31) (equal to :func:`dhfield.models.dh_elliptic.pull_off`
        to the solver tolerance; used as the like-for-like baseline).
    control : {"load", "displacement"}
        Pull-off control mode.

    Returns
    -------
    dhfield.core.records.PullOff
        The pull-off record (model :data:`MODEL_NAMES` of the closure).  Found as the
        last local minimum, seen from high load, of W*(a*) (or delta*(a*)) on a
        geometric scan of a*, refined with :func:`scipy.optimize.elementwise.find_minimum`
        (:func:`dhfield.core.pull_off_search.last_local_minimum`); ``at_zero_contact`` is True
        where W* (delta*) rises monotonically from the smallest scanned a*, and the
        state is then reported at a* = :data:`A_ZERO`, standing for a* -> 0.  The
        closure's own state there (amplitudes, Delta gamma and sigma0 on both axes):
        :func:`state_at_pull_off`.
    """
    mu, beta0 = _check_pull_off(mu, beta0, closure, control)
    state, zero = _pull_off_state(mu, beta0, closure, control)
    return pull_off_record(MODEL_NAMES[closure], beta0, mu, {**{k: getattr(state, k) for k in (
        "W_star", "a_star", "b_star", "c_star", "d_star", "delta_star")}, "at_zero_contact": zero},
        control=control, sin_skew=sin_skew_angle(beta0, checked=False), geometry="ellipse")


def state_at_pull_off(*, beta0, mu, closure="two_axis", control="load"):
    """Compute the closure's equilibrium state at its pull-off point (the diagnostics of the closure).

    Parameters
    ----------
    beta0, mu : array_like
        The grid point, as in :func:`pull_off_closure` [-].
    closure : {"paper", "ray_average", "two_axis"}
        As in :func:`pull_off_closure`.
    control : {"load", "displacement"}
        As in :func:`pull_off_closure`.

    Returns
    -------
    ClosureState
        The state :func:`solve_two_axis` (or :func:`solve_ray_average`) gives at the a* of
        :func:`pull_off_closure`'s record: the same point, with the amplitudes and
        Delta gamma, sigma0 on both axes.  Not a pull-off record: the state type of the
        closure solves.
    """
    mu, beta0 = _check_pull_off(mu, beta0, closure, control)
    return _pull_off_state(mu, beta0, closure, control)[0]


def pull_off_ray_average(beta0, mu, *, control="load"):
    """Compute the pull-off record of the ray-average closure, ``dh-elliptic-ray-average``.

    Parameters
    ----------
    beta0, mu : array_like
        Hertz ellipticity and Tabor parameter (Eq. 35) [-], in :data:`CLOSURE_BETA0_RANGE`
        and :data:`CLOSURE_MU_RANGE`.
    control : {'load', 'displacement'}
        Pull-off control mode.

    Returns
    -------
    dhfield.core.records.PullOff
        The pull-off point (:func:`pull_off_closure`), nondimensional.
    """
    return pull_off_closure(beta0=beta0, mu=mu, closure="ray_average", control=control)


def pull_off_two_axis(beta0, mu, *, control="load"):
    """Compute the pull-off record of the two-axis closure, ``dh-elliptic-two-axis``.

    Parameters
    ----------
    beta0, mu : array_like
        Hertz ellipticity and Tabor parameter (Eq. 35) [-], in :data:`CLOSURE_BETA0_RANGE`
        and :data:`CLOSURE_MU_RANGE`.
    control : {'load', 'displacement'}
        Pull-off control mode.

    Returns
    -------
    dhfield.core.records.PullOff
        The pull-off point (:func:`pull_off_closure`), nondimensional.
    """
    return pull_off_closure(beta0=beta0, mu=mu, closure="two_axis", control=control)
