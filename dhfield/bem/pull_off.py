"""The adhesive BEM pull-off in the paper's units (R = E* = Delta gamma = 1, Eqs. 32-35).

The engine takes its start as an argument: :class:`UnloadingStart` (the domain, the
range of the unloading path and the cold start of the bracket search) is chosen by
the caller -- :mod:`dhfield.analysis.bem_start` chooses it from the analytic models, so
that this package imports none of the models it is the ground truth for.

:func:`paper_problem` sets up the crossed-cylinder problem of the paper on a grid
(:class:`NondimensionalProblem`); :func:`solve_pull_off` runs the load- or
displacement-control route on it (:mod:`dhfield.bem.path`): under load control it
brackets the minimum of the unloading load with states warm-started from coarser
grids (:class:`NestedWarmStart`), or, with ``search='located'``, locates the
minimum on the coarser grids and solves only 3-4 states on the fine one (half the
time at lambda = 3, N = 256).  :func:`refine` carries a pull-off to a finer grid
(coarse to fine, :func:`interpolate_state`); :func:`richardson_extrapolation`
extrapolates pull-offs over N.  Every route is a short function on one
:class:`dhfield.bem.branch.Branch`, and every route answers with the one pull-off
record of dhfield, :class:`dhfield.core.records.PullOff` with its solver group
(:func:`pull_off_result`; :func:`pull_off_summary` is its JSON-ready form).
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..core.validation import check_count, check_ellipticity, check_positive
from ..core.geometry import radius_ratio, sin_skew_angle
from ..core.records import PullOff
from .branch import Branch, UnloadingPath
from .laws import DugdaleLaw, ExponentialLaw, check_law, law_from_name
from .operator import Grid
from .path import PathOptions, PathStart, load_control_path, path_on
from .solver import AdhesiveProblem, Prediction, state_options
from .state import ContactState

__all__ = ["solve_pull_off", "refine", "paper_problem", "UnloadingStart", "NondimensionalProblem",
           "NestedWarmStart", "dilation_factors",
           "interpolate_state", "richardson_extrapolation", "DISPLACEMENT_CONTROL_NOTE",
           "DOMAIN_MARGIN", "DEFAULT_STEPS", "SEARCHES", "MAX_CELLS", "MAX_STEPS", "pull_off_result",
           "pull_off_summary", "check_bem_pull_off", "unresolved_reasons", "discretisation_error",
           "ladder_cells", "ladder_error", "route_error", "LADDER_SAFETY"]


#: Half-width of the domain per expected semi-axis of the largest cohesive zone of
#: the path (the zone must lie inside the grid; DC-FFT needs no margin beyond it).
DOMAIN_MARGIN = 1.15
#: Default number of unloading steps from the start of unloading to the expected jump.
DEFAULT_STEPS = 20
#: Largest grid accepted (cells per axis): 2^16 x 2^16 cells already need ~100 GB of working arrays.
MAX_CELLS = 2 ** 16
#: Largest count of path steps (n_steps, window, refine_factor) accepted.
MAX_STEPS = 10 ** 6
#: Load-control searches of :func:`pull_off`.
SEARCHES = ("bracket", "march", "located")


@dataclass(frozen=True)
class UnloadingStart:
    """Where the BEM's unloading path starts (an input, not a result), chosen by the caller.

    The domain, the range of the unloading path and the cold start of the bracket search,
    e.g. from :func:`dhfield.analysis.bem_start.unloading_start`.

    Parameters
    ----------
    half_width_x, half_width_y : float
        Half-widths of the domain [c_r]: the cohesive zone of every state must lie inside.
    approach_max, approach_step : float
        Start of unloading (a state on the stable branch, above pull-off) and
        unloading step [c_r^2/R].
    approach : float
        Approach of the cold start of the bracket search (the expected
        load-control pull-off) [c_r^2/R]; NaN: none (the marching path).
    zone : (float, float)
        Semi-axes (c, d) of the cohesive zone of that cold start [c_r] (sigma0 on
        the ellipse); NaN: none.
    """

    half_width_x: float
    half_width_y: float
    approach_max: float
    approach_step: float
    approach: float = float("nan")
    zone: tuple = (float("nan"), float("nan"))


@dataclass(frozen=True)
class NondimensionalProblem:
    """The crossed-cylinder problem in the paper's units (R = E* = Delta gamma = 1).

    Parameters
    ----------
    mu, beta0 : float
        Tabor parameter (Eq. 35) and initial ellipticity (Hertz b/a) [-].
    grid : Grid
        The n x n cells over ``[-half_width_x, half_width_x] x [-half_width_y, half_width_y]``
        (rectangular cells when beta0 < 1: as many cells across the minor axis
        as across the major one).
    initial_gap : ndarray
        The gap z = x^2/(2R') + y^2/(2R''), Eq. (2), with R' = sqrt(rho), R'' = 1/sqrt(rho),
        rho = R'/R'' of beta0 (so R = sqrt(R'R'') = 1) [c_r].
    law : DugdaleLaw or ExponentialLaw
        Traction law: sigma0 = mu, range 1/mu (Delta gamma = 1).
    sin_skew : float
        The sine of the skew angle, sin(theta_skew), of beta0: the factor of Eq. (34) [-].
    approach_max, approach_step : float
        Start of unloading and unloading step [c_r^2/R] (:class:`UnloadingStart`).
    pull_off_approach : float
        Approach of the bracket search's cold start [c_r^2/R] (:attr:`UnloadingStart.approach`).
    pull_off_zone : (float, float)
        Semi-axes (c, d) of its cohesive zone [c_r] (:attr:`UnloadingStart.zone`).
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

    @property
    def has_cold_start(self) -> bool:
        """True when a cold start (approach and zone) is given."""
        return bool(np.all(np.isfinite(self.pull_off_zone)))

    def start_stress(self) -> np.ndarray:
        """Return sigma0 on the cold start's cohesive zone, full grid (a cold start).

        Returns
        -------
        ndarray
            The adhesive stress on the full grid: sigma0 inside the ellipse of
            semi-axes :attr:`pull_off_zone`, 0 outside [stress].
        """
        c, d = self.pull_off_zone
        x, y = self.grid.mesh()
        return self.law.max_stress * ((x / c) ** 2 + (y / d) ** 2 < 1.0).astype(float)

    def adhesive_problem(self, threads=None) -> AdhesiveProblem:
        """Build the solver's working arrays of this problem (symmetry from the gap, E* = 1).

        Parameters
        ----------
        threads : int, optional
            FFTW threads; None: the solver's default.

        Returns
        -------
        AdhesiveProblem
            The problem's gap, grid and law in the solver's working arrays.
        """
        return AdhesiveProblem(self.initial_gap, self.grid, self.law, None, threads, 1.0)

    def path_start(self, prob, warm_start=None) -> PathStart:
        """Build the cold start of a path on ``prob`` (this problem's working arrays).

        Parameters
        ----------
        prob : AdhesiveProblem
            This problem's working arrays (:meth:`adhesive_problem`).
        warm_start : callable, optional
            ``warm_start(approach)`` -> a guess on this grid or None (e.g. a
            :class:`NestedWarmStart`).

        Returns
        -------
        PathStart
            The cold start at :attr:`pull_off_approach` with sigma0 on
            :attr:`pull_off_zone`; without a cold start (:attr:`has_cold_start`
            False), only ``warm_start``.
        """
        if not self.has_cold_start:
            return PathStart(warm_start=warm_start)
        stress = np.clip(prob.to_work(self.start_stress()), 0.0, self.law.max_stress)
        return PathStart(self.pull_off_approach, stress, warm_start)

    def lattice_index(self, approach) -> int:
        """The index j of the pull-off lattice's approach nearest ``approach``.

        The lattice is ``approach_max - j approach_step / LOCATE_DIVISIONS`` (j integer), the
        same on every grid of a problem (:func:`predicted_path` solves its first sample at
        the one nearest :attr:`pull_off_approach`).

        Parameters
        ----------
        approach : float
            Approach [c_r^2/R].

        Returns
        -------
        int
            The index j of the lattice approach nearest it [-].
        """
        return int(round((self.approach_max - float(approach)) / (self.approach_step / LOCATE_DIVISIONS)))

    def lattice_approach(self, approach) -> float:
        """The approach of the pull-off lattice nearest ``approach`` (:meth:`lattice_index`).

        Parameters
        ----------
        approach : float
            Approach [c_r^2/R].

        Returns
        -------
        float
            The lattice approach nearest it [c_r^2/R].
        """
        return self.approach_max - self.lattice_index(approach) * (self.approach_step / LOCATE_DIVISIONS)

    def cells_y(self, nx, multiple=2) -> int:
        """Return the cells along y for ``nx`` along x that keep this grid's cell counts' ratio.

        Parameters
        ----------
        nx : int
            Cells along x [-].
        multiple : int, default 2
            The count is a multiple of it (even by default; ``2**levels`` for nested grids) [-].

        Returns
        -------
        int
            ``ny nx / self.nx`` rounded to a multiple of ``multiple``, at least 8 [-].
        """
        g, m = self.grid, int(multiple)
        return max(m * math.ceil(8 / m), m * round(g.ny * int(nx) / g.nx / m))

    def grid_on_cells(self, nx, ny=None) -> Grid:
        """Return the grid of ``nx x ny`` cells over this problem's domain.

        Parameters
        ----------
        nx : int
            Cells along x (even, 8 to 65536) [-].
        ny : int, optional
            Cells along y (even) [-]; default :meth:`cells_y`.

        Returns
        -------
        Grid
            The cells over the same half-widths.
        """
        g = self.grid
        nx = check_cells(nx)
        ny = self.cells_y(nx) if ny is None else check_cells(ny, "ny")
        return Grid.centered(nx, 0.5 * g.nx * g.dx, ny=ny, half_width_y=0.5 * g.ny * g.dy)

    def on_cells(self, nx, ny=None) -> "NondimensionalProblem":
        """Return this problem on ``nx x ny`` cells over the same domain.

        Parameters
        ----------
        nx : int
            Cells along x (even, 8 to 65536) [-].
        ny : int, optional
            Cells along y (even) [-]; default the cell counts' ratio kept (:meth:`cells_y`).

        Returns
        -------
        NondimensionalProblem
            The same problem (law, start, domain) on the new grid, with its
            initial gap (Eq. 2).
        """
        grid = self.grid_on_cells(nx, ny)
        return replace(self, grid=grid, initial_gap=_initial_gap(grid, self.beta0))

    def coarser(self, n) -> "NondimensionalProblem":
        """Return this problem on the grid with ``n`` cells along x over the same domain.

        Equal to :func:`paper_problem` at ``n`` with the same start (the cell sizes
        are exact multiples: 2 lx/(n/k) = k (2 lx/n) in floating point).

        Parameters
        ----------
        n : int
            Cells along x; ``grid.nx`` must be a multiple of ``n``.

        Returns
        -------
        NondimensionalProblem
            The same problem (law, start, domain) with the coarser
            grid and its initial gap.
        """
        g = self.grid
        k = g.nx // n
        grid = Grid(n, g.ny // k, g.dx * k, g.dy * k)
        return replace(self, grid=grid, initial_gap=_initial_gap(grid, self.beta0))


def _initial_gap(grid, beta0):
    """z = x^2/(2R') + y^2/(2R'') with R'R'' = 1, Eq. (2), on the cell centres [c_r]."""
    rho = float(radius_ratio(beta0))
    r_major, r_minor = math.sqrt(rho), 1.0 / math.sqrt(rho)
    x, y = grid.mesh()
    return x * x / (2.0 * r_major) + y * y / (2.0 * r_minor)  # Eq. (2)


def check_cells(n, name="n") -> int:
    """``n`` as cells per axis: an even integer in [8, MAX_CELLS] (ValueError naming ``name`` otherwise)."""
    n = check_count(name, n, 8, MAX_CELLS, "cells per axis, even")
    if n % 2:
        raise ValueError(f"{name} must be an even integer in [8, {MAX_CELLS}] (cells per axis); got {n!r}")
    return n


def paper_problem(*, beta0, mu, n, start, law="dugdale", ny=None) -> NondimensionalProblem:
    """Grid, initial gap and law of the paper's problem at (mu, beta0), from a given start.

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-]; sigma0 = mu in these units.
    n : int
        Cells along x, and along y unless ``ny`` is given (even, 8 to 65536) [-].
    start : UnloadingStart
        The domain, the path range and the cold start.
    law : {'dugdale', 'exponential'} or a law
        Traction law with sigma0 = mu and Delta gamma = 1.
    ny : int, optional
        Cells along y (even, 8 to 65536) [-]; default ``n`` (rectangular cells when beta0 < 1).

    Returns
    -------
    NondimensionalProblem
        The grid (n x ny cells over the start's domain), the initial gap
        (Eq. 2), the law, sin(theta_skew) (Eq. 34) and the start.

    Raises
    ------
    ValueError
        If ``mu``, ``beta0``, ``n``, ``law`` or ``start`` is out of range, or the
        start's zone does not lie inside the domain.
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    n = check_cells(n)
    ny = n if ny is None else check_cells(ny, "ny")
    law_obj = law_from_name(law, mu, 1.0) if isinstance(law, str) else check_law(law)
    if law_obj is None:
        raise ValueError("law must be 'dugdale' or 'exponential'; got None")
    if not isinstance(start, UnloadingStart):
        raise ValueError(f"start must be a UnloadingStart; got {type(start).__name__}")
    c, d = start.zone
    if not (c < start.half_width_x and d < start.half_width_y) and np.all(np.isfinite(start.zone)):
        raise ValueError(f"start.zone {start.zone!r} must lie inside the domain (half-widths "
                         f"{start.half_width_x:.4g} x {start.half_width_y:.4g}): the domain is too small for the "
                         "contact")
    grid = Grid.centered(n, start.half_width_x, ny=ny, half_width_y=start.half_width_y)
    return NondimensionalProblem(mu, beta0, grid, _initial_gap(grid, beta0), law_obj, float(sin_skew_angle(beta0)),
                                 start.approach_max, start.approach_step, start.approach, start.zone)


#: Coarsest grid (cells per axis) solved for nested warm starts (:class:`NestedWarmStart`).
NESTED_MIN_N = 64


def _carried_to_fine(state, fine_prob):
    """A converged coarse state carried onto the fine grid of ``fine_prob`` as a warm start.

    The state interpolated (:func:`interpolate_state`) and given the fine problem's law.  For the
    Dugdale law its zone fraction is then the fine grid's own sub-cell fraction of the
    interpolated gap under that law: the fine edge is sharper (its width scales with the cell),
    and a state of another mu gets the fine mu's zone, which saves ~10 % of the fine state's
    outer and ~20 % of its CG iterations (lambda = 3, N = 256).
    """
    fp = fine_prob
    guess = replace(interpolate_state(state, fp.grid), law=fp.law)   # the fine problem's law (its mu, if another)
    law = fp.law
    if not isinstance(law, DugdaleLaw):
        return guess
    zone = fp.to_full(fp.stress_from_gap(fp.to_work(guess.gap), fp.to_work(guess.contact)) / law.max_stress)
    return replace(guess, pressure=guess.repulsive_pressure - law.max_stress * zone,
                   cohesive=np.where(guess.contact, 0.0, zone))


class _HalfGridWarmStart:
    """Warm starts on a fine grid from the same approach solved on a coarser grid (the subclass's ``coarse_state``)."""

    _fine_nd = None       # the fine grid's NondimensionalProblem
    _fine_prob = None     # its working arrays, built on first use
    _threads = None

    def coarse_state(self, approach) -> ContactState:    # pragma: no cover - every subclass defines it
        raise NotImplementedError

    def __call__(self, approach):
        """Warm start on the fine grid, or None when the coarse state is not a converged contact state.

        The coarse state interpolated onto the fine grid (:func:`interpolate_state`); for the
        Dugdale law its zone fraction is then the fine grid's own sub-cell fraction of the
        interpolated gap (the fine edge is sharper: its width scales with the cell); see
        :func:`_carried_to_fine`.
        """
        st = self.coarse_state(approach)
        if not (st.converged and st.in_contact):
            return None
        if self._fine_prob is None:
            self._fine_prob = self._fine_nd.adhesive_problem(self._threads)
        return _carried_to_fine(st, self._fine_prob)


class NestedWarmStart(_HalfGridWarmStart):
    """Warm starts from the same approach solved on grids 2x, 4x, ... coarser (same domain).

    ``start(approach)`` solves the paper's problem at that approach on the grid with
    ``n/2`` cells per axis (itself warm-started the same way from ``n/4``, down to
    :data:`NESTED_MIN_N`; the coarsest level from its nearest solved state, the first
    one cold from the problem's cold-start zone) and carries the state onto the
    ``n`` grid (:func:`interpolate_state`).  A fine state started there needs about a
    quarter of the outer (zone) iterations of one warm-started from a neighbouring
    fine state (lambda = 3, N = 256), and a coarse state costs ~1/5 of a fine one.

    Parameters
    ----------
    problem : NondimensionalProblem
        The fine grid's problem (``n`` cells per axis, even, >= 2 NESTED_MIN_N).
    tol : float
        Solver tolerance, as in :func:`dhfield.bem.solve_adhesive`.
    max_iter : int
        Cap on GMRES iterations per linear solve, as in :func:`dhfield.bem.solve_adhesive`.
    threads : int, optional
        FFTW threads, as in :func:`dhfield.bem.solve_adhesive`.

    Attributes
    ----------
    states_solved, iterations : int
        Coarse states solved and their GMRES iterations, over all levels.
    """

    def __init__(self, problem, *, tol, max_iter, threads=None):
        if not isinstance(problem, NondimensionalProblem):
            raise ValueError(f"problem must be a NondimensionalProblem; got {type(problem).__name__}")
        n = problem.grid.nx
        nc = int(n) // 2
        if nc < NESTED_MIN_N or nc % 2 or problem.grid.ny % 2:
            raise ValueError(f"problem must have an even n >= {2 * NESTED_MIN_N} cells per axis and an even ny "
                             f"for nested warm starts; got {n!r} x {problem.grid.ny!r}")
        coarse = problem.coarser(nc)
        self._fine_nd = problem
        self._fine_prob = None
        self._nd = coarse
        self._threads = threads
        self._prob = coarse.adhesive_problem(threads)
        self._cold = Prediction(np.zeros_like(self._prob.z), self._prob.to_work(coarse.start_stress()))
        self._tol, self._max_iter = float(tol), int(max_iter)
        # a coarser level only where this one halves exactly along y too (2880 x 540 reached 720 x 135, whose
        # half, 360 x 67, covered another domain: the warm start raised)
        self._inner = (NestedWarmStart(coarse, tol=tol, max_iter=max_iter, threads=threads)
                       if nc // 2 >= NESTED_MIN_N and nc % 4 == 0 and coarse.grid.ny % 2 == 0 else None)
        # the coarse states, solved on one branch (kept: they are the warm starts), by approach
        self._branch = Branch(self._prob, self._tol, self._max_iter, progress=False, keep_states=True,
                              warm_start=self._inner)
        self._states = {}

    @property
    def states_solved(self) -> int:
        """Coarse states solved, over all levels."""
        return len(self._branch.records) + (self._inner.states_solved if self._inner else 0)

    @property
    def iterations(self) -> int:
        """GMRES iterations of the coarse states, over all levels."""
        own = sum(r["iterations"] for r in self._branch.records)
        return own + (self._inner.iterations if self._inner else 0)

    def coarse_state(self, approach):
        """Solve the state at ``approach`` on the coarse grid (once; later calls reuse it).

        Parameters
        ----------
        approach : float
            Approach [c_r^2/R].

        Returns
        -------
        ContactState
            The coarse grid's state, converged or not.
        """
        d = float(approach)
        if d not in self._states:
            b = self._branch
            guess = b.guess(d, b.nearest_usable(d))
            self._states[d] = b.solve(d, guess if guess is not None else self._cold, "unloading")[1]
        return self._states[d]

    def locate_pull_off(self, spacing):
        """Locate the approach of the load-control pull-off on the coarse grid (NaN when not found).

        The coarsest level whose Dugdale edge is (nearly) resolved
        (:data:`LOCATE_MAX_EDGE_RATIO`) runs the bracket search (with the problem's cold
        start, and the coarser levels as warm starts); every finer level solves the
        approaches of the lattice ``approach_max - j spacing`` next to the pull-off of the
        level below (:func:`_lattice_minimum`, warm-started from that level) and returns
        the vertex of their parabola.  The states are kept for the warm starts.  NaN when
        this grid is too coarse for the Dugdale edge.

        Parameters
        ----------
        spacing : float
            Spacing of the approach lattice [c_r^2/R].

        Returns
        -------
        float
            The pull-off approach [c_r^2/R]; NaN when not found (the edge
            unresolved here, or the minimum at an end of the samples).
        """
        nd, b = self._nd, self._branch
        if self._prob.edge_width_ratio > LOCATE_MAX_EDGE_RATIO:
            return float("nan")           # the Dugdale edge is far from resolved here: no reliable minimum
        if self._inner is None or self._inner._prob.edge_width_ratio > LOCATE_MAX_EDGE_RATIO:
            # the coarsest resolved grid: the bracket search (warm starts from the grid below, if any)
            # no vertex refinement: the next grid's lattice samples re-locate the minimum anyway
            # (the same pull-offs, 10 % less CPU than 2; docs/theory/bem.rst)
            opts = PathOptions(refine_levels=0, tol=self._tol, max_iter=self._max_iter,
                               threads=self._threads, keep_states=True, progress=False).checked()
            first = len(b.records)
            path = load_control_path(b, nd.path_start(self._prob, self._inner), nd.approach_max,
                                     nd.approach_step, opts)
            for i in range(first, len(b.records)):
                st = b.states[i]
                if st.converged and st.in_contact and st.approach not in self._states:
                    self._states[st.approach] = st
            return float(path.pull_off_approach)
        below = self._inner.locate_pull_off(spacing)
        if not np.isfinite(below):
            return float("nan")
        first = len(b.records)
        sm = _lattice_minimum(b, self.coarse_state, below, nd.approach_max, spacing)
        for i in range(first, len(b.records)):
            self._states.setdefault(b.approach(i), b.states[i])
        return float("nan") if (sm is None or sm.at_boundary) else float(sm.x)


#: Spacing of the approach lattice of the located search (``search='located'``), in unloading
#: steps: the lattice is ``approach_max - j approach_step / LOCATE_DIVISIONS`` on every grid, so
#: the samples of one level are the warm starts of the next (the first refinement level of the
#: marching path has the same spacing).
LOCATE_DIVISIONS = 2
#: Cap on lattice samples added when the load minimum sits at an end of the samples.
LOCATE_MAX_EXTEND = 6
#: Coarse grids of the located search must have an ``AdhesiveProblem.edge_width_ratio`` (edge
#: width wanted / its cap 2 h0; > 1 is flagged unresolved) of at most this: states converge at
#: 1.10-1.18 and not at 2.1-3.8 (docs/theory/bem.rst).
LOCATE_MAX_EDGE_RATIO = 1.25
#: Solver tolerance of the coarse grids of the located search (the fine grid keeps ``tol``).
#: Their states only locate the minimum and start the fine states: a zone-fraction error of
#: 1e-4 moves a coarse load by ~3e-5 relative, far below the lattice jaggedness of
#: the load (~5e-4), and far below the coarse-to-fine interpolation error of a warm start.
LOCATE_COARSE_TOL = 1e-4


def _lattice_minimum(branch, solve, approach, top, spacing, max_extend=LOCATE_MAX_EXTEND):
    """The load minimum of samples of the lattice ``top - j spacing`` around ``approach``, or None.

    ``solve(delta)`` solves the state at delta on ``branch``.  Three samples next to
    ``approach``, then one more beyond the end holding the lowest load until the discrete
    minimum is interior (:meth:`Branch.extend_until_interior`, at most ``max_extend``).
    Returns the SampledMinimum (None: no converged contact state).
    """
    j0 = int(round((top - approach) / spacing))
    first = len(branch.records)
    for j in (j0 - 1, j0, j0 + 1):
        solve(top - j * spacing)

    def next_approach(i, up):
        j = int(round((top - branch.approach(i)) / spacing))
        return top - (j - 1 if up else j + 1) * spacing

    _, order = branch.extend_until_interior(range(first, len(branch.records)), next_approach, max_extend)
    return branch.minimum(order)[1]


def located_path(problem, ws, options):
    """The load-control pull-off located on coarser grids (``search='located'``), or None.

    ``ws.locate_pull_off`` finds the pull-off on the grid half as fine (recursively: the
    bracket search on the coarsest grid, three lattice samples on every finer one); on this
    grid only the lattice samples around it (:func:`_lattice_minimum`) and at most
    one parabola vertex (none with ``refine_levels=0``) is solved,
    each warm-started from the same approach on the coarser grid.  None when the located
    minimum is not interior or a state did not converge (the caller then runs the bracket search).
    """
    spacing = problem.approach_step / LOCATE_DIVISIONS
    d_coarse = ws.locate_pull_off(spacing)
    if not np.isfinite(d_coarse):
        return None
    b = Branch(problem.adhesive_problem(options.threads), options.tol, options.max_iter,
               label=f"located N={problem.grid.nx}", progress=options.progress, keep_states=options.keep_states,
               warm_start=ws)
    sm = _lattice_minimum(b, lambda d: b.solve(d, b.guess(d, b.nearest_usable(d)), "unloading"), d_coarse,
                          problem.approach_max, spacing)
    if sm is None or sm.at_boundary or not all(r["converged"] for r in b.records):
        return None
    return _vertex_path(b, problem, options)


def _vertex_path(b, problem, options):
    """Solve the parabola vertex of the branch's minimum, take the minimum again, and return the load-control
    path (None when it then lies at the lattice's boundary or a state did not converge)."""
    xtol = problem.approach_step / options.refine_factor ** options.refine_levels
    b.refine_vertex(range(len(b.records)), xtol, min(options.refine_levels, 1))
    order, sm = b.minimum(range(len(b.records)))
    if sm.at_boundary or not all(b.records[i]["converged"] for i in b.kept()):
        return None
    return b.to_path(control="load", load=sm.y, approach=sm.x, pull_off_index=order[sm.index], converged=True,
                     error=b.minimum_error(order, sm))


#: The predicted route (:func:`predicted_path`) solves the parabola's vertex only when the
#: samples' own error (:meth:`Branch.minimum_error`, the vertex against the best sample) exceeds
#: this fraction of the grid's discretisation error (:func:`discretisation_error`): below it one
#: more fine state changes the stated error by less than this fraction.
VERTEX_ERROR_FRACTION = 0.1
def _dilated_start(branch, near, approach):
    """Warm start at ``approach``: the nearest solved state dilated to the contact it should have.

    Between neighbouring samples the contact and its zone grow or shrink by a cell or two;
    a state started from its neighbour as it is (or from the secant blend of two, which
    leaves two edges instead of moving one) spends most of its outer iterations creeping
    the edge by a fraction of a cell each.  Here the nearest state's fields
    are stretched about the centre by the semi-axis change expected at ``approach``: from
    the two nearest states when there are two (their a*, b* per approach), else from JKR's
    sphere of the same mean radius (:func:`dilation_factors`).
    """
    i = near[0]
    other = branch.records[near[1]] if len(near) > 1 else None
    return dilate_state(branch.states[i], *dilation_factors(branch.records[i], other, approach))


def dilation_factors(nearest, other, approach) -> tuple:
    """The stretch factors (sx, sy) that carry a state's contact to the one expected at ``approach``.

    From the semi-axes per approach of two states when there are two at different approaches,
    else from JKR's sphere of the same mean radius, ``d delta / d a = 2 a - sqrt(2 pi / a) / 2``
    in the paper's units (within 2 % of the BEM's slope on the sphere at mu = 5, pull-off).

    Parameters
    ----------
    nearest : dict
        The summary (``approach``, contact semi-axes ``a``, ``b``) of the state to stretch
        (:meth:`dhfield.bem.state.ContactState.summary`).
    other : dict or None
        The summary of a second state, or None.
    approach : float
        The approach to carry the state to [c_r^2/R].

    Returns
    -------
    (float, float)
        The stretch factors along x and y [-].
    """
    a, b = nearest["a"], nearest["b"]
    dd = approach - nearest["approach"]
    if other is not None and other["approach"] != nearest["approach"]:
        step = nearest["approach"] - other["approach"]
        da, db = (a - other["a"]) / step * dd, (b - other["b"]) / step * dd
    else:
        m = math.sqrt(a * b)
        slope = 1.0 / (2.0 * m - 0.5 * math.sqrt(2.0 * math.pi / m))       # JKR sphere: da/d delta
        da, db = slope * dd * a / m, slope * dd * b / m
    return 1.0 + da / a, 1.0 + db / b


def dilate_state(state, sx, sy):
    """A solved state stretched about the centre, ``f(x, y) -> f(x/sx, y/sy)`` (a warm start).

    Parameters
    ----------
    state : ContactState
        A solved state (with its repulsive pressure).
    sx, sy : float
        Stretch factors along x and y, > 0 [-].

    Returns
    -------
    ContactState
        Repulsive pressure, adhesive zone fraction and gap carried bilinearly (clipped as in
        :func:`interpolate_state`); a guess (``converged=False``), not a solution.
    """
    from scipy.interpolate import RegularGridInterpolator

    g = state.grid
    x, y = g.mesh()
    pts = np.stack([(x / sx).ravel(), (y / sy).ravel()], axis=-1)

    def carry(f):
        it = RegularGridInterpolator((g.x, g.y), np.asarray(f, float), bounds_error=False, fill_value=None)
        return it(pts).reshape(g.shape)

    p = np.maximum(carry(state.repulsive_pressure), 0.0)
    zone = np.clip(carry(state.adhesive_zone), 0.0, 1.0)
    contact = p > 0
    sigma0 = state.law.max_stress
    return ContactState(grid=g, pressure=p - sigma0 * zone, gap=np.maximum(carry(state.gap), 0.0),
                        approach=state.approach, load=float("nan"), contact=contact,
                        cohesive=np.where(contact, 0.0, zone), law=state.law, converged=False, iterations=0,
                        residual=float("inf"), repulsive_pressure=p)


def _predicted_solver(branch, cold):
    """``solve(approach)`` of the predicted route on ``branch``: the state there (its record index).

    The one start protocol: the first state from the branch's external warm start when it gives
    one (:meth:`Branch.guess`: the same approach on a coarser grid), else cold (sigma0 on the
    start's zone, ``cold``, working arrays); every later one from the nearest solved state
    dilated to the contact expected at its approach (:func:`_dilated_start`).  A state that does
    not converge from its start is solved by nested iteration from the coarsest grid
    (:func:`dhfield.bem.solver.solve_problem`).
    """
    b = branch

    def solve(d):
        done = [i for i in b.kept() if b.approach(i) == d]
        if done:
            return done[0]                      # solved already (e.g. the first sample)
        near = sorted((i for i in b.states if b.usable(i)), key=lambda i: abs(b.approach(i) - d))
        if near:
            return b.solve(d, _dilated_start(b, near, d), "unloading")[0]
        guess = b.guess(d, None)
        return b.solve(d, guess if guess is not None else Prediction(np.zeros_like(cold), cold.copy()),
                       "unloading")[0]

    return solve


def predicted_path(problem, options, warm_start=None):
    """The load-control pull-off from fine lattice samples around the problem's cold start, or None.

    For grids whose coarser levels cannot locate the minimum (high mu: the grid half as
    fine cannot hold the Dugdale edge), the
    caller's predicted pull-off (:attr:`NondimensionalProblem.pull_off_approach`, e.g.
    the JKR limit's) stands in for the coarse search: the lattice sample
    ``approach_max - j approach_step / LOCATE_DIVISIONS`` nearest it is solved first from
    the cold start (sigma0 on :attr:`NondimensionalProblem.pull_off_zone`), then its
    neighbours, each from the nearest solved state (secant over the two nearest), until
    the discrete load minimum is interior (:func:`_lattice_minimum`).  The parabola's
    vertex is solved only when the samples' error exceeds ``VERTEX_ERROR_FRACTION`` of
    the grid's discretisation error.  None when the minimum is not interior or a state
    did not converge.

    Parameters
    ----------
    problem : NondimensionalProblem
        The fine grid's problem, with a cold start (:attr:`NondimensionalProblem.has_cold_start`).
    options : PathOptions
        Checked path settings (tolerances, ``refine_levels``: no vertex state when 0).
    warm_start : callable, optional
        ``warm_start(approach)``: a start of the first state on this grid (e.g.
        :class:`NestedWarmStart`), or None.

    Returns
    -------
    UnloadingPath
        The samples' path with the pull-off at the parabola's vertex.  On failure the
        samples' path flagged ``pull_off_converged=False``, its ``pull_off_note`` saying why
        (the cold state did not converge, a sample did not, or the minimum stayed at an end);
        its pull-off is the load minimum of the converged samples, NaN when there is none.
        No other route is tried: the record says what failed (and the caller names the analytic
        W* to use instead).
    """
    spacing = problem.approach_step / LOCATE_DIVISIONS
    prob = problem.adhesive_problem(options.threads)
    b = Branch(prob, options.tol, options.max_iter, label=f"predicted N={problem.grid.nx}",
               progress=options.progress, keep_states=options.keep_states, warm_start=warm_start)
    solve = _predicted_solver(b, problem.path_start(prob).stress)

    def kept():
        return [b.records[i] for i in b.kept()]

    def failed(why):
        bad = [r for r in kept() if not r["converged"]]
        if bad:
            why = (f"{why} ({len(bad)} of {len(kept())} states unconverged, worst residual "
                   f"{max(r['residual'] for r in bad):.2g} > tol {b.tol:.2g} after up to "
                   f"{max(int(r['outer_iterations']) for r in bad)} Newton iterations)")
        path = b.load_pull_off(range(len(b.records)))
        return replace(path, pull_off_converged=False, pull_off_note=why)

    top = problem.approach_max
    j0 = problem.lattice_index(problem.pull_off_approach)
    k0 = solve(top - j0 * spacing)              # the sample nearest the prediction first
    if not b.usable(k0):
        first = "cold state" if warm_start is None else "first state (started from the grid half as fine)"
        return failed(f"the predicted route's {first} at GVG's pull-off did not converge")
    for j in (j0 - 1, j0 + 1):                  # its neighbours, then beyond the lowest end until interior
        solve(top - j * spacing)

    def next_approach(i, up):
        j = problem.lattice_index(b.approach(i))
        return top - (j - 1 if up else j + 1) * spacing

    _, order = b.extend_until_interior(range(len(b.records)), next_approach, LOCATE_MAX_EXTEND)
    sm = b.minimum(order)[1]
    every = range(len(b.records))
    if not all(r["converged"] for r in kept()):
        return failed("a sample of the predicted route did not converge")
    if sm is None or sm.at_boundary:
        return failed(f"the load minimum of the predicted route's samples stayed at an end after "
                      f"{len(b.records)} samples")
    order, sm = b.minimum(every)
    rec = b.records[order[sm.index]]
    grid_error = discretisation_error(sm.y, (rec["a"], rec["b"], rec["c"], rec["d"]), problem.grid)
    if b.minimum_error(order, sm) > VERTEX_ERROR_FRACTION * grid_error:
        return _vertex_path(b, problem, options)
    return b.to_path(control="load", load=sm.y, approach=sm.x, pull_off_index=order[sm.index], converged=True,
                     error=b.minimum_error(order, sm))


def solve_pull_off(problem, *, control="load", search="located", nested=None, options=PathOptions()) -> PullOff:
    """The BEM pull-off of a problem in the paper's units, by the route of ``control`` and ``search``.

    Parameters
    ----------
    problem : NondimensionalProblem
        From :func:`paper_problem` (its start chosen by the caller).
    control : {'load', 'displacement'}
        Load control: the minimum of the unloading load.  Displacement control:
        the jump, the minimum of the approach along the branch (its fold, or
        the loss of contact; :mod:`dhfield.bem.continuation`).
    search : {'located', 'bracket', 'march'}
        The load-control route (:func:`dhfield.analysis.bem_start.adhesive_pull_off`
        describes each); without a cold start in ``problem``: 'march'.
    nested : bool, optional
        Bracket search only: warm starts from the grid half as fine
        (:class:`NestedWarmStart`).  Default: when ``n >= 2 NESTED_MIN_N`` (and n % 4 == 0).
    options : PathOptions
        Path settings and solver tolerances.

    Returns
    -------
    dhfield.core.records.PullOff
        The BEM's record (:func:`pull_off_result`): W* in the normalisation of Eq. (34);
        ``search`` names the route taken.
    """
    if control not in ("load", "displacement"):
        raise ValueError(f"control must be one of ('load', 'displacement') (loading mode); got {control!r}")
    if search not in SEARCHES:
        raise ValueError(f"search must be one of {SEARCHES} (load-control path); got {search!r}")
    if not isinstance(problem, NondimensionalProblem):
        raise ValueError(f"problem must be a NondimensionalProblem; got {type(problem).__name__}")
    options = options.checked()
    n = problem.grid.nx
    prob = problem.adhesive_problem(options.threads)
    ws = None
    cold = problem.has_cold_start and (control == "displacement" or search != "march")
    if control == "load" and cold:
        if nested is None or search == "located":
            nested = n >= 2 * NESTED_MIN_N and n % 4 == 0
        if nested:
            # the located search's coarse states only locate the minimum and start the fine states
            coarse_tol = max(options.tol, LOCATE_COARSE_TOL) if search == "located" else options.tol
            ws = NestedWarmStart(problem, tol=coarse_tol, max_iter=options.max_iter, threads=options.threads)
        if search == "located" and nested:
            path = located_path(problem, ws, options)
            if path is not None:
                return pull_off_result(problem, n, path, "located", options=options)
    start = problem.path_start(prob, ws) if cold else PathStart()
    path = path_on(prob, start, problem.approach_max, problem.approach_step, control=control, options=options)
    if control == "displacement":
        route = "continuation"
    elif cold and not np.any(path.phase == "discarded"):
        route = "bracket"
    else:
        route = "march"     # requested, or the bracket's cold start gave no contact state
    return pull_off_result(problem, n, path, route, options=options)


#: Caveat carried by every displacement-control pull-off (the ``note`` of its :class:`dhfield.core.records.PullOff`).
#: On the sphere within 0.8 % of Maugis-Dugdale's displacement-control pull-off (the minimum of
#: delta(a), or its end a = 0) for lambda = 0.3-3 at N = 128 / 256.  Near lambda = 1 the fold lies
#: within ~1e-3 in approach of the end a = 0 of the contact branch (2.7 % apart in W): on coarse
#: grids the lattice jaggedness of the approach hides it.  The stated error is the fold fit's plus
#: the grid's, from the same pull-off on a coarser grid (:func:`route_error`; docs/theory/bem.rst).
DISPLACEMENT_CONTROL_NOTE = (
    "displacement-control pull-off: the minimum of the approach along the branch followed by adhesive "
    "force (the fold, or the loss of contact); W_star_error is the fold fit's plus the grid's, from the same "
    "pull-off on a coarser grid; near lambda = 1 coarse grids can mistake the loss of contact for the fold "
    "(N = 96: -3.1 %)")


#: Slack of the DMT bound on W*, relative to it: the accuracy the BEM states where it is
#: resolved (1 % of Maugis-Dugdale at N = 256, tests/test_cli_solve.py); a pull-off stronger
#: than DMT by more than this (or than its W_star_error) is not a physical answer.
DMT_BOUND_SLACK = 0.01
#: Fewest cells across the Dugdale zone (c* - a*, d* - b*) of a resolved pull-off state: a
#: zone narrower than a cell is not represented (at mu = 30, N = 64: c* = a*, W* = -7.24).
ZONE_MIN_CELLS = 1.0


#: Discretisation error of a pull-off relative to |W*|, times the cells across the narrowest
#: length the state must resolve (:func:`discretisation_error`): an upper bound, by a factor 1.5,
#: of |W* - W*_ref| / |W*| x cells against exact references (Maugis-Dugdale on the sphere, mu =
#: 0.3-2, N = 16-128, the located route).  With the Newton solve's ramped Dugdale edge
#: (2026-12-02) the worst was 0.079 (mu = 0.3, N = 16, 1.9 cells; 0.063 at mu = 0.5, N = 32),
#: measured by ``python -m verification.calibrate_grid_error``; with the former sub-cell
#: edge it was 0.033 (K was 0.05).  The error falls like 1/cells to 1/cells^2.  Established for
#: the Dugdale law only (there is no exact reference for the exponential law on the sphere):
#: applied to it unchecked, with (c*, d*) its adhesive zone's semi-axes.
DISCRETISATION_ERROR_PER_CELL = 0.12


def resolving_cells(axes, grid, contact=True) -> float:
    """Cells across the narrowest length of a pull-off state [-] (0 when a length is not positive).

    ``axes`` = (a*, b*, c*, d*): the contact semi-axes a*/dx, b*/dy (only when ``contact``) and,
    when a cohesive zone lies beyond the contact, its widths (c* - a*)/dx, (d* - b*)/dy.
    """
    a, b, c, d = (float(v) for v in axes)
    lengths = [a / grid.dx, b / grid.dy] if contact else []
    if c > a or d > b:
        lengths += [(c - a) / grid.dx, (d - b) / grid.dy]
    cells = min(lengths) if lengths else 0.0
    return cells if np.isfinite(cells) and cells > 0.0 else 0.0


def discretisation_error(w_star, axes, grid, contact=True) -> float:
    """Estimate the grid's error on W* [-]: DISCRETISATION_ERROR_PER_CELL |W*| / cells.

    Parameters
    ----------
    w_star : float
        The pull-off W* [-].
    axes : tuple of float
        (a*, b*, c*, d*) of the pull-off state [c_r].
    grid : Grid
        Its grid.
    contact : bool, default True
        Count the contact semi-axes among the lengths (:func:`resolving_cells`).

    Returns
    -------
    float
        ``DISCRETISATION_ERROR_PER_CELL |W*| / cells``; infinite when no length is resolved
        (or W* is not finite).

    Notes
    -----
    .. math:: \\epsilon_h = K \\frac{|W^*|}{\\min(a^*/h_x,\\ b^*/h_y,\\ (c^*-a^*)/h_x,\\ (d^*-b^*)/h_y)},
        \\qquad K = 0.12

    (an upper bound on the errors against exact references, :data:`DISCRETISATION_ERROR_PER_CELL`).
    """
    cells = resolving_cells(axes, grid, contact)
    if not (np.isfinite(w_star) and cells > 0.0):
        return float("inf")
    return DISCRETISATION_ERROR_PER_CELL * abs(float(w_star)) / cells


#: Safety factor of the grid-ladder error (:func:`ladder_error`) over first-order Richardson
#: extrapolation: the error of W*(n) is |W*(n) - W*(n_c)| / (r^p - 1) for a pull-off converging
#: like h^p (r = n/n_c); with p = 1, the order of a Dugdale edge within a cell and of the
#: fitted jump on the sampled branch (on the sphere, 32 -> 48 cells: the spring jump on the
#: separated branch at lambda = 0.56, K* = 1, 8.4 % -> 5.5 % of Maugis-Dugdale, ratio 1.52 =
#: 1.5^1.04), and a factor 2 for orders down to p = log2(1.5) = 0.58 at r = 2 and for the
#: lattice jaggedness of either grid.
LADDER_SAFETY = 2.0


def ladder_cells(n) -> tuple:
    """List the cells of the coarser grids that can check a pull-off on ``n`` cells, in order of preference.

    Parameters
    ----------
    n : int
        Cells per axis of the answer's grid [-].

    Returns
    -------
    tuple of int
        The grid half as fine, 2 (n // 4), then three quarters as fine, 2 round(3 n / 8) (where
        the half grid cannot hold the law's edge: its caller takes the first that can); even,
        at least 8 and below ``n`` [-].
    """
    n = int(n)
    return tuple(k for k in dict.fromkeys((2 * (n // 4), 2 * round(3 * n / 8))) if 8 <= k < n)


def ladder_error(w_fine, w_coarse, n_fine, n_coarse) -> float:
    """Estimate of the grid's error on W*(n) from the same pull-off on a coarser grid [-].

    Parameters
    ----------
    w_fine, w_coarse : float
        W* on ``n_fine`` and ``n_coarse`` cells per axis (the same domain) [-].
    n_fine, n_coarse : int
        Cells per axis, ``n_fine > n_coarse`` [-].

    Returns
    -------
    float
        ``LADDER_SAFETY |w_fine - w_coarse| / (n_fine/n_coarse - 1)``; infinite when either
        W* is not finite.

    Notes
    -----
    Richardson's estimate of the error of the finer value for an error ~ h^p,
    :math:`|W_h - W_{rh}|/(r^p - 1)`, at p = 1 and times :data:`LADDER_SAFETY`.  Under
    load control the route's error is :func:`discretisation_error` alone (its bound holds on
    every case of the sphere and the stored ellipses); under displacement control and under a
    spring the pull-off is a fold or the loss of contact of a fitted branch, whose grid error has
    no established bound per cell: :func:`route_error` takes the larger of the two.
    """
    if not (np.isfinite(w_fine) and np.isfinite(w_coarse)) or not n_fine > n_coarse > 0:
        return float("inf")
    return LADDER_SAFETY * abs(float(w_fine) - float(w_coarse)) / (float(n_fine) / float(n_coarse) - 1.0)


def route_error(fit_error, w_star, axes, grid, *, w_coarse, n_coarse) -> float:
    """The stated error of a displacement-control or spring pull-off [-]: the fit's plus the grid's.

    Parameters
    ----------
    fit_error : float
        Error of the fitted jump on the sampled branch (its quartic, inner quadratic and scatter) [-].
    w_star : float
        The pull-off W* on ``grid`` [-].
    axes : tuple of float
        (a*, b*, c*, d*) of the pull-off state [c_r].
    grid : Grid
        Its grid (``nx`` cells along x).
    w_coarse : float
        The same route's W* on ``n_coarse`` cells (one of :func:`ladder_cells`) over the same domain;
        NaN when there is none (the error is then infinite: no estimate).
    n_coarse : int
        Cells along x of that grid [-].

    Returns
    -------
    float
        ``fit_error + max(discretisation_error(..., contact=False), ladder_error(...))``;
        infinite when any term is.

    Notes
    -----
    The floor :func:`discretisation_error` counts only the zone's widths: at the loss of
    contact (a* -> 0, the displacement-control pull-off for lambda <~ 1 and the jump of a stiff
    spring) the contact's size does not set W*.  The ladder term (:func:`ladder_error`) is what
    bounds these routes, checked on the sphere against Maugis-Dugdale by
    ``verification/bem_stated_error.py``.
    """
    floor = discretisation_error(w_star, axes, grid, contact=False)
    ladder = ladder_error(w_star, w_coarse, grid.nx, n_coarse)
    return float(fit_error) + max(floor, ladder)


#: Fewest cells across the contact semi-axes (a*/dx, b*/dy) of a resolved load-control pull-off:
#: more than the 2 x 2 centre cells (a* = dx from their second moments): one cell is not a
#: contact shape (up to 7 % from Maugis-Dugdale on the sphere; docs/theory/bem.rst).  Under displacement control
#: the pull-off can be the loss of contact (a* -> 0): not applied there.
CONTACT_MIN_CELLS = 1.5


def _unresolved_reasons(prob, path, w_star, error, axes, stated_error=None):
    """Why a pull-off of ``path`` on ``prob`` is not a resolved answer: :func:`unresolved_reasons` of its route."""
    return unresolved_reasons(law=prob.law, grid=prob.grid, sin_skew=prob.sin_skew, edge_resolved=path.resolved,
                              control=path.control, w_star=w_star, search_error=error, axes=axes,
                              stated_error=stated_error)


def unresolved_reasons(*, law, grid, sin_skew, edge_resolved, control, w_star, search_error, axes,
                       stated_error=None, contact_cells=None) -> list:
    """Why a BEM pull-off is not a resolved answer (empty when it is): the grid, then the physical bounds.

    Parameters
    ----------
    law : TractionLaw
        The traction law of the problem.
    grid : Grid
        Its grid.
    sin_skew : float
        The sin(theta_skew) of beta0 (Eq. 34) [-].
    edge_resolved : bool
        The grid resolves the law's edge (``AdhesiveProblem.resolved``).
    control : {'load', 'displacement', 'spring'}
        The route.
    w_star : float
        The pull-off W* [-].
    search_error : float
        The search's (or fit's) error alone; it widens the DMT bound [-].
    axes : tuple of float
        (a*, b*, c*, d*) of the pull-off state [c_r].
    stated_error : float, optional
        The stated error (search or fit plus grid); not finite: "no error estimate".
    contact_cells : bool, optional
        Check that the contact spans at least :data:`CONTACT_MIN_CELLS` cells; default: under
        load control (a spring at K* = 0 is load control: its caller asks for it).

    Returns
    -------
    list of str
        Bounds: W* between the DMT limit -sin(theta_skew) (Eq. 34 of W = -2 pi Delta gamma
        sqrt(R'R''), the rigid limit of every law with that work of adhesion) and the zero-adhesion
        limit 0; for the Dugdale law a cohesive zone beyond the contact, at least
        :data:`ZONE_MIN_CELLS` cells wide on both axes; the contact check above; a finite
        ``stated_error``.
    """
    reasons = []
    if not edge_resolved:
        reasons.append("the grid is too coarse for the traction law's edge (EDGE_WIDTH_FACTOR): increase n")
    if not np.isfinite(w_star):
        return reasons + ["no pull-off was found (no converged contact state)"]
    dmt = -sin_skew
    if w_star < dmt - max(DMT_BOUND_SLACK * abs(dmt), search_error if np.isfinite(search_error) else 0.0):
        reasons.append(f"W* = {w_star:.4g} is stronger than the DMT limit {dmt:.4g}")
    if w_star > 0.0:
        reasons.append(f"W* = {w_star:.4g} is above the zero-adhesion limit 0")
    a, b, c, d = axes
    g = grid
    if isinstance(law, DugdaleLaw):
        if not (c > a and d > b):
            reasons.append(f"the Dugdale zone has collapsed onto the contact (c* = {c:.4g}, a* = {a:.4g})")
        elif min((c - a) / g.dx, (d - b) / g.dy) < ZONE_MIN_CELLS:
            reasons.append(f"the Dugdale zone is narrower than {ZONE_MIN_CELLS:g} cell (c* - a* = {c - a:.3g}, "
                           f"dx = {g.dx:.3g}; d* - b* = {d - b:.3g}, dy = {g.dy:.3g}): increase n")
    if (control == "load") if contact_cells is None else contact_cells:
        if not min(a / g.dx, b / g.dy) >= CONTACT_MIN_CELLS:
            reasons.append(f"the contact spans fewer than {CONTACT_MIN_CELLS:g} cells (a* = {a:.3g}, dx = {g.dx:.3g}; "
                           f"b* = {b:.3g}, dy = {g.dy:.3g}): increase n")
    if stated_error is not None and not np.isfinite(stated_error):
        reasons.append("no error estimate (the minimum is at an end of its samples, or no coarser grid gave the "
                       "same pull-off to compare with)")
    return reasons


def pull_off_result(prob: NondimensionalProblem, n: int, path: UnloadingPath, search: str, *,
                    coarse=None, options=None) -> PullOff:
    """Build the BEM's pull-off record of a path in the paper's units (Eq. 34), with the semi-axes of its state.

    Parameters
    ----------
    prob : NondimensionalProblem
        The problem the path was solved on.
    n : int
        Cells along x of its grid.
    path : UnloadingPath
        The path, with its pull-off state.
    search : str
        The route that found it (one of :data:`SEARCHES`, 'predicted' or 'refine').
    coarse : tuple of (float, int), optional
        Displacement control: (W*, cells along x) of the same pull-off on a coarser grid
        (:func:`ladder_cells`) over the same domain, for the grid's error (:func:`route_error`);
        (NaN, n_c) when that grid gave none.  Default: no such grid, the zone-width floor of
        :func:`discretisation_error` alone.
    options : PathOptions, optional
        The path's options (default ``PathOptions()``): ``solver_options`` records the Newton
        options of its states (:func:`dhfield.bem.solver.state_options`).

    Returns
    -------
    dhfield.core.records.PullOff
        The one pull-off record of dhfield, with ``model='bem'``, ``geometry='ellipse'``,
        ``sin_skew`` of beta0 (Eq. 34), ``v`` NaN, and its solver group
        (:data:`dhfield.core.schema.PULL_OFF_SOLVER_KEYS`); ``path`` holds the whole
        :class:`~dhfield.bem.branch.UnloadingPath`.  The BEM's fields:

        - ``a_star`` ... ``d_star``: second-moment semi-axes of the contact and of
          contact U cohesive zone at pull-off [c_r]; ``ellipticity`` = b*/a* and
          ``adhesive_ellipticity`` = d*/c* (NaN without contact or zone);
          ``at_zero_contact``: no contact cell at pull-off;
        - ``converged``: every state of the path down to the pull-off converged
          (:attr:`UnloadingPath.pull_off_converged`); ``failures`` lists every
          unconverged state (approach, residual, iterations, phase);
        - ``resolved``: False when the answer is not trustworthy, the reasons in
          ``note``: the grid is too coarse for the law's edge (``EDGE_WIDTH_FACTOR``),
          W* is stronger than the DMT limit -sin(theta_skew) or above 0, or the
          Dugdale zone is collapsed onto the contact (c* <= a*) or narrower than
          :data:`ZONE_MIN_CELLS` cells; under load control also when the contact spans
          fewer than :data:`CONTACT_MIN_CELLS` cells or the error has no estimate.  The
          values are reported, never clipped; ``warning`` is then the ``note`` (empty
          for a resolved pull-off);
        - ``W_star_error``: a resolved and converged answer lies within it of the
          grid-converged pull-off.  Under load control the search's error (the samples
          around the minimum, :meth:`dhfield.bem.branch.Branch.minimum_error`) plus
          :func:`discretisation_error`; under displacement control the fit's around
          the fold (:func:`dhfield.bem.continuation.fold_by_adhesive_force`) plus the grid's,
          :func:`route_error` with ``coarse`` (without it, the zone-width floor alone).
          Never NaN: infinite when there is no estimate or the answer is not ``resolved``;
        - ``note``: caveats (empty for a resolved load-control pull-off); every
          displacement-control result carries :data:`DISPLACEMENT_CONTROL_NOTE`, and says
          when the branch ends by loss of contact or no fold was bracketed;
        - ``search``: the route: under load control the search that bracketed the
          minimum ('located', 'bracket' or 'march', also when a requested search fell
          back to it); 'continuation' under displacement control
          (:mod:`dhfield.bem.continuation`); 'refine' for :func:`refine`;
        - ``n``, ``law``, ``n_steps``, ``iterations`` (GMRES iterations over the
          path), ``residual`` (largest over the path), ``half_width_x``,
          ``half_width_y`` (domain [c_r]) and ``elapsed`` (wall time of the path [s]);
        - ``solver_options``: the states' Newton options, as JSON.
    """
    options = PathOptions() if options is None else options
    solver_options = json.dumps(state_options(options.tol, options.max_iter).as_dict())
    note = path.pull_off_note
    if path.control == "displacement":
        note = "; ".join(filter(None, (note, DISPLACEMENT_CONTROL_NOTE)))
    st = path.pull_off_state
    a, b = st.contact_semi_axes()
    c, d = st.cohesive_semi_axes()
    scale = prob.sin_skew / (2.0 * math.pi)  # Eq. (34): W* = W sin(theta_skew) / (2 pi R dgamma)
    w_star = float(path.pull_off_load * scale)
    search_error = float(abs(path.pull_off_error * scale))
    if path.control == "load":
        # the search's error and the grid's
        error = search_error + discretisation_error(w_star, (a, b, c, d), prob.grid)
    elif coarse is None:
        error = search_error + discretisation_error(w_star, (a, b, c, d), prob.grid, contact=False)
    else:
        w_c, n_c = coarse
        error = route_error(search_error, w_star, (a, b, c, d), prob.grid, w_coarse=w_c, n_coarse=n_c)
        note = "; ".join(filter(None, (note, f"grid error from a coarser grid: W* = {w_c:.6g} on n = {n_c}")))
    # the DMT bound is checked with the search's error alone (the stricter test)
    reasons = _unresolved_reasons(prob, path, w_star, search_error, (a, b, c, d), stated_error=error)
    if reasons or not np.isfinite(error):
        error = float("inf")
    if reasons:
        note = "; ".join(filter(None, (note, "unresolved: " + "; ".join(reasons))))
    return PullOff(
        model="bem", control=path.control, geometry="ellipse", beta0=prob.beta0, mu=prob.mu,
        sin_skew=prob.sin_skew, W_star=w_star, a_star=a, b_star=b, c_star=c, d_star=d, v=float("nan"),
        delta_star=float(path.pull_off_approach), ellipticity=b / a if a > 0 else float("nan"),
        adhesive_ellipticity=d / c if c > 0 else float("nan"), at_zero_contact=not a > 0,
        warning=note if reasons else "", W_star_error=error, converged=path.pull_off_converged,
        resolved=not reasons, note=note, search=search, n=int(n), law=prob.law.name, n_steps=path.n_steps,
        iterations=int(path.iterations.sum()), residual=float(path.residual.max()), failures=path.failures,
        half_width_x=0.5 * prob.grid.nx * prob.grid.dx, half_width_y=0.5 * prob.grid.ny * prob.grid.dy,
        elapsed=path.elapsed, solver_options=solver_options, path=path)


def check_bem_pull_off(name, value) -> PullOff:
    """``value`` if it is a BEM pull-off record (a :class:`dhfield.core.records.PullOff` with its path), else ValueError.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    value : object
        The argument.

    Returns
    -------
    dhfield.core.records.PullOff
        ``value``.
    """
    if not (isinstance(value, PullOff) and value.model == "bem" and value.path is not None):
        raise ValueError(f"{name} must be a BEM pull-off (the dhfield.core.records.PullOff of adhesive_pull_off, "
                         f"with its path); got {type(value).__name__}")
    return value


def pull_off_summary(result) -> dict:
    """The JSON-ready summary of a BEM pull-off record (``dhfield solve --json``, case files).

    Parameters
    ----------
    result : dhfield.core.records.PullOff
        A BEM pull-off (:func:`pull_off_result`).

    Returns
    -------
    dict
        Every key of the record in its order (:data:`dhfield.core.schema.PULL_OFF_KEYS` then
        :data:`dhfield.core.schema.PULL_OFF_SOLVER_KEYS`), ``failures`` as a list of dicts
        (not the path).
    """
    out = dict(check_bem_pull_off("result", result))
    out["failures"] = [dict(f) for f in result.failures]
    return out


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


# ============================================================================ coarse to fine
#: Half-width, in finest path steps, of the window of approaches solved around the
#: coarse pull-off by :func:`refine` (the fine minimum moves by O(error) of
#: the coarse one: a fraction of a step at N >= 128).
REFINE_WINDOW = 3
#: Cap on window extensions when the fine minimum sits on the window's edge.
REFINE_MAX_EXTEND = 12


def refine(problem, coarse, *, window=REFINE_WINDOW, options=PathOptions()) -> PullOff:
    """Load-control pull-off on a finer grid, started from a coarser solution (coarse to fine).

    Parameters
    ----------
    problem : NondimensionalProblem
        The fine grid's problem, over the same domain and path range as ``coarse``'s.
    coarse : dhfield.core.records.PullOff
        A BEM load-control pull-off of the same (mu, beta0, law) on a coarser grid.
    window : int
        Half-width of the window of fine states around the coarse pull-off, in
        finest path steps (extended while the fine minimum sits on its edge).
    options : PathOptions
        ``refine_levels`` and ``refine_factor`` of the full path (the fine states
        sit on its finest approach lattice, ``approach_max - j h`` with
        ``h = approach_step / refine_factor**refine_levels``), and the solver settings.

    Returns
    -------
    dhfield.core.records.PullOff
        The BEM's record (:func:`pull_off_result`, ``search='refine'``), with
        ``path.phase == 'refine'`` for every state; ``converged`` when every
        state of the window converged and the minimum is interior.

    Notes
    -----
    Only the states around the load minimum are solved on the fine grid.  The
    first is warm-started from the coarse pull-off state interpolated onto the
    fine grid (:func:`interpolate_state`), the others from their neighbours
    (secant predictor), descending in approach like an unloading path; the
    window is extended while the minimum sits on its edge
    (:meth:`Branch.extend_until_interior`).  The load-control pull-off lies on
    the stable branch of displacement control, so the warm start stays on the
    branch of the full path; multistability after the jump does not enter.
    """
    check_bem_pull_off("coarse", coarse)
    if coarse.control != "load":
        raise ValueError(f"coarse must be a load-control pull-off; got control={coarse.control!r}")
    if not np.isfinite(coarse.delta_star):
        raise ValueError("coarse must hold a pull-off (its delta_star is NaN: no converged contact state)")
    window = check_count("window", window, 1, MAX_STEPS, "finest path steps")
    options = options.checked()
    n = problem.grid.nx
    if n <= coarse.n:
        raise ValueError(f"n must be an integer > coarse.n = {coarse.n} (cells per axis); got {n!r}")
    grid = problem.grid
    if not (math.isclose(0.5 * grid.nx * grid.dx, coarse.half_width_x, rel_tol=1e-9)
            and math.isclose(0.5 * grid.ny * grid.dy, coarse.half_width_y, rel_tol=1e-9)):
        raise ValueError("coarse must come from the same domain (adhesive_pull_off with the default margin)")
    h = problem.approach_step / options.refine_factor ** options.refine_levels
    top = problem.approach_max
    j_c = int(round((top - coarse.delta_star) / h))
    b = Branch(problem.adhesive_problem(options.threads), options.tol, options.max_iter, label=f"refine N={n}",
               progress=options.progress, keep_states=options.keep_states)
    # downwards from the top of the window: warm start from the coarse state, then secant
    st = first = interpolate_state(coarse.path.pull_off_state, grid)
    prev = None
    for j in range(j_c - window, j_c + window + 1):
        d = top - j * h
        new = b.solve(d, first if st is first else b.guess(d, st, prev), "refine")[1]
        prev, st = (None if st is first else st), new

    def next_approach(i, up):
        j = int(round((top - b.approach(i)) / h))
        return top - (j - 1 if up else j + 1) * h

    b.extend_until_interior(range(len(b.records)), next_approach, REFINE_MAX_EXTEND, phase="refine")
    order, sm = b.minimum(range(len(b.records)))
    if sm is None:
        k_po, w_po, d_po = order[-1], float("nan"), float("nan")
    else:
        k_po, w_po, d_po = order[sm.index], sm.y, sm.x
    converged = all(r["converged"] for r in b.records) and sm is not None and not sm.at_boundary
    path = b.to_path(control="load", load=w_po, approach=d_po, pull_off_index=k_po, converged=converged,
                     order=order, error=b.minimum_error(order, sm))
    return pull_off_result(problem, n, path, "refine", options=options)
