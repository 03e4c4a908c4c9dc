"""Loading-unloading paths of the adhesive BEM solver, and their pull-off.

:func:`unloading_path` follows the states of one adhesive contact problem
(:mod:`dhfield.bem.solver`), each warm-started from the previous ones (the
states are multistable: never a cold start part-way).

* **Load control** (the minimum of the unloading load): either the marching
  path (loading steps to ``approach_max``, unloading by ``approach_step`` until
  contact is lost, the bracket of the minimum re-solved ``refine_levels`` times
  with finer steps) or, given ``approach_guess``, a *bracket search* around it
  (a handful of states, parabolic vertex refinement).  The minimum is refined
  by :func:`dhfield.pull_off_search.refine_sampled_minimum`.
* **Displacement control** (the jump: the minimum of the approach, i.e. the
  fold of the contact branch, or the loss of contact when the approach still
  falls there): the branch is followed by prescribed adhesive force with the
  approach as an unknown (:mod:`dhfield.bem.continuation`), which is monotone
  through the fold, so the fold is interpolated between converged states on
  both sides.  :func:`fold_of_branch` (the older extrapolation of delta(W) from
  states before the fold) remains as the fallback when nothing is bracketed.

The pull-off in the paper's units (bracket search, nested warm starts, coarse
to fine) is :mod:`dhfield.bem.pull_off`.
"""
from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from .._validation import check_count, check_finite, check_positive, check_sequence
from .continuation import FOLD_STEPS, fold_by_adhesive_force
from .state import ContactState
from .solver import (DEFAULT_MAX_ITER, DEFAULT_TOL, AdhesiveProblem, Prediction, secant_prediction,
                     solve_problem)

__all__ = ["unloading_path", "UnloadingPath", "fold_of_branch", "Fold", "PathProgress"]


@dataclass(frozen=True, eq=False)
class UnloadingPath:
    """A displacement-controlled loading-unloading path and its pull-off.

    Attributes
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
    iterations : ndarray of int
        Inner CG iterations per state.
    outer_iterations : ndarray of int
    residual : ndarray of float
    control : str
        'load' or 'displacement': which pull-off is reported.
    pull_off_load, pull_off_approach : float
        Load-control: the minimum of the unloading load, refined by a parabola
        through the three finest samples around it.  Displacement control: the
        minimum of the approach along the branch followed by adhesive force
        (:func:`dhfield.bem.continuation.fold_by_adhesive_force`): the fold, or
        the loss of contact when the approach still falls there (said in
        ``pull_off_note``); when neither is bracketed, the fold of delta(W)
        extrapolated from the converged states (:func:`fold_of_branch`, said in
        ``pull_off_note``).
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
        States and CG iterations solved on coarser grids for the warm starts
        (``warm_start``; 0 without), not counted in the arrays above.
    pull_off_error : float
        Displacement control: error estimate of ``pull_off_load`` from the fit
        around the fold [force], without the grid's discretisation error (NaN
        when it cannot be estimated, and under load control).
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
        return bool(np.all(self.converged))

    @property
    def unloading_order(self) -> np.ndarray:
        """Indices of the unloading and refinement states by decreasing approach."""
        idx = np.nonzero(self.phase != "loading")[0]
        return idx[np.argsort(-self.approach[idx], kind="stable")]

    @classmethod
    def from_records(cls, records, *, control, pull_off_load, pull_off_approach, pull_off_state,
                     **rest) -> "UnloadingPath":
        """A path from one record per solved state (:meth:`ContactState.summary` plus its ``phase``).

        ``rest``: the keyword attributes (failures, states, elapsed, pull_off_converged, ...).
        """
        arr = {key: np.array([r[key] for r in records]) for key in
               ("approach", "load", "a", "b", "c", "d", "contact_area", "phase", "converged", "iterations",
                "outer_iterations", "residual")}
        return cls(arr["approach"], arr["load"], arr["a"], arr["b"], arr["c"], arr["d"], arr["contact_area"],
                   arr["phase"], arr["converged"].astype(bool), arr["iterations"].astype(int),
                   arr["outer_iterations"].astype(int), arr["residual"], control, float(pull_off_load),
                   float(pull_off_approach), pull_off_state, **rest)


@dataclass(frozen=True)
class Fold:
    """The fold of a sampled unloading branch (displacement-control pull-off).

    Attributes
    ----------
    load, approach : float
        Load W [force] and approach delta [length] at the fold, or of the last
        state when no fold is bracketed.
    load_error : float
        Error estimate of ``load`` [force]: the change of the vertex when the
        last state is left out (NaN when it cannot be estimated).
    found : bool
        True when a fold was bracketed beyond the last state; False when the
        last state is returned instead (a pull-off biased towards stronger
        adhesion: the branch was not followed close enough to its fold).
    """

    load: float
    approach: float
    load_error: float
    found: bool


def fold_of_branch(loads, approaches, *, points=5) -> Fold:
    """Displacement-control pull-off: the fold of a sampled unloading branch, with an error estimate.

    Parameters
    ----------
    loads, approaches : sequence of float
        Load W [force] and approach delta [length] of the converged contact states
        of the branch, by decreasing approach (the last one nearest the jump).
    points : int, default 5
        States used: the last ``points`` (3 to 1000).

    Returns
    -------
    Fold
        The vertex of the least-squares parabola delta(W) through the last
        ``points`` states, its load error estimated by the change of the vertex
        when the last state is left out.  When no fold is bracketed within the
        span of those states beyond the last one: the last state, NaN error and
        ``found=False``.

    Notes
    -----
    Near the jump (d delta/da = 0) the approach is a smooth function of the load
    with a minimum at the fold, delta ~ delta_f + k (W - W_f)^2, while W(delta)
    has a square-root branch point there.  The last states before the jump carry
    few contact cells and do not converge (the discrete contact set flips), so
    the fold is extrapolated from the converged ones; a least-squares fit over
    five states averages the lattice jaggedness of the load (a three-point
    parabola amplified it: -3.50 instead of -2.80 at lambda = 1, N = 128).
    """
    w = check_sequence("loads", loads, "load W of each state, force")
    d = check_sequence("approaches", approaches, "approach delta of each state, length")
    if w.shape != d.shape:
        raise ValueError(f"loads and approaches must have the same length; got {w.size} and {d.size}")
    points = check_count("points", points, 3, 1000, "states in the fit")
    if w.size == 0:
        return Fold(float("nan"), float("nan"), float("nan"), False)
    last = Fold(float(w[-1]), float(d[-1]), float("nan"), False)
    m = min(points, w.size)
    if m < 3:
        return last

    def vertex(k):
        ww, dd = w[-k:], d[-k:]
        if not (np.all(np.isfinite(ww)) and np.all(np.isfinite(dd))) or len(set(ww.tolist())) < 3:
            return None
        c2, c1, c0 = np.polyfit(ww, dd, 2)
        if not c2 > 0:
            return None
        wv = -c1 / (2.0 * c2)
        span = abs(ww[-1] - ww[0])
        if (wv - ww[-1]) * (ww[-1] - ww[0]) < 0.0 or abs(wv - ww[-1]) > span:
            return None
        return float(wv), float(c0 + c1 * wv + c2 * wv * wv)

    fold = vertex(m)
    if fold is None:
        return last
    err = float("nan")
    if m > 3:
        w_, d_ = w[:-1], d[:-1]
        c2, c1, _ = np.polyfit(w_[-(m - 1):], d_[-(m - 1):], 2)   # the same fit without the last state
        if c2 > 0:
            err = abs(-c1 / (2.0 * c2) - fold[0])
    return Fold(fold[0], fold[1], err, True)


class PathProgress:
    def __init__(self, enabled, label):
        if enabled is None:
            enabled = bool(getattr(sys.stderr, "isatty", lambda: False)())
        self.enabled = enabled
        self.label = label
        self.t0 = time.perf_counter()

    def update(self, k, st, phase):
        if self.enabled:
            el = time.perf_counter() - self.t0
            sys.stderr.write(f"\r{self.label} {phase:9s} state {k:3d}  delta={st.approach:+.5f}  "
                             f"W={st.load:+.5f}  it={st.iterations:5d}  {el:6.1f}s ")
            sys.stderr.flush()

    def close(self):
        if self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()


def unloading_path(initial_gap, grid, law, approach_max, approach_step, *, control="load",
                   n_loading=3, refine_levels=2, refine_factor=4, max_steps=200,
                   tol=DEFAULT_TOL, max_iter=DEFAULT_MAX_ITER, symmetric=None, threads=None,
                   reduced_modulus=1.0, keep_states=False, progress=None, predict=True,
                   approach_guess=None, start_stress=None, warm_start=None) -> UnloadingPath:
    """Displacement-controlled loading and unloading path to pull-off, with warm starts.

    Parameters
    ----------
    initial_gap : array_like, shape (nx, ny)
        Initial gap z(x, y) [length].
    grid : Grid
        Cell grid; must contain the cohesive zone of every state.
    law : DugdaleLaw or ExponentialLaw
        Traction law.
    approach_max : float
        Largest approach, reached at the end of loading [length].
    approach_step : float
        Unloading step in approach (> 0) [length]; the pull-off bracket is then
        re-solved ``refine_levels`` times with steps ``refine_factor`` times
        smaller.
    control : {'load', 'displacement'}
        Which pull-off to report (both come from the same path).
    n_loading : int
        Loading steps from approach 0 (first touch) to ``approach_max``.
    max_steps : int
        Cap on unloading states.

    Returns
    -------
    UnloadingPath

    Other Parameters
    ----------------
    tol, max_iter, symmetric, threads, reduced_modulus
        As in :func:`solve_adhesive`.
    keep_states : bool
        Keep every ContactState (memory: three full-grid arrays per state).
    progress : bool, optional
        Progress line on stderr (default: when stderr is a terminal).
    predict : bool, default True
        Warm-start each state from the secant extrapolation of the two previous
        states of the same branch (fewer outer iterations), else from the last.
    approach_guess : float, optional
        Expected approach of the load minimum (e.g. the analytic DH model's
        load-control pull-off) [length].  With ``control='load'`` the path then
        *brackets* the minimum instead of marching to it; with
        ``control='displacement'`` the branch is followed from a state solved
        there instead of from ``approach_max`` (see Notes).
    start_stress : array_like, shape (nx, ny), optional
        Adhesive stress to cold-start the first state of the bracket search from
        (e.g. sigma0 on the analytic cohesive zone at pull-off) [stress];
        default: from the rigid gap.
    warm_start : callable, optional
        ``warm_start(approach)`` returns a guess for that approach on this grid
        (a ContactState, e.g. the same approach solved on a coarser grid and
        interpolated, :class:`NestedWarmStart`) or None; used by the bracket
        search for every state before the defaults above.  Its
        ``states_solved`` and ``iterations`` attributes, when present, are
        reported as ``coarse_states`` and ``coarse_iterations``.

    Notes
    -----
    **Bracket search** (``control='load'`` with ``approach_guess``): the first
    state is solved at ``approach_guess`` from ``start_stress`` (a cold start on
    the contact branch: the analytic zone puts it in that branch's basin; when
    it is not a converged contact state it is kept, flagged 'discarded', and
    the marching path below is run instead).  Then steps of ``approach_step``
    (warm-started, secant predictor) go up or down until the discrete load
    minimum is interior to the samples; nothing beyond the bracket is solved
    (load control needs nothing past the minimum).  The minimum is then located
    by successive parabolic interpolation: at most ``refine_levels + 1`` states
    at the vertex of the parabola through the best sample and its neighbours,
    each warm-started from the nearest sample, stopping when the vertex is
    within ``approach_step / refine_factor**refine_levels`` (the spacing the
    marching refinement reaches) of a solved state.  When the minimum is at the
    end of the contact branch (the jump comes first), the bracket is refined
    with uniform sub-steps as below.

    **Marching path** (otherwise): loading runs from delta = 0 to ``approach_max`` in ``n_loading`` steps,
    unloading by ``approach_step`` until the first state without contact.
    Every state is warm-started from the previous one (never a cold start
    part-way: the states are multistable).  The bracket of the pull-off (the
    states on either side of the discrete load minimum, or of the contact loss
    for displacement control) is re-solved from its upper end with finer steps.
    The load minimum is refined by
    :func:`dhfield.pull_off_search.refine_sampled_minimum` on the finest
    samples.  Under displacement control the contact branch is stable until
    the jump, so no state is lost by stepping past it.

    **Displacement control**: the first state is solved at ``approach_guess``
    as above (else the loading steps end at ``approach_max``), and the branch
    is followed from it by decreasing *adhesive force* with the approach as an
    unknown (:func:`dhfield.bem.continuation.fold_by_adhesive_force`): that
    control is monotone through the fold of the approach, where a prescribed
    approach stops converging, so the fold (the jump) is interpolated between
    states on both sides of it.  ``refine_factor`` divides the force step in
    the window fitted around the fold; ``approach_step``, ``refine_levels`` and
    ``max_steps`` are not used.
    """
    from ..pull_off_search import refine_sampled_minimum

    if control not in ("load", "displacement"):
        raise ValueError(f"control must be one of ('load', 'displacement') (loading mode); got {control!r}")
    if law is None:
        raise ValueError("law must be a DugdaleLaw or an ExponentialLaw for an unloading path; got None")
    prob = AdhesiveProblem(initial_gap, grid, law, symmetric, threads, reduced_modulus)
    dmax = float(check_finite("approach_max", approach_max, "length"))
    step = float(check_positive("approach_step", approach_step, "length"))
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    n_loading = check_count("n_loading", n_loading, 1, 10_000, "loading steps")
    refine_levels = check_count("refine_levels", refine_levels, 0, 20, "refinements of the pull-off bracket")
    refine_factor = check_count("refine_factor", refine_factor, 2, 100, "step division per refinement")
    max_steps = check_count("max_steps", max_steps, 2, 100_000, "cap on unloading states")
    guess_d = None if approach_guess is None else float(
        check_finite("approach_guess", approach_guess, "expected approach of the load minimum, length"))
    start_gap_stress = None
    if start_stress is not None:
        s_full = check_finite("start_stress", start_stress, "adhesive stress of the cold start, stress")
        if s_full.shape != grid.shape:
            raise ValueError(f"start_stress must have the grid shape {grid.shape}; got {s_full.shape}")
        start_gap_stress = np.clip(prob.to_work(s_full), 0.0, law.max_stress)
    t0 = time.perf_counter()
    prog = PathProgress(progress, "path")
    records = []          # (state summary dict, phase)
    failures = []
    by_index = {}

    def run(delta, guess, phase):
        return keep(solve_problem(prob, float(delta), guess, tol, int(max_iter)), phase)

    def keep(st, phase):
        rec = st.summary()
        rec["phase"] = phase
        rec["in_contact"] = st.in_contact
        records.append(rec)
        k = len(records) - 1
        by_index[k] = st
        if not st.converged:
            failures.append({"approach": float(st.approach), "residual": float(st.residual),
                             "iterations": int(st.iterations), "phase": phase})
        prog.update(k, st, phase)
        return k, st

    def usable(i):
        r = records[i]
        return bool(r["converged"] and r["in_contact"] and r["phase"] not in ("jump", "discarded"))

    def by_approach(indices):
        return sorted(indices, key=lambda i: -records[i]["approach"])

    def external(delta):
        g = warm_start(float(delta)) if warm_start is not None else None
        return g if (isinstance(g, ContactState) and g.grid == grid) else None

    def search_minimum():
        """Bracket the load minimum around ``guess_d``: ('bracket' | 'branch end' | 'failed', indices)."""
        guess = external(guess_d)
        if guess is None and start_gap_stress is not None:
            guess = Prediction(np.zeros_like(start_gap_stress), start_gap_stress.copy())
        k, st = run(guess_d, guess, "unloading")
        if not (st.converged and st.in_contact):
            records[k]["phase"] = "discarded"
            return "failed", []
        idx = [k]
        while len(idx) < max_steps:
            order = by_approach(idx)
            j = int(np.argmin([records[i]["load"] for i in order]))
            if 0 < j < len(order) - 1:
                return "bracket", order
            up = j == 0               # the minimum is above the samples: extend upwards
            end, nxt = (order[0], order[1:2]) if up else (order[-1], order[-2:-1])
            d_new = records[end]["approach"] + (step if up else -step)
            last = by_index[end]
            g = external(d_new)
            if g is None:
                g = secant_prediction(prob, by_index[nxt[0]], last, d_new) if (predict and nxt) else last
            k, new = run(d_new, g, "unloading")
            idx.append(k)
            if not (new.converged and new.in_contact):
                if not new.converged:
                    # no state on the branch any more (the jump): the state reached from separation
                    idx.append(run(d_new, None, "jump")[0])
                return ("branch end" if not up else "failed"), by_approach(idx)
            prune(set(order[max(j - 1, 0):j + 2]) | {k})
        return "failed", by_approach(idx)

    def prune(keep):
        if not keep_states:
            for i in list(by_index):
                if i not in keep:
                    del by_index[i]

    if control == "displacement":
        return _displacement_pull_off(prob, keep, run, records, by_index, failures, prog, t0, external,
                                      guess_d, start_gap_stress, dmax, n_loading, refine_factor, tol,
                                      max_iter, keep_states, warm_start)
    outcome, unload = ("none", [])
    if control == "load" and guess_d is not None:
        outcome, unload = search_minimum()
        if outcome == "failed":
            for i in unload:
                if records[i]["phase"] == "unloading":
                    records[i]["phase"] = "discarded"
            unload = []
    if not unload:
        # loading
        st = None
        for delta in np.linspace(0.0, dmax, int(n_loading) + 1)[1:] if dmax > 0 else [dmax]:
            _, st = run(delta, st, "loading")
        # unloading until contact is lost
        delta = dmax
        k, st = run(delta, st, "unloading")
        unload.append(k)
        prev = None
        while st.in_contact and len(unload) < max_steps:
            delta -= step
            k, new = run(delta, secant_prediction(prob, prev, st, delta) if predict else st, "unloading")
            prev = st
            unload.append(k)
            if not new.converged:
                # no state on the branch any more (the jump): the state reached from separation
                k, new = run(delta, None, "jump")
                unload.append(k)
            st = new

    def bracket(indices):
        """(upper, lower, ordered indices) of the pull-off bracket among ``indices``."""
        idx = [i for i in indices if records[i]["phase"] not in ("jump", "discarded")]
        ds = np.array([records[i]["approach"] for i in idx])
        idx = [idx[j] for j in np.argsort(-ds, kind="stable")]
        good = [bool(records[i]["in_contact"] and records[i]["converged"]) for i in idx]
        if not any(good):
            return None
        if control == "displacement":
            # the last good contact state before the branch ends (contact lost or no state)
            first_bad = next((j for j, g in enumerate(good) if not g and j > 0 and good[j - 1]), None)
            if first_bad is None:
                last = max(j for j, g in enumerate(good) if g)
                return idx[last], (idx[last + 1] if last + 1 < len(idx) else None), idx
            return idx[first_bad - 1], idx[first_bad], idx
        w = np.array([records[i]["load"] if g else np.nan for i, g in zip(idx, good)])
        sm = refine_sampled_minimum(np.array([records[i]["approach"] for i in idx]), w, first=False)
        j = sm.index
        up = idx[max(j - 1, 0)]
        lo = idx[j + 1] if j + 1 < len(idx) else None
        return up, lo, idx

    current = list(unload)
    prune(set(current))
    h = step
    if outcome == "bracket":
        # successive parabolic interpolation on the samples around the discrete minimum
        xtol = step / int(refine_factor) ** int(refine_levels)
        for _level in range(int(refine_levels) + 1):
            order = [i for i in by_approach(current) if usable(i)]
            x = np.array([records[i]["approach"] for i in order])
            sm = refine_sampled_minimum(x, np.array([records[i]["load"] for i in order]), first=False)
            if sm.at_boundary or float(np.min(np.abs(x - sm.x))) <= xtol:
                break
            near = sorted(order, key=lambda i: abs(records[i]["approach"] - sm.x))
            g = external(sm.x)
            k, new = run(sm.x, g if g is not None else by_index.get(near[0]), "refine")
            current.append(k)
            if not (new.converged and new.in_contact):
                break
            prune(set(order[max(sm.index - 1, 0):sm.index + 2]) | {k})
    for _level in range(int(refine_levels) if outcome != "bracket" else 0):
        br = bracket(current)
        if br is None or br[1] is None:
            break
        up, lo, _ = br
        d_up, d_lo = records[up]["approach"], records[lo]["approach"]
        h = h / int(refine_factor)
        n_sub = max(2, int(round((d_up - d_lo) / h)))
        sub = [up]
        st = by_index[up]
        prev = None
        known = {records[i]["approach"]: i for i in current if i in by_index and records[i]["converged"]}
        for dd in np.linspace(d_up, d_lo, n_sub + 1)[1:-1]:
            same = [i for d0, i in known.items() if math.isclose(d0, dd, rel_tol=1e-12, abs_tol=1e-14)]
            if same:                      # already solved at this approach: reuse it
                k, new = same[0], by_index[same[0]]
            else:
                k, new = run(dd, secant_prediction(prob, prev, st, dd) if predict else st, "refine")
            prev, st = st, new
            sub.append(k)
        sub.append(lo)
        current = sub
        prune(set(current))
    prog.close()
    # pull-off
    br = bracket(current)
    w_po_error, po_note = float("nan"), ""
    if br is None:
        # no converged contact state at all: report the failure (NaN pull-off), never raise
        k_po = len(records) - 1
        w_po = d_po = float("nan")
        po_converged = False
    elif control == "displacement":
        up, lo, idx = br
        k_po = up
        # the fold from every converged contact state of the branch down to the last one
        # (the finest bracket alone holds too few states above it)
        branch = sorted((i for i in range(len(records)) if records[i]["phase"] in ("unloading", "refine")
                         and records[i]["converged"] and records[i]["in_contact"]
                         and records[i]["approach"] >= records[up]["approach"]),
                        key=lambda i: -records[i]["approach"])
        fold = fold_of_branch([records[i]["load"] for i in branch],
                              [records[i]["approach"] for i in branch])
        w_po, d_po, w_po_error = fold.load, fold.approach, fold.load_error
        if not fold.found:
            po_note = ("no fold of delta(W) is bracketed by the converged states: the pull-off is the last "
                       "converged contact state")
    else:
        up, lo, idx = br
        x = np.array([records[i]["approach"] for i in idx])
        w = np.array([records[i]["load"] if (records[i]["converged"] and records[i]["in_contact"])
                      else np.nan for i in idx])
        sm = refine_sampled_minimum(x, w, first=False)
        k_po = idx[sm.index]
        w_po, d_po = sm.y, sm.x
    if br is not None:
        # the pull-off is trusted when every state from the start down to it converged
        reached = [i for i in range(len(records)) if records[i]["phase"] not in ("jump", "discarded")
                   and records[i]["approach"] >= records[k_po]["approach"]]
        po_converged = all(records[i]["converged"] for i in reached)
    return _path_result(prob, records, by_index, failures, control, w_po, d_po, k_po, po_converged, t0,
                        keep_states, warm_start, w_po_error, po_note)


def _path_result(prob, records, by_index, failures, control, w_po, d_po, k_po, po_converged, t0, keep_states,
                 warm_start, w_po_error, po_note) -> UnloadingPath:
    if k_po not in by_index:
        k_po = max(by_index)
    states = tuple(by_index[i] for i in range(len(records))) if keep_states else ()
    return UnloadingPath.from_records(
        records, control=control, pull_off_load=w_po, pull_off_approach=d_po, pull_off_state=by_index[k_po],
        failures=tuple(failures), states=states, elapsed=time.perf_counter() - t0, pull_off_converged=po_converged,
        resolved=prob.resolved, coarse_states=int(getattr(warm_start, "states_solved", 0)),
        coarse_iterations=int(getattr(warm_start, "iterations", 0)), pull_off_error=float(w_po_error),
        pull_off_note=po_note)


#: Notes of a displacement-control pull-off by how the contact branch ends (:func:`fold_by_adhesive_force`).
CONTACT_LOSS_NOTE = ("the contact branch ends where its last contact cell opens, before a fold of the "
                     "approach (the end a = 0 of the Maugis-Dugdale curve): the pull-off is the load there; "
                     "the Dugdale contact then continues on the separated branch without a jump")
FOLD_NOT_FOUND_NOTE = ("no fold of the approach (nor a loss of contact) was bracketed along the adhesive "
                       "force: the pull-off is extrapolated from the converged states (fold_of_branch)")


def _displacement_pull_off(prob, keep, run, records, by_index, failures, prog, t0, external, guess_d,
                           start_gap_stress, dmax, n_loading, refine_factor, tol, max_iter, keep_states,
                           warm_start) -> UnloadingPath:
    """Displacement control: a start state, then the branch by adhesive force through its fold."""
    start = None
    if guess_d is not None:
        guess = external(guess_d)
        if guess is None and start_gap_stress is not None:
            guess = Prediction(np.zeros_like(start_gap_stress), start_gap_stress.copy())
        k, st = run(guess_d, guess, "unloading")
        if st.converged and st.in_contact:
            start = st
        else:
            records[k]["phase"] = "discarded"
    if start is None:
        st = None
        for delta in np.linspace(0.0, dmax, int(n_loading) + 1)[1:] if dmax > 0 else [dmax]:
            _, st = run(delta, st, "loading")
        if st.converged and st.in_contact:
            start = st
    if start is None:
        prog.close()
        # no converged contact state to start from: report the failure (NaN pull-off), never raise
        return _path_result(prob, records, by_index, failures, "displacement", float("nan"), float("nan"),
                            len(records) - 1, False, t0, keep_states, warm_start, float("nan"), "")
    index_of = {id(start): len(records) - 1}

    def record(state, phase):
        keep(state, phase)
        index_of[id(state)] = len(records) - 1

    fold = fold_by_adhesive_force(prob, start, steps=FOLD_STEPS, refine_factor=refine_factor, tol=tol,
                                  max_iter=int(max_iter), record=record)
    prog.close()
    k_po = index_of.get(id(fold.nearest), len(records) - 1)
    if not keep_states:               # the summaries stay; of the states only the reported one
        for i in [i for i in by_index if i != k_po]:
            del by_index[i]
    branch = [i for i in range(len(records)) if records[i]["phase"] in ("unloading", "continuation", "fold")]
    if fold.kind == "failed":
        good = sorted((i for i in branch if records[i]["converged"] and records[i]["in_contact"]),
                      key=lambda i: -records[i]["approach"])
        old = fold_of_branch([records[i]["load"] for i in good], [records[i]["approach"] for i in good])
        return _path_result(prob, records, by_index, failures, "displacement", old.load, old.approach, k_po,
                            False, t0, keep_states, warm_start, old.load_error, FOLD_NOT_FOUND_NOTE)
    # the fit uses converged states only: an unconverged state along the adhesive force is a hole
    # in the samples (listed in failures), not a failure of the pull-off; the states before
    # the branch (loading, the start) must have converged
    po_converged = all(records[i]["converged"] for i in range(len(records))
                       if records[i]["phase"] in ("loading", "unloading"))
    note = CONTACT_LOSS_NOTE if fold.kind == "contact loss" else ""
    return _path_result(prob, records, by_index, failures, "displacement", fold.load, fold.approach, k_po,
                        po_converged, t0, keep_states, warm_start, fold.load_error, note)
