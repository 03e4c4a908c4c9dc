"""The load-control pull-off on two grids by the semismooth Newton state solve, with its ladder error.

Problem
-------
The load-control pull-off of the paper's problem is the minimum of the load ``W(delta)``
along the displacement-controlled branch (:mod:`dhfield.bem.energy` explains why the
minimum is reached on the displacement-stable states).  On a grid, ``W(delta)`` is smooth
up to the lattice's jaggedness: as the approach changes, the contact's and the cohesive
zone's edges move through whole cells, and the exact tangent of the discrete system (one
linear solve, :func:`dhfield.bem.newton.load_slope`) is the slope of one tooth, not of the
curve.  The minimum is therefore located from the loads themselves.

Algorithm
---------
On each of two grids over the same domain (the answer's grid, and a coarser check grid), and
on finer ones while the stated error exceeds a target:

1. the first state, at the analytic prediction of the pull-off's approach (or at the check
   grid's minimum), is solved by nested iteration from the analytic cold start
   (:func:`dhfield.bem.newton.solve_state_nested` over grids halving the cells);
2. two more states at ``delta +- h`` are solved the same way (nested iteration from the
   analytic start: the coarse grids place the contact's rim).  From the nearest converged state
   dilated to the contact expected at their approach (``start="neighbour"``) they cost about
   half (at beta0 = 0.8, mu = 10 on 1984^2: 43 and 37 CPU s against 92 and 42), but at
   beta0 = 0.3, mu = 10 a state of the answer's grid then did not converge; from the
   neighbouring state moved along its tangent, the Newton iteration crept;
3. while the lowest load lies at an end of the solved approaches, one more state is solved
   beyond that end, each step twice the last (a bracket);
4. the state at the vertex of the parabola through the lowest load and its two neighbours
   is solved; the lowest load solved is the grid's pull-off, and the distance between the
   vertex state's load and the parabola's vertex value is the search's error.

The check grid's pull-off gives the grid's error by the ladder estimate
(:func:`dhfield.bem.pull_off.ladder_error`); where a grid with 3/4 of the check grid's cells
still resolves the edge, it is solved first, and the estimate of that coarser pair, carried to
the answer's grid at first order, bounds the error too (two grids can agree by chance).  The
stated error is the largest of these and the answer grid's search error.  Every state is solved
with :data:`dhfield.bem.newton.NESTED_OPTIONS` (the watchdog: the best merit falls at least once
in every nine Newton iterations).

The Dugdale edge on a grid is a ramp of width w in the cell's own gap (:mod:`dhfield.bem.newton`),
with ``w = edge_margin x`` the smallest energy-stable width, capped at 2 h0: at ``edge_margin``
= 1 the edge is marginally stable, and the Newton iteration creeps through the edge cells.
A grid resolves the edge when ``edge_margin x edge_width_ratio <= 1``.
"""
from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field

import numpy as np

from .newton import NESTED_OPTIONS, cold_start, load_slope, problem_preconditioner, solve_state, solve_state_nested
from ..core.records import PullOff
from .branch import PathProgress, UnloadingPath, answer_grid_changed
from .pull_off import NondimensionalProblem, ladder_error, unresolved_reasons
from .state import ContactState

__all__ = ["GridMinimum", "LadderPullOff", "nested_levels", "nested_cells", "NESTED_MIN_CELLS", "EDGE_MARGIN",
           "CHECK_RATIO", "TANGENT_RTOL", "NEWTON_SEARCH", "LADDER_STARTS", "dilated_neighbour",
           "adhesive_problem", "ladder_grids", "grid_minimum", "ladder_pull_off", "contact_state", "pull_off_record"]

#: The edge's ramp width per its smallest energy-stable width (a stability margin of the
#: discrete edge; the width still vanishes like dx ln(1/dx) under refinement) [-].
EDGE_MARGIN = 1.5


def adhesive_problem(problem: NondimensionalProblem, threads=1, edge_margin=EDGE_MARGIN):
    """The working arrays of ``problem`` with the Dugdale edge ``edge_margin`` times its stable width.

    Parameters
    ----------
    problem : NondimensionalProblem
        The problem.
    threads : int
        FFTW threads.
    edge_margin : float
        Ramp width per the smallest energy-stable width, >= 1 [-] (capped at 2 h0).

    Returns
    -------
    AdhesiveProblem
        With ``min_spread`` widened and ``resolved``/``edge_width_ratio`` scaled by the margin.
    """
    edge_margin = float(edge_margin)
    if not (math.isfinite(edge_margin) and edge_margin >= 1.0):
        raise ValueError(f"edge_margin must be a number >= 1 (ramp width per its smallest stable width); "
                         f"got {edge_margin!r}")
    prob = problem.adhesive_problem(threads)
    if prob.widest_spread > 0.0 and prob.min_spread < prob.widest_spread:
        prob.min_spread = min(prob.min_spread * edge_margin, prob.widest_spread)
        prob.edge_width_ratio *= edge_margin
        prob.resolved = prob.edge_width_ratio <= 1.0
    return prob


#: The record's ``search`` of this route.
NEWTON_SEARCH = "newton"

#: Relative tolerance of the tangent solve: the tangent only predicts the next state's start [-].
TANGENT_RTOL = 1e-3

#: Cells of the answer's grid per cells of the check grid along each axis [-].
CHECK_RATIO = 4.0 / 3.0


def ladder_grids(problem: NondimensionalProblem, edge_margin=EDGE_MARGIN, ratio=CHECK_RATIO, divisor=8):
    """The cells along x of the check grid and of the answer's grid.

    The check grid is the coarsest with at least ``problem.grid.nx / ratio`` cells whose edge
    is resolved with the margin (``edge_margin x edge_width_ratio <= 1``); the answer's grid
    has ``ratio`` times its cells.  Both are multiples of ``divisor``.

    Parameters
    ----------
    problem : NondimensionalProblem
        The problem; its grid sets the smallest answer's grid.
    edge_margin : float
        As in :func:`adhesive_problem`.
    ratio : float
        Answer's cells per check cells [-].
    divisor : int
        Both counts are multiples of it (the nested levels halve them) [-].

    Returns
    -------
    (int, int)
        Cells along x of the check grid and of the answer's grid.
    """
    from .solver import edge_width_ratio

    def up(n):
        return int(divisor * math.ceil(n / divisor))

    nc = up(problem.grid.nx / ratio)
    while True:
        g = problem.grid_on_cells(nc)
        if edge_margin * edge_width_ratio(g, problem.law) <= 1.0 or nc > 65536:
            break
        nc = up(1.05 * nc)
    return nc, up(ratio * nc)


def contact_state(problem, delta, state) -> ContactState:
    """The full-grid :class:`~dhfield.bem.state.ContactState` of a Newton state.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem it solves.
    delta : float
        Its approach [length].
    state : NewtonResult
        The state (:func:`dhfield.bem.newton.solve_state`).

    Returns
    -------
    ContactState
        :func:`dhfield.bem.solver.newton_contact_state` of the state, with its own GMRES and
        Newton iterations (``iterations``, ``outer_iterations``): the repulsive pressure
        ``q + sigma(h)`` on the contact cells, the adhesive stress ``sigma(h)`` of the grid's
        ramped law, the gap, and (Dugdale) the cohesive fraction ``sigma/sigma0`` off the contact.
    """
    from .solver import newton_contact_state

    return newton_contact_state(problem, delta, state, state.krylov_iterations, state.newton_iterations)


@dataclass
class GridMinimum:
    """The minimum of the load along the displacement-controlled branch on one grid.

    Parameters
    ----------
    shape : tuple of int
        Cells (nx, ny).
    approach : float
        Approach of the minimum [c_r^2/R].
    load : float
        Load of the state at ``approach`` (four quadrants) [problem units].
    search_error : float
        ``|load - vertex|``: the parabola's vertex value against the state solved there [problem units].
    approaches, loads : ndarray
        Every state solved, in order.
    newton_iterations, krylov_iterations : int
        Work over every state, tangent and coarse level.
    converged : bool
        Every state converged and the vertex lies inside the sampled window.
    reason : str
        Why it stopped.
    elapsed : float
        Wall time [s].
    state : ContactState
        The state at ``approach`` (:func:`contact_state`).
    records : list of dict
        :meth:`ContactState.summary` of every state, in order.
    """

    shape: tuple
    approach: float
    load: float
    search_error: float
    approaches: np.ndarray
    loads: np.ndarray
    newton_iterations: int
    krylov_iterations: int
    converged: bool
    reason: str
    elapsed: float
    state: object = field(repr=False, default=None)
    records: list = field(repr=False, default_factory=list)

    @property
    def states(self) -> int:
        """States solved on this grid (the nested first state counted once)."""
        return int(self.loads.size)


def _vertex(x, y):
    """Vertex (x, y) and curvature of the parabola through three points; NaN when not convex."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    a = np.polyfit(x - x[0], y, 2)
    if not a[0] > 0.0:
        return float("nan"), float("nan"), float(a[0])
    xv = -a[1] / (2.0 * a[0])
    return float(x[0] + xv), float(np.polyval(a, xv)), float(a[0])


#: Starts of the states after a grid's first (:func:`grid_minimum`).
LADDER_STARTS = ("nested", "neighbour", "tangent")


def dilated_neighbour(problem, solved, approach):
    """A start at ``approach``: the nearest converged state, dilated to the contact expected there.

    The nearest state's fields are stretched about the centre by the semi-axis change expected
    at ``approach`` (:func:`dhfield.bem.pull_off.dilate_state`, with the factors of
    :func:`dhfield.bem.pull_off.dilation_factors` from the two nearest states).  A neighbour carried as it is leaves its contact's rim a cell or more from the new
    one, which the Newton iteration then moves by a fraction of a cell ring per step.

    Parameters
    ----------
    problem : AdhesiveProblem
        The grid's problem.
    solved : list of (float, NewtonResult, object)
        The converged states of the grid, as (approach, state, tangent).
    approach : float
        Approach of the state to start [c_r^2/R].

    Returns
    -------
    ndarray
        The traction on the working grid [stress].
    """
    from .pull_off import dilate_state, dilation_factors

    near = sorted(solved, key=lambda r: abs(r[0] - approach))[:2]
    cs = contact_state(problem, near[0][0], near[0][1])
    other = contact_state(problem, near[1][0], near[1][1]).summary() if len(near) > 1 else None
    g = dilate_state(cs, *dilation_factors(cs.summary(), other, approach))
    return problem.to_work(g.pressure)


def grid_minimum(problems, approach, half_window, zone, options=NESTED_OPTIONS, max_moves=8, log=None,
                 start="nested"):
    """Locate the load's minimum on the finest grid of a nested ladder.

    Parameters
    ----------
    problems : list of AdhesiveProblem
        The grids of the first state's nested solve, coarsest first; the last is searched.
    approach : float
        Centre of the first window [c_r^2/R].
    half_window : float
        Half-width h of the sampled window [c_r^2/R].
    zone : (float, float)
        Semi-axes (c, d) of the predicted cohesive zone of the analytic cold start
        (:func:`dhfield.bem.newton.cold_start`) on the coarsest grid [length].
    options : SolverOptions
        Options of every state.
    max_moves : int
        Cap on the bracket's steps.
    log : callable, optional
        One line per state.
    start : {"nested", "neighbour", "tangent"}, default "nested"
        Start of every state after the first: nested iteration from the analytic cold start
        on the coarsest grid, as the first state's; or the nearest converged state dilated to
        the contact expected at its approach (:func:`dilated_neighbour`), nested iteration where
        Newton does not converge from it (half the GMRES iterations on five stored cases at
        mu 0.1-5, the same W*; but at beta0 = 0.3, mu = 10 a state of the answer's grid did not
        converge, where every state nested did); or the nearest converged state moved along its
        exact tangent ``dq/d delta`` (at Tabor parameters ~10 the Newton iteration then moves
        the contact's rim by a fraction of a cell ring per step, and creeps).

    Returns
    -------
    GridMinimum
        The minimum, flagged when a state did not converge or no bracket was found.
    """
    t0 = time.perf_counter()
    prob = problems[-1]
    shape = tuple(prob.grid.shape)
    work = [0, 0]
    solved = []                                   # (delta, state, tangent)
    pre = problem_preconditioner(prob, floor=options.symbol_floor)

    def note(d, st, kind):
        work[0] += st.newton_iterations
        work[1] += st.krylov_iterations
        if log is not None:
            log(f"  {shape[0]}x{shape[1]} state {len(solved) + 1}: approach {d:.8f} load {st.load:.8f} "
                f"newton {st.newton_iterations} gmres {st.krylov_iterations} {st.reason} ({kind}, "
                f"{time.perf_counter() - t0:.1f} s)")

    def finish(d, load, err, ok, reason, st):
        return GridMinimum(shape, float(d), float(load), float(err), np.array([r[0] for r in solved]),
                           np.array([r[1].load for r in solved]), work[0], work[1], ok, reason,
                           time.perf_counter() - t0, contact_state(prob, d, st), records)

    records = []
    progress = PathProgress(False, f"{shape[0]}x{shape[1]}")

    def add(d, st):
        cs = contact_state(prob, d, st)
        records.append(cs.summary())
        progress.update(len(records) - 1, cs, "refine")
        tangent = None
        if st.converged and start == "tangent":
            _, tangent = load_slope(prob, st, pre, options, rtol=TANGENT_RTOL)
        solved.append((float(d), st, tangent))
        return st

    if start not in LADDER_STARTS:
        raise ValueError(f"start must be one of {LADDER_STARTS}; got {start!r}")
    first = solve_state_nested(problems, float(approach), cold_start(problems[0], float(approach), zone), options)
    st = first.state
    work[0] += sum(v.newton_iterations for v in first.levels[:-1])
    work[1] += sum(v.krylov_iterations for v in first.levels[:-1])
    note(approach, st, "nested")
    add(approach, st)
    if not st.converged:
        return finish(approach, st.load, float("inf"), False, st.reason, st)

    def nested_at(d):
        got = solve_state_nested(problems, d, cold_start(problems[0], d, zone), options)
        work[0] += sum(v.newton_iterations for v in got.levels[:-1])
        work[1] += sum(v.krylov_iterations for v in got.levels[:-1])
        return got.state

    def solve_at(d):
        kind = f"{start} start"
        if start == "tangent":
            d0, s0, t0_ = min((r for r in solved if r[1].converged), key=lambda r: abs(r[0] - d))
            st = solve_state(prob, d, s0.traction + (d - d0) * t0_, options, pre)
        elif start == "neighbour":
            st = solve_state(prob, d, dilated_neighbour(prob, [r for r in solved if r[1].converged], d), options, pre)
            if not st.converged:          # the one protocol: the converged neighbour, else the coarser grids
                work[0] += st.newton_iterations
                work[1] += st.krylov_iterations
                st, kind = nested_at(d), f"nested start (the neighbour's: {st.reason})"
        else:
            st = nested_at(d)
        note(d, st, kind)
        return add(d, st)

    # bracket: step beyond the lowest end, doubling the step, until the lowest load is interior
    h = float(half_window)
    for d in (float(approach) + h, float(approach) - h):
        if not solve_at(d).converged:
            return finish(d, solved[-1][1].load, float("inf"), False, solved[-1][1].reason, solved[-1][1])
    step = h
    for move in range(max_moves + 1):
        pts = sorted((r[0], r[1].load) for r in solved)
        k = min(range(len(pts)), key=lambda i: pts[i][1])
        if 0 < k < len(pts) - 1:
            break
        if move >= max_moves:
            best = min(solved, key=lambda r: r[1].load)
            return finish(best[0], best[1].load, float("inf"), False, "diverged_bracket", best[1])
        step *= 2.0
        d = pts[k][0] + (step if k == len(pts) - 1 else -step)
        if not solve_at(d).converged:
            return finish(d, solved[-1][1].load, float("inf"), False, solved[-1][1].reason, solved[-1][1])
    # the parabola through the lowest state and its neighbours; the state at its vertex
    xv, yv, _ = _vertex(*zip(*pts[k - 1:k + 2]))
    if np.isfinite(xv):
        s = solve_at(xv)
        if not s.converged:
            return finish(xv, s.load, float("inf"), False, s.reason, s)
        err = abs(s.load - yv)
    else:
        err = float("inf")
    best = min(solved, key=lambda r: r[1].load)
    ok = bool(np.isfinite(err))
    return finish(best[0], best[1].load, err, ok, "converged_minimum" if ok else "diverged_vertex", best[1])


@dataclass
class LadderPullOff:
    """The load-control pull-off on a check grid and the answer's grid, with its stated error.

    Parameters
    ----------
    coarse, fine : GridMinimum
        The check grid's and the answer's grid's minimum.
    load : float
        The answer's load (the fine grid's) [problem units].
    stated_error : float
        Relative error of ``load``: the larger of the ladder estimate
        (:func:`dhfield.bem.pull_off.ladder_error`) and the fine search's error [-].
    options : dict
        The :class:`dhfield.bem.newton.SolverOptions` of every state, and ``edge_margin``.
    converged : bool
        Both grids' minima converged.
    reason : str
        Why it stopped.
    elapsed : float
        Wall time [s].
    answer : NondimensionalProblem
        The answer grid's problem.
    grids : list of GridMinimum
        Every grid's minimum, coarsest first (the check grid and the answer's are the last two).
    note : str
        What the caller should know (a refinement that did not converge) [-].
    """

    coarse: GridMinimum
    fine: GridMinimum
    load: float
    stated_error: float
    options: dict
    converged: bool
    reason: str
    elapsed: float
    answer: object = field(repr=False, default=None)
    grids: list = field(repr=False, default_factory=list)
    note: str = ""


#: Fewest cells per axis of the coarsest grid of a nested solve (:func:`nested_levels`) [-].
NESTED_MIN_CELLS = 16


def nested_levels(nx, ny, min_cells=NESTED_MIN_CELLS) -> int:
    """The grids of a nested solve on ``nx`` x ``ny`` cells: halve while the halves stay even and >= ``min_cells``.

    The global phase of a state (from the analytic cold start) is solved on the coarsest grid:
    a semismooth Newton iteration moves the contact's and the zone's rims by a few cells per
    step, so its iterations grow with the cells between the cold start's rims and the
    solution's; on the coarsest grid that distance is a few cells whatever the finest grid.
    (beta0 = 0.1, mu = 1 on 344 x 88 cells: from 172 x 44 the cold start did not converge in
    60 iterations, from 86 x 22 it converged in 9-11, and each finer grid in 6-7.)

    Parameters
    ----------
    nx, ny : int
        Cells per axis of the finest grid [-].
    min_cells : int
        Fewest cells per axis of the coarsest grid [-].

    Returns
    -------
    int
        Grids in the ladder, >= 1 (1: the finest alone).
    """
    nx, ny, levels = int(nx), int(ny), 1
    while (nx % 2 ** (levels + 1) == 0 and ny % 2 ** (levels + 1) == 0
           and min(nx, ny) // 2 ** levels >= int(min_cells)):
        levels += 1
    return levels


def nested_cells(problem: NondimensionalProblem, nx, round_up=True) -> tuple:
    """Choose cells (nx, ny) near ``nx`` along x, in ``problem``'s cell ratio, that halve down to ~16 per axis.

    Both counts are multiples of the largest power of two k >= 8 with ``min(nx, ny) / k`` still
    at least :data:`NESTED_MIN_CELLS`, so that :func:`nested_levels` reaches a coarsest grid of
    16-32 cells per axis (a count that is a multiple of 8 only stops the ladder at an eighth:
    on 512 x 856 cells at 128 x 214, from which the cold start of beta0 = 0.1, mu = 0.1 diverged).

    Parameters
    ----------
    problem : NondimensionalProblem
        Gives the domain and the cell ratio (:meth:`~dhfield.bem.pull_off.NondimensionalProblem.cells_y`).
    nx : int
        Cells along x wanted [-].
    round_up : bool, default True
        Round ``nx`` up to the multiple (else down).

    Returns
    -------
    (int, int)
        Cells along x and y [-].
    """
    nx = int(nx)
    k = 8
    while min(nx, problem.cells_y(nx)) // (2 * k) >= NESTED_MIN_CELLS:
        k *= 2
    nx = k * (math.ceil(nx / k) if round_up else max(1, math.floor(nx / k)))
    return nx, problem.cells_y(nx, k)


def ladder_pull_off(problem: NondimensionalProblem, n_coarse, *, levels=None, edge_margin=EDGE_MARGIN,
                    options=NESTED_OPTIONS, threads=1, half_window=None, log=None, start="nested",
                    target_error=None, max_refinements=0, grid_check=None, pre_check=True,
                    max_seconds=None) -> LadderPullOff:
    """Locate the load-control pull-off on ``problem``'s grid and on a coarser check grid.

    Parameters
    ----------
    problem : NondimensionalProblem
        The answer's problem (its grid is the answer's grid, unless refined for ``target_error``).
    n_coarse : int
        Cells along x of the check grid, below ``problem.grid.nx`` (even) [-].
    levels : int, optional
        Grids of each state's nested solve (each halving the cells; every grid's cell
        counts must be divisible by ``2**levels``, every level's counts even); default
        :func:`nested_levels` of each grid.
    edge_margin : float
        As in :func:`adhesive_problem`.
    options : SolverOptions
        Options of every state.
    threads : int
        FFTW threads.
    half_window : float, optional
        Half-width of the check grid's window [c_r^2/R]; default a quarter of the problem's
        ``approach_step``; every finer grid uses half of it, centred on the coarser grid's minimum.
    log : callable, optional
        One line per state and per grid.
    start : {"nested", "neighbour", "tangent"}, default "nested"
        Start of the states after each grid's first (:func:`grid_minimum`).
    target_error : float, optional
        Relative stated error wanted [-]: while the stated error exceeds it, a grid with
        :data:`CHECK_RATIO` times the cells is solved and the last two grids give the error
        again, at most ``max_refinements`` times.
    max_refinements : int, default 0
        Cap on those refinements [-].
    grid_check : callable, optional
        ``grid_check(nx, ny)`` raises ValueError for a refinement that must not be solved (memory);
        the refinement then stops, with the last error stated.
    pre_check : bool, default True
        Also solve a third grid with 3/4 of the check grid's cells per axis, where it resolves
        the edge with the margin, so that the stated error is the larger of the last two pairs'
        estimates (the coarser one carried to the finer grid at first order).  The pull-off of a
        grid converges erratically at the 1e-4 level as the rims cross cells, and two grids can
        agree by chance: at beta0 = 0.5, mu = 0.1 W* was -0.853637, -0.852967 and -0.852971 on
        144^2, 192^2 and 256^2 (so 2.4e-5 stated from the last two) and -0.852407 on 768^2.
    max_seconds : float, optional
        Time allowed [s]: a refinement is not started when the time spent so far plus its
        predicted time (the last grid's, times the ratio of cells, times 1.2 for the longer
        transforms and the extra state a finer lattice may take) would exceed it.

    Returns
    -------
    LadderPullOff
        The last two grids' minima and the stated error (infinite when either did not converge).
    """
    t0 = time.perf_counter()
    h = 0.25 * problem.approach_step if half_window is None else float(half_window)
    out = []
    centre = problem.pull_off_approach
    k = 8 if levels is None else 2 ** levels

    def cells(n, up=True):        # a grid's cells: its nested levels reach ~16 cells (or given levels)
        return nested_cells(problem, n, up) if levels is None else (n, problem.cells_y(n, k))

    grids = [problem.on_cells(*cells(n_coarse)), problem]
    n_pre = cells(n_coarse / CHECK_RATIO, False)[0] if levels is None else k * math.floor(n_coarse / CHECK_RATIO / k)
    if pre_check and 2 * k <= n_pre < grids[0].grid.nx:
        from .solver import edge_width_ratio

        pre = problem.on_cells(*cells(n_pre))
        if edge_margin * edge_width_ratio(pre.grid, problem.law) <= 1.0:   # only a grid that resolves its edge
            grids.insert(0, pre)
    opts = dict(options.as_dict(), edge_margin=float(edge_margin))
    err = float("inf")
    j = refinements = 0          # refinements: grids added for target_error (the pre-check grid is not one)
    while j < len(grids):
        nd = grids[j]
        n_levels = nested_levels(nd.grid.nx, nd.grid.ny) if levels is None else int(levels)
        if nd.grid.nx % 2 ** n_levels or nd.grid.ny % 2 ** n_levels:
            raise ValueError(f"{n_levels} levels need cells divisible by {2 ** n_levels}; got "
                             f"{nd.grid.nx} x {nd.grid.ny}")
        if min(nd.grid.nx, nd.grid.ny) // 2 ** (n_levels - 1) < 8:
            raise ValueError(f"levels must leave at least 8 cells per axis on the coarsest nested grid; got "
                             f"{n_levels} levels on {nd.grid.nx} x {nd.grid.ny} cells")
        # the nested grids, coarsest first; the finest is this grid's problem itself
        ladder = [adhesive_problem(nd.on_cells(nd.grid.nx // 2 ** i, nd.grid.ny // 2 ** i) if i else nd, threads,
                                   edge_margin) for i in range(n_levels - 1, -1, -1)]
        res = grid_minimum(ladder, centre, h if j == 0 else 0.5 * h, problem.pull_off_zone, options, log=log,
                           start=start)
        out.append(res)
        if log is not None:
            log(f"grid {res.shape[0]}x{res.shape[1]}: {res.reason} approach {res.approach:.8f} load {res.load:.8f} "
                f"search error {res.search_error:.2e} states {res.states} newton {res.newton_iterations} "
                f"gmres {res.krylov_iterations} ({res.elapsed:.1f} s)")
        if not res.converged:
            last = out[-1]
            if refinements and j == len(grids) - 1 and np.isfinite(err):
                # a refinement for the target error that did not converge: the answer stays the last
                # converged pair's, with its stated error (the refinement was optional)
                return LadderPullOff(out[-3], out[-2], out[-2].load, float(err), opts, True, "converged_minimum",
                                     time.perf_counter() - t0, grids[j - 1], out[:-1],
                                     f"the refinement to {res.shape[0]} x {res.shape[1]} cells did not converge "
                                     f"({res.reason}): the answer is the {out[-2].shape[0]} x {out[-2].shape[1]} "
                                     "grid's")
            return LadderPullOff(out[-2] if len(out) > 1 else last, last, last.load, float("inf"), opts, False,
                                 last.reason, time.perf_counter() - t0, nd, out)
        centre = res.approach
        if j >= 1:
            c, f = out[-2], out[-1]
            err = max(ladder_error(f.load, c.load, f.shape[0], c.shape[0]), f.search_error) / abs(f.load)
            if j >= 2:      # the coarser pair's estimate, carried to this grid at first order
                cc = out[-3]
                err = max(err, ladder_error(c.load, cc.load, c.shape[0], cc.shape[0]) * c.shape[0] / f.shape[0]
                          / abs(f.load))
            if (j == len(grids) - 1 and target_error is not None and err > target_error
                    and refinements < max_refinements):
                if levels is None:
                    nx, ny = cells(CHECK_RATIO * nd.grid.nx)
                else:
                    nx = 8 * math.ceil(CHECK_RATIO * nd.grid.nx / 8)
                    ny = nd.cells_y(nx, k)
                predicted = f.elapsed * (nx * ny) / (f.shape[0] * f.shape[1]) * 1.2
                try:
                    if grid_check is not None:
                        grid_check(nx, ny)
                    if max_seconds is not None and time.perf_counter() - t0 + predicted > max_seconds:
                        raise ValueError(f"it would take ~{predicted:.0f} s more, past the {max_seconds:.0f} s "
                                         "allowed")
                    grids.append(problem.on_cells(nx, ny))
                    refinements += 1
                    answer_grid_changed((nx, ny), f"stated error {err:.2%} above the target {target_error:.2%}")
                except ValueError as exc:
                    if log is not None:
                        log(f"no refinement to {nx}x{ny}: {exc}")
        j += 1
    return LadderPullOff(out[-2], out[-1], out[-1].load, float(err), opts, True, "converged_minimum",
                         time.perf_counter() - t0, grids[-1], out)


def pull_off_record(result: LadderPullOff) -> PullOff:
    """Build the BEM's pull-off record of a two-grid Newton pull-off, in the paper's units (Eq. 34).

    Parameters
    ----------
    result : LadderPullOff
        The pull-off (:func:`ladder_pull_off`).

    Returns
    -------
    dhfield.core.records.PullOff
        As :func:`dhfield.bem.pull_off.pull_off_result`, with ``search`` :data:`NEWTON_SEARCH`:
        W* and the semi-axes of the lowest state on the answer's grid; ``W_star_error`` the
        stated error of :func:`ladder_pull_off` (relative) times ``|W*|``, infinite when the
        pull-off is not resolved (the reasons of :func:`dhfield.bem.pull_off.unresolved_reasons`
        in ``note``); ``iterations`` the GMRES iterations and ``residual`` the largest over the
        answer grid's states; ``path`` the answer grid's states in solve order (phase 'refine');
        ``note`` names the check grid and its W*; ``solver_options`` the states' options and
        ``edge_margin``, as JSON.
    """
    f, c = result.fine, result.coarse
    problem = result.answer
    st = f.state
    a, b = st.contact_semi_axes()
    cc, d = st.cohesive_semi_axes()
    scale = problem.sin_skew / (2.0 * math.pi)         # Eq. (34): W* = W sin(theta_skew) / (2 pi R dgamma)
    w_star = float(f.load * scale)
    error = float(result.stated_error * abs(w_star))
    resolved = bool(st.resolved)
    reasons = unresolved_reasons(law=problem.law, grid=problem.grid, sin_skew=problem.sin_skew,
                                 edge_resolved=resolved, control="load", w_star=w_star,
                                 search_error=float(f.search_error * scale), axes=(a, b, cc, d),
                                 stated_error=error)
    note = (f"grid error from a check grid: W* = {c.load * scale:.6g} on {c.shape[0]} x {c.shape[1]} cells"
            if c is not f else "")
    if not result.converged:
        note = "; ".join(filter(None, (note, f"the search stopped: {result.reason}")))
    note = "; ".join(filter(None, (note, result.note)))
    if reasons or not np.isfinite(error):
        error = float("inf")
    if reasons:
        note = "; ".join(filter(None, (note, "unresolved: " + "; ".join(reasons))))
    records = [dict(r, phase="refine") for r in f.records]
    failures = tuple({"approach": r["approach"], "residual": r["residual"], "iterations": r["iterations"],
                      "phase": "refine"} for r in records if not r["converged"])
    path = UnloadingPath.from_records(records, control="load", pull_off_load=f.load, pull_off_approach=f.approach,
                                      pull_off_state=st, failures=failures, elapsed=result.elapsed,
                                      pull_off_converged=result.converged, resolved=resolved,
                                      coarse_states=c.states if c is not f else 0,
                                      coarse_iterations=c.krylov_iterations if c is not f else 0,
                                      pull_off_error=float(f.search_error))
    return PullOff(
        model="bem", control="load", geometry="ellipse", beta0=problem.beta0, mu=problem.mu,
        sin_skew=problem.sin_skew, W_star=w_star, a_star=a, b_star=b, c_star=cc, d_star=d, v=float("nan"),
        delta_star=float(f.approach), ellipticity=b / a if a > 0 else float("nan"),
        adhesive_ellipticity=d / cc if cc > 0 else float("nan"), at_zero_contact=not a > 0,
        warning=note if reasons else "", W_star_error=error, converged=bool(result.converged),
        resolved=not reasons, note=note, search=NEWTON_SEARCH, n=int(problem.grid.nx), law=problem.law.name,
        n_steps=len(records), iterations=int(f.krylov_iterations), residual=float(max(r["residual"] for r in records)),
        failures=failures, half_width_x=0.5 * problem.grid.nx * problem.grid.dx,
        half_width_y=0.5 * problem.grid.ny * problem.grid.dy, elapsed=float(result.elapsed),
        solver_options=json.dumps(result.options), path=path)
