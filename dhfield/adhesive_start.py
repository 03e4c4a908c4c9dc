"""Where the adhesive BEM starts, chosen from the analytic models; the BEM pull-off in the paper's units.

The BEM engine (:mod:`dhfield.bem`) is the ground truth the analytic models are
judged against, so it imports none of them: it takes its start as an argument
(:class:`dhfield.bem.pull_off.PullOffStart`).  This module chooses that start
from the models:

* the domain, from the DH model's cohesive zone at the start of unloading
  (:func:`dhfield.model.load_curve`);
* the range of the unloading path, from the DH model's pull-offs in both controls
  (:func:`dhfield.model.pull_off`);
* the cold start of the bracket search, from the two-axis closure's load-control
  pull-off for beta0 < 1 (``dh-elliptic-two-axis``, :func:`dhfield.compare.pull_off`),
  the DH model's at beta0 = 1.

:func:`adhesive_pull_off` and :func:`refine_pull_off`, the user-facing BEM
pull-offs, set the problem up here and run :func:`dhfield.bem.pull_off.solve_pull_off`
and :func:`dhfield.bem.pull_off.refine` on it; :mod:`dhfield.bem` forwards their
names, so ``from dhfield.bem import adhesive_pull_off`` keeps working.
"""
from __future__ import annotations

import functools

import numpy as np

from . import model
from ._validation import check_count, check_ellipticity, check_positive
from .bem.path import PathOptions
from .bem.pull_off import (DEFAULT_STEPS, DOMAIN_MARGIN, MAX_STEPS, AdhesivePullOff, NondimensionalProblem,
                           PullOffStart, check_cells, paper_problem, refine, solve_pull_off)
from .bem.solver import DEFAULT_MAX_ITER, DEFAULT_TOL

__all__ = ["pull_off_start", "nondimensional_problem", "adhesive_pull_off", "refine_pull_off"]


def pull_off_start(mu, beta0, *, n_steps=DEFAULT_STEPS, margin=DOMAIN_MARGIN) -> PullOffStart:
    """The start of the BEM pull-off at (mu, beta0), from the analytic models.

    Parameters
    ----------
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    n_steps : int
        Unloading steps from the start of unloading to the expected jump (4 to 1e6).
    margin : float
        Domain half-width per expected zone semi-axis, > 1 (the zone must lie inside the grid).

    Returns
    -------
    PullOffStart

    Notes
    -----
    The analytic DH model gives the expected pull-off (a_po, delta_po).  Unloading
    starts at a* = 1.1 a_po + 0.15 (a state on the stable branch, above pull-off), whose DH
    approach is ``approach_max`` and whose adhesive semi-axis c* sets the domain:
    half-widths ``margin c*`` along x and ``margin c* beta0^(3/4)`` along y (the
    adhesive ellipse is rounder than the contact ellipse).  The step takes the
    path in ``n_steps`` from ``approach_max`` to 20 % beyond the analytic
    displacement-control pull-off.  The bracket search's cold start is the
    two-axis closure's pull-off for beta0 < 1 (:func:`_two_axis_start`): the DH
    zone (d = beta0 c) is tens of cells off the BEM's at mu = 5, beta0 = 0.5,
    N = 512, where its cold start does not converge.
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    n_steps = check_count("n_steps", n_steps, 4, MAX_STEPS, "unloading steps")
    return _start(mu, beta0, n_steps, _check_margin(margin))


def _check_margin(margin) -> float:
    """``margin`` as a domain half-width per zone semi-axis: a number > 1 (ValueError naming it otherwise).

    The largest cohesive zone of the path (at the start of unloading) must lie inside the
    grid: with margin <= 1 the domain cuts it and the pull-off is that of another problem
    (issue 18: margin = 0.3 gave W* = -0.261, margin = 0.1 -0.029, for about -0.79).
    """
    margin = float(check_positive("margin", margin, "domain half-width per zone semi-axis"))
    if not margin > 1.0:
        raise ValueError("margin must be > 1 (domain half-width per semi-axis of the largest cohesive zone "
                         f"of the path, which must lie inside the grid); got {margin!r}")
    return margin


def _start(mu, beta0, n_steps, margin) -> PullOffStart:
    """:func:`pull_off_start` of checked inputs."""
    po = model.pull_off(mu, beta0)
    pod = model.pull_off(mu, beta0, control="displacement")
    a_start = 1.1 * float(po.a_star) + 0.15
    cur = model.load_curve(mu, beta0, [a_start])
    c_start = float(cur.c_star[0])
    d_max = float(cur.delta_star[0])
    d_end = float(pod.delta_star) - 0.2 * (d_max - float(pod.delta_star))
    # the cold start of the bracket search: the analytic load-control pull-off state
    start = _two_axis_start(mu, beta0) if beta0 < 1.0 else None
    if start is None:
        at_po = model.load_curve(mu, beta0, [max(float(po.a_star), 1e-3 * a_start)])
        start = (float(po.delta_star), (float(at_po.c_star[0]), float(at_po.d_star[0])))
    return PullOffStart(margin * c_start, margin * c_start * beta0 ** 0.75, d_max, (d_max - d_end) / int(n_steps),
                        start[0], start[1])


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
    from . import compare

    try:
        rec = compare.pull_off("dh-elliptic-two-axis", mu, beta0, "load")
        out = (float(rec["delta_star"]), (float(rec["c_star"]), float(rec["d_star"])))
    except (ValueError, ArithmeticError):
        return None
    return out if np.all(np.isfinite([out[0], *out[1]])) and min(out[1]) > 0 else None


def nondimensional_problem(mu, beta0, n, *, law="dugdale", n_steps=DEFAULT_STEPS,
                           margin=DOMAIN_MARGIN) -> NondimensionalProblem:
    """Grid, initial gap, law and path range of the paper's problem at (mu, beta0), started from the models.

    Parameters
    ----------
    mu, beta0, n, law
        As in :func:`dhfield.bem.pull_off.paper_problem` (n even, 8 to 65536 cells per axis).
    n_steps, margin
        As in :func:`pull_off_start`.

    Returns
    -------
    NondimensionalProblem
        :func:`dhfield.bem.pull_off.paper_problem` with the start of :func:`pull_off_start`.
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    n = check_cells(n)
    n_steps = check_count("n_steps", n_steps, 4, MAX_STEPS, "unloading steps")
    return paper_problem(mu, beta0, n, _start(mu, beta0, n_steps, _check_margin(margin)), law=law)


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
    n_steps, margin
        See :func:`pull_off_start`.
    refine_levels, tol, max_iter, threads, keep_states, progress
        See :class:`dhfield.bem.path.PathOptions`.
    search : {'located', 'bracket', 'march'}
        Load control only (the route taken is :attr:`AdhesivePullOff.search`).
        'located' (default) is 'bracket' with the minimum located on coarser
        grids first (below).  'bracket': cold-start at the analytic
        pull-off approach from its cohesive zone (:func:`pull_off_start`) and
        bracket the load minimum there (a handful of states;
        :func:`dhfield.bem.path.bracket_search`).  'march': unload from
        ``approach_max`` in uniform steps to the jump and refine the minimum's
        bracket (~5x more states, same pull-off).  'located': the minimum is
        located on the grids 2x, 4x, ... coarser (the bracket search on the
        coarsest resolved one; three samples of the approach lattice
        ``approach_max - j approach_step/2`` around the coarser level's minimum
        on every finer one), and on this grid only those lattice samples and at
        most one parabola vertex (none with ``refine_levels=0``) are solved,
        each from the same approach on the grid half as fine: 3-4 fine states
        instead of 4-6 (measured at N = 256), the same pull-off to the
        jaggedness of the discrete load curve (~5e-4).  Falls back to 'bracket'
        (keeping the coarse states) when ``n < 2 NESTED_MIN_N``, when the grid
        half as fine is too coarse for the Dugdale edge
        (:data:`dhfield.bem.pull_off.LOCATE_MAX_EDGE_RATIO`), when the located
        minimum is not interior, or when a fine state does not converge.
    nested : bool, optional
        Bracket search only: start every state from the same approach solved
        on a grid half as fine (:class:`dhfield.bem.pull_off.NestedWarmStart`).
        Default: when ``n >= 2 * NESTED_MIN_N``.

    Notes
    -----
    With R = E* = Delta gamma = 1 (Eqs. 32-35): the initial gap is Eq. (2) with
    R' R'' = 1, the law has sigma0 = mu and range 1/mu, and

    .. math:: W^* = \\frac{W \\sin\\theta_{skew}}{2\\pi R\\Delta\\gamma}

    (Eq. 34).  The domain and the path come from :func:`nondimensional_problem`.
    """
    from .bem.pull_off import SEARCHES

    if search not in SEARCHES:
        raise ValueError(f"search must be one of {SEARCHES} (load-control path); got {search!r}")
    if control not in ("load", "displacement"):
        raise ValueError(f"control must be one of ('load', 'displacement') (loading mode); got {control!r}")
    prob = nondimensional_problem(mu, beta0, n, law=law, n_steps=n_steps, margin=margin)
    options = PathOptions(refine_levels=refine_levels, tol=tol, max_iter=max_iter, threads=threads,
                          keep_states=keep_states, progress=progress)
    return solve_pull_off(prob, control=control, search=search, nested=nested, options=options)


def refine_pull_off(coarse, n, *, n_steps=DEFAULT_STEPS, refine_levels=2, refine_factor=4,
                    window=3, tol=DEFAULT_TOL, max_iter=DEFAULT_MAX_ITER, threads=None,
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
        state (:func:`dhfield.bem.pull_off.refine`).

    Other Parameters
    ----------------
    n_steps, refine_levels, refine_factor
        The path settings of the full path (:func:`adhesive_pull_off`): the fine
        states sit on its finest approach lattice, so that the fine pull-off
        equals the full fine path's wherever both bracket the same samples.
    tol, max_iter, threads, keep_states, progress
        See :class:`dhfield.bem.path.PathOptions`.
    """
    if not isinstance(coarse, AdhesivePullOff):
        raise ValueError(f"coarse must be an AdhesivePullOff; got {type(coarse).__name__}")
    n = check_count("n", n, 8, 2 ** 16, "cells per axis")
    if n <= coarse.n:
        raise ValueError(f"n must be an integer > coarse.n = {coarse.n} (cells per axis); got {n!r}")
    window = check_count("window", window, 1, MAX_STEPS, "finest path steps")
    options = PathOptions(refine_levels=refine_levels, refine_factor=refine_factor, tol=tol, max_iter=max_iter,
                          threads=threads, keep_states=keep_states, progress=progress).checked()
    prob = nondimensional_problem(coarse.mu, coarse.beta0, n, law=coarse.law, n_steps=n_steps)
    return refine(prob, coarse, window=window, options=options)

