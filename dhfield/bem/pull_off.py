"""The adhesive BEM pull-off in the paper's units (R = E* = Delta gamma = 1, Eqs. 32-35).

:func:`adhesive_pull_off` sets up the crossed-cylinder problem of the paper
(:func:`nondimensional_problem`) and runs :func:`dhfield.bem.path.unloading_path`
on it; under load control it brackets the minimum of the unloading load with
states warm-started from coarser grids (:class:`NestedWarmStart`), or, with
``search='located'``, locates the minimum on the coarser grids and solves only
3-4 states on the fine one (half the time at lambda = 3, N = 256).
:func:`refine_pull_off` carries a pull-off to a finer grid (coarse to fine,
:func:`interpolate_state`); :func:`richardson_extrapolation` extrapolates
pull-offs over N.
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from .._validation import check_count, check_ellipticity, check_positive
from .laws import DugdaleLaw, ExponentialLaw, check_law, law_from_name
from .operator import Grid
from .state import ContactState
from .path import PathProgress, UnloadingPath, unloading_path
from .solver import (DEFAULT_MAX_ITER, DEFAULT_TOL, AdhesiveProblem, Prediction, secant_prediction,
                     solve_problem)

__all__ = ["adhesive_pull_off", "AdhesivePullOff", "nondimensional_problem", "NondimensionalProblem",
           "NestedWarmStart", "refine_pull_off", "interpolate_state", "richardson_extrapolation",
           "DISPLACEMENT_CONTROL_NOTE", "DOMAIN_MARGIN", "DEFAULT_STEPS", "SEARCHES"]


#: Half-width of the domain per expected semi-axis of the largest cohesive zone of
#: the path (the zone must lie inside the grid; DC-FFT needs no margin beyond it).
DOMAIN_MARGIN = 1.15
#: Default number of unloading steps from the start of unloading to the expected jump.
DEFAULT_STEPS = 20
#: Largest grid accepted (cells per axis): 2^16 x 2^16 cells already need ~100 GB of working arrays.
MAX_CELLS = 2 ** 16
#: Largest count of path steps (n_steps, window, refine_factor) accepted.
MAX_STEPS = 10 ** 6


@dataclass(frozen=True)
class NondimensionalProblem:
    """The crossed-cylinder problem in the paper's units (R = E* = Delta gamma = 1).

    Attributes
    ----------
    mu, beta0 : float
        Tabor parameter (Eq. 35) and initial ellipticity (Hertz b/a) [-].
    grid : Grid
        n x n cells over ``[-half_width_x, half_width_x] x [-half_width_y, half_width_y]``
        (rectangular cells when beta0 < 1: as many cells across the minor axis
        as across the major one).
    initial_gap : ndarray
        z = x^2/(2R') + y^2/(2R''), Eq. (2), with R' = sqrt(rho), R'' = 1/sqrt(rho),
        rho = R'/R'' of beta0 (so R = sqrt(R'R'') = 1) [c_r].
    law : DugdaleLaw or ExponentialLaw
        sigma0 = mu, range 1/mu (Delta gamma = 1).
    sin_skew : float
        sin(theta_skew) of beta0, the factor of Eq. (34).
    approach_max, approach_step : float
        Start of unloading and unloading step [c_r^2/R], from the analytic DH
        model (:func:`dhfield.model.pull_off`, :func:`dhfield.model.load_curve`).
    pull_off_approach : float
        Approach at the analytic load-control pull-off [c_r^2/R]: where the
        bracket search of :func:`unloading_path` starts.  For beta0 < 1 that of
        the two-axis closure (``dh-elliptic-two-axis``: its adhesive ellipse is
        not tied to beta0, like the BEM's), at beta0 = 1 (and if the closure
        fails) that of the DH model (:func:`dhfield.model.pull_off`).
    pull_off_zone : (float, float)
        Semi-axes (c, d) of the same model's cohesive zone at that pull-off
        [c_r]: the zone of the bracket search's cold start.
    """

    mu: float
    beta0: float
    grid: Grid
    initial_gap: np.ndarray = field(repr=False)
    law: DugdaleLaw | ExponentialLaw
    sin_skew: float
    approach_max: float
    approach_step: float
    pull_off_approach: float = float("nan")
    pull_off_zone: tuple = (float("nan"), float("nan"))

    def start_stress(self) -> np.ndarray:
        """sigma0 on the analytic cohesive zone at pull-off, full grid [stress] (a cold start)."""
        c, d = self.pull_off_zone
        x, y = self.grid.mesh()
        return self.law.max_stress * ((x / c) ** 2 + (y / d) ** 2 < 1.0).astype(float)


def nondimensional_problem(mu, beta0, n, *, law="dugdale", n_steps=DEFAULT_STEPS,
                           margin=DOMAIN_MARGIN) -> NondimensionalProblem:
    """Grid, initial gap, law and path range of the paper's problem at (mu, beta0).

    Parameters
    ----------
    mu : float
        Tabor parameter of Eq. (35), > 0 [-]; sigma0 = mu in these units.
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    n : int
        Cells along each axis (even, >= 8) [-].
    law : {'dugdale', 'exponential'}
        Traction law with sigma0 = mu and Delta gamma = 1.
    n_steps : int
        Unloading steps from the start of unloading to the expected jump.
    margin : float
        Domain half-width per expected zone semi-axis.

    Notes
    -----
    The analytic DH model gives the expected pull-off (a_po, delta_po).  Unloading
    starts at a* = 1.1 a_po + 0.15 (a state on the stable branch, above pull-off), whose DH
    approach is ``approach_max`` and whose adhesive semi-axis c* sets the domain:
    half-widths ``margin c*`` along x and ``margin c* beta0^(3/4)`` along y (the
    adhesive ellipse is rounder than the contact ellipse).  The step takes the
    path in ``n_steps`` from ``approach_max`` to 20 % beyond the analytic
    displacement-control pull-off.  The bracket search's cold start
    (``pull_off_approach``, ``pull_off_zone``) is the two-axis closure's pull-off
    for beta0 < 1: the DH zone (d = beta0 c) is tens of cells off the BEM's at
    mu = 5, beta0 = 0.5, N = 512, where its cold start does not converge.
    """
    from .. import model
    from ..geometry import radius_ratio, sin_skew_angle

    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    n = check_count("n", n, 8, MAX_CELLS, "cells per axis, even")
    if n % 2:
        raise ValueError(f"n must be an even integer in [8, {MAX_CELLS}] (cells per axis); got {n!r}")
    n_steps = check_count("n_steps", n_steps, 4, MAX_STEPS, "unloading steps")
    margin = float(check_positive("margin", margin, "domain half-width per zone semi-axis"))
    law_obj = law_from_name(law, mu, 1.0) if isinstance(law, str) else check_law(law)
    if law_obj is None:
        raise ValueError("law must be 'dugdale' or 'exponential'; got None")
    rho = float(radius_ratio(beta0))
    r_major, r_minor = math.sqrt(rho), 1.0 / math.sqrt(rho)
    po = model.pull_off(mu, beta0)
    pod = model.pull_off(mu, beta0, control="displacement")
    a_start = 1.1 * float(po.a_star) + 0.15
    cur = model.load_curve(mu, beta0, [a_start])
    c_start = float(cur.c_star[0])
    d_max = float(cur.delta_star[0])
    d_end = float(pod.delta_star) - 0.2 * (d_max - float(pod.delta_star))
    lx = margin * c_start
    ly = margin * c_start * beta0 ** 0.75
    grid = Grid.centered(n, lx, half_width_y=ly)
    x, y = grid.mesh()
    z = x * x / (2.0 * r_major) + y * y / (2.0 * r_minor)  # Eq. (2)
    # the cold start of the bracket search: the analytic load-control pull-off state
    start = _two_axis_start(mu, beta0) if beta0 < 1.0 else None
    if start is None:
        at_po = model.load_curve(mu, beta0, [max(float(po.a_star), 1e-3 * a_start)])
        start = (float(po.delta_star), (float(at_po.c_star[0]), float(at_po.d_star[0])))
    return NondimensionalProblem(mu, beta0, grid, z, law_obj, float(sin_skew_angle(beta0)), d_max,
                                 (d_max - d_end) / int(n_steps), start[0], start[1])


@functools.lru_cache(maxsize=64)
def _two_axis_start(mu, beta0):
    """(approach, (c, d)) at the load-control pull-off of the two-axis closure, or None if it fails.

    The paper's closure keeps d = beta0 c; the BEM's adhesive ellipse is rounder (beta_cd =
    0.593 at beta0 = 0.5, mu = 5), and a cold start from the paper's zone (48 cells short
    along y at N = 512) creeps for 300 outer iterations without converging.  The two-axis
    closure (beta_cd free) is within 0.8 % of the BEM's pull-off approach and 0.4 % of its
    c, d there, and the cold start converges (measured: 73 outer iterations;
    ``python -m verification.diagnose_adhesive --beta0 0.5 --mu 5 --n 512``).
    """
    from .. import compare

    try:
        rec = compare.pull_off("dh-elliptic-two-axis", mu, beta0, "load")
        out = (float(rec["delta_star"]), (float(rec["c_star"]), float(rec["d_star"])))
    except (ValueError, ArithmeticError):
        return None
    return out if np.all(np.isfinite([out[0], *out[1]])) and min(out[1]) > 0 else None


@dataclass(frozen=True)
class AdhesivePullOff:
    """Pull-off of the BEM adhesive contact in the paper's units (Eqs. 32-35).

    Attributes
    ----------
    mu, beta0 : float
        Tabor parameter (Eq. 35) and initial ellipticity [-].
    n : int
        Cells per axis.
    law, control : str
        Traction law name; 'load' or 'displacement'.
    W_star : float
        W sin(theta_skew(beta0))/(2 pi R Delta gamma), Eq. (34) (negative: tensile).
    a_star, b_star, c_star, d_star : float
        Second-moment semi-axes of the contact and of contact U cohesive zone
        at pull-off [c_r].
    beta_ab, beta_cd : float
        b/a and d/c at pull-off (NaN without contact).
    delta_star : float
        Approach at pull-off [c_r^2/R].
    converged : bool
        True when every state of the path down to the pull-off converged
        (:attr:`UnloadingPath.pull_off_converged`); ``failures`` lists all.
    n_steps : int
        Solved states on the path.
    iterations : int
        Inner CG iterations over the whole path.
    residual : float
        Largest residual over the path.
    failures : tuple of dict
        Unconverged states (approach, residual, iterations, phase).
    resolved : bool
        False when the grid is too coarse to resolve the Dugdale edge
        (dx > 2 E* h0/(kappa_n sigma0), see ``EDGE_WIDTH_FACTOR``): increase n.
    half_width_x, half_width_y : float
        Domain half-widths [c_r].
    elapsed : float
        Wall time of the path [s].
    path : UnloadingPath
        The whole path.
    W_star_error : float
        Displacement control: error estimate of ``W_star`` from the fit around
        the fold (:func:`dhfield.bem.continuation.fold_by_adhesive_force`),
        without the grid's discretisation error; NaN under load control.
    note : str
        Caveats on the pull-off (empty under load control): every
        displacement-control result carries :data:`DISPLACEMENT_CONTROL_NOTE`
        (its measured errors against Maugis-Dugdale), and says when the branch
        ends by loss of contact or no fold was bracketed.
    search : str
        The route that gave the pull-off: under load control the search that
        bracketed the minimum ('located', 'bracket', or 'march', also when a
        requested search fell back to it); 'continuation' under displacement
        control (:mod:`dhfield.bem.continuation`); 'refine' for
        :func:`refine_pull_off`.
    """

    mu: float
    beta0: float
    n: int
    law: str
    control: str
    W_star: float
    a_star: float
    b_star: float
    c_star: float
    d_star: float
    beta_ab: float
    beta_cd: float
    delta_star: float
    converged: bool
    n_steps: int
    iterations: int
    residual: float
    failures: tuple
    resolved: bool
    half_width_x: float
    half_width_y: float
    elapsed: float
    path: UnloadingPath = field(repr=False, compare=False)
    W_star_error: float = float("nan")
    note: str = ""
    search: str = ""

    def as_dict(self) -> dict:
        """JSON-ready scalars (the path and failures summarised)."""
        out = {k: getattr(self, k) for k in (
            "mu", "beta0", "n", "law", "control", "W_star", "W_star_error", "a_star", "b_star", "c_star",
            "d_star", "beta_ab", "beta_cd", "delta_star", "converged", "resolved", "n_steps", "iterations",
            "residual", "half_width_x", "half_width_y", "elapsed", "note", "search")}
        out["failures"] = [dict(f) for f in self.failures]
        out["iterations_per_step"] = self.iterations / max(self.n_steps, 1)
        return out


#: Coarsest grid (cells per axis) solved for nested warm starts (:class:`NestedWarmStart`).
NESTED_MIN_N = 64


def _coarser_problem(problem, n):
    """``problem`` on the grid with ``n`` cells along x over the same domain (its analytic set-up reused).

    ``problem.grid.nx`` must be a multiple of ``n``.  Equal to :func:`nondimensional_problem` at
    ``n`` (the cell sizes are exact multiples: 2 lx/(n/k) = k (2 lx/n) in floating point), without
    its analytic DH pull-off and load-curve solves (~20 ms per level on a quiet machine).
    """
    from ..geometry import radius_ratio

    g = problem.grid
    k = g.nx // n
    grid = Grid(n, g.ny // k, g.dx * k, g.dy * k)
    rho = float(radius_ratio(problem.beta0))
    r_major, r_minor = math.sqrt(rho), 1.0 / math.sqrt(rho)
    x, y = grid.mesh()
    z = x * x / (2.0 * r_major) + y * y / (2.0 * r_minor)  # Eq. (2)
    return replace(problem, grid=grid, initial_gap=z)
#: Load-control searches of :func:`adhesive_pull_off`.
SEARCHES = ("bracket", "march", "located")


class NestedWarmStart:
    """Warm starts from the same approach solved on grids 2x, 4x, ... coarser (same domain).

    ``start(approach)`` solves the paper's problem at that approach on the grid with
    ``n/2`` cells per axis (itself warm-started the same way from ``n/4``, down to
    :data:`NESTED_MIN_N`; the coarsest level from its nearest solved state, the first
    one cold from the analytic DH zone at pull-off) and carries the state onto the
    ``n`` grid (:func:`interpolate_state`).  A fine state started there needs a
    fraction of the outer (zone) iterations of one warm-started from a neighbouring
    fine state (measured at lambda = 3, N = 256: 22 vs 74-87), and a coarse state
    costs ~1/5 of a fine one.

    Parameters
    ----------
    mu, beta0, n, law, margin
        As in :func:`nondimensional_problem` (``n`` is the *fine* grid).
    tol, max_iter, threads
        As in :func:`solve_adhesive`.
    problem : NondimensionalProblem, optional
        The fine grid's problem when already built (its grid must have ``n`` cells per
        axis); saves its analytic set-up.

    Attributes
    ----------
    states_solved, iterations : int
        Coarse states solved and their CG iterations, over all levels.
    """

    def __init__(self, mu, beta0, n, *, law="dugdale", margin=DOMAIN_MARGIN, tol=DEFAULT_TOL,
                 max_iter=DEFAULT_MAX_ITER, threads=None, problem=None):
        if problem is None:
            fine = nondimensional_problem(mu, beta0, n, law=law, margin=margin)
        elif isinstance(problem, NondimensionalProblem) and problem.grid.nx == n:
            fine = problem
        else:
            raise ValueError(f"problem must be the NondimensionalProblem of the fine grid (n = {n!r} cells)")
        nc = int(n) // 2
        if nc < NESTED_MIN_N or nc % 2:
            raise ValueError(f"n must be even and >= {2 * NESTED_MIN_N} for nested warm starts; got {n!r}")
        coarse = _coarser_problem(fine, nc)
        self.fine_grid = fine.grid
        self._fine_nd = fine
        self._fine_prob = None
        self._nd = coarse
        self._threads = threads
        self._prob = AdhesiveProblem(coarse.initial_gap, coarse.grid, coarse.law, None, threads, 1.0)
        self._cold = Prediction(np.zeros_like(self._prob.z), self._prob.to_work(coarse.start_stress()))
        self._tol, self._max_iter = float(tol), int(max_iter)
        self._inner = (NestedWarmStart(mu, beta0, nc, law=law, margin=margin, tol=tol, max_iter=max_iter,
                                       threads=threads, problem=coarse)
                       if nc // 2 >= NESTED_MIN_N and nc % 4 == 0 else None)
        self._states = {}
        self._n_solved = 0
        self._own_iterations = 0

    @property
    def states_solved(self) -> int:
        return self._n_solved + (self._inner.states_solved if self._inner else 0)

    @property
    def iterations(self) -> int:
        return self._own_iterations + (self._inner.iterations if self._inner else 0)

    def coarse_state(self, approach):
        """The state at ``approach`` on the coarse grid (solved once)."""
        d = float(approach)
        if d not in self._states:
            guess = self._inner(d) if self._inner else None
            if guess is None:
                good = [k for k, st in self._states.items() if st.converged and st.in_contact]
                guess = self._states[min(good, key=lambda k: abs(k - d))] if good else self._cold
            st = solve_problem(self._prob, d, guess, self._tol, self._max_iter)
            self._own_iterations += st.iterations
            self._n_solved += 1
            self._states[d] = st
        return self._states[d]

    def __call__(self, approach):
        """Warm start on the fine grid, or None when the coarse state is not a converged contact state.

        The coarse state interpolated onto the fine grid (:func:`interpolate_state`); for the
        Dugdale law its zone fraction is then the fine grid's own sub-cell fraction of the
        interpolated gap (the fine edge is sharper: its width scales with the cell), which
        starts the fine state ~10 % fewer outer and ~20 % fewer CG iterations from its
        solution (measured, lambda = 3, N = 256).
        """
        st = self.coarse_state(approach)
        if not (st.converged and st.in_contact):
            return None
        guess = interpolate_state(st, self.fine_grid)
        law = guess.law
        if not isinstance(law, DugdaleLaw):
            return guess
        if self._fine_prob is None:
            fine = self._fine_nd
            self._fine_prob = AdhesiveProblem(fine.initial_gap, fine.grid, fine.law, None, self._threads, 1.0)
        fp = self._fine_prob
        zone = fp.to_full(fp.stress_from_gap(fp.to_work(guess.gap), fp.to_work(guess.contact)) / law.max_stress)
        return replace(guess, pressure=guess.repulsive_pressure - law.max_stress * zone,
                       cohesive=np.where(guess.contact, 0.0, zone))

    def locate_pull_off(self, spacing):
        """Approach of the load-control pull-off on the coarse grid (NaN when not found).

        The coarsest level whose Dugdale edge is (nearly) resolved
        (:data:`LOCATE_MAX_EDGE_RATIO`) runs the bracket search (:func:`unloading_path` with the analytic DH guess, and
        the coarser levels as warm starts); every finer level solves the approaches of the lattice
        ``approach_max - j spacing`` next to the pull-off of the level below
        (:func:`_lattice_minimum`, warm-started from that level) and returns the
        vertex of their parabola.  The states are kept for the warm starts.  NaN
        when this grid is too coarse for the Dugdale edge.
        """
        nd = self._nd
        if self._prob.edge_width_ratio > LOCATE_MAX_EDGE_RATIO:
            return float("nan")           # the Dugdale edge is far from resolved here: no reliable minimum
        if self._inner is None or self._inner._prob.edge_width_ratio > LOCATE_MAX_EDGE_RATIO:
            # the coarsest resolved grid: the bracket search (warm starts from the grid below, if any)
            path = unloading_path(nd.initial_gap, nd.grid, nd.law, nd.approach_max, nd.approach_step,
                                  control="load", refine_levels=LOCATE_BOTTOM_REFINE, tol=self._tol,
                                  max_iter=self._max_iter, threads=self._threads,
                                  keep_states=True, progress=False, approach_guess=nd.pull_off_approach,
                                  start_stress=nd.start_stress(), warm_start=self._inner)
            for st in path.states:
                if st.converged and st.in_contact and st.approach not in self._states:
                    self._states[st.approach] = st
            self._own_iterations += int(path.iterations.sum())
            self._n_solved += path.n_steps
            return float(path.pull_off_approach)
        below = self._inner.locate_pull_off(spacing)
        if not np.isfinite(below):
            return float("nan")
        _, sm = _lattice_minimum(self.coarse_state, below, nd.approach_max, spacing)
        return float("nan") if (sm is None or sm.at_boundary) else float(sm.x)


#: Spacing of the approach lattice of the located search (``search='located'``), in unloading
#: steps: the lattice is ``approach_max - j approach_step / LOCATE_DIVISIONS`` on every grid, so
#: the samples of one level are the warm starts of the next (the first refinement level of the
#: marching path has the same spacing).
LOCATE_DIVISIONS = 2
#: Cap on lattice samples added when the load minimum sits at an end of the samples.
LOCATE_MAX_EXTEND = 6
#: Cap on the parabola-vertex states solved on the fine grid after the lattice samples.
LOCATE_VERTEX_STATES = 1
#: Vertex refinements of the bracket search on the coarsest grid of the located search: none,
#: the next grid's lattice samples re-locate the minimum anyway (measured over 4 cases at
#: N = 256: the same pull-offs, 10 % less CPU than 2).
LOCATE_BOTTOM_REFINE = 0
#: Coarse grids of the located search must have an ``AdhesiveProblem.edge_width_ratio`` (edge
#: width wanted / its cap 2 h0; > 1 is flagged unresolved) of at most this.  Measured: the
#: states converge at 1.10 (lambda = 3, N = 64) and 1.18 (mu = 5, N = 256), and not at 2.1-3.8
#: (mu = 5, N = 64-128: 35 s of unconverged coarse states before the fall-back to 'bracket').
LOCATE_MAX_EDGE_RATIO = 1.25
#: Solver tolerance of the coarse grids of the located search (the fine grid keeps ``tol``).
#: Their states only locate the minimum and start the fine states: a zone-fraction error of
#: 1e-4 moves a coarse load by ~3e-5 relative (measured), far below the lattice jaggedness of
#: the load (~5e-4), and far below the coarse-to-fine interpolation error of a warm start.
LOCATE_COARSE_TOL = 1e-4


def _usable(st):
    return bool(st.converged and st.in_contact)


def _lattice_minimum(solve, approach, top, spacing, max_extend=LOCATE_MAX_EXTEND):
    """Samples of the lattice ``top - j spacing`` around ``approach`` until the load minimum is interior.

    ``solve(delta)`` returns the state at delta.  Three samples next to ``approach``, then
    one more beyond the end holding the lowest load, until the discrete minimum is interior
    (or the branch ends there, or ``max_extend`` samples were added).  Returns
    ``({j: state}, SampledMinimum or None)`` (None: no converged contact state).
    """
    from ..pull_off_search import refine_sampled_minimum

    j0 = int(round((top - approach) / spacing))
    solved = {j: solve(top - j * spacing) for j in (j0 - 1, j0, j0 + 1)}
    sm = None
    for k in range(max_extend + 1):
        js = sorted(solved)
        w = np.array([solved[j].load if _usable(solved[j]) else np.nan for j in js])
        if not np.isfinite(w).any():
            return solved, None
        sm = refine_sampled_minimum(top - np.array(js) * spacing, w, first=False)
        if not sm.at_boundary or k == max_extend:
            break
        if sm.index == 0:
            j = js[0] - 1                 # minimum at the top: back up the branch
        elif sm.index == len(js) - 1:
            j = js[-1] + 1                # at the bottom: further down
        else:
            break                         # next to a failed state: the branch ends there
        solved[j] = solve(top - j * spacing)
    return solved, sm


def _located_path(nd, n, ws, *, refine_levels, refine_factor, tol, max_iter, threads, keep_states,
                  progress):
    """The load-control pull-off located on coarser grids (``search='located'``), or None.

    ``ws.locate_pull_off`` finds the pull-off on the grid half as fine (recursively: the
    bracket search on the coarsest grid, three lattice samples on every finer one); on this
    grid only the lattice samples around it (:func:`_lattice_minimum`) and at most
    ``refine_levels`` parabola vertices are solved, each warm-started from the same
    approach on the coarser grid.  None when the located minimum is not interior or a state
    did not converge (the caller then runs the bracket search).
    """
    from ..pull_off_search import refine_sampled_minimum

    t0 = time.perf_counter()
    spacing = nd.approach_step / LOCATE_DIVISIONS
    d_coarse = ws.locate_pull_off(spacing)
    if not np.isfinite(d_coarse):
        return None
    prob = AdhesiveProblem(nd.initial_gap, nd.grid, nd.law, None, threads, 1.0)
    prog = PathProgress(progress, f"located N={int(n)}")
    states, phases = [], []

    def run(delta, phase):
        guess = ws(delta)
        if guess is None:                 # the coarse state is off the branch: the nearest fine state
            good = [st for st in states if _usable(st)]
            guess = min(good, key=lambda st: abs(st.approach - delta)) if good else None
        st = solve_problem(prob, float(delta), guess, tol, int(max_iter))
        states.append(st)
        phases.append(phase)
        prog.update(len(states), st, phase)
        return st

    solved, sm = _lattice_minimum(lambda d: run(d, "unloading"), d_coarse, nd.approach_max, spacing)
    xtol = nd.approach_step / int(refine_factor) ** int(refine_levels)

    def minimum():
        order = sorted((i for i in range(len(states)) if _usable(states[i])), key=lambda i: -states[i].approach)
        x = np.array([states[i].approach for i in order])
        return order, x, refine_sampled_minimum(x, np.array([states[i].load for i in order]), first=False)

    if sm is not None and not sm.at_boundary and all(st.converged for st in states):
        for _ in range(min(int(refine_levels), LOCATE_VERTEX_STATES)):
            order, x, sm = minimum()
            if sm.at_boundary or float(np.min(np.abs(x - sm.x))) <= xtol:
                break
            if not _usable(run(sm.x, "refine")):
                break
    prog.close()
    if sm is None or not all(st.converged for st in states):
        return None
    order, x, sm = minimum()
    if sm.at_boundary:
        return None
    recs = [{**st.summary(), "phase": ph} for st, ph in zip(states, phases)]   # all converged (checked above)
    return UnloadingPath.from_records(
        recs, control="load", pull_off_load=sm.y, pull_off_approach=sm.x, pull_off_state=states[order[sm.index]],
        states=tuple(states) if keep_states else (), elapsed=time.perf_counter() - t0, pull_off_converged=True,
        resolved=prob.resolved, coarse_states=ws.states_solved, coarse_iterations=ws.iterations)


def adhesive_pull_off(mu, beta0, n, *, law="dugdale", control="load", n_steps=DEFAULT_STEPS,
                      refine_levels=2, tol=DEFAULT_TOL, max_iter=DEFAULT_MAX_ITER,
                      margin=DOMAIN_MARGIN, threads=None, keep_states=False,
                      progress=None, search="located", nested=None) -> AdhesivePullOff:
    """BEM pull-off of the adhesive crossed-cylinder (elliptical) contact, paper units.

    Parameters
    ----------
    mu : float
        Tabor parameter, Eq. (35), > 0 [-] (sigma0 = mu, Delta gamma = 1).
    beta0 : float
        Initial ellipticity (Hertz b/a of the geometry) in (0, 1] [-].
    n : int
        Cells per axis (even) [-].
    law : {'dugdale', 'exponential'}
        Traction law (:mod:`dhfield.bem.laws`).
    control : {'load', 'displacement'}
        Load control: the minimum of the unloading load.  Displacement control:
        the jump, the minimum of the approach along the branch (its fold, or
        the loss of contact; :mod:`dhfield.bem.continuation`).

    Returns
    -------
    AdhesivePullOff
        W* in the normalisation of Eq. (34) with sin(theta_skew) of beta0, like
        every other model of :mod:`dhfield.compare`; semi-axes in c_r.

    Other Parameters
    ----------------
    n_steps, refine_levels, tol, max_iter, threads, keep_states, progress
        See :func:`nondimensional_problem`, :func:`unloading_path` and
        :func:`solve_adhesive`.
    margin : float
        Domain half-width per expected zone semi-axis.
    search : {'located', 'bracket', 'march'}
        Load control only (the route taken is :attr:`AdhesivePullOff.search`).
        'located' (default) is 'bracket' with the minimum located on coarser
        grids first (below).  'bracket': cold-start at the analytic DH
        pull-off approach from the DH cohesive zone and bracket the load minimum
        there (a handful of states; :func:`unloading_path` with
        ``approach_guess``).  'march': unload from ``approach_max`` in uniform
        steps to the jump and refine the minimum's bracket (the path of
        dhfield <= the first session; ~5x more states, same pull-off).
        'located': the minimum is located on the grids 2x, 4x, ... coarser (the
        bracket search on the coarsest, N = 64; three samples of the approach
        lattice ``approach_max - j approach_step/2`` around the coarser
        level's minimum on every finer one), and on this grid only those
        lattice samples and at most one parabola vertex (none with
        ``refine_levels=0``) are solved, each from the same approach on the
        grid half as fine: 3-4 fine states instead of 4-6 (measured at
        N = 256), the same pull-off to the jaggedness of the discrete load
        curve (~5e-4).  Falls back to 'bracket' (keeping the coarse
        states) when ``n < 2 NESTED_MIN_N``, when the grid half as fine is too
        coarse for the Dugdale edge (:data:`LOCATE_MAX_EDGE_RATIO`), when the
        located minimum is not interior, or when a fine state does not converge.
    nested : bool, optional
        Bracket search only: start every state from the same approach solved
        on a grid half as fine (:class:`NestedWarmStart`).  Default: when
        ``n >= 2 * NESTED_MIN_N``.

    Notes
    -----
    With R = E* = Delta gamma = 1 (Eqs. 32-35): the initial gap is Eq. (2) with
    R' R'' = 1, the law has sigma0 = mu and range 1/mu, and

    .. math:: W^* = \\frac{W \\sin\\theta_{skew}}{2\\pi R\\Delta\\gamma}

    (Eq. 34).  The domain and the path come from :func:`nondimensional_problem`.
    """
    if search not in SEARCHES:
        raise ValueError(f"search must be one of {SEARCHES} (load-control path); got {search!r}")
    prob = nondimensional_problem(mu, beta0, n, law=law, n_steps=n_steps, margin=margin)
    guess = {}
    if control == "load" and search != "march" and np.all(np.isfinite(prob.pull_off_zone)):
        guess = dict(approach_guess=prob.pull_off_approach, start_stress=prob.start_stress())
        if nested is None or search == "located":
            nested = int(n) >= 2 * NESTED_MIN_N and int(n) % 4 == 0
        if nested:
            # the located search's coarse states only locate the minimum and start the fine states
            coarse_tol = max(tol, LOCATE_COARSE_TOL) if search == "located" else tol
            guess["warm_start"] = NestedWarmStart(mu, beta0, n, law=law, margin=margin, tol=coarse_tol,
                                                  max_iter=max_iter, threads=threads, problem=prob)
        if search == "located" and nested:
            path = _located_path(prob, n, guess["warm_start"], refine_levels=refine_levels, refine_factor=4,
                                 tol=tol, max_iter=max_iter, threads=threads, keep_states=keep_states,
                                 progress=progress)
            if path is not None:
                return _pull_off_result(prob, int(n), path, "located")
    if control == "displacement" and np.all(np.isfinite(prob.pull_off_zone)):
        # the branch is followed by adhesive force from the DH load-control pull-off (unloading_path)
        guess = dict(approach_guess=prob.pull_off_approach, start_stress=prob.start_stress())
    path = unloading_path(prob.initial_gap, prob.grid, prob.law, prob.approach_max, prob.approach_step,
                          control=control, refine_levels=refine_levels, tol=tol, max_iter=max_iter,
                          threads=threads, keep_states=keep_states, progress=progress, **guess)
    if control == "displacement":
        route = "continuation"
    elif "approach_guess" in guess and not np.any(path.phase == "discarded"):
        route = "bracket"
    else:
        route = "march"     # requested, or the bracket's cold start gave no contact state
    return _pull_off_result(prob, int(n), path, route)


#: Accuracy carried by every displacement-control pull-off (:attr:`AdhesivePullOff.note`).
#: Measured on the sphere against Maugis-Dugdale's displacement-control pull-off (the
#: minimum of delta(a), or its end a = 0) with
#: ``.venv/bin/python -m verification.displacement_pull_off`` (2026-11-23), N = 128 / 256:
#: lambda = 0.3: -0.12 / -0.03 %; 0.6: +0.26 / -0.02 %; 1: -0.57 / -0.43 %; 1.5: +0.80 / +0.44 %;
#: 2: +0.38 / +0.27 %; 3: +0.09 / -0.08 %, each inside W_star_error except lambda = 1 at
#: N = 128 (0.0026 vs 0.0021).  Near lambda = 1 the fold lies within ~1e-3 in approach of
#: the end a = 0 of the contact branch (2.7 % apart in W): on coarse grids the lattice
#: jaggedness of the approach hides it (N = 96: -3.1 %, inside its estimate 6 %).  (The fold
#: extrapolated from states before the jump, used until then, was -6 % to +18 % off.)
DISPLACEMENT_CONTROL_NOTE = (
    "displacement-control pull-off: the minimum of the approach along the branch followed by adhesive "
    "force (the fold, or the loss of contact); on the sphere within 0.8 % of Maugis-Dugdale for "
    "lambda = 0.3-3 at N = 128/256, inside W_star_error but at lambda = 1, N = 128 (0.57 % vs 0.48 %); "
    "near lambda = 1 coarser grids can mistake the loss of contact for the fold (N = 96: -3.1 %)")


def _pull_off_result(prob: NondimensionalProblem, n: int, path: UnloadingPath, search: str) -> AdhesivePullOff:
    """The pull-off of a path in the paper's units (Eq. 34), with the semi-axes of its state."""
    note = path.pull_off_note
    if path.control == "displacement":
        note = "; ".join(filter(None, (note, DISPLACEMENT_CONTROL_NOTE)))
    st = path.pull_off_state
    a, b = st.contact_semi_axes()
    c, d = st.cohesive_semi_axes()
    scale = prob.sin_skew / (2.0 * math.pi)  # Eq. (34): W* = W sin(theta_skew) / (2 pi R dgamma)
    return AdhesivePullOff(
        mu=prob.mu, beta0=prob.beta0, n=int(n), law=prob.law.name, control=path.control,
        W_star=float(path.pull_off_load * scale), a_star=a, b_star=b, c_star=c, d_star=d,
        beta_ab=b / a if a > 0 else float("nan"), beta_cd=d / c if c > 0 else float("nan"),
        delta_star=float(path.pull_off_approach), converged=path.pull_off_converged, n_steps=path.n_steps,
        iterations=int(path.iterations.sum()), residual=float(path.residual.max()), failures=path.failures,
        resolved=path.resolved, half_width_x=0.5 * prob.grid.nx * prob.grid.dx,
        half_width_y=0.5 * prob.grid.ny * prob.grid.dy, elapsed=path.elapsed, path=path,
        W_star_error=float(abs(path.pull_off_error * scale)), note=note, search=search)


def richardson_extrapolation(n, values):
    """Richardson extrapolation of a quantity computed at three grid sizes.

    Parameters
    ----------
    n : sequence of 3 int
        Cells per axis, in geometric progression (e.g. 256, 512, 1024) [-].
    values : sequence of 3 float
        The quantity at each n.

    Returns
    -------
    (float, float)
        The extrapolated value and the observed order q of the error ~ n^-q
        (NaN order and the finest value when the differences are not monotone).

    Notes
    -----
    With ratio r = n2/n1 = n3/n2 and differences e1 = f2 - f1, e2 = f3 - f2:
    q = ln(e1/e2)/ln r and f_inf = f3 + e2/(r^q - 1).
    """
    n = [float(v) for v in n]
    f = [float(v) for v in values]
    if len(n) != 3 or len(f) != 3:
        raise ValueError("n and values must each have 3 entries")
    r = n[1] / n[0]
    if not math.isclose(n[2] / n[1], r, rel_tol=1e-9) or r <= 1.0:
        raise ValueError(f"n must be increasing in geometric progression; got {n}")
    e1, e2 = f[1] - f[0], f[2] - f[1]
    if e2 == 0.0:
        return f[2], float("inf")
    if e1 == 0.0 or e1 / e2 <= 1.0:
        return f[2], float("nan")
    q = math.log(e1 / e2) / math.log(r)
    return f[2] + e2 / (r**q - 1.0), q


# ============================================================================ coarse to fine
#: Half-width, in finest path steps, of the window of approaches solved around the
#: coarse pull-off by :func:`refine_pull_off` (the fine minimum moves by O(error) of
#: the coarse one: a fraction of a step at N >= 128).
REFINE_WINDOW = 3
#: Cap on window extensions when the fine minimum sits on the window's edge.
REFINE_MAX_EXTEND = 12


def interpolate_state(state, grid):
    """A path state carried onto another grid of the same domain (a warm start).

    Parameters
    ----------
    state : ContactState
        A solved state (with its repulsive pressure).
    grid : Grid
        Target grid (same physical domain, any cell counts).

    Returns
    -------
    ContactState
        Repulsive pressure and adhesive zone fraction bilinearly interpolated
        (clipped to p >= 0 and [0, 1]); gap and masks follow from them.  It is a
        *guess* for :func:`solve_adhesive` (``converged=False``), not a solution.
    """
    from scipy.interpolate import RegularGridInterpolator

    if not isinstance(state, ContactState) or state.repulsive_pressure is None:
        raise ValueError("state must be a solved ContactState with its repulsive pressure")
    if not isinstance(grid, Grid):
        raise ValueError(f"grid must be a dhfield.bem.Grid; got {type(grid).__name__}")
    src = state.grid
    if not (math.isclose(src.nx * src.dx, grid.nx * grid.dx, rel_tol=1e-9)
            and math.isclose(src.ny * src.dy, grid.ny * grid.dy, rel_tol=1e-9)):
        raise ValueError("grid must cover the same domain as the state's grid")
    xf, yf = grid.mesh()
    pts = np.stack([xf.ravel(), yf.ravel()], axis=-1)

    def carry(f):
        it = RegularGridInterpolator((src.x, src.y), np.asarray(f, float), bounds_error=False, fill_value=None)
        return it(pts).reshape(grid.shape)

    p = np.maximum(carry(state.repulsive_pressure), 0.0)
    zone = np.clip(carry(state.adhesive_zone), 0.0, 1.0) if state.law is not None else np.zeros(grid.shape)
    contact = p > 0
    law = state.law
    sigma0 = law.max_stress if law is not None else 0.0
    cohesive = np.where(contact, 0.0, zone)
    return ContactState(grid=grid, pressure=p - sigma0 * zone, gap=np.maximum(carry(state.gap), 0.0),
                        approach=state.approach, load=float("nan"), contact=contact, cohesive=cohesive,
                        law=law, converged=False, iterations=0, residual=float("inf"),
                        repulsive_pressure=p)


def refine_pull_off(coarse, n, *, n_steps=DEFAULT_STEPS, refine_levels=2, refine_factor=4,
                    window=REFINE_WINDOW, tol=DEFAULT_TOL, max_iter=DEFAULT_MAX_ITER, threads=None,
                    keep_states=False, progress=None) -> AdhesivePullOff:
    """Load-control pull-off on a finer grid, started from a coarser solution (coarse to fine).

    Parameters
    ----------
    coarse : AdhesivePullOff
        A pull-off of the same (mu, beta0, law) on a coarser grid (load
        control), e.g. from :func:`adhesive_pull_off` at N = 256 or from a
        previous call of this function.
    n : int
        Cells per axis of the fine grid (even, > ``coarse.n``) [-].
    window : int
        Half-width of the window of fine states around the coarse pull-off, in
        finest path steps (extended while the fine minimum sits on its edge).

    Returns
    -------
    AdhesivePullOff
        As :func:`adhesive_pull_off`, with ``path.phase == 'refine'`` for every
        state.  ``converged`` is True when every state of the window converged.

    Other Parameters
    ----------------
    n_steps, refine_levels, refine_factor
        The path settings of the full path (:func:`adhesive_pull_off`): the fine
        states sit on its finest approach lattice, ``approach_max - j h`` with
        ``h = approach_step / refine_factor**refine_levels``, so that the fine
        pull-off equals the full fine path's wherever both bracket the same
        samples.
    tol, max_iter, threads, keep_states, progress
        As in :func:`unloading_path`.

    Notes
    -----
    Only the states around the load minimum are solved on the fine grid.  The
    first is warm-started from the coarse pull-off state interpolated onto the
    fine grid (:func:`interpolate_state`), the others from their neighbours
    (secant predictor), descending in approach like an unloading path; the
    minimum is refined by :func:`dhfield.pull_off_search.refine_sampled_minimum`
    over the window.  The load-control pull-off lies on the stable branch of
    displacement control, so the warm start stays on the branch of the full
    path; multistability after the jump does not enter.
    """
    from ..pull_off_search import refine_sampled_minimum

    if not isinstance(coarse, AdhesivePullOff):
        raise ValueError(f"coarse must be an AdhesivePullOff; got {type(coarse).__name__}")
    if coarse.control != "load":
        raise ValueError(f"coarse must be a load-control pull-off; got control={coarse.control!r}")
    if not np.isfinite(coarse.delta_star):
        raise ValueError("coarse must hold a pull-off (its delta_star is NaN: no converged contact state)")
    n = check_count("n", n, 8, MAX_CELLS, "cells per axis")
    if n <= coarse.n:
        raise ValueError(f"n must be an integer > coarse.n = {coarse.n} (cells per axis); got {n!r}")
    window = check_count("window", window, 1, MAX_STEPS, "finest path steps")
    refine_levels = check_count("refine_levels", refine_levels, 0, 16, "bracket refinements")
    refine_factor = check_count("refine_factor", refine_factor, 2, MAX_STEPS, "step division per refinement")
    prob_nd = nondimensional_problem(coarse.mu, coarse.beta0, int(n), law=coarse.law, n_steps=n_steps)
    grid = prob_nd.grid
    if not (math.isclose(0.5 * grid.nx * grid.dx, coarse.half_width_x, rel_tol=1e-9)
            and math.isclose(0.5 * grid.ny * grid.dy, coarse.half_width_y, rel_tol=1e-9)):
        raise ValueError("coarse must come from the same domain (adhesive_pull_off with the default margin)")
    prob = AdhesiveProblem(prob_nd.initial_gap, grid, prob_nd.law, None, threads, 1.0)
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    h = prob_nd.approach_step / int(refine_factor) ** int(refine_levels)
    top = prob_nd.approach_max
    j_c = int(round((top - coarse.delta_star) / h))
    t0 = time.perf_counter()
    prog = PathProgress(progress, f"refine N={int(n)}")
    solved = {}                       # lattice index -> ContactState

    def run(j, guess):
        st = solve_problem(prob, top - j * h, guess, tol, int(max_iter))
        solved[j] = st
        prog.update(len(solved), st, "refine")
        return st

    # downwards from the top of the window: warm start from the coarse state, then secant
    first = interpolate_state(coarse.path.pull_off_state, grid)
    lo_j, hi_j = j_c - int(window), j_c + int(window)
    prev, st = None, first
    for j in range(lo_j, hi_j + 1):
        new = run(j, first if st is first else secant_prediction(prob, prev, st, top - j * h))
        prev, st = (None if st is first else st), new

    def minimum():
        js = sorted(solved)
        w = np.array([solved[j].load if (solved[j].converged and solved[j].in_contact) else np.nan for j in js])
        if not np.any(np.isfinite(w)):
            return js, w, None
        return js, w, refine_sampled_minimum(np.array([top - j * h for j in js]), w, first=False)

    for _ in range(REFINE_MAX_EXTEND):
        js, w, sm = minimum()
        if sm is None or not sm.at_boundary:
            break
        if sm.index == 0:             # minimum at the top: extend upwards (back along the branch)
            j = js[0] - 1
            run(j, secant_prediction(prob, solved[js[1]], solved[js[0]], top - j * h))
        else:                         # at the bottom: continue unloading
            j = js[-1] + 1
            run(j, secant_prediction(prob, solved[js[-2]], solved[js[-1]], top - j * h))
    prog.close()
    js, w, sm = minimum()
    states = [solved[j] for j in js]
    if sm is None:
        k_po, w_po, d_po = len(states) - 1, float("nan"), float("nan")
    else:
        k_po, w_po, d_po = sm.index, sm.y, sm.x
    recs = [{**s.summary(), "phase": "refine"} for s in states]
    failures = tuple({"approach": r["approach"], "residual": r["residual"], "iterations": r["iterations"],
                      "phase": "refine"} for r in recs if not r["converged"])
    path = UnloadingPath.from_records(
        recs, control="load", pull_off_load=w_po, pull_off_approach=d_po, pull_off_state=states[k_po],
        failures=failures, states=tuple(states) if keep_states else (), elapsed=time.perf_counter() - t0,
        pull_off_converged=not failures and sm is not None and not sm.at_boundary, resolved=prob.resolved)
    return _pull_off_result(prob_nd, int(n), path, "refine")
