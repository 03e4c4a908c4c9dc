"""Adhesive states at a prescribed adhesive force: a path through the fold of the approach.

Under displacement control the contact branch of an adhesive contact ends at
its *fold*, where the approach delta is smallest (d delta/da = 0, a the contact
radius; Maugis 1992 [1]_).  Near the fold the fixed point at a prescribed
approach slows down critically (two states, the stable and the unstable one,
merge there) and, on the cell lattice, stops converging a few cells short of
the fold, which must then be extrapolated (docs/theory/bem.rst).

Here the *adhesive force* is prescribed instead,

.. math:: F_a = \\int \\sigma(h)\\, dA

(for the Dugdale law sigma0 times the area of contact U cohesive zone), and the
approach is an extra unknown.  F_a decreases monotonically along the whole
unloading branch, through the fold and past the loss of contact, so every
state on it is reached with a bounded number of outer iterations (20-27 per
state through the fold on the sphere at lambda = 3, N = 128), and the
displacement-control pull-off is *interpolated* between states on both sides
of the minimum of delta(F_a) instead of extrapolated.

Algorithm (:func:`solve_at_adhesive_force`): the semismooth Newton solve of
:mod:`dhfield.bem.newton` with the approach as an extra unknown and the force as
an extra equation (:func:`dhfield.bem.newton.solve_state_at_force`).  The state
is the one :func:`dhfield.bem.solver.solve_problem` gives at the returned approach.

References
----------
.. [1] D. Maugis (1992) Adhesion of spheres: the JKR-DMT transition using a
   Dugdale model. J. Colloid Interface Sci. 150:243-269.
   doi:10.1016/0021-9797(92)90288-C
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.validation import check_count, check_finite, check_positive, check_sequence
from .laws import DugdaleLaw
from .solver import AdhesiveProblem, Prediction, extrapolated_start
from .state import ContactState

__all__ = ["solve_at_adhesive_force", "adhesive_force", "fold_by_adhesive_force", "fit_fold", "FoldSearch",
           "FOLD_STEPS", "FOLD_WINDOW"]

#: Default number of adhesive-force steps from the start state to zero force.
FOLD_STEPS = 16
#: Half-width of the window fitted around the fold, in coarse force steps: +-2 steps
#: spans ~+-25 % of the fold's adhesive force at lambda = 3 (a cubic over it averages
#: the lattice jaggedness of the approach).  On the sphere at mu = 0.3, 1, 2, 3 (N = 96-256;
#: ``python -m verification.bench_fold_window``) the largest |W*/W*_MD - 1| was 0.65 %, 0.47 %,
#: 1.0 % and 1.3 % with half-windows 1, 2, 3 and 4, every answer within its stated error.
FOLD_WINDOW = 2
#: Standard deviations of the fold's load from the scatter of delta counted in its error estimate.
FOLD_SCATTER_SIGMAS = 2.0
#: A fold above a loss of contact counts as told apart from it when the cubic delta(F_a)
#: is deeper there than this many residual standard deviations (else the error estimate
#: spans the load of both).
FOLD_RESOLVED_SIGMAS = 3.0


def adhesive_force(state: ContactState) -> float:
    """Compute the adhesive force of a solved state, the integral of the adhesive stress [force].

    For the Dugdale law sigma0 x (area of contact U cohesive zone); for the
    exponential law the integral of sigma(h) (sigma0 in contact).

    Parameters
    ----------
    state : ContactState
        A solved state.

    Returns
    -------
    float
        The adhesive force [force].
    """
    if not isinstance(state, ContactState) or state.law is None:
        raise ValueError("state must be a ContactState with a traction law (adhesive)")
    law = state.law
    if isinstance(law, DugdaleLaw):
        return law.max_stress * state.adhesive_area
    s = np.where(state.contact, law.max_stress, law.stress(np.maximum(state.gap, 0.0)))
    return float(s.sum()) * state.cell_area


def solve_at_adhesive_force(prob: AdhesiveProblem, force, guess, approach, tol, max_iter) -> ContactState:
    """Adhesive state at a prescribed adhesive force, the approach being an unknown.

    The semismooth Newton solve of :mod:`dhfield.bem.newton` bordered by the force
    (:func:`dhfield.bem.newton.solve_state_at_force`), from ``guess``.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem (grid, initial gap, law); an adhesive law is required.
    force : float
        Adhesive force F_a = integral of the adhesive stress, > 0 [force].
    guess : ContactState or Prediction
        Warm start (a state of the same branch, e.g. the previous one).
    approach : float
        First guess of the approach [length].
    tol : float
        Tolerance [-]: ``max |min(h/h0, p/sigma0)|`` and ``|F_a - force|/force``.
    max_iter : int
        Cap on the GMRES iterations of each linear solve (at most
        :data:`dhfield.bem.newton.NESTED_OPTIONS` ``.max_krylov``, as every state's:
        :func:`dhfield.bem.solver.state_options`).

    Returns
    -------
    ContactState
        At the approach found (``state.approach``), flagged ``converged``.
    """
    from .newton import solve_state_at_force
    from .solver import newton_contact_state, start_traction, state_options

    law = prob.law
    if law is None:
        raise ValueError("prob must have an adhesive law (DugdaleLaw or ExponentialLaw); got None")
    target = float(check_positive("force", force, "adhesive force, force"))
    delta = float(check_finite("approach", approach, "first guess of the approach, length"))
    if not isinstance(guess, (Prediction, ContactState)):
        raise ValueError("guess must be a solved ContactState or a Prediction of the same problem")
    options = state_options(tol, max_iter)
    st, delta = solve_state_at_force(prob, target, delta, start_traction(prob, guess), options)
    return newton_contact_state(prob, delta, st, st.krylov_iterations, st.newton_iterations)


def _secant(prob, prev, last, t):
    """Warm start extrapolated by t (in units of the last force step) from two states."""
    if prev is None or not (prev.converged and last.converged) or prev.in_contact != last.in_contact:
        return last, last.approach
    return extrapolated_start(prob, prev, last, t), last.approach + t * (last.approach - prev.approach)


@dataclass(frozen=True)
class FoldSearch:
    """The end of a contact branch found along the adhesive force.

    Parameters
    ----------
    kind : str
        'fold' (interior minimum of the approach: the jump under displacement
        control), 'contact loss' (the approach still decreases when the last
        contact cell opens: the Maugis-Dugdale curve ends at a = 0, lambda <~ 0.94)
        or 'failed' (a state did not converge before either was bracketed).
    load, approach, adhesive_force : float
        Load W [force], approach delta [length] and adhesive force [force] at
        the fold or at the loss of contact (NaN when failed).
    load_error : float
        Error estimate of ``load`` from the fit [force]: the larger change of
        the result with a quartic over the window or a quadratic over its
        inner half (NaN when neither gives a result).  It does not include the
        discretisation error of the grid.
    nearest : ContactState or None
        The solved contact state nearest to the fold (its semi-axes are
        reported); None from :func:`fit_fold`.
    """

    kind: str
    load: float
    approach: float
    adhesive_force: float
    load_error: float
    nearest: ContactState | None = None


def _fold_fit(forces, approaches, loads, f_loss, deg):
    """(force, approach, load, kind) at the smallest approach of least-squares fits over the samples.

    delta(F_a) is fitted with a polynomial of degree ``deg``, W(F_a) with one of
    degree min(deg, 3).  The smallest approach is an interior minimum ('fold')
    or, when the contact is lost at ``f_loss`` (NaN: not lost) while the approach
    still falls, that end ('contact loss'); None when neither is bracketed.
    """
    x, d, w = (np.asarray(v, dtype=float) for v in (forces, approaches, loads))
    deg = min(deg, x.size - 1)
    if deg < 2:
        return None
    x0, sc = 0.5 * (x.min() + x.max()), max(0.5 * (x.max() - x.min()), 1e-300)
    t = (x - x0) / sc                 # centred, scaled abscissa: well-conditioned least squares
    pd = np.polyfit(t, d, deg)
    pw = np.polyfit(t, w, min(deg, 3))
    lost = bool(np.isfinite(f_loss))
    lo, hi = ((f_loss - x0) / sc if lost else t.min()), t.max()
    crit = np.roots(np.polyder(pd))
    crit = crit[np.abs(crit.imag) < 1e-9].real
    crit = [c for c in crit if lo < c < hi and np.polyval(np.polyder(pd, 2), c) > 0.0]
    if crit:
        tv, kind = min(crit, key=lambda c: np.polyval(pd, c)), "fold"
    elif lost and np.polyval(np.polyder(pd), lo) >= 0.0:
        tv, kind = lo, "contact loss"
    else:
        return None
    return float(x0 + sc * tv), float(np.polyval(pd, tv)), float(np.polyval(pw, tv)), kind


def _fold_scatter(forces, approaches, loads, fold_force, deg=3):
    """Standard deviation of the fold's load from the scatter of delta about its fit [force].

    The fold t_f solves p'(t_f) = 0 for the least-squares polynomial p of delta; an
    error dp' of the slope there moves it by dp'/p''(t_f), and the load by W'(t_f) times
    that.  dp' follows from the coefficients' covariance, scaled by the residual
    variance (the lattice jaggedness of delta is the noise).
    """
    x, d, w = (np.asarray(v, dtype=float) for v in (forces, approaches, loads))
    if x.size <= deg + 1:
        return float("nan")
    x0, sc = 0.5 * (x.min() + x.max()), max(0.5 * (x.max() - x.min()), 1e-300)
    t = (x - x0) / sc
    pd, cov = np.polyfit(t, d, deg, cov="unscaled")
    res = d - np.polyval(pd, t)
    cov = cov * float(res @ res) / (x.size - deg - 1)
    tf = (fold_force - x0) / sc
    grad = np.array([(deg - i) * tf ** (deg - i - 1) if i < deg else 0.0 for i in range(deg + 1)])
    curv = np.polyval(np.polyder(pd, 2), tf)
    if not curv > 0.0:
        return float("nan")
    sigma_t = math.sqrt(max(float(grad @ cov @ grad), 0.0)) / curv
    slope_w = np.polyval(np.polyder(np.polyfit(t, w, min(deg, 3))), tf)
    return abs(float(slope_w)) * sigma_t


def _shallow_fold_spread(forces, approaches, loads, fold_force, loss_force, deg=3):
    """|W(fold) - W(loss)| when the fold is not deeper than the scatter of delta, else 0 [force].

    Near lambda ~ 1 the fold lies just above the loss of contact, at most ~1e-3 deeper
    in delta; when the cubic's depth delta(loss) - delta(fold) is below
    ``FOLD_RESOLVED_SIGMAS`` residual standard deviations, the lattice cannot tell the
    fold from the loss of contact, and the spread of W between the two is the error.
    """
    x, d, w = (np.asarray(v, dtype=float) for v in (forces, approaches, loads))
    if x.size <= deg + 1:
        return 0.0
    x0, sc = 0.5 * (x.min() + x.max()), max(0.5 * (x.max() - x.min()), 1e-300)
    t = (x - x0) / sc
    pd = np.polyfit(t, d, deg)
    pw = np.polyfit(t, w, min(deg, 3))
    sigma = math.sqrt(float(np.sum((d - np.polyval(pd, t)) ** 2)) / (x.size - deg - 1))
    tf, tl = (fold_force - x0) / sc, (loss_force - x0) / sc
    depth = float(np.polyval(pd, tl) - np.polyval(pd, tf))
    if depth >= FOLD_RESOLVED_SIGMAS * sigma:
        return 0.0
    return abs(float(np.polyval(pw, tl) - np.polyval(pw, tf)))


def fit_fold(adhesive_forces, approaches, loads, *, contact_loss=None) -> FoldSearch:
    """The smallest approach of a sampled contact branch and its load, by least squares, with an error estimate.

    Parameters
    ----------
    adhesive_forces, approaches, loads : sequence of float
        Adhesive force F_a [force], approach delta [length] and load W [force]
        of converged contact states of one branch around its fold (at least 4).
    contact_loss : (float, float), optional
        When the contact is lost among the samples: the adhesive force of the
        first separated state and the estimated force of the loss of contact
        (at or below the smallest sampled force) [force].

    Returns
    -------
    FoldSearch
        Of kind 'fold' (interior minimum of delta), 'contact loss' (delta still
        falls at the loss of contact) or 'failed'; ``nearest`` is None.

    Notes
    -----
    delta(F_a) is fitted by a least-squares cubic and W(F_a) by a cubic; the
    fold is the interior minimum of the first, its load the second there.  The
    error estimate is the largest change of that load with a quartic over all
    samples, a quadratic over the inner half around the result and, at a
    loss of contact, the loss put at either end of its bracket; at a fold at
    least ``FOLD_SCATTER_SIGMAS`` standard deviations of the load from the
    scatter of delta about its cubic (the slope error at the vertex divided by
    the curvature moves the fold, times dW/dF_a), and, when the fold lies above
    a loss of contact by less than ``FOLD_RESOLVED_SIGMAS`` such deviations in
    delta, the spread of W between the fold and the loss.
    """
    x = check_sequence("adhesive_forces", adhesive_forces, "adhesive force of each state, force")
    d = check_sequence("approaches", approaches, "approach of each state, length")
    w = check_sequence("loads", loads, "load of each state, force")
    if not (x.size == d.size == w.size) or x.size < 4:
        raise ValueError("adhesive_forces, approaches and loads must have the same length >= 4; got "
                         f"{x.size}, {d.size}, {w.size}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(d)) and np.all(np.isfinite(w))):
        raise ValueError("adhesive_forces, approaches and loads must be finite (converged states only)")
    f_sep = f_loss = float("nan")
    if contact_loss is not None:
        try:
            f_sep, f_loss = (float(v) for v in contact_loss)
        except (TypeError, ValueError):
            raise ValueError("contact_loss must be (force of the first separated state, force of the loss); "
                             f"got {contact_loss!r}") from None
        if not (f_sep <= f_loss <= x.min()):
            raise ValueError("contact_loss must satisfy first separated force <= loss force <= smallest "
                             f"sampled force {x.min():g}; got {contact_loss!r}")
    order = np.argsort(x)
    x, d, w = x[order], d[order], w[order]
    best = _fold_fit(x, d, w, f_loss, 3)
    if best is None:
        return FoldSearch("failed", float("nan"), float("nan"), float("nan"), float("nan"), None)
    alts = [_fold_fit(x, d, w, f_loss, 4)]
    inner = np.abs(x - best[0]) <= 0.25 * (x[-1] - x[0])
    if np.count_nonzero(inner) >= 4:
        alts.append(_fold_fit(x[inner], d[inner], w[inner], f_loss, 2))
    if best[3] == "contact loss":
        alts += [_fold_fit(x, d, w, f_end, 3) for f_end in (f_sep, x[0])]
    err = max((abs(alt[2] - best[2]) for alt in alts if alt is not None), default=float("nan"))
    if best[3] == "fold":
        # the vertex moves with the scatter of delta (the lattice jaggedness): two standard deviations
        err = np.nanmax([err, FOLD_SCATTER_SIGMAS * _fold_scatter(x, d, w, best[0])])
        if np.isfinite(f_loss):
            # a fold above the loss of contact, not deeper than that scatter: either could be the end
            err = max(err, _shallow_fold_spread(x, d, w, best[0], f_loss))
    return FoldSearch(best[3], best[2], best[1], best[0], float(err), None)


def _contact_loss_force(forces, areas):
    """Force where the contact area, linear in the force near a = 0, extrapolates to zero."""
    f, a = np.asarray(forces), np.asarray(areas)
    if f.size < 2 or np.ptp(f) == 0.0:
        return float("nan")
    slope, icpt = np.polyfit(f, a, 1)
    return float(-icpt / slope) if slope > 0 else float("nan")


def fold_by_adhesive_force(prob: AdhesiveProblem, start: ContactState, *, steps=FOLD_STEPS, window=FOLD_WINDOW,
                           refine_factor=4, tol=1e-6, max_iter=20000, record=None) -> FoldSearch:
    """Follow a contact branch by decreasing adhesive force to its fold (or loss of contact).

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem; an adhesive law is required.
    start : ContactState
        A converged contact state of the branch above the fold (e.g. near the
        load-control pull-off).
    steps : int
        Force steps from the start state's adhesive force to zero (>= 4): the
        coarse step dF = F_a(start)/steps.
    window : int
        Half-width of the fitting window around the smallest sampled approach,
        in coarse steps (>= 1).
    refine_factor : int
        The window is sampled with steps dF/refine_factor (>= 1).
    tol : float
        Tolerance [-], as in :func:`solve_at_adhesive_force`.
    max_iter : int
        Iteration cap, as in :func:`solve_at_adhesive_force`.
    record : callable, optional
        ``record(state, phase)`` is called for every solved state (phase
        'continuation' for the coarse steps, 'fold' for the window).

    Returns
    -------
    FoldSearch
        The fold, the loss of contact or the failure, with ``nearest`` the solved
        state nearest to it.

    Notes
    -----
    Along the branch delta(F_a) and W(F_a) are smooth; delta has its minimum
    at the fold.  The branch is followed in coarse steps dF until the
    smallest approach lies ``window`` steps behind (or the contact is lost),
    the window of +-``window`` dF around it is sampled with steps
    dF/``refine_factor``, and the fold is the minimum of a least-squares cubic
    delta(F_a) over the contact states of the window, its load the cubic
    least-squares W(F_a) there.  The fit averages the lattice jaggedness of
    delta (+-0.005 at lambda = 3, N = 128, where W(F_a) is within 0.0015 of
    Maugis-Dugdale): near the fold delta - delta_f ~ (F_a - F_f)^2, so a
    three-point vertex moves with the square root of that noise.  When the
    window holds separated states (no contact cell), the contact area, linear
    in F_a near a = 0 (Maugis-Dugdale: F_a - F_0 ~ a^2), is extrapolated to
    zero over the last contact states; when delta still falls there, the
    pull-off is the end of the contact branch (kind 'contact loss', the end
    a = 0 of the Maugis-Dugdale curve, lambda <~ 0.94).  The error estimate is
    the spread of the result over a quadratic on the inner half window and a
    quartic on the whole window.
    """
    if not (isinstance(start, ContactState) and start.converged and start.in_contact):
        raise ValueError("start must be a converged ContactState in contact")
    steps = check_count("steps", steps, 4, 10_000, "force steps to zero")
    window = check_count("window", window, 1, 100, "coarse steps each side of the fold")
    refine_factor = check_count("refine_factor", refine_factor, 1, 100, "window sub-steps per coarse step")
    f0 = adhesive_force(start)
    df = f0 / steps
    samples = {f0: start}            # adhesive force -> converged state

    def solve(force, guess, approach, phase):
        st = solve_at_adhesive_force(prob, force, guess, approach, tol, max_iter)
        if record is not None:
            record(st, phase)
        if st.converged:
            samples[force] = st
        return st

    def contact_min():
        fs = [k for k in samples if samples[k].in_contact]
        return min(fs, key=lambda k: samples[k].approach)

    prev, last, force, f_last = None, start, f0, f0
    misses = 0                        # unconverged states in a row (each one a hole in the samples)
    while force - df > 0.25 * df and misses < 2:
        force -= df
        # secant predictor in units of the last step (2 after a hole)
        guess, d_guess = _secant(prob, prev, last, (f_last - force) / df)
        st = solve(force, guess, d_guess, "continuation")
        if not st.converged:
            misses += 1
            continue
        misses = 0
        if not st.in_contact or contact_min() - force >= window * df - 1e-9 * df:
            break
        prev, last, f_last = last, st, force
    f_min = contact_min()

    def fill(lattice):
        """Solve the states of ``lattice`` (forces, descending) on the contact branch."""
        for f in sorted(lattice, reverse=True):
            if any(math.isclose(f, k, rel_tol=0.0, abs_tol=1e-9 * df) for k in samples):
                continue
            lowest_separated = max((k for k in samples if not samples[k].in_contact), default=-np.inf)
            if f <= lowest_separated - 1e-9 * df:
                continue              # beyond a separated state: not on the contact branch
            near = samples[min(samples, key=lambda k: abs(k - f) + (0 if samples[k].in_contact else df))]
            solve(f, near, near.approach, "fold")     # an unconverged state is left out (a hole)

    def fit_between(lo, hi, step):
        """fit_fold over the contact states in [lo, hi] (the loss of contact located when in it)."""
        sep = [k for k in samples if not samples[k].in_contact]
        con = sorted(k for k in samples if samples[k].in_contact and lo - 1e-9 * df <= k <= hi + 1e-9 * df
                     and k > max(sep, default=-np.inf))
        if len(con) < 4:
            return None, None
        loss = None
        if sep and max(sep) >= lo - step:
            # the contact area is linear in F_a near a = 0: extrapolate it to zero
            near_loss = con[:4]
            f_loss = _contact_loss_force(near_loss, [samples[k].contact_area for k in near_loss])
            f_loss = min(max(f_loss, max(sep)), con[0]) if np.isfinite(f_loss) else 0.5 * (max(sep) + con[0])
            loss = (max(sep), f_loss)
        return fit_fold(con, [samples[k].approach for k in con], [samples[k].load for k in con],
                        contact_loss=loss), loss

    # the window, sampled with steps df/refine_factor (on the coarse lattice f0 - j df/refine_factor)
    h = df / refine_factor
    j_min = int(round((f0 - f_min) / h))
    lattice = [f0 - j * h for j in range(j_min - window * refine_factor, j_min + window * refine_factor + 1)]
    lattice = [f for f in lattice if f > 0.25 * h]
    fill(lattice)
    fit, loss = fit_between(min(lattice), max(lattice), h)
    near_end = fit is not None and loss is not None and (
        fit.kind != "fold" or fit.adhesive_force <= loss[1] + window * h)
    if near_end:
        # the window's result is at (or within window h of) the loss of contact: the end of
        # the branch is sampled again, steps h/refine_factor over [loss, loss + window h], and
        # fitted alone.  Near lambda = 1 the fold lies within 0.1 dF of the loss and 7e-4 deep
        # in delta: at N = 256 the window fit took the loss (+2.1 % vs MD), the finer end finds
        # the fold (-0.4 %).  A fold further up is left to the window fit (the finer end, fitted
        # alone, then shows a spurious minimum at its top: lambda = 1.2, N = 96, +11 %).
        hz = h / refine_factor
        top = max(loss[1], fit.adhesive_force if fit.kind != "failed" else loss[1]) + window * h
        zoom = [top - j * hz for j in range(int(round((top - loss[1]) / hz)) + 1)]
        fill([f for f in zoom if f > 0.25 * hz])
        fit_z, _ = fit_between(loss[0], top, hz)
        if fit_z is not None and fit_z.kind != "failed":
            fit = fit_z
    if fit is None or fit.kind == "failed":
        return FoldSearch("failed", float("nan"), float("nan"), float("nan"), float("nan"), samples[f_min])
    nearest = samples[min((k for k in samples if samples[k].in_contact), key=lambda k: abs(k - fit.adhesive_force))]
    return FoldSearch(fit.kind, fit.load, fit.approach, fit.adhesive_force, fit.load_error, nearest)
