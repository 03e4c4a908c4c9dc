"""Loading-unloading paths of the adhesive BEM solver, and their pull-off.

:func:`unloading_path` follows the states of one adhesive contact problem
(:mod:`dhfield.bem.solver`), each warm-started from the previous ones (the
states are multistable: never a cold start part-way).

* **Load control** (the minimum of the unloading load): either the marching
  path (loading steps to ``approach_max``, unloading by ``approach_step`` until
  contact is lost, the bracket of the minimum re-solved ``refine_levels`` times
  with finer steps) or, given ``approach_guess``, a *bracket search* around it
  (a handful of states, parabolic vertex refinement).  The minimum is refined
  by :func:`dhfield.core.pull_off_search.refine_sampled_minimum`.
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

from dataclasses import dataclass, fields, replace

import numpy as np

from ..core.validation import check_count, check_finite, check_positive, check_sequence
from .branch import Branch, PathProgress, UnloadingPath
from .continuation import FOLD_STEPS, fold_by_adhesive_force
from .solver import DEFAULT_MAX_ITER, DEFAULT_TOL, AdhesiveProblem, Prediction, secant_prediction

__all__ = ["unloading_path", "UnloadingPath", "fold_of_branch", "Fold", "PathProgress", "PathOptions",
           "PathStart", "bracket_search", "marching_path", "continuation_path", "loading_steps"]


@dataclass(frozen=True)
class Fold:
    """The fold of a sampled unloading branch (displacement-control pull-off).

    Parameters
    ----------
    load : float
        Load W at the fold, or of the last state when no fold is bracketed [force].
    approach : float
        Approach delta at the fold, or of the last state when no fold is bracketed [length].
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



@dataclass(frozen=True)
class PathOptions:
    """Settings of a path (:func:`unloading_path`) and of the pull-off routes on it.

    Parameters
    ----------
    n_loading : int, default 3
        Loading steps from approach 0 (first touch) to ``approach_max`` (1-10000).
    refine_levels : int, default 2
        Refinements of the pull-off bracket (0-20).
    refine_factor : int, default 4
        Step division per refinement (2-100).
    max_steps : int, default 200
        Cap on unloading states (2-100000).
    tol : float, default DEFAULT_TOL
        Solver tolerance [-], as in :func:`dhfield.bem.solve_adhesive`.
    max_iter : int, default DEFAULT_MAX_ITER
        Iteration cap per state, as in :func:`dhfield.bem.solve_adhesive`.
    symmetric : bool, optional
        Quadrant symmetry, as in :func:`dhfield.bem.solve_adhesive`.
    threads : int, optional
        FFT worker threads, as in :func:`dhfield.bem.solve_adhesive`.
    reduced_modulus : float, default 1.0
        E* [stress], as in :func:`dhfield.bem.solve_adhesive`.
    keep_states : bool, default False
        Keep every ContactState (memory: three full-grid arrays per state).
    progress : bool, optional
        Progress line on stderr (default: when stderr is a terminal).
    """

    n_loading: int = 3
    refine_levels: int = 2
    refine_factor: int = 4
    max_steps: int = 200
    tol: float = DEFAULT_TOL
    max_iter: int = DEFAULT_MAX_ITER
    symmetric: bool | None = None
    threads: int | None = None
    reduced_modulus: float = 1.0
    keep_states: bool = False
    progress: bool | None = None

    def checked(self) -> "PathOptions":
        """Check every count and tolerance of these options.

        Returns
        -------
        PathOptions
            The options, converted to their types.

        Raises
        ------
        ValueError
            Naming the first bad option and its valid range.
        """
        return replace(
            self, n_loading=check_count("n_loading", self.n_loading, 1, 10_000, "loading steps"),
            refine_levels=check_count("refine_levels", self.refine_levels, 0, 20,
                                      "refinements of the pull-off bracket"),
            refine_factor=check_count("refine_factor", self.refine_factor, 2, 100, "step division per refinement"),
            max_steps=check_count("max_steps", self.max_steps, 2, 100_000, "cap on unloading states"),
            tol=float(check_positive("tol", self.tol, "solver tolerance, dimensionless")),
            max_iter=check_count("max_iter", self.max_iter, 1, 10_000_000, "iterations per state"))

    @classmethod
    def from_keywords(cls, options) -> "PathOptions":
        """Build checked options from keyword arguments.

        Parameters
        ----------
        options : dict
            Option name -> value.

        Returns
        -------
        PathOptions
            The checked options.

        Raises
        ------
        ValueError
            Naming an unknown option.
        """
        known = {f.name for f in fields(cls)}
        for name in options:
            if name not in known:
                raise ValueError(f"unknown path option {name!r}; the options are {sorted(known)}")
        return cls(**options).checked()


@dataclass(frozen=True)
class PathStart:
    """Where a path starts, chosen by the caller: the cold start of the bracket search.

    Parameters
    ----------
    approach : float, optional
        Approach of the first state (e.g. an analytic model's load-control pull-off) [length];
        None: the marching path from ``approach_max``.
    stress : ndarray, optional
        Adhesive stress (working arrays of the problem) of its cold start [stress]; None: from the rigid gap.
    warm_start : callable, optional
        ``warm_start(approach)`` -> a guess on this grid or None (:class:`Branch`).
    """

    approach: float | None = None
    stress: np.ndarray | None = None
    warm_start: object = None

    def cold_start(self, branch, phase="unloading"):
        """Solve the first state at :attr:`approach`.

        From the warm start at that approach, else from :attr:`stress`, else from the rigid gap;
        a state that is not a converged contact state is kept, flagged 'discarded'.

        Parameters
        ----------
        branch : dhfield.bem.branch.Branch
            The branch that solves and records the state.
        phase : str, default "unloading"
            Phase recorded with the state.

        Returns
        -------
        ContactState or None
            The state, or None when it is not a converged contact state.
        """
        guess = branch.external(self.approach)
        if guess is None and self.stress is not None:
            guess = Prediction(np.zeros_like(self.stress), self.stress.copy())
        k, st = branch.solve(self.approach, guess, phase)
        if st.converged and st.in_contact:
            return st
        branch.records[k]["phase"] = "discarded"
        return None


def bracket_search(branch, start, step, options):
    """Bracket the load minimum around ``start.approach`` under load control (a handful of states).

    The cold start, then steps of
    ``step`` up or down (:meth:`Branch.extend_until_interior`) until the discrete minimum is
    interior, then parabola vertices (:meth:`Branch.refine_vertex`) to the spacing the
    marching refinement reaches; when the branch ends below the minimum (the jump comes
    first), its bracket is refined with uniform sub-steps (:meth:`Branch.refine_bracket`).

    Parameters
    ----------
    branch : dhfield.bem.branch.Branch
        The branch that solves and records the states.
    start : PathStart
        The cold start (its ``approach`` must be set).
    step : float
        Approach step [length].
    options : PathOptions
        Checked settings.

    Returns
    -------
    outcome : {"interior", "branch end", "failed"}
        How the search ended.
    indices : list of int
        Records of the bracket on ``branch``.
    """
    first = start.cold_start(branch)
    if first is None:
        return "failed", []
    outcome, current = branch.extend_until_interior(
        [len(branch.records) - 1], lambda i, up: branch.approach(i) + (step if up else -step),
        options.max_steps - 1, resolve_jump=True)
    if outcome == "failed":
        return outcome, current
    branch.prune(set(current))
    if outcome == "interior":
        xtol = step / options.refine_factor ** options.refine_levels
        return outcome, branch.refine_vertex(current, xtol, options.refine_levels + 1)
    return outcome, branch.refine_bracket(current, step, options.refine_factor, options.refine_levels)


def loading_steps(branch, approach_max, n_loading):
    """Solve loading steps from approach 0 (first touch) to ``approach_max``, each from the last.

    Parameters
    ----------
    branch : Branch
        The branch the states are solved and recorded on.
    approach_max : float
        The last approach [c_r^2/R].
    n_loading : int
        The number of equal steps.

    Returns
    -------
    ContactState
        The last state.
    """
    st = None
    for delta in np.linspace(0.0, approach_max, int(n_loading) + 1)[1:] if approach_max > 0 else [approach_max]:
        _, st = branch.solve(delta, st, "loading")
    return st


def marching_path(branch, approach_max, step, options):
    """March a load-control path: loading, then unloading until contact is lost.

    Loading to ``approach_max``, unloading by ``step`` until contact is lost, then
    the bracket of the load minimum re-solved ``refine_levels`` times with finer steps.

    Parameters
    ----------
    branch : dhfield.bem.branch.Branch
        The branch that solves and records the states.
    approach_max : float
        Largest approach [length].
    step : float
        Unloading approach step [length].
    options : PathOptions
        Checked settings.

    Returns
    -------
    list of int
        Records of the final bracket on ``branch``.
    """
    st = loading_steps(branch, approach_max, options.n_loading)
    delta = approach_max
    k, st = branch.solve(delta, st, "unloading")
    unload = [k]
    prev = None
    while st.in_contact and len(unload) < options.max_steps:
        delta -= step
        k, new = branch.solve(delta, secant_prediction(branch.prob, prev, st, delta), "unloading")
        prev = st
        unload.append(k)
        if not new.converged:
            # no state on the branch any more (the jump): the state reached from separation
            k, new = branch.solve(delta, None, "jump")
            unload.append(k)
        st = new
    return branch.refine_bracket(unload, step, options.refine_factor, options.refine_levels)


#: Notes of a displacement-control pull-off by how the contact branch ends (:func:`fold_by_adhesive_force`).
CONTACT_LOSS_NOTE = ("the contact branch ends where its last contact cell opens, before a fold of the "
                     "approach (the end a = 0 of the Maugis-Dugdale curve): the pull-off is the load there; "
                     "the Dugdale contact then continues on the separated branch without a jump")
FOLD_NOT_FOUND_NOTE = ("no fold of the approach (nor a loss of contact) was bracketed along the adhesive "
                       "force: the pull-off is extrapolated from the converged states (fold_of_branch)")


def continuation_path(branch, start, approach_max, options) -> UnloadingPath:
    """Follow the branch by adhesive force through its fold (displacement control).

    The start is solved at ``start.approach`` (else the loading steps end at
    ``approach_max``); :func:`dhfield.bem.continuation.fold_by_adhesive_force` records
    every state of the branch on ``branch``.

    Parameters
    ----------
    branch : dhfield.bem.branch.Branch
        The branch that solves and records the states.
    start : PathStart
        The cold start.
    approach_max : float
        Largest approach of the loading steps [length].
    options : PathOptions
        Checked settings.

    Returns
    -------
    UnloadingPath
        The path and its displacement-control pull-off (NaN, not converged, when
        no contact state could be started).
    """
    first = start.cold_start(branch) if start.approach is not None else None
    if first is None:
        st = loading_steps(branch, approach_max, options.n_loading)
        first = st if (st.converged and st.in_contact) else None
    if first is None:
        # no converged contact state to start from: report the failure (NaN pull-off), never raise
        return branch.to_path(control="displacement", load=float("nan"), approach=float("nan"),
                              pull_off_index=len(branch.records) - 1, converged=False)
    index_of = {id(first): len(branch.records) - 1}

    def record(state, phase):
        index_of[id(state)] = branch.record(state, phase)

    fold = fold_by_adhesive_force(branch.prob, first, steps=FOLD_STEPS, refine_factor=options.refine_factor,
                                  tol=options.tol, max_iter=options.max_iter, record=record)
    k_po = index_of.get(id(fold.nearest), len(branch.records) - 1)
    branch.prune({k_po})              # the summaries stay; of the states only the reported one
    records = branch.records
    if fold.kind == "failed":
        good = branch.by_approach(i for i in range(len(records))
                                  if records[i]["phase"] in ("unloading", "continuation", "fold")
                                  and records[i]["converged"] and records[i]["in_contact"])
        old = fold_of_branch([records[i]["load"] for i in good], [records[i]["approach"] for i in good])
        return branch.to_path(control="displacement", load=old.load, approach=old.approach, pull_off_index=k_po,
                              converged=False, error=old.load_error, note=FOLD_NOT_FOUND_NOTE)
    # the fit uses converged states only: an unconverged state along the adhesive force is a hole
    # in the samples (listed in failures), not a failure of the pull-off; the states before
    # the branch (loading, the start) must have converged
    converged = all(r["converged"] for r in records if r["phase"] in ("loading", "unloading"))
    return branch.to_path(control="displacement", load=fold.load, approach=fold.approach, pull_off_index=k_po,
                          converged=converged, error=fold.load_error,
                          note=CONTACT_LOSS_NOTE if fold.kind == "contact loss" else "")


def load_control_path(branch, start, approach_max, step, options) -> UnloadingPath:
    """Load control: the bracket search from ``start`` when it has an approach, else (or when it
    fails: its states are kept, flagged 'discarded') the marching path; the pull-off is the load minimum."""
    outcome, current = ("none", [])
    if start.approach is not None:
        outcome, current = bracket_search(branch, start, step, options)
        if outcome == "failed":
            for i in current:
                if branch.records[i]["phase"] == "unloading":
                    branch.records[i]["phase"] = "discarded"
            current = []
    if not current:
        current = marching_path(branch, approach_max, step, options)
    return branch.load_pull_off(current)


def unloading_path(initial_gap, grid, law, approach_max, approach_step, *, control="load",
                   approach_guess=None, start_stress=None, warm_start=None, **options) -> UnloadingPath:
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
        Which pull-off to report.
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
        interpolated, :class:`dhfield.bem.pull_off.NestedWarmStart`) or None; used
        for every state of the bracket search before the defaults above.  Its
        ``states_solved`` and ``iterations`` attributes, when present, are
        reported as ``coarse_states`` and ``coarse_iterations``.
    **options
        The fields of :class:`PathOptions`: n_loading, refine_levels,
        refine_factor, max_steps, tol, max_iter, symmetric, threads,
        reduced_modulus, keep_states, progress.

    Returns
    -------
    UnloadingPath
        The states' summaries and the pull-off of ``control``.

    Notes
    -----
    A dispatcher: the states are solved on one :class:`dhfield.bem.branch.Branch`.

    **Bracket search** (``control='load'`` with ``approach_guess``,
    :func:`bracket_search`): the first state is solved at ``approach_guess``
    from ``start_stress`` (a cold start on the contact branch: the analytic
    zone puts it in that branch's basin; when it is not a converged contact
    state it is kept, flagged 'discarded', and the marching path is run
    instead).  Then steps of ``approach_step`` (warm-started, secant
    predictor) go up or down until the discrete load minimum is interior to
    the samples; nothing beyond the bracket is solved.  The minimum is then
    located by successive parabolic interpolation: at most
    ``refine_levels + 1`` states at the vertex of the parabola through the
    best sample and its neighbours, each warm-started from the nearest sample,
    stopping when the vertex is within ``approach_step /
    refine_factor**refine_levels`` of a solved state.  When the minimum is at
    the end of the contact branch (the jump comes first), the bracket is
    refined with uniform sub-steps as below.

    **Marching path** (otherwise, :func:`marching_path`): loading from
    delta = 0 to ``approach_max`` in ``n_loading`` steps, unloading by
    ``approach_step`` until the first state without contact, every state
    warm-started from the previous ones; the bracket of the discrete load
    minimum is re-solved from its upper end with finer steps.  The load
    minimum is refined by :func:`dhfield.core.pull_off_search.refine_sampled_minimum`
    on the finest samples.

    **Displacement control** (:func:`continuation_path`): the first state is
    solved at ``approach_guess`` as above (else the loading steps end at
    ``approach_max``), and the branch is followed from it by decreasing
    *adhesive force* with the approach as an unknown
    (:func:`dhfield.bem.continuation.fold_by_adhesive_force`): that control is
    monotone through the fold of the approach, where a prescribed approach
    stops converging, so the fold (the jump) is interpolated between states on
    both sides of it.  ``refine_factor`` divides the force step in the window
    fitted around the fold; ``approach_step``, ``refine_levels`` and
    ``max_steps`` are not used.
    """
    if control not in ("load", "displacement"):
        raise ValueError(f"control must be one of ('load', 'displacement') (loading mode); got {control!r}")
    if law is None:
        raise ValueError("law must be a DugdaleLaw or an ExponentialLaw for an unloading path; got None")
    opts = PathOptions.from_keywords(options)
    prob = AdhesiveProblem(initial_gap, grid, law, opts.symmetric, opts.threads, opts.reduced_modulus)
    dmax = float(check_finite("approach_max", approach_max, "length"))
    step = float(check_positive("approach_step", approach_step, "length"))
    guess_d = None if approach_guess is None else float(
        check_finite("approach_guess", approach_guess, "expected approach of the load minimum, length"))
    stress = None
    if start_stress is not None:
        s_full = check_finite("start_stress", start_stress, "adhesive stress of the cold start, stress")
        if s_full.shape != grid.shape:
            raise ValueError(f"start_stress must have the grid shape {grid.shape}; got {s_full.shape}")
        stress = np.clip(prob.to_work(s_full), 0.0, law.max_stress)
    return path_on(prob, PathStart(guess_d, stress, warm_start), dmax, step, control=control, options=opts)


def path_on(prob, start, approach_max, step, *, control, options, label="path") -> UnloadingPath:
    """The path of ``control`` on the problem ``prob`` from ``start`` (checked inputs; :func:`unloading_path`)."""
    branch = Branch(prob, options.tol, options.max_iter, label=label, progress=options.progress,
                    keep_states=options.keep_states, warm_start=start.warm_start)
    if control == "displacement":
        return continuation_path(branch, start, approach_max, options)
    return load_control_path(branch, start, approach_max, step, options)
