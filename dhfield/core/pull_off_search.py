"""Pull-off search: the one place where dhfield locates a pull-off point.

A pull-off point is where an unloading path leaves its stable branch: the minimum
of the load W (load control) or of the approach delta (displacement control)
reached from the high-load end of the path.  On sampled values every search here
applies one rule, :func:`stable_minimum_index`: walking from the high-load end,
sample i is the pull-off when v_i <= v_(i-1) (ties go to the lower-load sample)
and v_i < v_(i+1); the low-load end point when v_last <= v_(last-1); on slopes, the
first sample whose slope is above zero (or a noise floor).  dhfield meets the
pull-off in five forms:

* **a smooth family with an analytic derivative** (the analytic DH model and its
  closures): the pull-off is the *largest* contact size a at which dW/da (or
  d delta/da) crosses from negative to non-negative.
  :func:`stable_branch_end` brackets that crossing on a scan (one row of
  contact sizes per problem, so the scan can be scaled with the problem) and
  refines it with Chandrupatla's bracketing root finder
  (:func:`scipy.optimize.elementwise.find_root`), vectorised over problems and
  evaluated in bounded chunks;
* **a smooth family without a derivative** (the two-axis and ray-average
  closures): :func:`last_local_minimum` takes the local minimum of the values
  on a scan nearest its high end and refines it with
  :func:`scipy.optimize.elementwise.find_minimum`;
* **a closed-form family, complex-safe** (MD, circular DH, elliptical JKR):
  :func:`scan_minimum` takes the local minimum nearest the high-load end of a
  graded scan and refines it at the root of the complex-step derivative;
* **a discretely sampled path** (the BEM unloading path): the pull-off is the
  minimum of sampled values; :func:`refine_sampled_minimum` takes the first
  (or global) discrete minimum and refines it with the parabola through the
  three samples around it;
* **a noisy sampled path** (the BEM branch under a machine spring,
  :mod:`dhfield.analysis.bem_spring`): the rule on the :func:`fitted_slopes` of the
  samples, then on the two samples around the first rise.

The machine-spring jump of the analytic models (:mod:`dhfield.analysis.spring`) takes
its zoom brackets from :func:`stable_minimum_index` too.  Every function here is
pure numpy/scipy, with no knowledge of the physics.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import elementwise

__all__ = ["SampledMinimum", "BranchEnd", "stable_minimum_index", "fitted_slopes", "refine_sampled_minimum",
           "stable_branch_end",
           "last_local_minimum", "scan_minimum", "DEFAULT_CHUNK_BYTES", "SCAN_BLOCK"]

#: Default working-memory budget of one chunk of :func:`stable_branch_end`
#: (one step of the scan evaluates ``chunk * SCAN_BLOCK`` states).
DEFAULT_CHUNK_BYTES = 64 * 2**20
#: Scan points evaluated per problem and step when :func:`stable_branch_end` walks its
#: scan from the top down (the stable-branch end is usually within a few points of the top).
SCAN_BLOCK = 8


@dataclass(frozen=True)
class SampledMinimum:
    """Minimum of a sampled path (see :func:`refine_sampled_minimum`).

    Parameters
    ----------
    x : float
        Abscissa of the refined minimum (the vertex of the parabola, or the sample
        itself on a boundary or a degenerate parabola).
    y : float
        Refined minimum value (never above the best sample).
    index : int
        Index of the discrete minimum among the samples.
    at_boundary : bool
        True where the discrete minimum is the first or the last finite sample
        (no interior minimum was bracketed; no refinement is done).
    """

    x: float
    y: float
    index: int
    at_boundary: bool


@dataclass(frozen=True)
class BranchEnd:
    """End of the stable branch found by :func:`stable_branch_end`.

    Parameters
    ----------
    x : ndarray
        Root of the derivative (the pull-off contact size); NaN where not ``found``.
    found : ndarray of bool
        False where the derivative is non-negative on the whole scan (no crossing:
        the minimum is at the small end of the scan, e.g. the zero-contact limit).
    """

    x: np.ndarray
    found: np.ndarray


def stable_minimum_index(values=None, *, slopes=None, floor=0.0, first=True):
    """Index of the pull-off sample: the one local-minimum rule and tie rule of dhfield.

    Parameters
    ----------
    values : array_like, shape (..., n), optional
        Values along the path, the high-load end first (rounding noise included:
        the rule, not a tolerance, decides ties).
    slopes : array_like, shape (..., n), optional
        Instead of ``values``: the slope of the path at each sample, along unloading
        (negative: still falling), from a derivative or a fit to noisy samples.
    floor : array_like, default 0
        With ``slopes``: the noise floor; only ``slopes > floor`` is a rise.
    first : bool, default True
        With ``values``: False takes the global minimum instead of the local minimum
        nearest the high-load end (the same tie rule).

    Returns
    -------
    ndarray of int, shape (...)
        With ``values``: the first i (from index 0) with ``v[i] <= v[i-1]`` and
        ``v[i] < v[i+1]``; ``n - 1`` when none is interior and ``v[-1] <= v[-2]`` (the
        low-load end is the minimum); 0 where neither (the values rise strictly from the
        high-load end, which is then the lowest sample).  ``first=False``: the lowest
        sample, the last of equal ones.  With ``slopes``: the first sample where the path
        rises (``slopes > floor``; the minimum lies between it and the sample before it),
        ``n`` where it never does.

    Notes
    -----
    The one local-minimum rule and tie rule of every pull-off search in dhfield: walking
    from the high-load end, the pull-off is where the path stops falling, and a flat step
    (equal samples, a zero slope or one within the noise floor) is not a rise.  On a
    plateau of equal samples the pull-off is the plateau's lowest-load sample that is
    followed by a rise, so a flat stretch of the path is walked down, never stopped on;
    of equal global minima the lowest-load one is taken.  The searches differ only in
    how the samples or slopes are obtained and how the sample is refined: a parabola
    (:func:`refine_sampled_minimum`), a bracketing minimiser (:func:`last_local_minimum`),
    the complex-step derivative (:func:`scan_minimum`), the analytic derivative
    (:func:`stable_branch_end`, whose scan gives ``slopes``), and the fitted slopes of
    the BEM's noisy branch (:mod:`dhfield.analysis.bem_spring`).
    """
    if slopes is not None:
        rises = np.asarray(slopes) > np.asarray(floor)
        return np.where(rises.any(axis=-1), np.argmax(rises, axis=-1), rises.shape[-1])
    v = np.asarray(values)
    n = v.shape[-1]
    if not first:
        return n - 1 - np.argmin(v[..., ::-1], axis=-1)
    loc = np.zeros(v.shape, dtype=bool)
    if n >= 3:
        loc[..., 1:-1] = (v[..., 1:-1] <= v[..., :-2]) & (v[..., 1:-1] < v[..., 2:])
    if n >= 2:
        loc[..., -1] = v[..., -1] <= v[..., -2]
    return np.where(loc.any(axis=-1), np.argmax(loc, axis=-1), 0)


def fitted_slopes(x, values, window):
    """Estimate the slopes of a noisy sampled path by least-squares quadratics over +-``window`` samples.

    Parameters
    ----------
    x : array_like, shape (n,)
        Path parameter, decreasing along the path (high-load end first), so that
        ``x[i] - x`` grows along unloading (e.g. the square root of a decreasing force)
        [any unit].
    values : array_like, shape (n,)
        Sampled values (e.g. the BEM's loads or approaches) [any unit].
    window : int
        Half-width of the fit, in samples.

    Returns
    -------
    ndarray, shape (n,)
        The slope d values / d(x[i] - x) at each sample, along unloading; NaN where fewer than
        three samples lie in the window.  For :func:`stable_minimum_index` (``slopes=``).

    Notes
    -----
    The lattice jaggedness of the BEM's loads and approaches (~1e-3 at N = 64) makes
    single differences change sign before the minimum; the fitted slope does not.
    """
    x, f = np.asarray(x, float), np.asarray(values, float)
    out = np.full(f.size, np.nan)
    for i in range(f.size):
        lo, hi = max(0, i - window), min(f.size, i + window + 1)
        if hi - lo < 3:
            continue
        u = x[i] - x[lo:hi]  # increases along unloading, 0 at sample i
        out[i] = np.polyfit(u, f[lo:hi], 2)[1]
    return out


def refine_sampled_minimum(x, y, *, first=True):
    """Minimum of a sampled path, refined by the parabola through three samples.

    Parameters
    ----------
    x : array_like, shape (n,)
        Path parameter of the samples (e.g. approach or step number), strictly
        monotone (increasing or decreasing) [any unit].
    y : array_like, shape (n,)
        Sampled values (e.g. the load) [any unit].  Non-finite samples (failed
        states) are ignored.
    first : bool, default True
        Take the first discrete local minimum met from ``x[0]`` (put the high-load
        end of an unloading path first: this is the end of the stable branch);
        otherwise the global minimum of the samples.  Both by
        :func:`stable_minimum_index` (ties to the later sample).

    Returns
    -------
    SampledMinimum
        The refined minimum and where it was found.

    Notes
    -----
    With the discrete minimum at sample i and its finite neighbours (x0, y0),
    (x1, y1), (x2, y2), the vertex of the interpolating parabola is

    .. math::

        x^* = x_1 - \\frac{1}{2}\\frac{(x_1-x_0)^2 (y_1-y_2) - (x_1-x_2)^2 (y_1-y_0)}
                                    {(x_1-x_0)(y_1-y_2) - (x_1-x_2)(y_1-y_0)},

    kept only when it lies between x0 and x2 and its value is not above y1 (else the
    sample itself is returned).  The error is O(h^3) in the sample spacing h for a
    smooth path (O(h^2) in the location).
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.ndim != 1 or y.shape != x.shape:
        raise ValueError(f"x and y must be 1-d arrays of equal length; got shapes {x.shape} and {y.shape}")
    ok = np.isfinite(x) & np.isfinite(y)
    idx = np.nonzero(ok)[0]
    if idx.size == 0:
        raise ValueError("y must contain at least one finite sample (with a finite x); got none")
    xs, ys = x[idx], y[idx]
    dx = np.diff(xs)
    if xs.size > 1 and not (np.all(dx > 0) or np.all(dx < 0)):
        raise ValueError("x must be strictly monotone over the finite samples")
    n = xs.size
    i = int(stable_minimum_index(ys, first=first))
    if i == 0 or i == n - 1:
        return SampledMinimum(float(xs[i]), float(ys[i]), int(idx[i]), True)
    (x0, x1, x2), (y0, y1, y2) = xs[i - 1:i + 2], ys[i - 1:i + 2]
    p = (x1 - x0) * (y1 - y2)
    q = (x1 - x2) * (y1 - y0)
    den = p - q
    xv, yv = x1, y1
    if den != 0.0:
        cand = x1 - 0.5 * ((x1 - x0) * p - (x1 - x2) * q) / den
        if min(x0, x2) <= cand <= max(x0, x2):
            # Lagrange interpolation at the vertex.
            l0 = (cand - x1) * (cand - x2) / ((x0 - x1) * (x0 - x2))
            l1 = (cand - x0) * (cand - x2) / ((x1 - x0) * (x1 - x2))
            l2 = (cand - x0) * (cand - x1) / ((x2 - x0) * (x2 - x1))
            val = l0 * y0 + l1 * y1 + l2 * y2
            if np.isfinite(val) and val <= y1:
                xv, yv = cand, val
    return SampledMinimum(float(xv), float(yv), int(idx[i]), False)


def stable_branch_end(derivative, scan, args=(), *, floor=0.0, extend=8.0, max_extend=6, xtol=1e-13,
                      chunk_bytes=None, bytes_per_state=2048, block=SCAN_BLOCK):
    """Find the largest contact size where ``derivative`` crosses from negative to non-negative.

    Vectorised over problems: ``scan`` has shape ``(m, n)`` (or ``(n,)`` shared by
    all problems), increasing along the last axis; ``args`` are arrays of shape
    ``(m,)`` (or broadcastable to it) passed to ``derivative``.

    Parameters
    ----------
    derivative : callable
        ``derivative(a, *args)`` -> dW/da (or d delta/da) at contact size ``a``;
        broadcasts ``a`` of shape ``(k, j)`` against args of shape ``(k, 1)`` and
        ``a`` of shape ``(k,)`` against args of shape ``(k,)``.  Only its sign and
        its zero matter, so ``a`` may be any increasing function of the contact
        size (e.g. a ratio that parametrises the states without iteration).
    scan : array_like, shape (m, n) or (n,)
        Scan of contact sizes per problem, increasing and positive.
    args : tuple of array_like
        Per-problem parameters.
    floor : array_like, default 0
        Noise floor of the derivative per problem: only ``derivative < -floor``
        counts as negative (rounding noise of a flat path makes no minimum).
    extend : float
        Where the derivative is still negative at the top of the scan (the stable
        branch is not reached), the problem's scan is multiplied by ``extend`` and
        evaluated again, at most ``max_extend`` times.
    max_extend : int
        Most extensions of the scan.
    xtol : float
        Absolute and relative tolerance of Chandrupatla's method on the root.
    chunk_bytes : int, optional
        Working-memory budget of one chunk of problems; default
        :data:`DEFAULT_CHUNK_BYTES` (read at call time).
    bytes_per_state : int
        Memory one evaluation of ``derivative`` at one contact size needs (the
        caller's estimate; used to size the chunks).
    block : int
        Scan points evaluated per problem and step of the walk down the scan.

    Returns
    -------
    BranchEnd
        Flat arrays of length m.

    Raises
    ------
    RuntimeError
        If some problem's derivative is still negative at the top of its scan after
        ``max_extend`` extensions.

    Notes
    -----
    The crossing is bracketed by the last scan point with ``derivative < -floor``
    and the next one with ``derivative >= 0`` (if the derivative stays in
    [-floor, 0) up to the top, the next scan point is returned unrefined).
    Crossings that come and go inside one scan interval are not seen: the scan
    must resolve the path.  The scan is walked from its top down, ``block``
    points at a time, and a problem stops at its first block with a point below
    ``-floor``: the bracket is the one the whole scan gives, at a fraction of the
    evaluations where the pull-off is near the top of the scan.
    """
    args = tuple(np.atleast_1d(np.asarray(q, dtype=float)) for q in args)
    scan = np.asarray(scan, dtype=float)
    floor = np.atleast_1d(np.asarray(floor, dtype=float))
    m = max([q.shape[0] for q in args] + [floor.shape[0], scan.shape[0] if scan.ndim == 2 else 1])
    args = tuple(np.broadcast_to(q, (m,)) for q in args)
    floor = np.broadcast_to(floor, (m,))
    scan = np.broadcast_to(scan, (m, scan.shape[-1]))
    n = scan.shape[-1]
    block = max(1, int(block))
    budget = DEFAULT_CHUNK_BYTES if chunk_bytes is None else chunk_bytes
    chunk = max(1, int(budget // max(1, min(n, block) * bytes_per_state)))
    x = np.full(m, np.nan)
    found = np.zeros(m, bool)
    for start in range(0, m, chunk):
        sl = slice(start, min(m, start + chunk))
        sub_scan = np.array(scan[sl])
        sub_args = tuple(q[sl] for q in args)
        sub_floor = floor[sl]
        k = sub_scan.shape[0]
        d = np.full((k, n), np.nan)
        d[:, -1] = derivative(sub_scan[:, -1], *sub_args)
        for _ in range(max_extend):
            low = d[:, -1] < 0
            if not low.any():
                break
            sub_scan[low] *= extend
            d[low, -1] = derivative(sub_scan[low, -1], *(q[low] for q in sub_args))
        if np.any(d[:, -1] < 0):
            raise RuntimeError("stable_branch_end: the derivative is still negative at the top of "
                               f"the scan (a = {sub_scan[d[:, -1] < 0, -1][0]:g}); please report the inputs")
        # Walk down: the last index with d < -floor (below the top), -1 where there is none.
        last = np.full(k, -1)
        active = np.ones(k, bool)
        top = n - 1
        while top > 0 and active.any():
            bottom = max(0, top - block)
            rows = np.nonzero(active)[0]
            d[rows, bottom:top] = derivative(sub_scan[rows, bottom:top], *(q[rows][:, None] for q in sub_args))
            # the rule of stable_minimum_index on the slopes along unloading, -dW/da from the top down
            j = stable_minimum_index(slopes=-d[rows, bottom:top][:, ::-1], floor=sub_floor[rows][:, None])
            hit = j < top - bottom
            last[rows[hit]] = top - 1 - j[hit]
            active[rows[hit]] = False
            top = bottom
        rows = np.nonzero(last >= 0)[0]
        if rows.size == 0:
            continue
        last = last[rows]
        pos = (d[rows] >= 0) & (np.arange(n) > last[:, None])
        got = pos.any(axis=-1)
        nxt = np.where(got, np.argmax(pos, axis=-1), last + 1)
        lo = sub_scan[rows, last]
        hi = sub_scan[rows, nxt]
        xr = np.array(hi)
        if got.any():
            r = rows[got]
            root = elementwise.find_root(derivative, (lo[got], hi[got]), args=tuple(q[r] for q in sub_args),
                                         tolerances=dict(xatol=xtol, xrtol=xtol))
            xr[got] = np.where(np.isfinite(root.x), root.x, 0.5 * (lo[got] + hi[got]))
        x[start + rows] = xr
        found[start + rows] = True
    return BranchEnd(x, found)


def last_local_minimum(objective, scan, args=(), *, block=SCAN_BLOCK, xatol=1e-8, xrtol=1e-8):
    """Local minimum of ``objective`` nearest the top of a scan, refined; vectorised over problems.

    Parameters
    ----------
    objective : callable
        ``objective(a, *args)`` -> W (or delta) at contact size ``a``; broadcasts ``a`` of
        shape ``(k, j)`` against args of shape ``(k, 1)`` and ``a`` of shape ``(k,)``
        against args of shape ``(k,)``.
    scan : array_like, shape (n,)
        Contact sizes, increasing and positive, shared by all problems.
    args : tuple of array_like
        Per-problem parameters, shape ``(m,)``.
    block : int
        Scan points evaluated per problem and step of the walk down the scan.
    xatol, xrtol : float
        Tolerances of :func:`scipy.optimize.elementwise.find_minimum` on the abscissa.

    Returns
    -------
    BranchEnd
        ``x`` is the refined minimum (NaN where not ``found``); ``found`` is False where
        no interior scan point is a local minimum (the values rise from the smallest
        scanned a: the zero-contact side).

    Notes
    -----
    Scan point i is the pull-off by the rule of :func:`stable_minimum_index` read from the
    top of the scan (f_i <= f_(i+1), f_i < f_(i-1)); it is refined on the bracket
    (a_(i-1), a_i, a_(i+1)).  The scan is walked from
    its top down, ``block`` points at a time, and a problem stops as soon as its
    largest local minimum is known: the result of evaluating the whole scan, at a
    fraction of the evaluations where the pull-off is near the top.
    """
    scan = np.asarray(scan, dtype=float)
    args = tuple(np.atleast_1d(np.asarray(q, dtype=float)) for q in args)
    m = max([q.shape[0] for q in args] + [1])
    args = tuple(np.broadcast_to(q, (m,)) for q in args)
    n = scan.size
    block = max(1, int(block))
    f = np.full((m, n), np.nan)
    last = np.full(m, -1)
    active = np.ones(m, bool)
    top = n
    while top > 0 and active.any():
        bottom = max(0, top - block)
        rows = np.nonzero(active)[0]
        f[rows, bottom:top] = objective(np.broadcast_to(scan[bottom:top], (rows.size, top - bottom)),
                                        *(q[rows][:, None] for q in args))
        # The rule of stable_minimum_index, high-load end first, on the points whose neighbours are
        # known now (i in [bottom + 1, n - 2]); the scan's low end is the zero-contact side, not a minimum.
        if n - 1 - bottom >= 2:
            j = stable_minimum_index(f[rows, bottom:][:, ::-1])
            hit = (j >= 1) & (j < n - 1 - bottom)
            last[rows[hit]] = n - 1 - j[hit]
            active[rows[hit]] = False
        top = bottom
    found = last >= 0
    x = np.full(m, np.nan)
    if found.any():
        r = np.nonzero(found)[0]
        i = last[r]
        res = elementwise.find_minimum(objective, (scan[i - 1], scan[i], scan[i + 1]), args=tuple(q[r] for q in args),
                                       tolerances=dict(xatol=xatol, xrtol=xrtol, fatol=0.0, frtol=0.0))
        x[r] = res.x
    return BranchEnd(x, found)


def scan_minimum(func, scan, args=(), *, xatol=1e-13):
    """The pull-off on a graded scan of a closed-form, complex-safe family, refined.

    Parameters
    ----------
    func : callable
        ``func(t, *args)`` -> W (or delta) at path parameter ``t``; broadcasts ``t`` of
        shape ``(..., n)`` against args of shape ``(..., 1)``, and is analytic and
        complex-safe (its complex-step derivative is exact to rounding).
    scan : array_like, shape (..., n)
        Path parameter per problem, the high-load end first.
    args : tuple of array_like
        Per-problem parameters, broadcast together to the problems' shape.
    xatol : float
        Absolute tolerance of the refined minimiser.

    Returns
    -------
    t : ndarray
        Minimiser, with the problems' shape.
    f : ndarray
        Minimum, with the problems' shape.

    Notes
    -----
    The scan point is chosen by :func:`stable_minimum_index` (the high-load end where the
    values rise strictly from it); an end point is returned as is.  An interior one is
    refined at the root of the complex-step derivative Im f(t + ih)/h on its two
    neighbours (Chandrupatla, :func:`scipy.optimize.elementwise.find_root`, xrtol 1e-15):
    the minimiser is then accurate to ~1e-15 rather than ~sqrt(eps).  The refined point
    is kept only where its value is not above the scan point's (to 1e-14 relative).
    """
    args = tuple(np.asarray(a, dtype=float) for a in args)
    shape = np.broadcast_shapes(*(a.shape for a in args))
    args = tuple(np.broadcast_to(a, shape) for a in args)
    grid = np.broadcast_to(scan, shape + np.shape(scan)[-1:])
    n = grid.shape[-1]
    vals = func(grid, *(a[..., None] for a in args))
    vals = np.where(np.isfinite(vals), vals, np.inf)
    i = stable_minimum_index(vals)
    t = np.take_along_axis(grid, i[..., None], -1)[..., 0]
    f = np.take_along_axis(vals, i[..., None], -1)[..., 0]
    inner = (i > 0) & (i < n - 1)
    if np.any(inner):
        xl = np.take_along_axis(grid, np.clip(i - 1, 0, n - 1)[..., None], -1)[..., 0][inner]
        xr = np.take_along_axis(grid, np.clip(i + 1, 0, n - 1)[..., None], -1)[..., 0][inner]
        sub_args = tuple(a[inner] for a in args)

        def dfunc(x, *a):
            return np.imag(func(x + 1e-30j, *a)) / 1e-30

        res = elementwise.find_root(dfunc, (xl, xr), args=sub_args, tolerances=dict(xatol=xatol, xrtol=1e-15))
        fx = func(res.x, *sub_args)
        better = np.isfinite(fx) & (fx <= f[inner] + 1e-14 * np.abs(f[inner]))
        t = t.copy()
        f = f.copy()
        t[inner] = np.where(better, res.x, t[inner])
        f[inner] = np.where(better, fx, f[inner])
    return t, f
