"""States solved along the approach of one adhesive problem: the engine under every pull-off route.

A :class:`Branch` solves the states of one :class:`~dhfield.bem.solver.AdhesiveProblem`
at prescribed approaches (or takes them from the continuation), each warm-started
by one policy (:meth:`Branch.guess`), and keeps one record per state, the
failures and, for the warm starts, the states themselves.  On it every route of
:mod:`dhfield.bem.path` and :mod:`dhfield.bem.pull_off` is a short function:
the load minimum of the samples (:meth:`Branch.minimum`), one more state beyond
the end holding it until it is interior (:meth:`Branch.extend_until_interior`),
states at the vertex of the parabola through it (:meth:`Branch.refine_vertex`),
uniform sub-steps of its bracket (:meth:`Branch.refine_bracket`), and the
record of the whole, :class:`UnloadingPath` (:meth:`Branch.to_path`).

The states are multistable: a state is never cold-started part-way along a
branch, only warm-started from a state of the same branch (or the same approach
on a coarser grid).
"""
from __future__ import annotations

import contextlib
import contextvars
import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from ..core.pull_off_search import refine_sampled_minimum
from .solver import secant_prediction, solve_problem
from .state import ContactState

__all__ = ["Branch", "UnloadingPath", "PathProgress", "state_reporter", "answer_grid_changed", "NOT_ON_BRANCH"]

#: Phases of states that are not on the branch: re-solved from separation after the branch
#: ended ('jump'), or a cold start that gave no converged contact state ('discarded').
NOT_ON_BRANCH = ("jump", "discarded")


@dataclass(frozen=True, eq=False)
class UnloadingPath:
    """A displacement-controlled loading-unloading path and its pull-off.

    Parameters
    ----------
    approach, load : ndarray
        Approach delta [length] and load W [force] of every solved state, in
        solve order (loading, unloading, then the refinements of the pull-off
        bracket).
    a, b, c, d : ndarray
        Second-moment semi-axes of contact and of contact U cohesive zone
        [length] per state.
    contact_area : ndarray
        Contact area per state [length^2].
    phase : ndarray of str
        'loading', 'unloading', 'refine', 'jump' (re-solved from separation),
        'discarded' (a cold start of the bracket search that gave no converged
        contact state; kept, flagged, excluded from the pull-off), and under
        displacement control 'continuation' and 'fold' (states at a prescribed
        adhesive force: the coarse steps and the window around the fold) per state.
    converged : ndarray of bool
        True where the state converged, per state.
    iterations : ndarray of int
        GMRES iterations per state (CG without adhesion).
    outer_iterations : ndarray of int
        Outer (cohesive-zone) iterations per state.
    residual : ndarray of float
        Final residual of the solver per state.
    control : str
        'load' or 'displacement': which pull-off is reported.
    pull_off_load, pull_off_approach : float
        Load-control: the minimum of the unloading load, refined by a parabola
        through the three finest samples around it.  Displacement control: the
        minimum of the approach along the branch followed by adhesive force
        (:func:`dhfield.bem.continuation.fold_by_adhesive_force`): the fold, or
        the loss of contact when the approach still falls there (said in
        ``pull_off_note``); when neither is bracketed, the fold of delta(W)
        extrapolated from the converged states
        (:func:`dhfield.bem.path.fold_of_branch`, said in ``pull_off_note``).
    pull_off_state : ContactState
        The solved state nearest to the pull-off (its semi-axes are reported).
    failures : tuple of dict
        Every state that did not converge: approach, residual, iterations,
        phase.  Unconverged states are kept in the arrays (flagged) and
        excluded from the pull-off search.  When a warm-started state does not
        converge on unloading the branch has ended (the jump): the state at
        that approach is re-solved from separation (phase 'jump').
    states : tuple of ContactState
        All states when requested (``keep_states=True``), else empty.
    elapsed : float
        Wall time [s].
    pull_off_converged : bool
        True when every state from the start of the path down to the pull-off
        converged (failures beyond the jump do not count).  Under displacement
        control: a fold or loss of contact was located and the states before the
        branch (loading, start) converged; an unconverged state along the branch
        is left out of the fit (listed in ``failures``).
    resolved : bool
        False when the grid is too coarse for the Dugdale edge (see
        ``EDGE_WIDTH_FACTOR``): the results are then not trustworthy.
    coarse_states, coarse_iterations : int
        States and GMRES iterations solved on coarser grids for the warm starts
        (``warm_start``; 0 without), not counted in the arrays above.
    pull_off_error : float
        Error estimate of ``pull_off_load`` [force], without the grid's
        discretisation error: from the fit around the fold (displacement
        control) or the samples around the minimum (load control,
        :meth:`Branch.minimum_error`); NaN when it cannot be estimated.
    pull_off_note : str
        Caveats on the pull-off (empty if none): under displacement control, a
        branch that ends by loss of contact, or a fold that is not bracketed.
    """

    approach: np.ndarray
    load: np.ndarray
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    contact_area: np.ndarray
    phase: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    outer_iterations: np.ndarray
    residual: np.ndarray
    control: str
    pull_off_load: float
    pull_off_approach: float
    pull_off_state: ContactState
    failures: tuple = ()
    states: tuple = field(default=(), repr=False)
    elapsed: float = 0.0
    pull_off_converged: bool = True
    resolved: bool = True
    coarse_states: int = 0
    coarse_iterations: int = 0
    pull_off_error: float = float("nan")
    pull_off_note: str = ""

    @property
    def n_steps(self) -> int:
        """Number of solved states."""
        return int(self.approach.size)

    @property
    def all_converged(self) -> bool:
        """True when every state of the path converged."""
        return bool(np.all(self.converged))

    @property
    def unloading_order(self) -> np.ndarray:
        """Indices of the unloading and refinement states by decreasing approach."""
        idx = np.nonzero(self.phase != "loading")[0]
        return idx[np.argsort(-self.approach[idx], kind="stable")]

    @classmethod
    def from_records(cls, records, *, control, pull_off_load, pull_off_approach, pull_off_state,
                     **rest) -> "UnloadingPath":
        """Build a path from one record per solved state (:meth:`ContactState.summary` plus its ``phase``).

        Parameters
        ----------
        records : sequence of dict
            One record per state, in the path's order, with the keys ``approach``,
            ``load``, ``a``, ``b``, ``c``, ``d``, ``contact_area``, ``phase``,
            ``converged``, ``iterations``, ``outer_iterations`` and ``residual``.
        control : str
            'load' or 'displacement'.
        pull_off_load, pull_off_approach : float
            The pull-off [force], [length].
        pull_off_state : ContactState
            The solved state nearest to the pull-off.
        **rest
            The other fields, by keyword (``failures``, ``states``, ``elapsed``,
            ``pull_off_converged``, ...).

        Returns
        -------
        UnloadingPath
            The records' columns as arrays, with the given pull-off and fields.
        """
        arr = {key: np.array([r[key] for r in records]) for key in
               ("approach", "load", "a", "b", "c", "d", "contact_area", "phase", "converged", "iterations",
                "outer_iterations", "residual")}
        return cls(arr["approach"], arr["load"], arr["a"], arr["b"], arr["c"], arr["d"], arr["contact_area"],
                   arr["phase"], arr["converged"].astype(bool), arr["iterations"].astype(int),
                   arr["outer_iterations"].astype(int), arr["residual"], control, float(pull_off_load),
                   float(pull_off_approach), pull_off_state, **rest)


#: The callable every solved state of every branch is handed to, within :func:`state_reporter`.
_STATE_REPORTER = contextvars.ContextVar("dhfield_state_reporter", default=None)


@contextlib.contextmanager
def state_reporter(report):
    """Hand every state solved within the block, on any branch, to ``report``.

    Parameters
    ----------
    report : callable
        ``report(label, k, state, phase)`` with the branch's label, the state's record index,
        the :class:`~dhfield.bem.state.ContactState` and its phase; called after the state is
        recorded, also on the branches that draw no progress line (the coarser grids).  It may
        raise to stop the solve (a time limit).  The terminal's progress line is not drawn
        while a reporter is set.

    Yields
    ------
    callable
        ``report``, set for the block.
    """
    token = _STATE_REPORTER.set(report)
    try:
        yield report
    finally:
        _STATE_REPORTER.reset(token)


def answer_grid_changed(shape, reason=""):
    """Tell the reporter of :func:`state_reporter` that the answer's grid is now ``shape`` (a refinement).

    Parameters
    ----------
    shape : (int, int)
        Cells (nx, ny) of the new answer's grid [-].
    reason : str, optional
        Why (e.g. the stated error above its target), for the reporter's line.
    """
    report = _STATE_REPORTER.get()
    if report is not None and hasattr(report, "set_answer_grid"):
        report.set_answer_grid(shape, reason)


class PathProgress:
    """One progress line on stderr (default: when stderr is a terminal), or the states to a reporter.

    Parameters
    ----------
    enabled : bool or None
        Write the line; None: when stderr is a terminal.  False while a
        :func:`state_reporter` is set: the reporter says what runs instead.
    label : str
        Label at the start of the line.
    """

    def __init__(self, enabled, label):
        self.reporter = _STATE_REPORTER.get()
        if enabled is None:
            enabled = bool(getattr(sys.stderr, "isatty", lambda: False)())
        self.enabled = enabled and self.reporter is None
        self.label = label
        self.t0 = time.perf_counter()

    def update(self, k, st, phase):
        """Rewrite the line with state ``k`` (when enabled).

        Parameters
        ----------
        k : int
            Record index of the state.
        st : ContactState
            The state (its approach, load and GMRES iterations are shown).
        phase : str
            Its phase.
        """
        if self.reporter is not None:
            self.reporter(self.label, k, st, phase)
        if self.enabled:
            el = time.perf_counter() - self.t0
            sys.stderr.write(f"\r{self.label} {phase:9s} state {k:3d}  delta={st.approach:+.5f}  "
                             f"W={st.load:+.5f}  it={st.iterations:5d}  {el:6.1f}s ")
            sys.stderr.flush()

    def close(self):
        """End the line (when enabled)."""
        if self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()


class Branch:
    """The states of one problem solved along the approach, their records and their load minimum.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem (grid, initial gap, law) every state solves.
    tol : float
        Solver tolerance, as in :func:`dhfield.bem.solver.solve_problem`.
    max_iter : int
        Cap on GMRES iterations per linear solve, as in :func:`dhfield.bem.solver.solve_problem`.
    label : str
        Label of the progress line.
    progress : bool, optional
        Progress line on stderr (default: when stderr is a terminal).
    keep_states : bool
        Keep every state (else only those :meth:`prune` keeps, for the warm starts).
    warm_start : callable, optional
        ``warm_start(approach)``: a guess for that approach on this grid (a
        ContactState, e.g. the same approach on a coarser grid) or None; its
        ``states_solved`` and ``iterations`` attributes, when present, are
        reported as ``coarse_states`` and ``coarse_iterations``.

    Attributes
    ----------
    records : list of dict
        :meth:`ContactState.summary` of every state, with its ``phase`` and ``in_contact``, in solve order.
    states : dict
        Record index -> ContactState, of the states held.
    """

    def __init__(self, prob, tol, max_iter, *, label="path", progress=None, keep_states=False, warm_start=None):
        self.prob = prob
        self.tol, self.max_iter = float(tol), int(max_iter)
        self.keep_states = bool(keep_states)
        self.warm_start = warm_start
        self.records = []
        self.states = {}
        self._failures = []           # (record index, failure dict), as solved
        self._progress = PathProgress(progress, label)
        self.t0 = time.perf_counter()

    # ------------------------------------------------------------------ solving and recording
    def record(self, st, phase) -> int:
        """Record a solved state under ``phase``.

        Parameters
        ----------
        st : ContactState
            The solved state (held in :attr:`states`; an unconverged one is
            listed as a failure).
        phase : str
            Its phase ('loading', 'unloading', 'refine', 'jump', ...).

        Returns
        -------
        int
            Its record index.
        """
        rec = st.summary()
        rec["phase"] = phase
        rec["in_contact"] = st.in_contact
        self.records.append(rec)
        k = len(self.records) - 1
        self.states[k] = st
        if not st.converged:
            self._failures.append((k, {"approach": float(st.approach), "residual": float(st.residual),
                                       "iterations": int(st.iterations), "phase": phase}))
        self._progress.update(k, st, phase)
        return k

    def solve(self, approach, guess, phase):
        """Solve and record the state at ``approach`` from ``guess``.

        The one start protocol (:func:`dhfield.bem.solver.solve_problem`): Newton from
        ``guess`` (a converged neighbour, or the same approach on a coarser grid), else
        nested iteration from the coarsest grid of the domain.

        Parameters
        ----------
        approach : float
            Approach [length].
        guess : ContactState or Prediction or None
            Warm start (:meth:`guess`); None: nested iteration from the rigid gap's zone.
        phase : str
            Phase of the record.

        Returns
        -------
        (int, ContactState)
            The record index and the state.
        """
        st = solve_problem(self.prob, float(approach), guess, self.tol, self.max_iter)
        return self.record(st, phase), st

    def kept(self) -> list:
        """Return the indices of the records not 'discarded' (a discarded state was solved again).

        Returns
        -------
        list of int
            Record indices in solve order, every phase but 'discarded'.
        """
        return [i for i, r in enumerate(self.records) if r["phase"] != "discarded"]

    def usable(self, i) -> bool:
        """Tell whether record ``i`` is a converged contact state on the branch.

        Parameters
        ----------
        i : int
            Record index.

        Returns
        -------
        bool
            True when it converged, is in contact and its phase is not in
            :data:`NOT_ON_BRANCH`.
        """
        r = self.records[i]
        return bool(r["converged"] and r["in_contact"] and r["phase"] not in NOT_ON_BRANCH)

    def approach(self, i) -> float:
        """Return the approach of record ``i`` [length].

        Parameters
        ----------
        i : int
            Record index.

        Returns
        -------
        float
            Its approach [length].
        """
        return self.records[i]["approach"]

    def by_approach(self, indices) -> list:
        """Sort record indices by decreasing approach (stable).

        Parameters
        ----------
        indices : iterable of int
            Record indices.

        Returns
        -------
        list of int
            ``indices`` by decreasing approach.
        """
        return sorted(indices, key=lambda i: -self.records[i]["approach"])

    def external(self, approach):
        """Return the warm start of ``warm_start`` at ``approach`` when it is a state of this grid.

        Parameters
        ----------
        approach : float
            Approach [length].

        Returns
        -------
        ContactState or None
            The guess of ``warm_start`` (e.g. a coarser grid's state carried onto
            this grid); None without ``warm_start`` or when it is not a state of
            this grid.
        """
        g = self.warm_start(float(approach)) if self.warm_start is not None else None
        return g if (isinstance(g, ContactState) and g.grid == self.prob.grid) else None

    def guess(self, approach, last, prev=None):
        """Choose the warm start at ``approach``.

        The warm start of the coarser grid when there is one (:meth:`external`),
        else the secant extrapolation of ``prev`` and ``last`` when they allow it,
        else ``last``.

        Parameters
        ----------
        approach : float
            Approach of the state to solve [length].
        last : int or ContactState or None
            The last state (record index or state).
        prev : int or ContactState, optional
            The state before it (record index or state).

        Returns
        -------
        ContactState or Prediction or None
            The warm start (None: ``last`` is None or not held).
        """
        last, prev = (self.states.get(s) if isinstance(s, int) else s for s in (last, prev))
        g = self.external(approach)
        if g is not None:
            return g
        return secant_prediction(self.prob, prev, last, approach)

    def nearest_usable(self, approach):
        """Find the held usable state nearest to ``approach``.

        Parameters
        ----------
        approach : float
            Approach [length].

        Returns
        -------
        int or None
            Its record index; None when no held state is usable (:meth:`usable`).
        """
        good = [i for i in self.states if self.usable(i)]
        return min(good, key=lambda i: abs(self.approach(i) - approach)) if good else None

    def prune(self, keep):
        """Drop the held states not in ``keep`` (unless every state is kept).

        Parameters
        ----------
        keep : set of int
            Record indices of the states to hold.
        """
        if not self.keep_states:
            for i in [i for i in self.states if i not in keep]:
                del self.states[i]

    # ------------------------------------------------------------------ the load minimum
    def minimum(self, indices):
        """Find the load minimum over ``indices`` on the branch.

        Parameters
        ----------
        indices : iterable of int
            Record indices.

        Returns
        -------
        order : list of int
            Those indices by decreasing approach, states off the branch left out.
        minimum : SampledMinimum or None
            The load minimum (:func:`dhfield.core.pull_off_search.refine_sampled_minimum`,
            global) over the usable states only; None when there is none.
        """
        order = self.by_approach(i for i in indices if self.records[i]["phase"] not in NOT_ON_BRANCH)
        w = np.array([self.records[i]["load"] if self.usable(i) else np.nan for i in order])
        if not np.any(np.isfinite(w)):
            return order, None
        return order, refine_sampled_minimum(np.array([self.approach(i) for i in order]), w, first=False)

    def minimum_error(self, order, sm) -> float:
        """Error estimate of the load minimum ``sm`` of the states ``order`` [force] (inf at an end).

        The change of the minimum between the parabola's vertex and the best sample (the
        vertex's own error is O(h^3), far smaller); when the vertex is the sample, the load
        step to its nearer neighbour (the samples resolve no better).  It does not include
        the grid's discretisation error.  Infinite when the minimum is at an end of the samples.

        Parameters
        ----------
        order : list of int
            Record indices by decreasing approach (the ``order`` of :meth:`minimum`).
        sm : SampledMinimum or None
            Their load minimum (:meth:`minimum`).

        Returns
        -------
        float
            The error estimate [force]; inf when ``sm`` is None or at an end.
        """
        if sm is None or sm.at_boundary:
            return float("inf")
        w = np.array([self.records[i]["load"] if self.usable(i) else np.nan for i in order])
        best = float(np.nanmin(w))
        if sm.y != best:
            return abs(best - sm.y)
        good = np.flatnonzero(np.isfinite(w))
        at = int(np.searchsorted(good, sm.index))
        near = [w[good[j]] for j in (at - 1, at + 1) if 0 <= j < good.size]
        return float(min(abs(v - best) for v in near)) if near else float("inf")

    def extend_until_interior(self, indices, next_approach, max_states, *, phase="unloading", resolve_jump=False):
        """One more state beyond the end holding the lowest load, until the load minimum is interior.

        Parameters
        ----------
        indices : list of int
            The states of the search so far.
        next_approach : callable
            ``next_approach(i, up)``: the approach one lattice step above (``up``) or below state ``i``.
        max_states : int
            Cap on the states added.
        phase : str
            Phase of the states added.
        resolve_jump : bool
            Re-solve an unconverged state from separation (phase 'jump'): the state after the jump.

        Returns
        -------
        (str, list of int)
            'interior' (the minimum has usable states on both sides), 'branch end' (the state below
            the minimum is off the branch: the jump comes first) or 'failed' (off the branch above it,
            or the cap), and the indices on the branch by decreasing approach.  A state that does not
            converge ends the branch.
        """
        idx = list(indices)
        added = 0
        while True:
            order, sm = self.minimum(idx)
            if sm is None:
                return "failed", order
            if not sm.at_boundary:
                return "interior", order
            good = [p for p, i in enumerate(order) if self.usable(i)]
            if sm.index == good[0]:
                up = True
                if good[0] > 0:       # a state above the minimum is off the branch
                    return "failed", order
            elif good[-1] < len(order) - 1:
                return "branch end", order     # the branch ends below the minimum (the jump)
            else:
                up = False
            if added >= max_states:
                return "failed", order
            end = order[0] if up else order[-1]
            nxt = (order[1] if up else order[-2]) if len(order) > 1 else None
            d_new = next_approach(end, up)
            k, new = self.solve(d_new, self.guess(d_new, end, nxt), phase)
            idx.append(k)
            added += 1
            if resolve_jump and not new.converged:
                # no state on the branch any more (the jump): the state reached from separation
                idx.append(self.solve(d_new, None, "jump")[0])
            self.prune(set(order[max(sm.index - 1, 0):sm.index + 2]) | {k})

    def refine_vertex(self, indices, xtol, max_states, phase="refine"):
        """Solve states at the vertex of the parabola through the load minimum, until it is within ``xtol``.

        Each state from the warm start of the coarser grid or the nearest usable
        state; stops when the vertex is at an end of the samples, within ``xtol``
        of a solved approach, or a vertex state is off the branch.

        Parameters
        ----------
        indices : iterable of int
            Record indices of the samples so far.
        xtol : float
            Stop when the vertex is within this of a solved approach [length].
        max_states : int
            Cap on the states added.
        phase : str, default 'refine'
            Phase of the states added.

        Returns
        -------
        list of int
            ``indices`` and those of the states added.
        """
        current = list(indices)
        for _ in range(int(max_states)):
            order = [i for i in self.by_approach(current) if self.usable(i)]
            x = np.array([self.approach(i) for i in order])
            sm = refine_sampled_minimum(x, np.array([self.records[i]["load"] for i in order]), first=False)
            if sm.at_boundary or float(np.min(np.abs(x - sm.x))) <= xtol:
                break
            k, new = self.solve(sm.x, self.guess(sm.x, self.nearest_usable(sm.x)), phase)
            current.append(k)
            if not (new.converged and new.in_contact):
                break
            self.prune(set(order[max(sm.index - 1, 0):sm.index + 2]) | {k})
        return current

    def refine_bracket(self, indices, step, refine_factor, levels):
        """Re-solve the bracket of the load minimum ``levels`` times with steps ``refine_factor`` smaller.

        Each level re-solves the approaches between the states on either side of the discrete
        minimum from the upper one down (secant warm starts; a state already solved at an
        approach is reused).

        Parameters
        ----------
        indices : iterable of int
            Record indices of the samples.
        step : float
            Their approach step [length].
        refine_factor : int
            Step reduction per level.
        levels : int
            Number of levels.

        Returns
        -------
        list of int
            The record indices of the finest level, by decreasing approach.
        """
        current = list(indices)
        self.prune(set(current))
        h = step
        for _level in range(int(levels)):
            order, sm = self.minimum(current)
            if sm is None or sm.index + 1 >= len(order):
                break
            up, lo = order[max(sm.index - 1, 0)], order[sm.index + 1]
            d_up, d_lo = self.approach(up), self.approach(lo)
            h = h / int(refine_factor)
            n_sub = max(2, int(round((d_up - d_lo) / h)))
            sub = [up]
            st, prev = self.states[up], None
            known = {self.approach(i): i for i in current if i in self.states and self.records[i]["converged"]}
            for dd in np.linspace(d_up, d_lo, n_sub + 1)[1:-1]:
                same = [i for d0, i in known.items() if math.isclose(d0, dd, rel_tol=1e-12, abs_tol=1e-14)]
                if same:                      # already solved at this approach: reuse it
                    k, new = same[0], self.states[same[0]]
                else:
                    k, new = self.solve(dd, secant_prediction(self.prob, prev, st, dd), "refine")
                prev, st = st, new
                sub.append(k)
            sub.append(lo)
            current = sub
            self.prune(set(current))
        return current

    # ------------------------------------------------------------------ the record
    def to_path(self, *, control, load, approach, pull_off_index, converged, order=None,
                error=float("nan"), note="") -> UnloadingPath:
        """Build the :class:`UnloadingPath` of the branch (and close the progress line).

        Parameters
        ----------
        control : str
            'load' or 'displacement'.
        load, approach : float
            The pull-off load [force] and approach [length].
        pull_off_index : int
            Record index of the state nearest to the pull-off (if not held: the
            last held state).
        converged : bool
            The path's ``pull_off_converged``.
        order : sequence of int, optional
            Record indices in the path's order; None (default): solve order.
        error : float, default NaN
            The path's ``pull_off_error`` [force].
        note : str, default ''
            The path's ``pull_off_note``.

        Returns
        -------
        UnloadingPath
            The records in ``order``, the failures, the held states (with
            ``keep_states``), the elapsed time and the warm starts' counts.
        """
        self._progress.close()
        idx = list(range(len(self.records))) if order is None else list(order)
        k = pull_off_index if pull_off_index in self.states else max(self.states)
        rank = {i: r for r, i in enumerate(idx)}
        failures = tuple(f for _, f in sorted(self._failures, key=lambda kf: rank.get(kf[0], len(idx))))
        ws = self.warm_start
        return UnloadingPath.from_records(
            [self.records[i] for i in idx], control=control, pull_off_load=load, pull_off_approach=approach,
            pull_off_state=self.states[k], failures=failures,
            states=tuple(self.states[i] for i in idx) if self.keep_states else (),
            elapsed=time.perf_counter() - self.t0, pull_off_converged=bool(converged),
            resolved=self.prob.resolved, coarse_states=int(getattr(ws, "states_solved", 0)),
            coarse_iterations=int(getattr(ws, "iterations", 0)), pull_off_error=float(error),
            pull_off_note=note)

    def load_pull_off(self, indices) -> UnloadingPath:
        """Find the load-control pull-off of the states ``indices``: the minimum of the load.

        Trusted (``pull_off_converged``) when every state on the branch from the start down to
        it converged; a NaN pull-off (never an exception) when no state is a converged contact state.

        Parameters
        ----------
        indices : iterable of int
            Record indices of the samples.

        Returns
        -------
        UnloadingPath
            The path in solve order, its pull-off the load minimum and its error
            (:meth:`minimum_error`).
        """
        order, sm = self.minimum(indices)
        if sm is None:
            return self.to_path(control="load", load=float("nan"), approach=float("nan"),
                                pull_off_index=len(self.records) - 1, converged=False)
        k_po = order[sm.index]
        reached = [i for i in range(len(self.records)) if self.records[i]["phase"] not in NOT_ON_BRANCH
                   and self.approach(i) >= self.approach(k_po)]
        return self.to_path(control="load", load=sm.y, approach=sm.x, pull_off_index=k_po,
                            converged=all(self.records[i]["converged"] for i in reached),
                            error=self.minimum_error(order, sm))
