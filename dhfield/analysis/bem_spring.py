"""The BEM pull-off under a machine spring: the unloading branch by adhesive force, jumped out of by a spring.

:mod:`dhfield.analysis.spring` gives every analytic model's pull-off under a machine
spring of stiffness K*: the jump out is the first minimum, met on unloading, of
the (scaled) machine position

.. math:: F_s = s\\,\\delta^* + (1 - s)\\,W^*, \\qquad s = \\frac{K^*}{1 + K^*},

where dW*/d(delta*) = -K* (Maugis & Barquins 1978 [1]_; derived in
:mod:`dhfield.analysis.spring`).  K* -> 0 (s = 0) is load control, the minimum of W*;
K* -> infinity (s = 1) displacement control, the minimum of delta*.

Here the curve is the BEM's.  Between the two pull-offs the spring's jump lies on
the branch beyond the load minimum, which a displacement-controlled path cannot
reach near the fold (the fixed point at a prescribed approach slows down and
stops converging there).  The branch is followed instead at prescribed adhesive
force F_a (:func:`dhfield.bem.continuation.solve_at_adhesive_force`), which
decreases monotonically along the whole unloading branch, through the fold and
past the loss of contact: :func:`bem_unloading_branch` samples it once, in
uniform steps of F_a from above the load minimum to beyond the minimum of delta*
(finer on the separated branch), and :func:`bem_pull_off_under_spring` locates,
for every K*, the first minimum of F_s met from high force by the least-squares
fit of :func:`dhfield.bem.continuation.fit_fold` (a cubic in sqrt(F_a), ~ the zone
radius, over +-``window`` samples around the discrete minimum, with its error
estimate), the same fit that gives the BEM's displacement-control pull-off.  One
branch serves every stiffness.  :func:`spring_pull_off` is the route's answer
(``dhfield solve --machine-stiffness``): that jump with the resolution checks of every BEM
pull-off and a stated error of the fit's plus the grid's, from the same jump on a coarser
grid (:func:`coarse_branch`, :func:`dhfield.bem.pull_off.route_error`).  :func:`bem_loading_cycle` extends the branch up to
where the jump in lands and gives the cycle of :mod:`dhfield.analysis.spring` (both
jumps, the energy lost) on it.

Accuracy: on the sphere at N = 256 every pull-off is within 0.4 % of Maugis-Dugdale
under the same spring (lambda = 0.5-3, K* = 0.1-10), and the cycle's jump-in load,
jump-out load and energy lost within 0.9 % (``python -m verification.bem_spring``;
docs/theory/bem.rst, 'Measurements behind the solver's constants').

Units: the paper's (R = E* = Delta gamma = 1, Eqs. 32-35): W* = W sin(theta_skew)/(2 pi)
(Eq. 34), delta* = delta (c_r = 1, Eq. 33), K* as :func:`dhfield.analysis.spring.stiffness_star`.

References
----------
.. [1] D. Maugis, M. Barquins, J. Phys. D 11 (1978) 1989,
   doi:10.1088/0022-3727/11/14/011 (the jump under a machine of finite stiffness:
   dW/d(delta) = -K)
"""
from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..core.validation import check_count, check_ellipticity, check_positive
from ..bem.branch import Branch
from ..bem.continuation import adhesive_force, fit_fold, solve_at_adhesive_force
from ..bem.solver import DEFAULT_MAX_ITER, DEFAULT_TOL, extrapolated_start, state_options
from .spring import spring_weight
from ..core.geometry import sin_skew_angle
from ..core.pull_off_search import fitted_slopes, stable_minimum_index
from ..core.records import PullOff, broadcast_field

__all__ = ["BemBranch", "BranchOptions", "bem_unloading_branch", "bem_pull_off_under_spring", "bem_loading_cycle",
           "coarse_branch", "spring_pull_off",
           "BRANCH_STEPS", "BRANCH_WINDOW", "SPRING_NOTE"]

#: Adhesive-force steps from the cold start (near the load-control pull-off) to zero force:
#: the sampling step dF = F_a(start)/BRANCH_STEPS of the whole branch.
BRANCH_STEPS = 32
#: Half-width of the fitted window around each discrete minimum, in steps (a cubic over
#: 2 x 3 + 1 = 7 samples averages the lattice jaggedness, as the fold fit does).
BRANCH_WINDOW = 3
#: Steps of adhesive force over the separated branch, from the first separated state to zero force
#: (its zone shrinks to nothing there; the minimum of delta lies at F_a = 16 mu^3/pi on MD's).
SEPARATED_STEPS = 16
#: Step halvings allowed toward zero force (the last samples of the separated branch).
MAX_HALVINGS = 64
#: Largest count of states solved along one branch.
MAX_BRANCH_STATES = 400


@dataclass(frozen=True)
class BemBranch:
    """The BEM's unloading branch of (mu, beta0) sampled at prescribed adhesive force, paper units.

    Parameters
    ----------
    mu, beta0 : float
        Transition parameter (Eq. 35) and Hertz ellipticity [-].
    n : int
        Cells per axis.
    adhesive_force : ndarray
        F_a of each converged state, descending (unloading order) [sigma0-area, paper units].
    W_star, delta_star : ndarray
        Load (Eq. 34) and approach [c_r^2/R] of each state.
    in_contact : ndarray of bool
        False on the separated branch (no contact cell).
    step : float
        The sampling step dF of F_a.
    window : int
        Half-width of the fitted window, in steps.
    failures : int
        States that did not converge (left out: holes in the samples).
    complete : bool
        True when the samples hold the load minimum and the minimum of delta*
        with ``window`` samples on each side (every stiffness's jump is then
        bracketed); False when the branch ended first (unconverged states or
        zero force).
    elapsed : float
        Wall time [s].
    start_delta : float
        Approach where the force-free approach from separation ends, -h0 (the
        law's range: the central gap reaches it) [c_r^2/R].
    law : str
        The traction law's name.
    a_star, b_star, c_star, d_star : ndarray, optional
        Second-moment semi-axes of the contact and of contact U cohesive zone of
        each converged state [c_r] (None: not kept, e.g. a branch built from a curve).
    iterations : int
        GMRES iterations over every state solved.
    residual : float
        Largest residual over every state solved.
    failed_states : tuple of dict
        The unconverged states (approach, residual, iterations, phase).
    half_width_x, half_width_y : float
        Domain half-widths [c_r].
    edge_resolved : bool
        The grid resolves the traction law's edge (``AdhesiveProblem.resolved``).
    failed_forces : tuple of float
        F_a of each state that did not converge (the holes in the samples).
    solver_options : str
        The Newton options of every state, as JSON (:func:`dhfield.bem.solver.state_options`;
        empty for a branch built from a curve).
    """

    mu: float
    beta0: float
    n: int
    adhesive_force: np.ndarray = field(repr=False)
    W_star: np.ndarray = field(repr=False)
    delta_star: np.ndarray = field(repr=False)
    in_contact: np.ndarray = field(repr=False)
    step: float
    window: int
    failures: int
    complete: bool
    elapsed: float
    start_delta: float = float("nan")
    law: str = "dugdale"
    a_star: np.ndarray = field(default=None, repr=False)
    b_star: np.ndarray = field(default=None, repr=False)
    c_star: np.ndarray = field(default=None, repr=False)
    d_star: np.ndarray = field(default=None, repr=False)
    iterations: int = 0
    residual: float = float("nan")
    failed_states: tuple = ()
    half_width_x: float = float("nan")
    half_width_y: float = float("nan")
    edge_resolved: bool = True
    failed_forces: tuple = ()
    solver_options: str = ""


@dataclass(frozen=True)
class BranchOptions:
    """Numerical settings of :func:`bem_unloading_branch` (the defaults are the tested ones).

    Parameters
    ----------
    steps : int, default BRANCH_STEPS
        The step dF of adhesive force is F_a(start)/steps (8 to 10000) [-].
    window : int, default BRANCH_WINDOW
        Samples kept beyond each minimum (and fitted each side of it), 2 to 100 [-].
    tol : float, default DEFAULT_TOL
        Solver tolerance of every state (:func:`dhfield.bem.continuation.solve_at_adhesive_force`) [-].
    max_iter : int, default DEFAULT_MAX_ITER
        Inner iterations allowed per state [-].
    """

    steps: int = BRANCH_STEPS
    window: int = BRANCH_WINDOW
    tol: float = DEFAULT_TOL
    max_iter: int = DEFAULT_MAX_ITER


def _first_rise(x, f, window):
    """Index of the first sample, walking down the branch (index 0: highest F_a), where f stops falling.

    The one rule of :func:`dhfield.core.pull_off_search.stable_minimum_index` on the slopes
    df/d(-F_a) of least-squares quadratics over +-``window`` samples
    (:func:`dhfield.core.pull_off_search.fitted_slopes`: the lattice jaggedness of the BEM's
    loads and approaches, ~1e-3 at N = 64, makes single differences change sign before
    the minimum).  Returns ``f.size`` when f falls at every sample (no minimum met).
    """
    return int(stable_minimum_index(slopes=fitted_slopes(x, f, window)))


def bem_unloading_branch(*, beta0, mu, n, landing=None, margin=None, law="dugdale", threads=None,
                         options=None) -> BemBranch:
    """Sample the BEM's unloading branch at prescribed adhesive force, from above the load minimum past the fold.

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity of the geometry, in (0, 1] [-].
    mu : float
        Transition parameter of Eq. (35), > 0 [-].
    n : int
        Cells per axis (even, >= 8).
    landing : array_like, optional
        Machine stiffnesses K* >= 0 whose jump in must land on the samples: the
        branch is extended up until their machine position passes that of the end
        of the force-free approach (for the cycle, :func:`bem_loading_cycle`).
    margin : float, optional
        Domain half-width per zone semi-axis of the start of unloading
        (:func:`dhfield.analysis.bem_start.unloading_start`; default its own).  The
        domain must hold the cohesive zone of the top state.
    law : {'dugdale', 'exponential'}
        Traction law (:mod:`dhfield.bem.laws`).
    threads : int, optional
        FFT threads.
    options : BranchOptions, optional
        Numerical settings (force steps, fitted window, solver tolerance, iteration cap);
        default ``BranchOptions()``.

    Returns
    -------
    BemBranch
        The converged states in unloading order, paper units.

    Notes
    -----
    The problem and the cold start are those of the BEM's pull-off
    (:func:`dhfield.analysis.bem_start.nondimensional_problem`: the analytic
    load-control pull-off's approach and zone).  From its adhesive force F0 the
    branch is followed up in steps dF = F0/steps until the discrete minimum of W*
    has ``window`` samples above it, then down until the discrete minimum of
    delta* has ``window`` samples below it (or two states in a row fail, or F_a
    reaches zero), each state warm-started by the secant of the last two.  On the
    separated branch (no contact cell) the step is F_a(first separated)/``SEPARATED_STEPS``:
    its zone shrinks to nothing over the last few dF, and Maugis-Dugdale's minimum of
    delta lies there for lambda <~ 1 (c* = 4 mu/pi, :mod:`dhfield.models.maugis_dugdale_separated`).
    """
    from .bem_start import nondimensional_problem

    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    options = BranchOptions() if options is None else options
    if not isinstance(options, BranchOptions):
        raise ValueError(f"options must be a BranchOptions; got {type(options).__name__}")
    steps = check_count("steps", options.steps, 8, 10_000, "adhesive-force steps to zero")
    window = check_count("window", options.window, 2, 100, "samples each side of a minimum")
    tol, max_iter = options.tol, options.max_iter
    t0 = time.perf_counter()
    problem = nondimensional_problem(mu=mu, beta0=beta0, n=n, law=law, **({} if margin is None else {"margin": margin}))
    prob = problem.adhesive_problem(threads)
    branch = Branch(prob, tol, max_iter, label="spring")
    first = problem.path_start(prob).cold_start(branch)
    if first is None:
        from ..bem.path import loading_steps  # the marching path's loading steps: a state above pull-off

        st = loading_steps(branch, problem.approach_max, 4)
        first = st if (st.converged and st.in_contact) else None
    if first is None:
        raise RuntimeError(f"bem_unloading_branch: no converged contact state to start from at mu = {mu:g}, "
                           f"beta0 = {beta0:g}, n = {n} (increase n)")
    f0 = adhesive_force(first)
    df = f0 / steps
    samples = {f0: first}             # adhesive force -> converged state
    failures = 0
    failed_forces = []
    scale = problem.sin_skew / (2.0 * math.pi)  # Eq. (34)

    def solve(force):
        """Solve the state at ``force`` from its two nearest neighbours on the side nearer to it (secant)."""
        nonlocal failures
        toward = 1.0 if force > max(samples) else -1.0 if force < min(samples) else 0.0
        side = sorted((k for k in samples if toward == 0.0 or (force - k) * toward > 0),
                      key=lambda k: abs(k - force))
        last = samples[side[0]]
        prev = samples[side[1]] if len(side) > 1 else None
        if prev is not None and prev.in_contact == last.in_contact:
            t = (force - side[0]) / (side[0] - side[1])  # secant in units of their spacing
            guess = extrapolated_start(prob, prev, last, t)
            d_guess = last.approach + t * (last.approach - prev.approach)
        else:
            guess, d_guess = last, last.approach
        st = solve_at_adhesive_force(prob, force, guess, d_guess, tol, max_iter)
        branch.record(st, "spring")
        if st.converged:
            samples[force] = st
        else:
            failures += 1
            failed_forces.append(float(force))
        return st

    def series(key):
        fs = sorted(samples, reverse=True)  # unloading order
        return np.array(fs), np.array([key(samples[f]) for f in fs])

    def machine_low(s_land):
        """True while a landing spring's machine position at the top is below that of the jump-in."""
        fs, w = series(lambda s: s.load)
        d_top = samples[fs[0]].approach
        return any(sm * d_top + (1.0 - sm) * w[0] * scale < sm * start_delta for sm in s_land)

    # up: until the load minimum has `window` samples above it (and the landings are passed)
    complete = True
    s_land = [] if landing is None else list(np.atleast_1d(spring_weight(landing)[0]))
    start_delta = -float(prob.law.range)  # the force-free approach ends where the central gap reaches the range
    above = 0
    while len(samples) < MAX_BRANCH_STATES:
        fs, w = series(lambda s: s.load)
        if _first_rise(np.sqrt(fs), w, window) >= window:  # the load minimum, window samples in
            if not s_land or not machine_low(s_land):
                above += 1
                if not s_land or above > 2:  # two samples beyond the last landing, for its interpolation
                    break
        st = solve(fs[0] + df)
        if not st.converged:
            # the end of what converges above: incomplete unless the minimum and the landings are in
            complete = above > 0
            break
    # down: until the minimum of delta has `window` samples below it; on the separated branch
    # (no contact cell) the step is refined: the zone shrinks to nothing over the last few dF
    misses = 0
    step = df
    while len(samples) < MAX_BRANCH_STATES:
        fs, d = series(lambda s: s.approach)
        i = _first_rise(np.sqrt(fs), d, window)
        if i < fs.size and fs.size - 1 - i >= window:  # the minimum of delta, window samples beyond
            break
        last = samples[fs[-1]]
        if not last.in_contact and step == df:
            step = min(df, fs[-1] / SEPARATED_STEPS)
        force = fs[-1] - step * (1 + misses)
        while force <= 0.25 * step and step > df / MAX_HALVINGS:
            step *= 0.5       # toward zero force: the zone shrinks to nothing, c ~ sqrt(F_a)
            force = fs[-1] - step * (1 + misses)
        if force <= 0.25 * step or misses >= 2:
            complete = False
            break
        st = solve(force)
        misses = 0 if st.converged else misses + 1
    fs = np.array(sorted(samples, reverse=True))
    axes = np.array([samples[f].contact_semi_axes() + samples[f].cohesive_semi_axes() for f in fs], float)
    failed = tuple({"approach": float(r["approach"]), "residual": float(r["residual"]),
                    "iterations": int(r["iterations"]), "phase": r["phase"]}
                   for r in branch.records if not r["converged"])
    g = problem.grid
    return BemBranch(mu, beta0, int(n), fs, np.array([samples[f].load for f in fs]) * scale,
                     np.array([samples[f].approach for f in fs]),
                     np.array([samples[f].in_contact for f in fs]), df, window, failures, complete,
                     time.perf_counter() - t0, start_delta, law=problem.law.name, a_star=axes[:, 0],
                     b_star=axes[:, 1], c_star=axes[:, 2], d_star=axes[:, 3],
                     iterations=int(sum(r["iterations"] for r in branch.records)),
                     residual=float(max(r["residual"] for r in branch.records)), failed_states=failed,
                     half_width_x=0.5 * g.nx * g.dx, half_width_y=0.5 * g.ny * g.dy,
                     edge_resolved=bool(prob.resolved), failed_forces=tuple(failed_forces),
                     solver_options=json.dumps(state_options(tol, max_iter).as_dict()))


def bem_pull_off_under_spring(branch, machine_stiffness) -> PullOff:
    """Pull-off of the BEM under a machine spring of stiffness K*, from a sampled branch.

    Parameters
    ----------
    branch : BemBranch
        From :func:`bem_unloading_branch`.
    machine_stiffness : array_like
        K* >= 0, finite, or None (a rigid machine), in the paper's units
        (:func:`dhfield.analysis.spring.stiffness_star`) [-]; 0 is load control.

    Returns
    -------
    dhfield.core.records.PullOff
        The one pull-off record of every model (as :func:`dhfield.analysis.spring.pull_off_under_spring`
        for the analytic models), ``model='bem'``, ``control='spring'``, arrays of the shape of
        K*: ``W_star`` (load at the jump out, Eq. 34), ``delta_star`` (approach at the jump
        [c_r^2/R]), the semi-axes and ellipticities of the sample nearest the jump (NaN when
        the branch keeps none), ``v`` NaN, ``at_zero_contact`` (the jump starts out of contact);
        the spring group: ``machine_stiffness_star``, ``separation_delta_star`` (the machine
        position delta* + W*/K*; -inf at K* = 0, delta* for a rigid machine),
        ``max_tension_W_star`` (the smallest W* met from high load to the jump: the K* = 0 jump
        once passed), ``on_separated_branch``; the solver group: ``W_star_error`` (the fit's error
        estimate, without the grid's discretisation error; inf when the minimum is not
        bracketed), ``resolved`` (a bracketed interior minimum was fitted; ``warning`` says
        so where not), ``converged`` (every state of the branch converged), ``note``
        (:data:`SPRING_NOTE`), ``search`` ('branch') and the branch's cost.

    Notes
    -----
    For each K*, s = K*/(1 + K*) and F_s = s delta* + (1 - s) W* along the
    samples (descending F_a); the first discrete minimum met from high force,
    and the least-squares cubic of :func:`dhfield.bem.continuation.fit_fold`
    over the samples within +-``window`` steps of it (on the same side of the
    loss of contact), give its force, F_s and W*; delta* is a cubic of delta*(F_a)
    there.  The error estimate is fit_fold's (quartic, inner quadratic and the
    scatter of F_s about its cubic).  K* = 0 is the minimum of W*, the BEM's
    load-control pull-off; a rigid machine the minimum of delta*, its
    displacement-control pull-off (the same fit as
    :func:`dhfield.bem.continuation.fold_by_adhesive_force`).
    """
    jump = _jump_out(branch, machine_stiffness)
    soft = _jump_out(branch, 0.0)
    return _spring_record(branch, jump, float(soft["W_star"]))


def coarse_branch(branch, *, threads=None, options=None):
    """The same unloading branch on a coarser grid, for the grid's error of a spring pull-off.

    Parameters
    ----------
    branch : BemBranch
        From :func:`bem_unloading_branch` (its default domain margin).
    threads : int, optional
        FFT threads.
    options : BranchOptions, optional
        As for ``branch`` (default ``BranchOptions()``).

    Returns
    -------
    BemBranch or None
        :func:`bem_unloading_branch` over the same domain on the first of
        :func:`dhfield.bem.pull_off.ladder_cells` (half, then three quarters of the cells per axis)
        whose edge ratio is at most :data:`dhfield.bem.pull_off.LOCATE_MAX_EDGE_RATIO` (its states
        converge); None where there is none, or it has no converged state
        to start from (the spring pull-off then has no error estimate: :func:`spring_pull_off`).
        None also when ``branch``'s own grid does not resolve the law's edge (its pull-off is not an
        answer whatever the error).
    """
    from .bem_start import nondimensional_problem
    from ..bem.laws import law_from_name
    from ..bem.pull_off import LOCATE_MAX_EDGE_RATIO, ladder_cells
    from ..bem.solver import edge_width_ratio

    if not isinstance(branch, BemBranch):
        raise ValueError(f"branch must be a BemBranch (from bem_unloading_branch); got {type(branch).__name__}")
    if not branch.edge_resolved:
        return None
    n_c = next((k for k in ladder_cells(branch.n) if edge_width_ratio(
        nondimensional_problem(mu=branch.mu, beta0=branch.beta0, n=k, law=branch.law).grid,
        law_from_name(branch.law, branch.mu, 1.0)) <= LOCATE_MAX_EDGE_RATIO), None)
    if n_c is None:
        return None
    try:
        return bem_unloading_branch(beta0=branch.beta0, mu=branch.mu, n=n_c, law=branch.law, threads=threads,
                                    options=options)
    except RuntimeError:
        return None


def spring_pull_off(branch, machine_stiffness, coarse=None) -> PullOff:
    """The BEM pull-off under a machine spring with its stated error and resolution check (one K*).

    Parameters
    ----------
    branch : BemBranch
        From :func:`bem_unloading_branch` on the grid of the answer.
    machine_stiffness : float
        K* >= 0, finite, or None (a rigid machine) [-] (paper's units); 0 is load control.
    coarse : BemBranch, optional
        The same branch on a coarser grid (:func:`coarse_branch`); None: no grid error estimate,
        the answer is then not resolved.

    Returns
    -------
    dhfield.core.records.PullOff
        :func:`bem_pull_off_under_spring`'s record (scalar fields) with the route's checks:

        - ``W_star_error``: the fit's error plus the grid's,
          :func:`dhfield.bem.pull_off.route_error` (the larger of the zone-width floor of
          :func:`dhfield.bem.pull_off.discretisation_error` and the difference from the jump on
          ``coarse``, :func:`dhfield.bem.pull_off.ladder_error`); infinite when not resolved;
        - ``resolved``: the jump is bracketed and fitted on both grids, and the checks of
          every BEM pull-off hold (:func:`dhfield.bem.pull_off.unresolved_reasons`: the grid
          resolves the law's edge, W* within the DMT and zero-adhesion limits, a Dugdale zone at
          least one cell wide; at K* = 0, load control, a contact of at least
          :data:`dhfield.bem.pull_off.CONTACT_MIN_CELLS` cells); the reasons in ``note`` and
          ``warning`` where not;
        - ``converged``: no state of the branch failed at an adhesive force within ``window``
          steps of the jump (the samples its fit rests on: a hole there is a failed state the
          answer depends on); failed states elsewhere (each state is solved at its own force,
          warm-started from converged ones) are listed in ``failures`` only.
    """
    from ..bem.laws import law_from_name
    from ..bem.operator import Grid
    from ..bem.pull_off import route_error, unresolved_reasons

    if machine_stiffness is not None and np.ndim(machine_stiffness) != 0:
        raise ValueError(f"machine_stiffness must be a scalar (one spring per call); got an array of shape "
                         f"{np.shape(machine_stiffness)}")
    po = bem_pull_off_under_spring(branch, machine_stiffness)
    w, fit_err = float(po.W_star), float(po.W_star_error)
    axes = tuple(float(v) for v in (po.a_star, po.b_star, po.c_star, po.d_star))
    grid = Grid.centered(branch.n, branch.half_width_x, ny=branch.n, half_width_y=branch.half_width_y)
    w_c, n_c = float("nan"), 0
    if coarse is not None:
        if not isinstance(coarse, BemBranch):
            raise ValueError(f"coarse must be a BemBranch (from coarse_branch) or None; got {type(coarse).__name__}")
        got = bem_pull_off_under_spring(coarse, machine_stiffness)
        n_c = int(coarse.n)
        if bool(got.resolved):
            w_c = float(got.W_star)
    error = route_error(fit_err, w, axes, grid, w_coarse=w_c, n_coarse=n_c) if po.resolved else float("inf")
    k = float(po.machine_stiffness_star)
    reasons = unresolved_reasons(law=law_from_name(branch.law, branch.mu, 1.0), grid=grid,
                                 sin_skew=float(po.sin_skew), edge_resolved=bool(branch.edge_resolved),
                                 control="spring", w_star=w, search_error=fit_err, axes=axes, stated_error=error,
                                 contact_cells=k == 0.0)
    if not po.resolved:
        reasons.insert(0, UNRESOLVED_SPRING_WARNING)
    # the samples the jump is fitted on: `window` steps either side of it (F_a descending along the branch)
    i = int(np.asarray(_jump_out(branch, machine_stiffness)["index"]))
    f = branch.adhesive_force
    high, low = f[max(i - branch.window, 0)], f[min(i + branch.window, f.size - 1)]
    converged = not any(low <= x <= high for x in branch.failed_forces)
    note = "; ".join(filter(None, (SPRING_ROUTE_NOTE, f"grid error from a coarser grid: W* = {w_c:.6g} on n = {n_c}"
                                   if coarse is not None else "no coarser grid to estimate the grid's error",
                                   "unresolved: " + "; ".join(reasons) if reasons else "")))
    return replace(po, W_star_error=float("inf") if reasons else error, resolved=not reasons, converged=converged,
                   warning="; ".join(reasons), note=note)


#: Caveat carried by every BEM pull-off under a spring (the ``note`` of its record), from the
#: sphere at N = 256 against Maugis-Dugdale under the same spring (``python -m verification.bem_spring``).
SPRING_NOTE = ("pull-off under a machine spring: the first minimum of the machine position on the BEM's unloading "
               "branch sampled at prescribed adhesive force; W_star_error is the fit's, without the grid's "
               "discretisation error; on the sphere within 0.4 % of Maugis-Dugdale for lambda = 0.5-3, "
               "K* = 0.1-10 at N = 256")
#: Caveat of the route-checked spring pull-off (:func:`spring_pull_off`), in place of :data:`SPRING_NOTE`.
SPRING_ROUTE_NOTE = ("pull-off under a machine spring: the first minimum of the machine position on the BEM's "
                     "unloading branch sampled at prescribed adhesive force; W_star_error is the fit's plus the "
                     "grid's (from the same jump on a coarser grid)")
#: ``warning`` of a BEM pull-off under a spring whose jump is not bracketed and fitted.
UNRESOLVED_SPRING_WARNING = "the jump out is not bracketed on the sampled branch: not an answer (increase n)"


def _spring_record(branch, jump, soft_w):
    """The :class:`dhfield.core.records.PullOff` (spring and solver groups) of the jump ``jump`` (:func:`_jump_out`)
    on ``branch``; ``soft_w``: W* of its K* = 0 jump (the load minimum, passed before every other jump)."""
    shape = np.shape(jump["W_star"])
    k, w, d = (np.asarray(jump[key], float) for key in ("machine_stiffness_star", "W_star", "delta_star"))
    i = np.asarray(jump["index"], int)
    nan = np.full(shape, np.nan)
    a, b, c, e = ((nan if getattr(branch, key) is None else np.asarray(getattr(branch, key), float)[i])
                  for key in ("a_star", "b_star", "c_star", "d_star"))
    separated = ~np.asarray(jump["in_contact"], bool)
    resolved = np.asarray(jump["resolved"], bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        sep = np.where(k > 0, d + w / k, -np.inf)  # Delta* = delta* + W*/K*
        sep = np.where(np.isinf(k), d, sep)
        ell = np.where(a > 0, b / np.where(a > 0, a, 1.0), np.nan)
        adh = np.where(c > 0, e / np.where(c > 0, c, 1.0), np.nan)
    w_min = np.fmin(w, soft_w)  # every jump lies at or beyond the load minimum (dW*/d delta* = -K* <= 0)

    def full(x, dtype=float):
        return broadcast_field(x, shape, dtype)

    return PullOff(model="bem", control="spring", geometry="ellipse", beta0=full(branch.beta0), mu=full(branch.mu),
                   sin_skew=full(float(sin_skew_angle(branch.beta0))), W_star=full(w), a_star=full(a),
                   b_star=full(b), c_star=full(c), d_star=full(e), v=full(np.nan), delta_star=full(d),
                   ellipticity=full(ell), adhesive_ellipticity=full(adh), at_zero_contact=full(separated, bool),
                   warning=full(np.where(resolved, "", UNRESOLVED_SPRING_WARNING), object),
                   machine_stiffness_star=full(k), separation_delta_star=full(sep), max_tension_W_star=full(w_min),
                   on_separated_branch=full(separated, bool), W_star_error=full(jump["W_star_error"]),
                   converged=branch.failures == 0, resolved=full(resolved, bool),
                   note=SPRING_NOTE, search="branch", n=int(branch.n), law=branch.law,
                   n_steps=int(np.size(branch.adhesive_force)) + int(branch.failures),
                   iterations=int(branch.iterations), residual=float(branch.residual),
                   failures=tuple(branch.failed_states), half_width_x=float(branch.half_width_x),
                   half_width_y=float(branch.half_width_y), elapsed=float(branch.elapsed),
                   solver_options=str(branch.solver_options))


def _jump_out(branch, machine_stiffness):
    """The jump out of :func:`bem_pull_off_under_spring` as a dict of arrays over K*: ``machine_stiffness_star``,
    ``W_star``, ``W_star_error``, ``delta_star``, ``adhesive_force`` (F_a there), ``in_contact``, ``resolved``
    and ``index`` (the sample nearest the jump)."""
    if not isinstance(branch, BemBranch):
        raise ValueError(f"branch must be a BemBranch (from bem_unloading_branch); got {type(branch).__name__}")
    s, k = spring_weight(machine_stiffness)
    shape = np.shape(s)
    s1 = np.atleast_1d(s).astype(float)
    k1 = np.broadcast_to(np.atleast_1d(k), s1.shape).astype(float)
    out = {key: np.full(s1.shape, np.nan) for key in ("W_star", "W_star_error", "delta_star", "adhesive_force")}
    out["in_contact"] = np.zeros(s1.shape, bool)
    out["resolved"] = np.zeros(s1.shape, bool)
    # abscissa q = sqrt(F_a), ~ the zone radius: on the separated branch delta* and W* are
    # quadratics in it (Maugis 1992; F_a = sigma0 pi c^2), in F_a they have a sqrt(F_a) end
    x = np.sqrt(branch.adhesive_force)
    w, d, c = branch.W_star, branch.delta_star, branch.in_contact
    win = branch.window
    for m, sm in enumerate(s1):
        f = sm * d + (1.0 - sm) * w
        rise = _first_rise(x, f, win)
        i = min(rise, x.size - 1)
        if 0 < i < x.size - 1:
            i += int(stable_minimum_index(f[i - 1:i + 1])) - 1  # the lower of the two samples (the one rule)
        fit = sel = None
        for half in range(win, 2 * win + 1):  # widened while the lattice noise hides the vertex
            near = np.abs(np.arange(x.size) - i) <= half
            same = near & (c == c[i])
            sel = same if np.count_nonzero(same) >= 2 * win - 1 else near
            if not (rise < x.size and 0 < i < x.size - 1 and np.count_nonzero(sel) >= 4):
                break
            fit = fit_fold(x[sel], f[sel], w[sel])
            if fit.kind == "fold":
                break
        if fit is not None and fit.kind == "fold":
            xs = x[sel]
            x0, sc = 0.5 * (xs.min() + xs.max()), max(0.5 * np.ptp(xs), 1e-300)
            pd = np.polyfit((xs - x0) / sc, d[sel], min(3, xs.size - 1))
            # the fitted load's own scatter: the residual deviation of W* about its cubic, times
            # sqrt(4/n) (four coefficients from n samples); fit_fold's estimate holds the slope's
            # scatter only, which vanishes at the minimum of W* (K* = 0)
            pw = np.polyfit((xs - x0) / sc, w[sel], min(3, xs.size - 1))
            resid = w[sel] - np.polyval(pw, (xs - x0) / sc)
            dof = max(xs.size - 4, 1)
            scatter = math.sqrt(float(resid @ resid) / dof) * math.sqrt(4.0 / xs.size)
            out["W_star"][m], out["W_star_error"][m] = fit.load, max(fit.load_error, scatter)
            out["adhesive_force"][m] = fit.adhesive_force ** 2
            out["delta_star"][m] = np.polyval(pd, (fit.adhesive_force - x0) / sc)
            out["resolved"][m] = bool(np.isfinite(fit.load_error))
        else:  # not bracketed: the discrete sample, flagged
            out["W_star"][m], out["delta_star"][m], out["adhesive_force"][m] = w[i], d[i], x[i] ** 2
            out["W_star_error"][m] = np.inf
        out["in_contact"][m] = bool(c[i])
        if not out["resolved"][m]:
            out["W_star_error"][m] = np.inf
    with np.errstate(invalid="ignore"):
        # the sample nearest the jump: its state gives the semi-axes (as the BEM's other pull-offs)
        out["index"] = np.argmin(np.abs(x[None, :] - np.sqrt(out["adhesive_force"])[:, None]), axis=1)
    rec = {"machine_stiffness_star": k1, **out}
    return {key: v.reshape(shape)[()] for key, v in rec.items()}


def _cycle_margin(mu, beta0, k_positive):
    """Domain margin holding the jump-in landing state of the softest spring.

    The landing of a soft spring lies near W* = 0, above the start of unloading the
    pull-off's domain is sized for (:func:`dhfield.analysis.bem_start.unloading_start`).
    Maugis-Dugdale's landing contact radius a* (the sphere's), the DH model's zone
    semi-axis c* there (:func:`dhfield.models.dh_elliptic.load_curve`, as the pull-off's domain
    is sized), 10 % beyond, sets the margin (the pull-off's own domain can cut the landing
    zone of a soft spring).
    """
    from . import spring as compliance
    from ..models import dh_elliptic
    from .bem_start import unloading_start
    from ..bem.pull_off import DOMAIN_MARGIN

    rec = compliance.loading_cycle("md", mu=mu, beta0=1.0, machine_stiffness=float(np.min(k_positive)))
    a_in = max(float(rec["jump_in_a_star"]), 1e-3)
    c_land = float(np.asarray(dh_elliptic.load_curve(mu=mu, beta0=beta0, a_star=[a_in]).c_star)[0])
    if not np.isfinite(c_land):
        c_land = 1.5 * a_in
    c_start = unloading_start(mu=mu, beta0=beta0).half_width_x / DOMAIN_MARGIN
    return DOMAIN_MARGIN * max(1.0, 1.1 * c_land / c_start)


def _landing(x, f, w, d, x_out, target, window):
    """(W*, delta*, W* error) where f(x) = target on the stable branch above x_out (x descending).

    Cubic (and, for the error, quadratic) least squares of f, W*, delta* over +-``window``
    samples around the crossing; the error is the larger of the two fits' difference and
    the residual deviation of W* about its fit times sqrt(p/n) (p coefficients, n samples).
    """
    above = np.flatnonzero(x > x_out)
    cross = [j for j in above if f[j] < target]  # below the machine position of the jump-in
    j = (min(cross) if cross else above[-1] + 1) if above.size else 0
    # the crossing lies between samples j - 1 (f >= target) and j (f < target)
    if j < 1 or j >= x.size or f[j - 1] < target:
        return float("nan"), float("nan"), float("inf")
    lo, hi = max(0, j - window), min(x.size, j + window)
    res = []
    for deg in (3, 2):
        xs = x[lo:hi]
        x0, sc = 0.5 * (xs.min() + xs.max()), max(0.5 * np.ptp(xs), 1e-300)
        u = (xs - x0) / sc
        deg = min(deg, xs.size - 1)
        pf, pw, pd = (np.polyfit(u, v[lo:hi], deg) for v in (f, w, d))
        ua, ub = (x[j] - x0) / sc, (x[j - 1] - x0) / sc
        ga, gb = np.polyval(pf, ua) - target, np.polyval(pf, ub) - target
        if ga * gb > 0:
            r = ua + (ub - ua) * (target - f[j]) / (f[j - 1] - f[j])  # the fit misses: linear
        else:
            from scipy.optimize import brentq

            r = brentq(lambda v: np.polyval(pf, v) - target, ua, ub)
        resid = w[lo:hi] - np.polyval(pw, u)
        scatter = math.sqrt(float(resid @ resid) / max(xs.size - deg - 1, 1) * (deg + 1) / xs.size)
        res.append((float(np.polyval(pw, r)), float(np.polyval(pd, r)), scatter))
    # the model error (cubic vs quadratic) or the fitted value's scatter, the larger
    return res[0][0], res[0][1], max(abs(res[0][0] - res[1][0]), res[0][2])


def _trapezoid(w, d):
    return float(np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(d)))


def bem_loading_cycle(*, beta0, mu, n, machine_stiffness=None, branch=None, margin=None, law="dugdale",
                      threads=None, options=None):
    """Loading-unloading cycle of the BEM under a machine spring: both jumps and the energy lost.

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity of the geometry, in (0, 1] [-].
    mu : float
        Transition parameter of Eq. (35), > 0 [-].
    n : int
        Cells per axis (even, >= 8).
    machine_stiffness : array_like or None
        K* > 0 and finite in the paper's units (:func:`dhfield.analysis.spring.stiffness_star`),
        or None: a rigid machine [-].  Under load control, K* = 0, the energy lost
        is infinite (:func:`dhfield.analysis.spring.loading_cycle`).
    branch : BemBranch, optional
        A branch sampled with ``landing`` holding these stiffnesses (default:
        sampled here).
    margin : float, optional
        Domain margin; default one whose domain holds the softest spring's landing
        state (:func:`_cycle_margin`, from MD and the DH zone).
    law : {'dugdale', 'exponential'}
        As :func:`bem_unloading_branch`.
    threads : int, optional
        As :func:`bem_unloading_branch`.
    options : BranchOptions, optional
        As :func:`bem_unloading_branch`.

    Returns
    -------
    dict
        Arrays of the shape of K*: ``machine_stiffness_star``;
        ``jump_in_start_delta_star`` (-h0: where the force-free approach ends),
        ``jump_in_W_star``, ``jump_in_W_star_error``, ``jump_in_delta_star`` (where
        it lands); ``jump_out_W_star``, ``jump_out_W_star_error``,
        ``jump_out_delta_star``, ``jump_out_adhesive_force`` (F_a where the jump out starts,
        on the branch's abscissa); ``separation_delta_star``; ``energy_lost_star``
        and ``energy_lost_error_star`` (units of :func:`dhfield.analysis.spring.loading_cycle`);
        ``resolved``; and ``branch``.

    Notes
    -----
    The cycle of :mod:`dhfield.analysis.spring` on the BEM's branch.  With the Dugdale
    law the approach from separation is force-free until the central gap reaches
    the range h0 (delta_s = -h0); the separated branch is unstable there, and the
    contact jumps at fixed machine position to the stable state where
    s delta* + (1 - s) W* = s delta_s (a cubic of the samples in sqrt(F_a) around
    the crossing; error: the change with a quadratic).  The jump out is
    :func:`bem_pull_off_under_spring`.  The energy lost per cycle is

    .. math:: U^* = -\\int_{o}^{i} W^*\\,d\\delta^* + \\frac{W_o^{*2} - W_i^{*2}}{2K^*}

    along the branch from the jump out to the landing, by the trapezoid rule over
    the samples and the two end states; its error estimate is the change with every
    other sample plus the end states' load errors times the approach spanned.
    """
    if machine_stiffness is not None:
        k = np.asarray(spring_weight(machine_stiffness)[1], float)
        if np.any(k <= 0.0):
            raise ValueError("machine_stiffness of a cycle must be > 0 and finite (or None: a rigid machine); "
                             f"got {machine_stiffness!r} (K* = 0 loses an infinite energy)")
    s, k = spring_weight(machine_stiffness)
    shape = np.shape(s)
    s1 = np.atleast_1d(s).astype(float)
    k1 = np.broadcast_to(np.atleast_1d(k), s1.shape).astype(float)
    if branch is None:
        mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
        beta0 = float(check_ellipticity("beta0", beta0))
        if margin is None:
            finite = k1[np.isfinite(k1)]
            margin = _cycle_margin(mu, beta0, finite) if finite.size else None
        landing = [1e300 if not np.isfinite(v) else v for v in k1]
        branch = bem_unloading_branch(beta0=beta0, mu=mu, n=n, landing=landing, margin=margin, law=law,
                                      threads=threads, options=options)
    elif not isinstance(branch, BemBranch):
        raise ValueError(f"branch must be a BemBranch (from bem_unloading_branch); got {type(branch).__name__}")
    x = np.sqrt(branch.adhesive_force)
    w, d = branch.W_star, branch.delta_star
    ds = branch.start_delta
    keys = ("jump_in_W_star", "jump_in_W_star_error", "jump_in_delta_star", "jump_out_W_star",
            "jump_out_W_star_error", "jump_out_delta_star", "separation_delta_star", "energy_lost_star",
            "energy_lost_error_star")
    out = {key: np.full(s1.shape, np.nan) for key in keys}
    out["resolved"] = np.zeros(s1.shape, bool)
    out["jump_out_adhesive_force"] = np.full(s1.shape, np.nan)
    for m, (sm, km) in enumerate(zip(s1, k1)):
        po = _jump_out(branch, None if not np.isfinite(km) else km)
        w_o, d_o, e_o = float(po["W_star"]), float(po["delta_star"]), float(po["W_star_error"])
        x_o = math.sqrt(float(po["adhesive_force"]))
        out["jump_out_adhesive_force"][m] = po["adhesive_force"]
        f = sm * d + (1.0 - sm) * w
        w_i, d_i, e_i = _landing(x, f, w, d, x_o, sm * ds, branch.window)
        sep = d_o if not np.isfinite(km) else d_o + w_o / km
        # samples strictly between the jump out and the landing, in loading order (x ascending)
        between = np.flatnonzero((x > x_o) & (f < sm * ds)) if np.isfinite(w_i) else np.array([], int)
        between = between[np.argsort(x[between])]
        ww = np.concatenate([[w_o], w[between], [w_i]])
        dd = np.concatenate([[d_o], d[between], [d_i]])
        integ = _trapezoid(ww, dd)
        coarse = _trapezoid(np.concatenate([ww[:-1:2], ww[-1:]]), np.concatenate([dd[:-1:2], dd[-1:]]))
        spring = 0.0 if not np.isfinite(km) else (w_o ** 2 - w_i ** 2) / (2.0 * km)
        energy = -integ + spring
        spring_err = 0.0 if not np.isfinite(km) else (abs(w_o) * e_o + abs(w_i) * e_i) / km
        err = abs(integ - coarse) + (e_o + e_i) * abs(d_i - d_o) + spring_err
        for key, v in zip(keys, (w_i, e_i, d_i, w_o, e_o, d_o, sep, energy, err)):
            out[key][m] = v
        out["resolved"][m] = bool(po["resolved"]) and np.isfinite(w_i) and np.isfinite(err)
    rec = {"machine_stiffness_star": k1, "jump_in_start_delta_star": np.full(s1.shape, ds), **out}
    rec = {key: v.reshape(shape)[()] for key, v in rec.items()}
    rec["branch"] = branch
    return rec
