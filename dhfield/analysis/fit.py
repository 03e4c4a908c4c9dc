"""The inverse problem: work of adhesion and adhesive stress from measurements.

Two estimators, on the SI front end :mod:`dhfield.analysis.dimensional` (so that what is
fitted is exactly what ``dhfield pulloff`` and ``dhfield curve`` compute):

* :func:`fit_work_of_adhesion` -- the work of adhesion dgamma from measured
  pull-off forces (one or several replicates), for a known adhesive stress
  sigma0 (one root in one unknown per replicate), with the standard error of
  the replicates; :func:`propagate_input_uncertainty` adds that of uncertain
  inputs (sigma0, moduli, radii, angle).
* :func:`fit_curve` -- dgamma and sigma0 from a measured load curve (load
  against contact size, optionally approach), by nonlinear least squares, with
  standard errors, NaN with the reason where the data cannot determine them.

Both carry the warning ``dhfield pulloff`` gives at the fitted state (a model
outside its validated range; dh-elliptic departing from the recommended model md-elliptic).

Both take the geometry and the material as a
:class:`dhfield.analysis.dimensional.ContactParameters` (from
:func:`dhfield.analysis.dimensional.contact_parameters` or
:func:`dhfield.analysis.dimensional.contact_parameters_from_principal_radii`): its
reduced modulus E* and principal radii R', R'' are used; its work of adhesion
and adhesive stress only serve as defaults or starting values.

Scaling (Eqs. 33-35): with R = sqrt(R'R''),

.. math::

    \\mu = \\sigma_0 \\left(\\frac{R}{E^{*2} \\Delta\\gamma}\\right)^{1/3}, \\qquad
    W_{\\max} = \\frac{2 \\pi R \\Delta\\gamma}{\\sin\\theta_{skew}} W^*_{\\max}(\\mu, \\beta_0),

so at fixed sigma0 the pull-off force depends on dgamma both directly and
through mu.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy import optimize

from ..core import units as units
from ..models import dh_elliptic_closure
from . import compare, dimensional
from ..core.validation import TABOR_RANGE, check_finite, check_positive

__all__ = ["WorkOfAdhesionFit", "CurveFit", "JointFit", "fit_work_of_adhesion", "fit_curve", "fit_joint",
           "JOINT_CONFIDENCE", "FIT_MU_RANGE", "fit_mu_range",
           "CURVE_FIT_MODEL_NAMES", "propagate_input_uncertainty", "replicate_statistics", "COVERAGE_FACTOR",
           "INPUT_REL_STEP", "JACOBIAN_COND_MAX", "CORRELATION_MAX", "CURVE_NODES", "CURVE_INTERPOLATION_RTOL"]

#: Tabor parameters mu (Eq. 35) the pull-off fit searches: the range every model
#: accepts (:data:`dhfield.core.validation.TABOR_RANGE`, DMT limit to 1e-3 at the low
#: end, JKR limit to 1e-6 at the high end), narrowed for the two closures to
#: :data:`dhfield.models.dh_elliptic_closure.CLOSURE_MU_RANGE` (mu <= 30) by :func:`fit_mu_range`.  A
#: force that needs mu outside it is rejected, with the attainable range of
#: forces in the message.
FIT_MU_RANGE = TABOR_RANGE
_CLOSURE_MODELS = ("dh-elliptic-two-axis", "dh-elliptic-ray-average")
#: Convergence of the root in ln(dgamma): the fitted dgamma is exact to this
#: relative error for the forward model (round trip).
_LOG_XTOL = 1e-13
#: Models whose load curve depends on sigma0 (mu), so that :func:`fit_curve` can
#: identify it; JKR, DMT and elliptical JKR have no adhesive stress.
CURVE_FIT_MODEL_NAMES = tuple(m for m in compare.CURVE_MODEL_NAMES if m not in ("jkr", "dmt", "jkr-elliptic",
                                                                            "jkr-elliptic-energy"))


#: Two-sided 95 % normal quantile z_0.975: ``work_of_adhesion_stderr`` is scaled so that
#: +- COVERAGE_FACTOR of it is the Student-t 95 % interval (see :func:`replicate_statistics`).
COVERAGE_FACTOR = 1.959963984540054
#: Relative step of the central differences of :func:`propagate_input_uncertainty`: the
#: truncation error is O(step^2) ~ 1e-6 relative, the rounding of the fitted root (1e-13,
#: :data:`_LOG_XTOL`) contributes 1e-13/step ~ 1e-10.
INPUT_REL_STEP = 1e-3


@dataclass(frozen=True)
class WorkOfAdhesionFit:
    """Work of adhesion that reproduces measured pull-off forces (one or several replicates).

    Parameters
    ----------
    work_of_adhesion : float
        Work of adhesion dgamma [J m^-2]: the mean of the replicates' dgamma (one root each).
    mu : float
        Tabor parameter of Eq. (35) at the fitted dgamma [-].
    beta0 : float
        Hertz ellipticity of the geometry [-].
    max_adhesive_stress : float
        The adhesive stress sigma0 used [Pa].
    pull_off_force : float
        The measured force fitted [N] (negative); the mean of the replicates.
    model, control : str
        The model name and the loading mode ('load' or 'displacement').
    evaluations : int
        Forward pull-off evaluations used.
    warning : str
        Empty, or why the fitted state should not be trusted: the warning
        :func:`dhfield.analysis.compare.pull_off` (and ``dhfield pulloff``) gives at the
        fitted (mu, beta0) -- a model outside its validated range
        (:func:`dhfield.analysis.compare.validity_message`) or, for ``dh-elliptic``, a
        departure from the recommended model ``md-elliptic`` above
        :data:`dhfield.analysis.compare.WARNING_THRESHOLD` (dgamma biased).
    work_of_adhesion_stderr : float
        Standard error of dgamma [J m^-2], t-adjusted: the replicates' standard
        error of the mean combined with the propagated input uncertainty, scaled
        so that +- :data:`COVERAGE_FACTOR` (about 2) of it is the 95 % interval
        (:func:`replicate_statistics`).  NaN, with ``stderr_note``, for a single
        force or identical replicates (no scatter to estimate).
    pull_off_forces : tuple of float
        The replicate forces [N].
    replicate_works : tuple of float
        The dgamma of each replicate [J m^-2].
    replicate_stderr : float
        Plain standard error of the mean of ``replicate_works``, s/sqrt(n) [J m^-2].
    input_stderr : float
        Standard uncertainty of dgamma propagated from the inputs [J m^-2]
        (0 unless :func:`propagate_input_uncertainty` added some).
    input_contributions : dict
        Input name -> its contribution |d dgamma/d x| std(x) [J m^-2].
    effective_dof : float
        Welch-Satterthwaite degrees of freedom of the combined uncertainty [-].
    confidence_interval : (float, float)
        The 95 % interval of dgamma [J m^-2] (NaN without a standard error).
    stderr_note : str
        Why ``work_of_adhesion_stderr`` is NaN, or empty.
    """
    work_of_adhesion: float
    mu: float
    beta0: float
    max_adhesive_stress: float
    pull_off_force: float
    model: str
    control: str
    evaluations: int
    warning: str = ""
    work_of_adhesion_stderr: float = float("nan")
    pull_off_forces: tuple = ()
    replicate_works: tuple = ()
    replicate_stderr: float = float("nan")
    input_stderr: float = 0.0
    input_contributions: dict = field(default_factory=dict)
    effective_dof: float = float("nan")
    confidence_interval: tuple = (float("nan"), float("nan"))
    stderr_note: str = ""

    def as_record(self) -> dict:
        """Return a plain dict (for ``--json``), keys named as in :mod:`dhfield.core.schema`.

        Returns
        -------
        dict
            The results and their uncertainties, in SI units.
        """
        return {"model": self.model, "control": self.control, "work_of_adhesion": self.work_of_adhesion,
                "work_of_adhesion_stderr": self.work_of_adhesion_stderr,
                "work_of_adhesion_ci95": list(self.confidence_interval),
                "mu": self.mu, "beta0": self.beta0, "max_adhesive_stress": self.max_adhesive_stress,
                "force": self.pull_off_force, "n_replicates": len(self.pull_off_forces),
                "forces": list(self.pull_off_forces), "replicate_works": list(self.replicate_works),
                "replicate_stderr": self.replicate_stderr, "input_stderr": self.input_stderr,
                "input_contributions": dict(self.input_contributions), "effective_dof": self.effective_dof,
                "stderr_note": self.stderr_note, "evaluations": self.evaluations, "warning": self.warning}


def replicate_statistics(values, input_stderr=0.0):
    """Mean of replicate estimates and its t-adjusted standard error, with input uncertainty.

    Parameters
    ----------
    values : array_like
        The n >= 1 replicate estimates (here: dgamma of each pull-off force).
    input_stderr : float
        Standard uncertainty from the inputs, common to all replicates (infinite
        degrees of freedom: the given standard deviations are taken as known).

    Returns
    -------
    dict
        ``mean``; ``stderr`` (t-adjusted, below); ``plain_stderr`` = s/sqrt(n);
        ``dof`` (Welch-Satterthwaite); ``interval`` (95 %); ``note`` (why
        ``stderr`` is NaN, else "").

    Notes
    -----
    With s the sample standard deviation of the n values (ddof = 1), the
    replicate part is :math:`u_r = s/\\sqrt{n}` and the combined standard
    uncertainty :math:`u_c = \\sqrt{u_r^2 + u_i^2}`.  Its effective degrees of
    freedom (Welch-Satterthwaite, GUM G.4) are
    :math:`\\nu = u_c^4 / (u_r^4/(n-1))`, the 95 % interval is
    mean +- :math:`t_{0.975,\\nu} u_c`, and the reported standard error is
    :math:`t_{0.975,\\nu} u_c / z_{0.975}`: +- 1.96 (about 2) of it is the
    95 % interval, also for three replicates, where the plain s/sqrt(n)
    would give 82 % (t with 2 degrees of freedom: 4.30 instead of 1.96).  As
    n grows it tends to the plain combined standard error.  A single value or
    identical replicates give no scatter estimate: ``stderr`` NaN, with the
    reason in ``note``.
    """
    from scipy import stats

    v = np.atleast_1d(np.asarray(values, float)).ravel()
    n = v.size
    mean = float(np.mean(v))
    u_i = float(input_stderr)
    nan = float("nan")
    if n < 2:
        return {"mean": mean, "stderr": nan, "plain_stderr": nan, "dof": nan, "interval": (nan, nan),
                "note": "one pull-off force: no replicate scatter to estimate a standard error from; "
                        "give two or more replicates"}
    s = float(np.std(v, ddof=1))
    u_r = s / math.sqrt(n)
    if not u_r > 1e-12 * abs(mean):
        return {"mean": mean, "stderr": nan, "plain_stderr": u_r, "dof": nan, "interval": (nan, nan),
                "note": f"the {n} replicates give the same dgamma: no scatter to estimate a standard error "
                        "from (forces below the instrument's resolution?)"}
    u_c = math.hypot(u_r, u_i)
    dof = (n - 1) * (u_c / u_r) ** 4  # Welch-Satterthwaite; the inputs' part has infinite dof
    half = float(stats.t.ppf(0.975, dof)) * u_c
    return {"mean": mean, "stderr": half / COVERAGE_FACTOR, "plain_stderr": u_r, "dof": dof,
            "interval": (mean - half, mean + half), "note": ""}


@dataclass(frozen=True)
class CurveFit:
    """Least-squares estimates of dgamma and sigma0 from a load curve.

    Parameters
    ----------
    work_of_adhesion, max_adhesive_stress : float
        Estimates of dgamma [J m^-2] and sigma0 [Pa].
    work_of_adhesion_stderr, max_adhesive_stress_stderr : float
        Their standard errors [J m^-2], [Pa] (delta method from the log
        parameters; see :func:`fit_curve`).
    correlation : float
        Correlation of the two estimates (of their logarithms) [-].
    mu, beta0 : float
        Tabor parameter (Eq. 35) at the estimates, Hertz ellipticity [-].
    contact_size, load, approach : ndarray
        The data [m], [N], [m] (``approach`` None if not given).
    load_fitted, approach_fitted : ndarray
        The model at the estimates [N], [m].
    load_residuals, approach_residuals : ndarray
        Data minus model [N], [m].
    load_noise, approach_noise : float
        Residual standard deviations (the weights of each block) [N], [m].
    model : str
        The model name.
    success : bool
        Whether the least-squares solver converged.
    message : str
        The solver's message.
    evaluations : int
        Forward load-curve evaluations.
    covariance_log : ndarray, optional
        Covariance of the log estimates (ln dgamma, ln sigma0), shape (2, 2) [-].
    warning : str
        Empty, or the warning :func:`dhfield.analysis.compare.pull_off` (and
        ``dhfield pulloff``) gives at the fitted (mu, beta0): the model outside
        its validated range, or ``dh-elliptic`` departing from the recommended
        model ``md-elliptic`` (the estimates are then biased).
    params : dhfield.analysis.dimensional.ContactParameters
        The contact at the estimates (for :meth:`model_curve`).
    not_identifiable : tuple of str
        Names of the estimates the data do not determine (``"work_of_adhesion"``,
        ``"max_adhesive_stress"``): their value is where the search stopped, not
        an estimate (``success`` is then False and ``message`` says why).
    """
    work_of_adhesion: float
    max_adhesive_stress: float
    work_of_adhesion_stderr: float
    max_adhesive_stress_stderr: float
    correlation: float
    mu: float
    beta0: float
    contact_size: np.ndarray
    load: np.ndarray
    approach: np.ndarray | None
    load_fitted: np.ndarray
    approach_fitted: np.ndarray | None
    load_residuals: np.ndarray
    approach_residuals: np.ndarray | None
    load_noise: float
    approach_noise: float
    model: str
    success: bool
    message: str
    evaluations: int
    covariance_log: np.ndarray = field(repr=False, default=None)
    warning: str = ""
    params: dimensional.ContactParameters = field(repr=False, default=None)
    not_identifiable: tuple = ()

    def as_record(self) -> dict:
        """Return a plain dict of the scalar results (for ``--json``).

        Returns
        -------
        dict
            The estimates, their uncertainties and the solver's outcome, in SI units.
        """
        return {"model": self.model, "work_of_adhesion": self.work_of_adhesion,
                "work_of_adhesion_stderr": self.work_of_adhesion_stderr,
                "max_adhesive_stress": self.max_adhesive_stress,
                "max_adhesive_stress_stderr": self.max_adhesive_stress_stderr,
                "correlation": self.correlation, "mu": self.mu, "beta0": self.beta0,
                "n_points": int(self.load.size), "load_noise": self.load_noise,
                "approach_noise": self.approach_noise, "success": self.success, "message": self.message,
                "evaluations": self.evaluations, "warning": self.warning,
                "not_identifiable": list(self.not_identifiable)}

    def model_curve(self, n=200):
        """Evaluate the fitted model as a smooth curve over the data's range of contact sizes.

        Parameters
        ----------
        n : int
            Number of contact sizes, evenly spaced from the smallest to the
            largest measured one (2 to 100000).

        Returns
        -------
        (ndarray, ndarray, ndarray)
            Contact semi-major axes a [m], loads W [N] and approaches delta [m]
            of the model at the estimates.
        """
        from ..core.validation import check_count

        n = check_count("n", n, 2, 100_000)
        if self.params is None:
            raise ValueError("this CurveFit has no params (the contact at the estimates); refit with fit_curve")
        a = np.linspace(float(np.min(self.contact_size)), float(np.max(self.contact_size)), n)
        w, d = _curve(self.params, a, self.model)
        return a, w, d


def _with(params, work_of_adhesion, max_adhesive_stress):
    """``params`` with another dgamma and sigma0 (the scales of Eqs. 33-35 recomputed)."""
    e, r, sin_skew = params.reduced_modulus, params.effective_radius, params.sin_skew
    return dimensional.ContactParameters(
        e, params.r_major, params.r_minor, r, params.beta0, sin_skew,
        float(units.tabor_parameter(max_adhesive_stress, r, e, work_of_adhesion)),  # Eq. (35)
        float(units.length_unit(r, e, work_of_adhesion)),  # Eq. (33)
        float(units.approach_unit(r, e, work_of_adhesion)),
        float(units.load_unit(r, work_of_adhesion, sin_skew)),  # Eq. (34)
        float(work_of_adhesion), float(max_adhesive_stress))


def _check_params(params):
    if not isinstance(params, dimensional.ContactParameters):
        raise ValueError("params must be a dhfield.analysis.dimensional.ContactParameters (from contact_parameters or "
                         f"contact_parameters_from_principal_radii); got {type(params).__name__}")
    if np.ndim(params.mu) or np.ndim(params.beta0):
        raise ValueError("params must be scalar ContactParameters (one geometry and material); got arrays")


def fit_mu_range(model) -> tuple:
    """Return the range of Tabor parameters (Eq. 35) :func:`fit_work_of_adhesion` searches.

    Parameters
    ----------
    model : str
        The model name.

    Returns
    -------
    tuple of float
        The smallest and largest mu [-].
    """
    if model in _CLOSURE_MODELS:
        lo, hi = dh_elliptic_closure.CLOSURE_MU_RANGE
        return (max(lo, FIT_MU_RANGE[0]), min(hi, FIT_MU_RANGE[1]))
    return FIT_MU_RANGE


def _work_at_mu(mu, max_adhesive_stress, params):
    """dgamma at which the Tabor parameter is mu, for fixed sigma0: inverts Eq. (35)."""
    r, e = params.effective_radius, params.reduced_modulus
    return max_adhesive_stress ** 3 * r / (mu ** 3 * e * e)  # Eq. (35) solved for dgamma


def fit_work_of_adhesion(pull_off_force, params, *, max_adhesive_stress=None, model=compare.DEFAULT_MODEL,
                         control="load", check_closure=True):
    """Work of adhesion dgamma that gives measured pull-off forces, with its standard error.

    Parameters
    ----------
    pull_off_force : float or array_like
        Measured pull-off force, negative (tensile) [N]; or a 1-d sequence of
        replicate forces of the same contact.
    params : dhfield.analysis.dimensional.ContactParameters
        Geometry and material (E*, R', R''); its ``work_of_adhesion`` is ignored.
    max_adhesive_stress : float, optional
        Adhesive stress sigma0 > 0 [Pa]; default ``params.max_adhesive_stress``.
    model : str
        One of :data:`dhfield.analysis.compare.MODEL_NAMES`; default the paper's model.
    control : {'load', 'displacement'}
        Loading mode of the measurement.

    Returns
    -------
    WorkOfAdhesionFit
        ``work_of_adhesion`` is the mean of the replicates' dgamma and
        ``work_of_adhesion_stderr`` its t-adjusted standard error
        (:func:`replicate_statistics`; NaN for one force).  Uncertain inputs:
        :func:`propagate_input_uncertainty`.

    Other Parameters
    ----------------
    check_closure : bool
        For ``dh-elliptic``: evaluate the recommended model ``md-elliptic`` at
        the fitted state (about a millisecond) and add the departure to ``warning``
        as :func:`dhfield.analysis.compare.pull_off` does.  The validity range of every
        model is checked regardless.

    Raises
    ------
    ValueError
        A force not negative, or outside the forces the model attains for
        Tabor parameters in :data:`FIT_MU_RANGE` (the range is in the message).

    Notes
    -----
    Each replicate force is inverted on its own; the estimate is their mean,
    and its standard error that of the mean of the n values (t-adjusted, see
    :func:`replicate_statistics`).  Over the scatter of a few per cent the
    map from force to dgamma is linear to second order, so the mean of the
    inverted values and the inverse of the mean force agree to that order.

    Each inversion solves :math:`\\ln(-W_{\\max}(\\Delta\\gamma)) = \\ln(-F)` in
    :math:`x = \\ln \\Delta\\gamma` with Eqs. (34)-(35):

    .. math::

        \\frac{d \\ln(-W_{\\max})}{d x} = 1 - \\frac{1}{3}
            \\frac{d \\ln(-W^*_{\\max})}{d \\ln \\mu},

    because mu is proportional to dgamma^(-1/3).  The root is unique as long as
    the log-slope of |W*max| in mu stays below 3.  |W*max| goes from the DMT
    value at small mu to the JKR value at large mu: over mu in
    [1e-4, 1e6], the log-slope lies in [-0.62, +0.001] (dh-elliptic at
    beta0 = 0.05; -0.10 for the circle, -0.11 for MD), so the function
    increases with slope between 1 and 1.21 (tests/test_fit.py checks it).
    The iteration is a secant method started from two fixed-point steps
    ``x <- x - f(x)``, which converges in a few evaluations (exactly in one
    for the mu-independent models JKR, DMT and elliptical JKR); Brent's method
    on the bracket of :data:`FIT_MU_RANGE` is the fallback.
    """
    _check_params(params)
    forces = _check_forces(pull_off_force)
    s0 = params.max_adhesive_stress if max_adhesive_stress is None else max_adhesive_stress
    s0 = float(check_positive("max_adhesive_stress", s0, "Pa"))
    if model not in compare.MODEL_NAMES:
        raise ValueError(f"model must be one of {', '.join(compare.MODEL_NAMES)}; got {model!r}")
    count = [0]
    works = [_solve_work(f, params, s0, model, control, count) for f in forces]
    stats = replicate_statistics(works)
    p = _with(params, stats["mean"], s0)
    warning = _validity_warning(model, p, control, check_closure)
    return WorkOfAdhesionFit(
        stats["mean"], float(p.mu), float(p.beta0), s0, float(np.mean(forces)), model, control, count[0], warning,
        work_of_adhesion_stderr=stats["stderr"], pull_off_forces=tuple(float(f) for f in forces),
        replicate_works=tuple(works), replicate_stderr=stats["plain_stderr"], effective_dof=stats["dof"],
        confidence_interval=stats["interval"], stderr_note=stats["note"])


def _validity_warning(model, p, control, check_closure):
    """The warning :func:`dhfield.analysis.compare.pull_off` (and ``dhfield pulloff``) gives at ``p``'s (mu, beta0)."""
    return str(compare.pull_off(model, mu=p.mu, beta0=p.beta0, control=control, check_closure=check_closure)["warning"])


def _reject_complex(name, value):
    """Complex input is refused by name (numpy would keep only its real part)."""
    if np.iscomplexobj(value) or isinstance(value, complex):
        raise ValueError(f"{name} must be real; got complex input {np.asarray(value).ravel()[:3]!r}")


def _check_forces(pull_off_force):
    _reject_complex("pull_off_force", pull_off_force)
    forces = check_finite("pull_off_force", pull_off_force, "N")
    if forces.ndim > 1:
        raise ValueError(f"pull_off_force must be a number or a 1-d sequence of replicate forces [N]; "
                         f"got an array of shape {forces.shape}")
    forces = np.atleast_1d(forces).astype(float)
    if forces.size == 0:
        raise ValueError("pull_off_force must contain at least one force [N]; got an empty sequence")
    if not np.all(forces < 0.0):
        raise ValueError(f"pull_off_force must be negative (tensile, N); got {float(forces[~(forces < 0)][0])!r}")
    return forces


def _solve_work(f_meas, params, s0, model, control, count):
    """dgamma [J m^-2] whose pull-off force is ``f_meas`` at sigma0 = ``s0`` (Notes of fit_work_of_adhesion)."""
    f_meas = float(f_meas)
    target = math.log(-f_meas)

    def force(work):
        count[0] += 1
        rec = dimensional.pull_off_force(_with(params, work, s0), model, control, check_closure=False, warn=False)
        return float(rec["force"])

    def f(x):
        w = force(math.exp(x))
        if not w < 0.0:
            raise ValueError(f"model {model!r} gives a non-negative pull-off force {w!r} N at "
                             f"work_of_adhesion={math.exp(x)!r}; cannot fit")
        return math.log(-w) - target

    # ends of the search, nudged inside FIT_MU_RANGE so that rounding stays within the models' range
    mu_range = fit_mu_range(model)
    x_lo = math.log(_work_at_mu(mu_range[1] * (1 - 1e-9), s0, params))  # large mu: small dgamma
    x_hi = math.log(_work_at_mu(mu_range[0] * (1 + 1e-9), s0, params))

    def attainable():
        try:
            ends = (force(math.exp(x_hi)), force(math.exp(x_lo)))
        except (ValueError, RuntimeError):  # the model fails at an end
            ends = (float("nan"), float("nan"))
        if all(math.isfinite(e) for e in ends):
            rng = f"[{ends[0]:.6g}, {ends[1]:.6g}] N"
        else:  # state the range of dgamma instead
            rng = f"the forces of work_of_adhesion in [{math.exp(x_lo):.6g}, {math.exp(x_hi):.6g}] J/m^2"
        return (f"pull_off_force must be in {rng} for model {model!r} at max_adhesive_stress={s0:.6g} Pa "
                f"(Tabor parameter mu in [{mu_range[0]:g}, {mu_range[1]:g}]); got {f_meas!r}")

    def clip(x):
        return min(max(x, x_lo), x_hi)

    # start at mu = 1 (dgamma from Eq. 35), one fixed-point step x <- x - f(x), then secant steps;
    # f increases with x (Notes), so f > 0 at x_lo or f < 0 at x_hi means no root in the range
    x0 = clip(math.log(_work_at_mu(1.0, s0, params)))
    f0 = f(x0)
    x1 = clip(x0 - f0)
    root = None
    for _ in range(40):
        if x1 == x0:
            f1 = f0
        else:
            f1 = f(x1)
        if f1 == 0.0 or (abs(x1 - x0) < _LOG_XTOL and abs(f1) < 10 * _LOG_XTOL):
            root = x1
            break
        if (x1 == x_lo and f1 > 0.0) or (x1 == x_hi and f1 < 0.0):
            raise ValueError(attainable())
        slope = (f1 - f0) / (x1 - x0) if x1 != x0 else 1.0
        if not 0.1 < slope < 10.0:  # the function is monotone with slope ~1 (Notes)
            slope = 1.0
        x0, f0 = x1, f1
        x1 = clip(x1 - f1 / slope)
    if root is None:  # fallback: bracketed Brent
        f_a, f_b = f(x_lo), f(x_hi)
        if not f_a <= 0.0 <= f_b:
            raise ValueError(attainable())
        root = optimize.brentq(f, x_lo, x_hi, xtol=_LOG_XTOL, rtol=4 * np.finfo(float).eps)
    return math.exp(root)


def propagate_input_uncertainty(fit, build, inputs, input_std, *, rel_step=INPUT_REL_STEP):
    """Add to a pull-off fit the uncertainty of dgamma from uncertain inputs.

    Parameters
    ----------
    fit : WorkOfAdhesionFit
        From :func:`fit_work_of_adhesion` (its forces, model and control are reused).
    build : callable
        ``build(**inputs)`` -> :class:`dhfield.analysis.dimensional.ContactParameters`, e.g.
        :func:`dhfield.analysis.dimensional.contact_parameters` or
        :func:`dhfield.analysis.dimensional.contact_parameters_from_principal_radii`; its
        ``max_adhesive_stress`` is the sigma0 of the fit (so sigma0 may be one of
        the uncertain inputs) and its ``work_of_adhesion`` is ignored.
    inputs : dict
        Keyword arguments of ``build`` (scalars) at their nominal values; they
        must give the fit's sigma0.
    input_std : dict
        Standard deviation of some of ``inputs`` (same keys, same units; 0 or
        absent: exact).  Taken as independent.

    Returns
    -------
    WorkOfAdhesionFit
        ``fit`` with ``input_stderr``, ``input_contributions`` and the combined
        ``work_of_adhesion_stderr`` (:func:`replicate_statistics`) filled in.

    Other Parameters
    ----------------
    rel_step : float
        Relative step of the central differences (:data:`INPUT_REL_STEP`).

    Notes
    -----
    Linear (first-order) propagation, GUM Eq. (10):
    :math:`u_i^2 = \\sum_k (\\partial\\Delta\\gamma/\\partial x_k)^2 \\sigma_k^2`,
    the derivatives by central differences of the fit of the mean force with
    step h = rel_step |x_k| (one-sided where x_k +- h leaves the accepted range,
    e.g. a skew angle of exactly 90 degrees or nu = 0.5).  Each input costs two
    inversions.  Valid while dgamma is close to linear over +- sigma_k, which a
    relative standard deviation of 10-20 % still satisfies on the smooth
    pull-off curves (verification/fit_coverage.py checks the coverage).
    """
    if not isinstance(fit, WorkOfAdhesionFit):
        raise ValueError(f"fit must be a WorkOfAdhesionFit (from fit_work_of_adhesion); got {type(fit).__name__}")
    if not callable(build):
        raise ValueError(f"build must be a callable returning ContactParameters; got {type(build).__name__}")
    inputs = dict(inputs)
    unknown = sorted(set(input_std) - set(inputs))
    if unknown:
        raise ValueError(f"input_std names inputs that are not in inputs: {', '.join(unknown)}; "
                         f"inputs: {', '.join(inputs)}")
    base = build(**inputs)
    _check_params(base)
    if not math.isclose(float(base.max_adhesive_stress), fit.max_adhesive_stress, rel_tol=1e-12):
        raise ValueError(f"build(**inputs) gives max_adhesive_stress {float(base.max_adhesive_stress)!r} Pa, "
                         f"not the fit's {fit.max_adhesive_stress!r} Pa")
    force = float(np.mean(fit.pull_off_forces)) if fit.pull_off_forces else fit.pull_off_force
    count = [0]

    def work_at(name, value):
        p = build(**{**inputs, name: value})
        return _solve_work(force, p, float(p.max_adhesive_stress), fit.model, fit.control, count)

    contributions = {}
    for name, std in input_std.items():
        std = float(check_positive(f"input_std[{name!r}]", std, "standard deviation", allow_zero=True))
        if std == 0.0:
            continue
        x = float(check_finite(f"inputs[{name!r}]", inputs[name]))
        h = rel_step * abs(x) if x != 0.0 else rel_step * std
        ends = []
        for v in (x + h, x - h):
            try:
                ends.append((v, work_at(name, v)))
            except ValueError:  # outside the accepted range on this side: one-sided difference
                pass
        if len(ends) == 1:
            ends.append((x, work_at(name, x)))
        if len(ends) < 2:
            raise ValueError(f"cannot vary input {name!r} by +-{h:.3g} around {x!r}: both sides are outside "
                             "the accepted range")
        (v1, w1), (v2, w2) = ends
        contributions[name] = abs((w1 - w2) / (v1 - v2)) * std
    u_i = math.sqrt(sum(c * c for c in contributions.values()))
    stats = replicate_statistics(fit.replicate_works or (fit.work_of_adhesion,), u_i)
    note = stats["note"]
    if note and u_i > 0:
        note += f" (the inputs alone contribute {u_i:.3g} J/m^2: input_stderr)"
    return replace(fit, work_of_adhesion_stderr=stats["stderr"], input_stderr=u_i,
                   input_contributions=contributions, effective_dof=stats["dof"],
                   confidence_interval=stats["interval"], stderr_note=note,
                   evaluations=fit.evaluations + count[0])


_CURVE_PARAMETERS = ("work_of_adhesion", "max_adhesive_stress")
#: Largest condition number of the (weighted, log-parameter) Jacobian for which dgamma and sigma0
#: are reported as separately identifiable.  Its columns are computed by finite differences
#: (relative error ~ sqrt(eps) = 1.5e-8), so a singular value below 1e-6 of the largest is within
#: 100 x of that error, i.e. not resolved.  Typical values: well-posed PDMS curves 3-18; five
#: copies of one row 2e16; sigma0 on the JKR side (mu ~ 22) 6e7.
JACOBIAN_COND_MAX = 1e6
#: |correlation| of the two log-estimates at or above which they count as correlated at +-1
#: (only a combination determined): the covariance is then rounding.
CORRELATION_MAX = 1.0 - 1e-6


def _log_standard_errors(jac, fun, n_res, names=None):
    """Standard errors, covariance and correlation of the log parameters, and what is not identifiable.

    ``names`` are the parameters of the columns of ``jac`` (default ``(work_of_adhesion,
    max_adhesive_stress)``, i.e. ln dgamma and ln sigma0).  Returns ``(se, cov, corr, problems,
    unknown)``: ``se`` NaN for a parameter the data cannot determine (``unknown`` True), with the
    reason in ``problems`` (list of str); ``corr`` is that of the first two (NaN for one parameter).
    """
    names = _CURVE_PARAMETERS if names is None else tuple(names)
    n_par = len(names)
    nan = float("nan")
    dof = n_res - n_par
    s2 = float(np.sum(fun ** 2)) / dof if dof > 0 else nan
    problems = []
    unknown = np.zeros(n_par, bool)
    u, sv, vt = np.linalg.svd(np.asarray(jac, float), full_matrices=False)
    cond = sv[0] / sv[-1] if sv[-1] > 0 else math.inf
    if not (np.all(np.isfinite(sv)) and sv[0] > 0):
        unknown[:] = True
        problems.append("the Jacobian of the residuals is zero or not finite: the data do not constrain "
                        f"{' and '.join(names)}; no standard errors")
        return np.full(n_par, nan), np.full((n_par, n_par), nan), nan, problems, unknown
    if cond > JACOBIAN_COND_MAX:
        # the null direction names the parameters it involves (NaN); a parameter nearly outside it
        # keeps the standard error of the full inverse, in which the null direction still weighs
        # v_i^2/s_min^2 (no pretence: large where it is not quite outside)
        unknown = np.abs(vt[-1]) > 0.1
        named = " and ".join(n for n, m in zip(names, unknown) if m)
        # numerical rank as numpy.linalg.matrix_rank counts it: s_min <= eps max(m, n) s_max
        deficient = sv[-1] <= np.finfo(float).eps * max(np.shape(jac)) * sv[0]
        problems.append(f"{named} not identifiable: the Jacobian is "
                        f"{'rank-deficient' if deficient else 'ill-conditioned'} (condition number {cond:.3g} > "
                        f"{JACOBIAN_COND_MAX:g})"
                        + ("; only a combination of the two is determined; no standard errors"
                           if unknown.all() and n_par > 1 else "; no standard error for it"))
    keep = sv > 0  # an exactly zero singular value: its direction is dropped (its parameters are NaN)
    inv = (vt[keep].T / sv[keep] ** 2) @ vt[keep]
    cov = s2 * inv
    se = np.sqrt(np.maximum(np.diag(cov), 0.0))
    se[unknown] = nan
    cov[unknown, :] = nan
    cov[:, unknown] = nan
    corr = float(cov[0, 1] / (se[0] * se[1])) if n_par > 1 and np.all(np.isfinite(se)) and np.all(se > 0) else nan
    if math.isfinite(corr) and abs(corr) >= CORRELATION_MAX:
        unknown[:] = True
        problems.append(f"work_of_adhesion and max_adhesive_stress are correlated at {corr:+.7f}: only a "
                        "combination of the two is determined; no standard errors")
        se[:] = nan
        cov[:] = nan
        corr = nan
    return se, cov, corr, problems, unknown


def _curve(params, semi_major, model):
    c = dimensional.load_curve_si(params, semi_major=semi_major, model=model)
    return np.asarray(c["force"], float), np.asarray(c["approach"], float)


#: Number of contact sizes (log-spaced over the data's range) at which :func:`fit_curve` evaluates the
#: model when the data have more than twice as many distinct sizes; the model at the data is then the
#: cubic spline in ln a through them.  On md-elliptic (mu 0.37-3700, a* from 1e-3 to 30) the
#: spline departs from the model by at most 8e-9 of the range of the loads (and of the approaches)
#: with 4096 nodes, 2.4e-7 with 1024.
CURVE_NODES = 4096
#: Largest departure of the spline through :data:`CURVE_NODES` nodes from the model, relative to the
#: range of the loads (of the approaches), accepted at the estimates; checked there on up to
#: :data:`CURVE_NODES` data sizes spread over the data, and the fit is redone at every data point if
#: it is exceeded.  1e-6 of the range is far below any measurement's noise and below the models'
#: own error (0.46 % for md-elliptic against the boundary-element solution).
CURVE_INTERPOLATION_RTOL = 1e-6
#: Seconds between two progress lines of :func:`fit_curve` (none for a fit faster than this).
PROGRESS_INTERVAL = 2.0


def _curve_evaluator(a_data, model, nodes):
    """``f(params) -> (loads [N], approaches [m])`` of the model at ``a_data`` [m].

    Each distinct contact size is evaluated once; with ``nodes`` (sizes [m], increasing, spanning
    ``a_data``), the model is evaluated there only and a cubic spline in ln a gives it at the data.
    """
    from scipy.interpolate import CubicSpline

    sizes, inverse = np.unique(a_data, return_inverse=True)
    if nodes is None:
        def curve(p):
            w, d = _curve(p, sizes, model)
            return w[inverse], d[inverse]
        return curve
    x_nodes, x_sizes = np.log(nodes), np.log(sizes)

    def curve(p):
        w, d = _curve(p, nodes, model)
        return CubicSpline(x_nodes, w)(x_sizes)[inverse], CubicSpline(x_nodes, d)(x_sizes)[inverse]
    return curve


def _interpolation_error(params, a_data, model, nodes):
    """Largest departure of the spline through ``nodes`` from the model, relative to the range of
    each, on up to :data:`CURVE_NODES` distinct data sizes spread over the data: (loads, approaches)."""
    sizes = np.unique(a_data)
    probe = sizes[np.unique(np.linspace(0, sizes.size - 1, min(CURVE_NODES, sizes.size)).round().astype(int))]
    w_exact, d_exact = _curve(params, probe, model)
    w_spline, d_spline = _curve_evaluator(probe, model, nodes)(params)
    return (float(np.max(np.abs(w_spline - w_exact)) / max(float(np.ptp(w_exact)), 1e-300)),
            float(np.max(np.abs(d_spline - d_exact)) / max(float(np.ptp(d_exact)), 1e-300)))


class _Progress:
    """One line on stderr every :data:`PROGRESS_INTERVAL` seconds of a long fit (nothing for a short one)."""

    def __init__(self, enabled, n_points):
        import time

        self.enabled, self.n_points, self.clock = bool(enabled), n_points, time.monotonic
        self.start = self.last = self.clock()

    def __call__(self, evaluations, stage):
        if not self.enabled:
            return
        now = self.clock()
        if now - self.last >= PROGRESS_INTERVAL:
            import sys

            self.last = now
            print(f"dhfield: fitting {self.n_points} points: {stage}, {evaluations} model evaluations, "
                  f"{now - self.start:.0f} s", file=sys.stderr, flush=True)


def fit_curve(load, contact_size, params, *, approach=None, model=compare.DEFAULT_MODEL, initial=None,
              check_closure=True, progress=False):
    """Work of adhesion and adhesive stress from a measured load curve, by least squares.

    Parameters
    ----------
    load : array_like
        Measured loads W, positive compressive [N].
    contact_size : array_like
        Contact semi-major axes a at those loads, > 0 [m] (the radius for a
        circular contact).
    params : dhfield.analysis.dimensional.ContactParameters
        Geometry and material (E*, R', R'').  Its ``work_of_adhesion`` and
        ``max_adhesive_stress`` are the starting values unless ``initial`` is
        given.
    approach : array_like, optional
        Measured approaches delta [m], fitted together with the loads.
    model : str
        One of :data:`CURVE_FIT_MODEL_NAMES`; default the paper's model.
    initial : (float, float), optional
        Starting (dgamma [J m^-2], sigma0 [Pa]).

    Returns
    -------
    CurveFit
        The estimates, their standard errors and the model at the estimates.

    Other Parameters
    ----------------
    check_closure : bool
        For ``dh-elliptic``: compare with the recommended model ``md-elliptic``
        at the fitted state (about a millisecond) and add the departure to
        ``warning``, as :func:`dhfield.analysis.compare.pull_off` does.  The validity range of every
        model is checked regardless.
    progress : bool
        Print a line on stderr every :data:`PROGRESS_INTERVAL` seconds while fitting (nothing
        for a faster fit).

    Notes
    -----
    Unknowns are :math:`\\theta = (\\ln\\Delta\\gamma, \\ln\\sigma_0)` (both stay
    positive).  The residuals are the load misfits, and the approach misfits if
    given, each block divided by its noise level :math:`s_k`; the model is the
    load curve of :func:`dhfield.analysis.dimensional.load_curve_si` at the measured
    contact sizes.  ``scipy.optimize.least_squares`` (trust-region reflective)
    minimises them; with approaches, a first fit with unit-range weights sets
    :math:`s_k` to each block's residual standard deviation and a second fit
    uses them.  The covariance of :math:`\\theta` is

    .. math::

        C = s^2 (J^T J)^{-1}, \\qquad s^2 = \\frac{\\sum r_i^2}{m - 2},

    with J the Jacobian of the weighted residuals at the solution, and the
    standard errors of dgamma and sigma0 follow by the delta method,
    :math:`\\mathrm{se}(\\Delta\\gamma) = \\Delta\\gamma \\sqrt{C_{11}}`.
    They assume independent, equal-variance errors within each block, and are
    meaningful only when the data reach the adhesive part of the curve (near
    pull-off), where the load depends on sigma0.  Not identifiable, with
    ``success`` False and the reason in ``message``:

    * fewer distinct contact sizes than parameters (times 2 with approaches):
      a ValueError, before any fit;
    * a Jacobian whose condition number exceeds :data:`JACOBIAN_COND_MAX`
      (rank-deficient or ill-conditioned; computed from its SVD): the
      parameters in its null direction get a NaN standard error, the other
      keeps that of the full inverse;
    * correlation at +-1 (:data:`CORRELATION_MAX`): both NaN;
    * a standard error above the estimate, or a run to the search bound
      (infinite standard error).

    Each distinct contact size is evaluated once.  With more than 2 :data:`CURVE_NODES`
    distinct sizes, the model is evaluated at :data:`CURVE_NODES` log-spaced sizes over the
    data's range and interpolated (cubic spline in ln a) to the data; at the estimates the
    spline is checked against the model on up to :data:`CURVE_NODES` data sizes, and the fit is
    redone at every data point if it departs by more than :data:`CURVE_INTERPOLATION_RTOL` of
    the range of the loads or approaches.  A fit then costs about as much for a million rows
    as for ten thousand.

    On 40 seeded noisy PDMS curves the truth was within 2 standard errors 38/40 (dgamma) and 39/40 (sigma0)
    times (``python -m verification.fit_round_trip``).  A fit takes 20-35
    load-curve evaluations: under a second for dh-elliptic, MD and DH circular,
    15-35 s for the two closures.
    """
    _check_params(params)
    if model not in CURVE_FIT_MODEL_NAMES:
        raise ValueError(f"model must be one of {', '.join(CURVE_FIT_MODEL_NAMES)} (models whose load curve "
                         f"depends on the adhesive stress); got {model!r}")
    for name, value in (("load", load), ("contact_size", contact_size), ("approach", approach)):
        _reject_complex(name, value)
    w_data = np.atleast_1d(check_finite("load", load, "N")).astype(float).ravel()
    a_data = np.atleast_1d(check_positive("contact_size", contact_size, "m")).astype(float).ravel()
    if w_data.size != a_data.size:
        raise ValueError(f"load and contact_size must have the same length; got {w_data.size} and {a_data.size}")
    d_data = None
    if approach is not None:
        d_data = np.atleast_1d(check_finite("approach", approach, "m")).astype(float).ravel()
        if d_data.size != a_data.size:
            raise ValueError(f"approach must have the length of contact_size ({a_data.size}); got {d_data.size}")
    n_res = w_data.size + (0 if d_data is None else d_data.size)
    if n_res < 3:
        raise ValueError(f"load must have at least 3 points to fit 2 parameters with an error estimate; "
                         f"got {w_data.size}")
    if not np.any(w_data != 0.0):
        raise ValueError(f"load must not be 0 at every point (a load curve needs the measured loads, N); "
                         f"got {w_data.size} zeros")
    n_sizes = np.unique(a_data).size
    if n_sizes * (1 if d_data is None else 2) < 2:
        raise ValueError(f"contact_size has {n_sizes} distinct value in {a_data.size} points: fewer distinct "
                         "points than the 2 parameters (work_of_adhesion, max_adhesive_stress); measure the load "
                         "at 2 or more contact sizes")
    if initial is None:
        initial = (params.work_of_adhesion, params.max_adhesive_stress)
    w0 = float(check_positive("initial work_of_adhesion", initial[0], "J m^-2"))
    s0 = float(check_positive("initial max_adhesive_stress", initial[1], "Pa"))
    count = [0]
    report = _Progress(progress, a_data.size)
    nodes = None
    if n_sizes > 2 * CURVE_NODES:
        nodes = np.geomspace(float(np.min(a_data)), float(np.max(a_data)), CURVE_NODES)
        nodes[0], nodes[-1] = np.min(a_data), np.max(a_data)
    curve = [_curve_evaluator(a_data, model, nodes)]
    stage = ["least squares"]

    def model_at(theta):
        count[0] += 1
        report(count[0], stage[0])
        return curve[0](_with(params, math.exp(theta[0]), math.exp(theta[1])))

    def span(x):
        s = float(np.ptp(x)) if x.size > 1 else 0.0
        return s if s > 0 else max(float(np.max(np.abs(x))), 1e-300)

    scales = [span(w_data), span(d_data) if d_data is not None else 1.0]

    def residuals(theta):
        try:
            w, d = model_at(theta)
        except ValueError:  # a trial (dgamma, sigma0) outside the model's accepted range
            return np.full(n_res, 1e3)
        r = [(w - w_data) / scales[0]]
        if d_data is not None:
            r.append((d - d_data) / scales[1])
        out = np.concatenate(r)
        return np.where(np.isfinite(out), out, 1e6)

    theta = np.log([w0, s0])
    # keep mu inside FIT_MU_RANGE's neighbourhood: search within 4 decades of the start
    bounds = (theta - math.log(1e4), theta + math.log(1e4))
    opts = dict(method="trf", x_scale=1.0, xtol=1e-14, ftol=1e-14, gtol=1e-14, max_nfev=200, bounds=bounds)

    def solve(start):
        sol = optimize.least_squares(residuals, start, **opts)
        if d_data is not None:  # reweight each block by its own residual scatter, refit
            w, d = model_at(sol.x)
            dof = max(n_res - 2, 1)
            for k, (res, x) in enumerate(((w - w_data, w_data), (d - d_data, d_data))):
                sd = math.sqrt(float(np.sum(res ** 2)) / dof * n_res / x.size)
                scales[k] = sd if sd > 1e-12 * span(x) else scales[k]
            sol = optimize.least_squares(residuals, sol.x, **opts)
        return sol

    sol = solve(theta)
    if nodes is not None:
        stage[0] = "checking the interpolated model"
        report(count[0], stage[0])
        errors = _interpolation_error(_with(params, *np.exp(sol.x)), a_data, model, nodes)
        if max(errors[0], errors[1] if d_data is not None else 0.0) > CURVE_INTERPOLATION_RTOL:
            curve[0], stage[0] = _curve_evaluator(a_data, model, None), "least squares at every data point"
            scales[:] = [span(w_data), span(d_data) if d_data is not None else 1.0]
            sol = solve(sol.x)
    work, stress = (float(v) for v in np.exp(sol.x))
    se, cov, corr, problems, unknown = _log_standard_errors(sol.jac, sol.fun, n_res)
    success, message = bool(sol.success), str(sol.message)
    # not identifiable: ran to the search bounds (within 1 %), or a standard error above the estimate
    at_bound = (np.abs(sol.x - bounds[0]) < 0.01) | (np.abs(sol.x - bounds[1]) < 0.01)
    vague = at_bound | (~(se < 1.0) & ~unknown)
    if np.any(vague):
        names = [n for n, m in zip(_CURVE_PARAMETERS, vague) if m]
        se = np.where(at_bound, np.inf, se)
        problems.insert(0, f"{' and '.join(names)} not identifiable from these data (standard error above the "
                        "estimate, or the search bound 4 decades from the start reached): data near pull-off, in "
                        "the JKR-DMT transition, are needed")
    not_identifiable = tuple(n for n, m in zip(_CURVE_PARAMETERS, unknown | vague) if m)
    if problems:
        success = False
        message = "; ".join(problems)
    if not np.all(np.isfinite(se)):
        corr = float("nan")
    w_fit, d_fit = model_at(sol.x)
    p = _with(params, work, stress)
    warning = _validity_warning(model, p, "load", check_closure)
    return CurveFit(
        work_of_adhesion=work, max_adhesive_stress=stress,
        work_of_adhesion_stderr=work * float(se[0]), max_adhesive_stress_stderr=stress * float(se[1]),
        correlation=corr, mu=float(p.mu), beta0=float(p.beta0),
        contact_size=a_data, load=w_data, approach=d_data,
        load_fitted=w_fit, approach_fitted=None if d_data is None else d_fit,
        load_residuals=w_data - w_fit, approach_residuals=None if d_data is None else d_data - d_fit,
        load_noise=float(np.sqrt(np.sum((w_data - w_fit) ** 2) / max(w_data.size - (2 if d_data is None else 1), 1))),
        approach_noise=float("nan") if d_data is None else
        float(np.sqrt(np.sum((d_data - d_fit) ** 2) / max(d_data.size - 1, 1))),
        model=model, success=success, message=message, evaluations=count[0],
        covariance_log=cov, warning=warning, params=p, not_identifiable=not_identifiable)


#: Confidence level of the intervals of :class:`JointFit` [-] (Student t with the residual degrees of freedom).
JOINT_CONFIDENCE = 0.95
#: Search range of :func:`fit_joint` about its start, in decades of each parameter (as :func:`fit_curve`).
_JOINT_SEARCH_DECADES = 4.0


@dataclass(frozen=True)
class JointFit:
    """Work of adhesion (and adhesive stress) fitted to data at several crossing angles at once.

    Parameters
    ----------
    work_of_adhesion : float
        Estimate of dgamma [J m^-2], common to every angle.
    max_adhesive_stress : float
        The adhesive stress sigma0 [Pa]: the estimate, or the given value when it was held fixed (``fitted``).
    work_of_adhesion_stderr, max_adhesive_stress_stderr : float
        Standard errors [J m^-2], [Pa]: the square roots of the diagonal of the least-squares
        covariance (delta method from the log parameters; :func:`fit_joint`), which for
        replicates of one quantity is the familiar s/sqrt(n).  NaN for sigma0 when it was held
        fixed, and for a parameter the data do not determine.
    work_of_adhesion_interval, max_adhesive_stress_interval : (float, float)
        The :data:`JOINT_CONFIDENCE` (95 %) intervals [J m^-2], [Pa]:
        estimate +- t(0.975, ``dof``) standard error.
    dof : int
        Residual degrees of freedom, data rows less fitted parameters [-].
    correlation : float
        Correlation of the two log estimates [-] (NaN when one parameter is fitted).
    fitted : tuple of str
        The parameters fitted: ``("work_of_adhesion",)`` or both.
    kind : {'pull_off', 'load_curve'}
        What each data row is: a pull-off force at its angle, or a load at a contact size and angle.
    skew_angle_deg : ndarray
        Crossing angle of each row [deg].
    force : ndarray
        The measured pull-off forces or loads [N].
    contact_size : ndarray or None
        Contact semi-major axes of a load curve [m] (None for pull-off forces).
    force_fitted : ndarray
        The model at the estimates, at each row [N].
    residual_sd : float
        Residual standard deviation: relative (of ln|F|) for pull-off forces [-], in newtons for
        load curves [N].
    angles : tuple of float
        The distinct crossing angles [deg], increasing.
    mu, beta0 : tuple of float
        Tabor parameter (Eq. 35) at the estimates and Hertz ellipticity, per distinct angle [-].
    model, control : str
        The model and (pull-off forces) the loading mode.
    success : bool
        False when the fit is flagged (a parameter not identifiable, or no convergence); ``message`` says why.
    message : str
        The solver's message, or why the fit is flagged.
    evaluations : int
        Forward model evaluations (one per angle per trial).
    warning : str
        Empty, or the warning :func:`dhfield.analysis.compare.pull_off` gives at the fitted state, per angle.
    not_identifiable : tuple of str
        The parameters the data do not determine.
    contact_at : callable
        ``contact_at(skew_angle_deg)`` -> :class:`dhfield.analysis.dimensional.ContactParameters` of the
        geometry (its dgamma and sigma0 are replaced by the estimates).
    """
    work_of_adhesion: float
    max_adhesive_stress: float
    work_of_adhesion_stderr: float
    max_adhesive_stress_stderr: float
    work_of_adhesion_interval: tuple
    max_adhesive_stress_interval: tuple
    dof: int
    correlation: float
    fitted: tuple
    kind: str
    skew_angle_deg: np.ndarray
    force: np.ndarray
    contact_size: np.ndarray | None
    force_fitted: np.ndarray
    residual_sd: float
    angles: tuple
    mu: tuple
    beta0: tuple
    model: str
    control: str
    success: bool
    message: str
    evaluations: int
    warning: str = ""
    not_identifiable: tuple = ()
    contact_at: object = field(repr=False, default=None)

    def params_at(self, skew_angle_deg):
        """The contact at the estimates at one crossing angle.

        Parameters
        ----------
        skew_angle_deg : float
            Crossing angle [deg].

        Returns
        -------
        dhfield.analysis.dimensional.ContactParameters
            Geometry and material with the fitted dgamma and sigma0.
        """
        return _with(self.contact_at(float(skew_angle_deg)), self.work_of_adhesion, self.max_adhesive_stress)

    def model_pull_off(self, skew_angle_deg):
        """Pull-off force of the fitted model at crossing angles.

        Parameters
        ----------
        skew_angle_deg : array_like
            Crossing angles [deg].

        Returns
        -------
        ndarray
            Pull-off forces [N] (negative).
        """
        angles = np.atleast_1d(np.asarray(skew_angle_deg, float))
        return np.array([_pull_off_at(self.params_at(a), self.model, self.control) for a in angles])

    def model_curve(self, skew_angle_deg, n=200):
        """The fitted load curve at one crossing angle over that angle's measured contact sizes.

        Parameters
        ----------
        skew_angle_deg : float
            One of :attr:`angles` [deg].
        n : int
            Number of contact sizes, evenly spaced over the measured ones (2 to 100000).

        Returns
        -------
        (ndarray, ndarray)
            Contact semi-major axes [m] and loads [N].
        """
        from ..core.validation import check_count

        n = check_count("n", n, 2, 100_000)
        if self.contact_size is None:
            raise ValueError("model_curve needs a load-curve fit (kind 'load_curve'); this one fitted pull-off forces")
        sizes = self.contact_size[self.skew_angle_deg == float(skew_angle_deg)]
        if sizes.size == 0:
            raise ValueError(f"skew_angle_deg must be one of the data's angles {list(self.angles)}; "
                             f"got {skew_angle_deg!r}")
        a = np.linspace(float(np.min(sizes)), float(np.max(sizes)), n)
        return a, _curve(self.params_at(skew_angle_deg), a, self.model)[0]

    def as_record(self) -> dict:
        """Return a plain dict of the results (for ``--json``), in SI units.

        Returns
        -------
        dict
            ``*_stderr`` are standard errors; ``*_ci95`` the 95 % intervals.  The sigma0
            entries' standard error and interval are absent when sigma0 was held fixed.
        """
        rec = {"model": self.model, "kind": self.kind, "work_of_adhesion": self.work_of_adhesion,
               "work_of_adhesion_stderr": self.work_of_adhesion_stderr,
               "work_of_adhesion_ci95": list(self.work_of_adhesion_interval),
               "max_adhesive_stress": self.max_adhesive_stress}
        if "max_adhesive_stress" in self.fitted:
            rec.update({"max_adhesive_stress_stderr": self.max_adhesive_stress_stderr,
                        "max_adhesive_stress_ci95": list(self.max_adhesive_stress_interval),
                        "correlation": self.correlation})
        rec.update({"fitted": list(self.fitted), "dof": self.dof, "n_points": int(self.force.size),
                    "skew_angles_deg": list(self.angles), "mu": list(self.mu), "beta0": list(self.beta0),
                    ("relative_noise" if self.kind == "pull_off" else "load_noise"): self.residual_sd,
                    "success": self.success, "message": self.message, "evaluations": self.evaluations,
                    "warning": self.warning, "not_identifiable": list(self.not_identifiable)})
        if self.kind == "pull_off":
            rec["control"] = self.control
        return rec


def _pull_off_at(params, model, control):
    return float(dimensional.pull_off_force(params, model, control, check_closure=False, warn=False)["force"])


def fit_joint(force, skew_angle_deg, contact_at, *, contact_size=None, max_adhesive_stress=None,
              model=compare.DEFAULT_MODEL, control="load", initial=None, check_closure=True):
    """Work of adhesion, and adhesive stress where identifiable, from data at several crossing angles.

    One dgamma (and one sigma0) is fitted to every row together; each row's model is evaluated
    on its own crossing angle's geometry, so that R = sqrt(R'R''), beta0 and mu (Eq. 35) change
    from angle to angle while the material parameters do not.

    Parameters
    ----------
    force : array_like
        Measured pull-off forces, negative [N] (without ``contact_size``); or measured loads,
        positive compressive [N] (with it).
    skew_angle_deg : array_like
        Crossing angle of each row, in (0, 90] [deg].
    contact_at : callable
        ``contact_at(skew_angle_deg)`` -> :class:`dhfield.analysis.dimensional.ContactParameters` of the
        geometry and material at that angle [deg] (e.g. :func:`dhfield.analysis.dimensional.contact_parameters`
        with the angle in radians); its dgamma and sigma0 are replaced by the trial values.
    contact_size : array_like, optional
        Contact semi-major axis of each row [m]: the rows are then points of load curves.
    max_adhesive_stress : float, optional
        The adhesive stress sigma0 [Pa], held fixed; default: fitted with dgamma.
    model : str
        Default the recommended model (:data:`dhfield.analysis.compare.DEFAULT_MODEL`).  With
        ``contact_size``, one of :data:`CURVE_FIT_MODEL_NAMES`.
    control : {'load', 'displacement'}
        Loading mode of pull-off forces (ignored for load curves).
    initial : (float, float), optional
        Starting (dgamma [J m^-2], sigma0 [Pa]); default for pull-off forces dgamma =
        -F sin(theta)/(1.75 pi R) (between JKR and DMT) with mu = 1, for load curves those of
        ``contact_at`` at the first angle.

    Returns
    -------
    JointFit
        Estimates, standard errors, 95 % intervals and the model at the estimates.

    Other Parameters
    ----------------
    check_closure : bool
        For ``dh-elliptic``: compare with the recommended model at each fitted state and add the
        departure to ``warning`` (:func:`dhfield.analysis.compare.pull_off`).

    Raises
    ------
    ValueError
        Inputs of different lengths, fewer rows than fitted parameters plus one, a pull-off force
        not negative, an angle outside (0, 90], or an unknown model.

    Warns
    -----
    dhfield.analysis.validity.OutsideVerifiedDomainWarning
        One warning with the text of ``warning``, when it is not empty.

    Notes
    -----
    The unknowns are :math:`\\theta = \\ln\\Delta\\gamma` (and :math:`\\ln\\sigma_0`).  The residual
    of a pull-off row is :math:`r_i = \\ln(F_{model}(\\theta_i)/F_i)` (relative, so that rows of
    different force weigh by their relative scatter); that of a load-curve row is
    :math:`(W_{model}(a_i, \\theta_i) - W_i)/\\mathrm{range}(W)`.  ``scipy.optimize.least_squares``
    (trust-region reflective, within 4 decades of the start) minimises them, and

    .. math::

        C = s^2 (J^T J)^{-1}, \\qquad s^2 = \\frac{\\sum r_i^2}{m - p}, \\qquad
        \\mathrm{se}(\\Delta\\gamma) = \\Delta\\gamma \\sqrt{C_{11}},

    with J the Jacobian at the solution, m rows and p parameters.  For n replicate pull-off
    forces at one angle and one parameter this is s/sqrt(n) divided by the slope
    d ln|F|/d ln dgamma (1 to 1.21, see :func:`fit_work_of_adhesion`): the standard error, with
    no coverage factor.  The interval is estimate +- t(0.975, m - p) se.  A parameter is flagged
    not identifiable (``success`` False) as in :func:`fit_curve`: an ill-conditioned Jacobian
    (:data:`JACOBIAN_COND_MAX`), correlation at +-1, a standard error above the estimate, or the
    search bound.  From pull-off forces on the JKR side (mu above about 5) sigma0 barely moves the
    force: hold it fixed (``max_adhesive_stress``) there.
    """
    for name, value in (("force", force), ("skew_angle_deg", skew_angle_deg), ("contact_size", contact_size)):
        _reject_complex(name, value)
    if not callable(contact_at):
        raise ValueError(f"contact_at must be a callable returning ContactParameters; got {type(contact_at).__name__}")
    f_data = np.atleast_1d(check_finite("force", force, "N")).astype(float).ravel()
    angle = np.atleast_1d(check_finite("skew_angle_deg", skew_angle_deg, "deg")).astype(float).ravel()
    if angle.size != f_data.size:
        raise ValueError(f"skew_angle_deg must have the length of force ({f_data.size}); got {angle.size}")
    bad = ~((angle > 0.0) & (angle <= 90.0))
    if np.any(bad):
        raise ValueError(f"skew_angle_deg must be in (0, 90] degrees; got {float(angle[bad][0])!r}")
    kind = "pull_off" if contact_size is None else "load_curve"
    a_data = None
    if kind == "load_curve":
        a_data = np.atleast_1d(check_positive("contact_size", contact_size, "m")).astype(float).ravel()
        if a_data.size != f_data.size:
            raise ValueError(f"contact_size must have the length of force ({f_data.size}); got {a_data.size}")
        if model not in CURVE_FIT_MODEL_NAMES:
            raise ValueError(f"model must be one of {', '.join(CURVE_FIT_MODEL_NAMES)} for load curves (models whose "
                             f"load curve depends on the adhesive stress); got {model!r}")
        if not np.any(f_data != 0.0):
            raise ValueError(f"force must not be 0 at every point (a load curve needs the measured loads, N); "
                             f"got {f_data.size} zeros")
    else:
        if model not in compare.MODEL_NAMES:
            raise ValueError(f"model must be one of {', '.join(compare.MODEL_NAMES)}; got {model!r}")
        if not np.all(f_data < 0.0):
            raise ValueError(f"force must be negative (tensile pull-off forces, N); got {float(f_data[~(f_data < 0)][0])!r}")
    if control not in ("load", "displacement"):
        raise ValueError(f"control must be 'load' or 'displacement'; got {control!r}")
    fixed_stress = None
    if max_adhesive_stress is not None:
        fixed_stress = float(check_positive("max_adhesive_stress", max_adhesive_stress, "Pa"))
    names = ("work_of_adhesion",) if fixed_stress is not None else _CURVE_PARAMETERS
    n_par = len(names)
    if f_data.size < n_par + 1:
        raise ValueError(f"force must have at least {n_par + 1} rows to fit {n_par} parameter(s) with an error "
                         f"estimate; got {f_data.size}")
    angles = tuple(float(a) for a in np.unique(angle))
    base = {}
    for a in angles:
        p = contact_at(a)
        _check_params(p)
        base[a] = p
    rows = {a: np.flatnonzero(angle == a) for a in angles}

    if initial is None:
        if kind == "pull_off":
            # between JKR (1.5 pi R dgamma) and DMT (2 pi R dgamma), Eq. (34): W = 2 pi R dgamma W*/sin
            w0 = float(np.median([-f_data[i] * base[angle[i]].sin_skew / (1.75 * math.pi * base[angle[i]].effective_radius)
                                  for i in range(f_data.size)]))
            p0 = base[angles[0]]
            s0 = float((p0.reduced_modulus ** 2 * w0 / p0.effective_radius) ** (1.0 / 3.0))  # mu = 1, Eq. (35)
        else:
            w0, s0 = float(base[angles[0]].work_of_adhesion), float(base[angles[0]].max_adhesive_stress)
    else:
        w0 = float(check_positive("initial work_of_adhesion", initial[0], "J m^-2"))
        s0 = float(check_positive("initial max_adhesive_stress", initial[1], "Pa"))
    if fixed_stress is not None:
        s0 = fixed_stress

    count = [0]
    evaluators = {}
    if kind == "load_curve":
        evaluators = {a: _curve_evaluator(a_data[rows[a]], model, None) for a in angles}
    scale = float(np.ptp(f_data)) if f_data.size > 1 and np.ptp(f_data) > 0 else float(np.max(np.abs(f_data)))

    def unpack(theta):
        return math.exp(theta[0]), (math.exp(theta[1]) if fixed_stress is None else fixed_stress)

    def model_at(theta):
        w, s = unpack(theta)
        out = np.empty_like(f_data)
        for a in angles:
            count[0] += 1
            p = _with(base[a], w, s)
            if kind == "pull_off":
                out[rows[a]] = _pull_off_at(p, model, control)
            else:
                out[rows[a]] = evaluators[a](p)[0]
        return out

    def residuals(theta):
        try:
            fm = model_at(theta)
        except ValueError:  # a trial outside the model's accepted range
            return np.full(f_data.size, 1e3)
        with np.errstate(invalid="ignore", divide="ignore"):
            r = np.log(fm / f_data) if kind == "pull_off" else (fm - f_data) / scale
        return np.where(np.isfinite(r), r, 1e6)

    theta0 = np.log([w0, s0][:n_par])
    span = math.log(10.0 ** _JOINT_SEARCH_DECADES)
    bounds = (theta0 - span, theta0 + span)
    sol = optimize.least_squares(residuals, theta0, method="trf", x_scale=1.0, xtol=1e-14, ftol=1e-14,
                                 gtol=1e-14, max_nfev=200, bounds=bounds)
    se_log, _, corr, problems, unknown = _log_standard_errors(sol.jac, sol.fun, f_data.size, names)
    at_bound = (np.abs(sol.x - bounds[0]) < 0.01) | (np.abs(sol.x - bounds[1]) < 0.01)
    vague = at_bound | (~(se_log < 1.0) & ~unknown)
    if np.any(vague):
        se_log = np.where(at_bound, np.inf, se_log)
        problems.insert(0, f"{' and '.join(n for n, m in zip(names, vague) if m)} not identifiable from these data "
                        "(standard error above the estimate, or the search bound 4 decades from the start reached)")
    not_identifiable = tuple(n for n, m in zip(names, unknown | vague) if m)
    if "max_adhesive_stress" in not_identifiable:
        problems.append("hold max_adhesive_stress fixed (--adhesive-stress on the command line), or add data "
                        "near pull-off in the JKR-DMT transition")
    success, message = bool(sol.success), str(sol.message)
    if problems:
        success, message = False, "; ".join(problems)
    work, stress = unpack(sol.x)
    dof = f_data.size - n_par
    from scipy import stats

    t = float(stats.t.ppf(0.5 + JOINT_CONFIDENCE / 2.0, dof))
    estimates = (work, stress)
    se = [estimates[k] * float(se_log[k]) if k < n_par else float("nan") for k in range(2)]
    intervals = [(v - t * e, v + t * e) if math.isfinite(e) else (float("nan"), float("nan"))
                 for v, e in zip(estimates, se)]
    f_fit = model_at(sol.x)
    res = np.log(f_fit / f_data) if kind == "pull_off" else f_fit - f_data
    residual_sd = float(np.sqrt(np.sum(res ** 2) / max(dof, 1)))
    fitted_params = {a: _with(base[a], work, stress) for a in angles}
    warnings_ = []
    for a in angles:
        p = fitted_params[a]
        w_a = str(compare.pull_off(model, mu=p.mu, beta0=p.beta0, control=control, check_closure=check_closure,
                                   warn=False)["warning"])
        if w_a:
            warnings_.append(f"at {a:g} deg: {w_a}")
    if warnings_:  # one Python warning, with the record's text
        import warnings

        from .validity import OutsideVerifiedDomainWarning

        warnings.warn("; ".join(warnings_), OutsideVerifiedDomainWarning, stacklevel=2)
    return JointFit(
        work_of_adhesion=work, max_adhesive_stress=stress, work_of_adhesion_stderr=se[0],
        max_adhesive_stress_stderr=se[1], work_of_adhesion_interval=intervals[0],
        max_adhesive_stress_interval=intervals[1], dof=dof,
        correlation=corr if n_par > 1 and np.all(np.isfinite(se_log)) else float("nan"), fitted=names, kind=kind,
        skew_angle_deg=angle, force=f_data, contact_size=a_data, force_fitted=f_fit, residual_sd=residual_sd,
        angles=angles, mu=tuple(float(fitted_params[a].mu) for a in angles),
        beta0=tuple(float(fitted_params[a].beta0) for a in angles), model=model, control=control,
        success=success, message=message, evaluations=count[0], warning="; ".join(warnings_),
        not_identifiable=not_identifiable, contact_at=contact_at)
