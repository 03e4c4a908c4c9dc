"""Self-consistent adhesive normal contact on the elastic half-space (DC-FFT BEM).

This is the ground truth the analytic closures are checked against: a
free-boundary (non-periodic) boundary-element solver for the adhesive normal
contact of two elastic bodies with an arbitrary initial gap z(x, y), under
displacement control, with a Dugdale (Maugis) or an exponential traction law
(:mod:`dhfield.bem.laws`).

Problem
-------
Unknowns are the repulsive (contact) pressure ``p >= 0`` and the adhesive
stress ``s`` per cell.  With the DC-FFT operator K (:mod:`dhfield.bem.operator`)
and the approach delta,

.. math::

    h = z - \\delta + K(p - s) \\ge 0, \\quad p \\ge 0, \\quad p\\,h = 0,
    \\qquad s = \\sigma(h),

the traction law acting over the whole surface (also inside the contact, where
h = 0 and s = sigma0, as in Maugis' model).  The total pressure is ``p - s``
and the load ``W = sum (p - s) dx dy``.

Algorithm
---------
* **Inner problem** (convex): for a given adhesive stress s, the non-adhesive
  contact with the modified gap ``g0 = z - delta - K s``, solved for the
  pressure by the Polonsky-Keer constrained conjugate gradient (displacement
  control: the gradient is the gap on the active set; cells that overlap are
  added, cells that go tensile are released and conjugacy is reset; Polonsky &
  Keer 1999).  The pressure is the unknown, so no inverse of the non-periodic
  operator is needed.  An empty active set (no contact) is the linear case
  ``h = g0``, returned at once.
* **Outer problem**: a fixed point on the adhesive stress, accelerated by
  Anderson mixing (type II, memory 6), warm-started from the previous state
  of a path.  For the Dugdale law the unknown is the cell fraction chi in the
  zone h < h0, so ``s = sigma0 chi``.
* **Sub-cell zone edge** (Dugdale): a cell-wise law pins the zone edge to the
  cell boundaries (lattice trapping: jagged load curves, pull-off biased
  towards stronger adhesion).  Here chi of a cell is the exact area fraction
  of the cell where the *linearly interpolated* gap is below h0
  (:func:`dhfield.bem.laws.cell_fraction_below`, with the central-difference
  gradient of h), so the edge moves continuously through the cells and the
  fixed-point map is continuous.  Contact cells have chi = 1.
* **Stable discrete edge** (found here): a discrete state is energy-stable
  only if the spectral radius of ``|d sigma/dh| K`` is below 1, and for a
  ring of edge cells K sums to ~(2/pi) ln(c/dx) dx/E*.  With the bare sub-cell
  fraction the edge's gap spread |grad h| dx can be smaller than
  sigma0 (2/pi) ln(c/dx) dx/E* (lambda >~ 2): then no discrete state is
  stable, the outer iteration wanders and the path jumps (lattice trapping in
  another guise; damping cannot cure it).  The fraction is therefore taken
  over a gap spread of at least ``EDGE_WIDTH_FACTOR (1 + (2/pi) ln n) sigma0 dx/E*``
  (capped at 2 h0, symmetric about h0 so the work of adhesion is unchanged;
  it vanishes like dx ln(1/dx)).  Grids that would need more than 2 h0 are
  flagged ``resolved=False``: in the paper's units that is roughly
  dx > 2/(kappa_n mu^2), i.e. mu = 5 needs n >~ 512.
* **Symmetry**: when z is even in x and y (and nx, ny are even) the solver
  works on the quadrant ``x > 0, y > 0`` with the operator's symmetry mode
  (a quarter of the unknowns, the same discrete sum); the returned state is
  always on the full grid.

Path and pull-off
-----------------
:func:`unloading_path` loads under displacement control to a given approach
and unloads with warm starts until contact is lost, then re-solves the
bracket of the pull-off with finer steps (``refine_levels`` times).  The
load-control pull-off is the minimum of the unloading load (refined by
:func:`dhfield.pull_off_search.refine_sampled_minimum`); the
displacement-control pull-off is the fold of delta(W) extrapolated from the
converged states of the branch (:func:`fold_of_branch`; the last states before
the jump hold few contact cells and do not converge).
:func:`adhesive_pull_off` runs it in the paper's nondimensional units.  Under
load control it *brackets* the minimum instead (``search='bracket'``): a cold
start at the analytic DH pull-off approach from the DH cohesive zone, steps
until the load minimum is interior, and parabolic vertex states (3-6 states
instead of ~32, the same pull-off to the jaggedness of the discrete load
curve); every state starts from the same approach solved on the grid half as
fine (:class:`NestedWarmStart`), which cuts the outer iterations ~4x.
:func:`refine_pull_off` carries a pull-off to a finer grid (coarse to fine):
only ~7 states around the coarse pull-off are solved, warm-started from the
coarse state interpolated onto the fine grid (:func:`interpolate_state`); this
is what makes N = 1024 affordable for Richardson extrapolation.

Units
-----
Any consistent units: lengths (z, delta, grid cells), stresses (E*, the law's
sigma0) and forces (load = stress x area).  :func:`adhesive_pull_off` uses the
paper's (R = E* = Delta gamma = 1, Eqs. 32-35).

References
----------
.. [1] I. A. Polonsky, L. M. Keer (1999) A numerical method for solving rough
   contact problems based on the multi-level multi-summation and conjugate
   gradient techniques. Wear 231:206-219. doi:10.1016/S0043-1648(99)00113-1
.. [2] D. Maugis (1992) Adhesion of spheres: the JKR-DMT transition using a
   Dugdale model. J. Colloid Interface Sci. 150:243-269.
   doi:10.1016/0021-9797(92)90288-C
.. [3] H. F. Walker, P. Ni (2011) Anderson acceleration for fixed-point
   iterations. SIAM J. Numer. Anal. 49:1715-1735. doi:10.1137/10078356X
.. [4] N. H. M. Zini et al. (2018) Tribol. Lett. 66:30. doi:10.1007/s11249-017-0976-8
"""
from __future__ import annotations

import functools
import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from .._validation import check_ellipticity, check_finite, check_positive
from .laws import DugdaleLaw, ExponentialLaw, cell_fraction_below, law_from_name
from .operator import Grid, get_operator, influence_coefficients, quadrant, unfold_quadrant
from .state import ContactState

__all__ = ["solve_adhesive", "unloading_path", "adhesive_pull_off", "richardson_extrapolation",
           "nondimensional_problem", "UnloadingPath", "AdhesivePullOff", "NondimensionalProblem",
           "refine_pull_off", "interpolate_state", "NestedWarmStart", "fold_of_branch", "Fold", "DEFAULT_TOL", "DEFAULT_MAX_ITER", "DOMAIN_MARGIN", "DEFAULT_STEPS"]

#: Default solver tolerance: complementarity error of the contact problem relative to
#: the law's range (or |delta| without adhesion), and largest change of the zone
#: fraction between outer iterations [-].
DEFAULT_TOL = 1e-6
#: Default cap on the inner (conjugate-gradient) iterations of one state.
DEFAULT_MAX_ITER = 20000
#: Cap on outer (zone) iterations of one state.
MAX_OUTER = 300
#: Smallest width (in gap) of the sub-cell Dugdale edge, as a multiple of
#: kappa_n sigma0 dx/E* with kappa_n = 1 + (2/pi) ln n (n cells per axis): the cell
#: fraction is taken over at least this gap spread.  Energy stability of a discrete
#: state needs the spectral radius of |d sigma/dh| K below 1; for a ring of edge cells
#: K sums to ~(2/pi) ln(c/dx) dx/E*, so an edge narrower than that makes every discrete
#: state unstable (lattice trapping: no converged state, jumps).  The regularisation is
#: symmetric about h0 (the work of adhesion is unchanged) and vanishes like dx ln(1/dx).
#: It is capped at 2 h0; a grid that would need more is under-resolved
#: (``resolved=False`` in the results: the process zone c - a is not resolved, expect
#: unconverged states), which needs roughly dx < 2 E* h0/(kappa_n sigma0), i.e.
#: dx < 2/(kappa_n mu^2) in the paper's units.
EDGE_WIDTH_FACTOR = 1.25
#: Inner tolerance per outer iteration = INNER_FACTOR x the last outer residual.
INNER_FACTOR = 0.1
#: A state whose outer residual has not reached a new minimum for this many outer
#: iterations has stalled: its best iterate is returned (flagged unless within tol).
STALL_OUTER = 60
#: Outer iterations between Anderson restarts.
ANDERSON_RESTART = 40
#: Anderson memory (number of previous iterates mixed).
ANDERSON_MEMORY = 6
#: Evenness tolerance for the automatic symmetry mode (relative to max |z|).
_EVEN_RTOL = 1e-12


# ============================================================================ helpers
def _check_law(law):
    if law is None or isinstance(law, (DugdaleLaw, ExponentialLaw)):
        return law
    raise ValueError(f"law must be a DugdaleLaw, an ExponentialLaw or None (no adhesion); got {law!r}")


def _is_even_even(z):
    nx, ny = z.shape
    if nx % 2 or ny % 2:
        return False
    tol = _EVEN_RTOL * max(float(np.max(np.abs(z))), 1e-300)
    return bool(np.max(np.abs(z - z[::-1, :])) <= tol and np.max(np.abs(z - z[:, ::-1])) <= tol)


class _Problem:
    """Working arrays of one (grid, z, law) problem: full grid or even-even quadrant."""

    def __init__(self, initial_gap, grid, law, symmetric, threads, reduced_modulus):
        if not isinstance(grid, Grid):
            raise ValueError(f"grid must be a dhfield.bem.Grid; got {type(grid).__name__}")
        z = check_finite("initial_gap", initial_gap, "initial gap z(x, y), length")
        if z.shape != grid.shape:
            raise ValueError(f"initial_gap must have the grid shape {grid.shape}; got {z.shape}")
        self.law = _check_law(law)
        even = _is_even_even(z)
        if symmetric is None:
            symmetric = even
        elif symmetric and not even:
            raise ValueError("symmetric=True needs even nx, ny and an initial_gap even in x and in y")
        self.symmetric = bool(symmetric)
        self.grid = grid
        self.op = get_operator(grid, reduced_modulus, symmetric=self.symmetric, threads=threads)
        self.z = quadrant(z) if self.symmetric else np.ascontiguousarray(z)
        self.z_full = z
        # self-influence K00 (centre of a loaded cell), for the cold-start pressure
        e = float(reduced_modulus)
        dx, dy = grid.dx, grid.dy
        d = math.hypot(dx, dy)
        self.k0 = (dx * math.log((dy + d) / (d - dy)) + dy * math.log((dx + d) / (d - dx))) / (math.pi * e)
        self.weight = (4.0 if self.symmetric else 1.0) * grid.dx * grid.dy
        # smallest edge width of the Dugdale zone (see EDGE_WIDTH_FACTOR)
        self.min_spread = 0.0
        self.resolved = True
        if isinstance(self.law, DugdaleLaw):
            cells = math.sqrt(grid.nx * grid.ny)
            kappa = EDGE_WIDTH_FACTOR * (1.0 + 2.0 / math.pi * math.log(cells))
            want = kappa * self.law.max_stress * math.sqrt(dx * dy) / e
            # at most 2 h0: the smeared edge stays within h >= 0 and keeps the work of adhesion
            self.min_spread = min(want, 2.0 * self.law.range)
            self.resolved = want <= 2.0 * self.law.range

    def to_full(self, q):
        return unfold_quadrant(q) if self.symmetric else q

    def to_work(self, f):
        return quadrant(f) if self.symmetric else np.ascontiguousarray(f)

    def gradient_spreads(self, h):
        """|dh/dx| dx and |dh/dy| dy per cell (central differences; mirrored at symmetry axes)."""
        if self.symmetric:
            hp = np.pad(h, ((1, 0), (1, 0)), mode="symmetric")
            hp = np.pad(hp, ((0, 1), (0, 1)), mode="edge")
            sx = 0.5 * np.abs(hp[2:, 1:-1] - hp[:-2, 1:-1])
            sy = 0.5 * np.abs(hp[1:-1, 2:] - hp[1:-1, :-2])
            # one-sided at the outer edge (the padded value repeats the edge)
            sx[-1] *= 2.0
            sy[:, -1] *= 2.0
        else:
            gx, gy = np.gradient(h)
            sx, sy = np.abs(gx), np.abs(gy)
        if self.min_spread > 0.0:
            tot = sx + sy
            low = tot < self.min_spread
            if np.any(low):
                f = self.min_spread / np.maximum(tot[low], 1e-300)
                sx[low] = np.where(tot[low] > 0, sx[low] * f, self.min_spread)
                sy[low] = np.where(tot[low] > 0, sy[low] * f, 0.0)
        return sx, sy

    def stress_from_gap(self, h, contact):
        """Adhesive stress per cell for the gap h (the fixed-point map) [stress]."""
        law = self.law
        if isinstance(law, DugdaleLaw):
            sx, sy = self.gradient_spreads(h)
            chi = cell_fraction_below(law.range - h, sx, sy)
            chi[contact] = 1.0
            return law.max_stress * chi
        return law.stress(np.maximum(h, 0.0))

    def zone_fraction(self, h, contact):
        """Fraction of each cell in contact U zone (h below the law's zone gap)."""
        sx, sy = self.gradient_spreads(h)
        chi = cell_fraction_below(self.law.zone_gap - h, sx, sy)
        chi[contact] = 1.0
        return chi


def _complementarity(h, active):
    """max of |h| on the active set and of max(-h, 0) off it."""
    if h.size == 0:
        return 0.0
    v = np.where(active, np.abs(h), -h)
    return max(float(v.max()), 0.0)


def _dot(a, b):
    """Inner product without BLAS (a threaded BLAS ddot is very slow on a loaded machine)."""
    return float(np.einsum("ij,ij->", a, b))


#: Largest number of direct-sum terms (cells whose pressure a Polonsky-Keer step changes
#: beyond the CG update, i.e. released or newly loaded, times their 4 mirror images in
#: symmetric mode) for which the gap is corrected by adding influence coefficients instead
#: of a new convolution.  One term is two passes over the working grid; a convolution
#: costs ~7x (N = 256) to ~25x (N = 512) one term (measured, symmetric quadrant).
DIRECT_CORRECTION_TERMS = 16


@functools.lru_cache(maxsize=4)
def _extended_kernel(grid, reduced_modulus):
    """Influence coefficients for every signed offset, ``E[u + nx - 1, v + ny - 1] = K[|u|, |v|]``."""
    k = influence_coefficients(grid, reduced_modulus)[:grid.nx, :grid.ny]
    k = np.concatenate([k[:0:-1], k], axis=0)
    return np.ascontiguousarray(np.concatenate([k[:, :0:-1], k], axis=1))


def _add_point_loads(op, h, cells, amounts):
    """h += K(amounts at cells) by direct summation (4 mirror images in symmetric mode)."""
    ext = _extended_kernel(op.grid, op.reduced_modulus)
    nx, ny = op.grid.shape
    mx, my = h.shape
    for (i, j), a in zip(zip(*cells), amounts):
        if op.symmetric:
            rows = (slice(nx - 1 - i, nx - 1 - i + mx), slice(nx + i, nx + i + mx))
            cols = (slice(ny - 1 - j, ny - 1 - j + my), slice(ny + j, ny + j + my))
            for r in rows:
                for c in cols:
                    h += a * ext[r, c]
        else:
            h += a * ext[nx - 1 - i:2 * nx - 1 - i, ny - 1 - j:2 * ny - 1 - j]


#: Smallest grid (cells per axis) of the nested cold start of :func:`_polonsky_keer`.
NESTED_COLD_MIN_N = 64


def _nested_cold_start(op, g0, scale, tol, max_iter, k0):
    """Pressure of the same contact problem on the grid half as fine (recursively), or None.

    The gap is restricted by 2 x 2 cell averages and the coarse pressure prolonged as
    piecewise constant: a cold start whose smooth error is gone (measured: Hertz N = 512,
    74 -> ~50 fine CG iterations, the coarse ones costing ~1/5 each).
    """
    grid = op.grid
    if min(grid.nx, grid.ny) < 2 * NESTED_COLD_MIN_N or grid.nx % 4 or grid.ny % 4:
        return None, 0
    coarse = Grid(grid.nx // 2, grid.ny // 2, 2.0 * grid.dx, 2.0 * grid.dy)
    cop = get_operator(coarse, op.reduced_modulus, symmetric=op.symmetric, threads=op.threads)
    gc = 0.25 * (g0[0::2, 0::2] + g0[1::2, 0::2] + g0[0::2, 1::2] + g0[1::2, 1::2])
    # the self-influence of a cell scales with its size
    pc, _, it, _ = _polonsky_keer(cop, gc, np.zeros_like(gc), scale, tol, max_iter, 2.0 * k0)
    return np.repeat(np.repeat(pc, 2, axis=0), 2, axis=1), it


def _polonsky_keer(op, g0, p, scale, tol, max_iter, k0, stress=None):
    """Polonsky-Keer CG for min 1/2 p.Kp + (g0 - K stress).p, p >= 0 (displacement control).

    The gap is ``h = g0 + K(p - stress)`` (``stress`` is a known tensile load, e.g. the
    adhesive stress; one operator call per gap evaluation instead of two).
    Returns (p, h, iterations, error) with error the complementarity error / scale.
    """
    p = np.array(p, dtype=float, copy=True)
    np.maximum(p, 0.0, out=p)

    def gap(p):
        return g0 + op(p if stress is None else p - stress)

    coarse_it = 0
    if np.any(p > 0):
        h = gap(p)
    else:
        h = gap(p)
        neg = h < 0
        if not np.any(neg):
            return p, h, 0, 0.0          # empty active set: linear, done
        pc = None
        if stress is None:               # cold start of a contact problem: from the coarser grid
            pc, coarse_it = _nested_cold_start(op, g0, scale, tol, max_iter, k0)
        if pc is not None and np.any(pc > 0):
            p = pc
        else:
            p[neg] = -h[neg] / k0        # cold start: local (Jacobi) estimate
        h = gap(p)
    t = np.zeros_like(p)
    r = np.empty_like(p)
    kt = np.empty_like(p)
    g_old = 1.0
    conj = False
    it = 0
    since_full = 0
    active = p > 0
    err = _complementarity(h, active) / scale
    while err > tol and it < max_iter:
        it += 1
        np.multiply(h, active, out=r)
        g = _dot(r, r)
        if conj and g_old > 0.0:
            t *= g / g_old
            t += r
        else:
            t[...] = r
        g_old = g
        op(t, out=kt)
        den = _dot(kt, t)
        if not den > 0.0:
            break
        tau = _dot(h, t) / den
        p -= tau * t
        released = p < 0.0
        any_rel = bool(released.any())
        if any_rel:
            rel_cells = np.nonzero(released)
            rel_amounts = -p[rel_cells]
            p[released] = 0.0
        overlap = (~active) & (h < 0.0)
        any_ol = bool(overlap.any())
        if any_ol:
            ol_cells = np.nonzero(overlap)
            ol_amounts = -tau * h[ol_cells]
            p[ol_cells] += ol_amounts
        conj = not any_ol
        since_full += 1
        n_changed = (rel_amounts.size if any_rel else 0) + (ol_amounts.size if any_ol else 0)
        if since_full >= 25 or n_changed * (4 if op.symmetric else 1) > DIRECT_CORRECTION_TERMS:
            h = gap(p)
            since_full = 0
        else:
            # the CG step is linear; cells clipped at zero or newly loaded are few: add them directly
            h -= tau * kt
            if any_rel:
                _add_point_loads(op, h, rel_cells, rel_amounts)
            if any_ol:
                _add_point_loads(op, h, ol_cells, ol_amounts)
        active = p > 0
        err = _complementarity(h, active) / scale
    if since_full:
        h = gap(p)
        err = _complementarity(h, p > 0) / scale
    return p, h, it + coarse_it, err   # CG iterations on every grid (coarse ones are cheaper)


class _Anderson:
    """Anderson mixing (type II) for x = F(x); residual f = F(x) - x."""

    def __init__(self, memory=ANDERSON_MEMORY, mixing=1.0):
        self.m = memory
        self.beta = mixing
        self.reset()

    def reset(self):
        self.dx = None
        self.df = None
        self.count = 0
        self.x_prev = self.f_prev = None

    def step(self, x, f):
        xf, ff = x.ravel(), f.ravel()
        if self.dx is None:
            self.dx = np.empty((self.m, xf.size))
            self.df = np.empty((self.m, xf.size))
        if self.x_prev is not None:
            k = self.count % self.m
            np.subtract(xf, self.x_prev, out=self.dx[k])
            np.subtract(ff, self.f_prev, out=self.df[k])
            self.count += 1
        self.x_prev, self.f_prev = xf.copy(), ff.copy()
        new = xf + self.beta * ff
        n = min(self.count, self.m)
        if n:
            dfm = self.df[:n]
            dxm = self.dx[:n]
            # small normal equations (n x n), Tikhonov-regularised relative to their scale
            gram = dfm @ dfm.T
            reg = 1e-12 * max(float(np.trace(gram)), 1e-300)
            try:
                gamma = np.linalg.solve(gram + reg * np.eye(n), dfm @ ff)
            except np.linalg.LinAlgError:
                self.reset()
                return new.reshape(x.shape)
            new -= gamma @ dxm + self.beta * (gamma @ dfm)
        return new.reshape(x.shape)


# ============================================================================ solver
def solve_adhesive(initial_gap, grid, approach, law, *, guess=None, tol=DEFAULT_TOL,
                   max_iter=DEFAULT_MAX_ITER, symmetric=None, threads=None,
                   reduced_modulus=1.0) -> ContactState:
    """Adhesive normal contact at a given approach (displacement control), by BEM.

    Parameters
    ----------
    initial_gap : array_like, shape (nx, ny)
        Initial gap z(x, y) >= its minimum at the cell centres of ``grid``
        (e.g. x^2/(2R') + y^2/(2R'') for the crossed cylinders, Eq. 2) [length].
    grid : dhfield.bem.Grid
        Cell grid; the domain must contain the whole cohesive zone (the load is
        the integral over the grid; nothing acts outside it).
    approach : float
        Approach of distant points delta [length]; ``h = z - delta + omega``.
    law : DugdaleLaw, ExponentialLaw or None
        Traction-separation law (:mod:`dhfield.bem.laws`); None for non-adhesive
        (Hertz-type) contact.
    guess : ContactState, optional
        Warm start (a state on the same grid, e.g. the previous state of a path).
        Along a path always warm-start: the adhesive states are multistable.
    symmetric : bool, optional
        Solve on the even-even quadrant (default: when z is even in x and y and
        nx, ny are even).
    threads : int, optional
        FFTW threads.
    reduced_modulus : float, default 1
        E* [stress].

    Returns
    -------
    ContactState
        On the full grid, with ``converged``, ``iterations``, ``residual``.  An
        unconverged state is returned flagged, never silently.

    Other Parameters
    ----------------
    tol : float
        Tolerance on the complementarity error (relative to the law's range,
        or to |delta| and max z without adhesion) and on the largest change of
        the zone fraction (Dugdale) or of the stress relative to sigma0
        (exponential) between outer iterations.
    max_iter : int
        Cap on the total inner conjugate-gradient iterations.

    Notes
    -----
    See the module docstring for the algorithm: Polonsky-Keer CG for the
    repulsive pressure inside an Anderson-accelerated fixed point on the
    adhesive stress, with the sub-cell Dugdale zone edge.
    """
    prob = _Problem(initial_gap, grid, law, symmetric, threads, reduced_modulus)
    delta = float(check_finite("approach", approach, "approach of distant points, length"))
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    if int(max_iter) < 1:
        raise ValueError(f"max_iter must be an integer >= 1; got {max_iter!r}")
    if guess is not None and not (isinstance(guess, ContactState) and guess.grid == grid):
        raise ValueError("guess must be a ContactState on the same grid")
    return _solve(prob, delta, guess, tol, int(max_iter))


def _solve(prob, delta, guess, tol, max_iter):
    law = prob.law
    op = prob.op
    zd = prob.z - delta
    if law is None:
        scale = max(abs(delta), float(np.max(np.abs(prob.z))) * 1e-3, 1e-300)
    else:
        scale = law.range
    # gap error -> zone-fraction error: a Dugdale cell's fraction moves by dh/spread, so the
    # inner (gap) tolerances are scaled by spread/h0 (<= 1): at N = 1024 an inner error of
    # 1e-7 h0 moved the fraction by 4e-6 and the outer residual could not reach 1e-6.
    gain = min(1.0, prob.min_spread / scale) if (law is not None and prob.min_spread > 0.0) else 1.0
    inner_tol = 0.1 * tol * gain
    if isinstance(guess, _Prediction):
        p = guess.pressure.copy()
    elif guess is not None and guess.repulsive_pressure is not None:
        p = prob.to_work(guess.repulsive_pressure).copy()
    else:
        p = np.zeros_like(prob.z)
    total_it = 0
    if law is None:
        # no outer loop to feed: the contact problem itself is solved to tol (converged iff err <= tol)
        p, h, it, err = _polonsky_keer(op, zd, p, scale, tol, max_iter, prob.k0)
        total_it += it
        s = np.zeros_like(p)
        converged = err <= tol
        return _state(prob, delta, p, s, h, total_it, err, converged, 1)
    sigma0 = law.max_stress
    # initial adhesive stress
    if isinstance(guess, _Prediction):
        s = guess.stress.copy()
    elif guess is not None:
        if isinstance(law, DugdaleLaw):
            s = sigma0 * prob.to_work(guess.adhesive_zone)
        else:
            s = law.stress(np.maximum(prob.to_work(guess.gap), 0.0))
    else:
        h_rigid = zd.copy()
        s = prob.stress_from_gap(np.maximum(h_rigid, 0.0), h_rigid <= 0)
    acc = _Anderson()
    res = np.inf
    err = np.inf
    outer = 0
    h = None
    best = None
    best_outer = 0
    while outer < MAX_OUTER and total_it < max_iter and outer - best_outer <= STALL_OUTER:
        outer += 1
        # inexact inner solves: tighten with the outer residual (Anderson tolerates it), in units
        # of the zone fraction (gain): a looser inner solve feeds the fixed point noise larger
        # than its residual (measured at N = 1024: the contact set flipped by 3 % every iteration)
        itol = gain * (1e-3 if not np.isfinite(res) else min(max(INNER_FACTOR * res, 0.1 * tol), 1e-2))
        p, h, it, err = _polonsky_keer(op, zd, p, scale, itol, max_iter - total_it, prob.k0, stress=s)
        total_it += it
        f = prob.stress_from_gap(h, p > 0) - s
        res = float(np.max(np.abs(f))) / sigma0
        if best is None or res < best[0]:
            best = (res, s.copy(), p.copy(), h.copy(), err)
            best_outer = outer
        if res <= tol and err <= tol:
            if err <= inner_tol or itol <= inner_tol:
                break
        s = np.clip(acc.step(s, f), 0.0, sigma0)
        if outer % ANDERSON_RESTART == 0:
            acc.reset()
    else:
        # out of iterations: report the best iterate, flagged
        res, s, p, h, err = best
    converged = res <= tol and err <= tol
    return _state(prob, delta, p, s, h, total_it, max(res, err), converged, outer)


@dataclass
class _Prediction:
    """Warm start extrapolated along a path (working arrays: repulsive pressure, stress)."""

    pressure: np.ndarray
    stress: np.ndarray


def _predict(prob, prev, last, delta):
    """Secant predictor from the last two states of a path (same branch), else ``last``."""
    if prev is None or last is None or not (prev.converged and last.converged):
        return last
    if prev.in_contact != last.in_contact or prev.approach == last.approach:
        return last
    t = (delta - last.approach) / (last.approach - prev.approach)
    if not 0.0 < t <= 1.5:
        return last
    law = prob.law

    def stress_of(st):
        if isinstance(law, DugdaleLaw):
            return law.max_stress * prob.to_work(st.adhesive_zone)
        return law.stress(np.maximum(prob.to_work(st.gap), 0.0))

    s1, s0 = stress_of(last), stress_of(prev)
    p1, p0 = prob.to_work(last.repulsive_pressure), prob.to_work(prev.repulsive_pressure)
    stress = np.clip(s1 + t * (s1 - s0), 0.0, law.max_stress)
    pressure = np.maximum(p1 + t * (p1 - p0), 0.0)
    return _Prediction(pressure, stress)


def _state(prob, delta, p, s, h, iterations, residual, converged, outer):
    contact_w = p > 0
    law = prob.law
    if law is None:
        coh = np.zeros_like(p)
    else:
        coh = prob.zone_fraction(h, contact_w)
        coh[contact_w] = 0.0
    load = float(np.sum(p - s)) * prob.weight
    full = prob.to_full
    return ContactState(
        grid=prob.grid, pressure=full(p - s), gap=full(h), approach=float(delta), load=load,
        contact=full(contact_w), cohesive=full(coh), law=law, converged=bool(converged),
        iterations=int(iterations), residual=float(residual), outer_iterations=int(outer),
        repulsive_pressure=full(p))


# ============================================================================ path
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
        'loading', 'unloading', 'refine', 'jump' (re-solved from separation) or
        'discarded' (a cold start of the bracket search that gave no converged
        contact state; kept, flagged, excluded from the pull-off) per state.
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
        fold of delta(W) extrapolated from the converged contact states of the
        branch (:func:`fold_of_branch`); when no fold is bracketed, the last
        converged contact state (said in ``pull_off_note``).
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
        converged (failures beyond the jump do not count).
    resolved : bool
        False when the grid is too coarse for the Dugdale edge (see
        ``EDGE_WIDTH_FACTOR``): the results are then not trustworthy.
    coarse_states, coarse_iterations : int
        States and CG iterations solved on coarser grids for the warm starts
        (``warm_start``; 0 without), not counted in the arrays above.
    pull_off_error : float
        Displacement control: error estimate of ``pull_off_load`` from the fold
        extrapolation [force] (NaN when it cannot be estimated, and under load
        control).
    pull_off_note : str
        Caveats on the pull-off (empty if none): under displacement control, a
        fold that is not bracketed.
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
        States used: the last ``points`` (at least 3).

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
    w = np.asarray(loads, dtype=float)
    d = np.asarray(approaches, dtype=float)
    if w.size == 0:
        return Fold(float("nan"), float("nan"), float("nan"), False)
    last = Fold(float(w[-1]), float(d[-1]), float("nan"), False)
    m = min(max(int(points), 3), w.size)
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


class _Progress:
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
        *brackets* the minimum instead of marching to it (see Notes).
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
    """
    from ..pull_off_search import refine_sampled_minimum

    if control not in ("load", "displacement"):
        raise ValueError(f"control must be one of ('load', 'displacement') (loading mode); got {control!r}")
    if law is None:
        raise ValueError("law must be a DugdaleLaw or an ExponentialLaw for an unloading path; got None")
    prob = _Problem(initial_gap, grid, law, symmetric, threads, reduced_modulus)
    dmax = float(check_finite("approach_max", approach_max, "length"))
    step = float(check_positive("approach_step", approach_step, "length"))
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    for name, v, lo in (("n_loading", n_loading, 1), ("refine_levels", refine_levels, 0),
                        ("refine_factor", refine_factor, 2), ("max_steps", max_steps, 2)):
        if int(v) != v or int(v) < lo:
            raise ValueError(f"{name} must be an integer >= {lo}; got {v!r}")
    guess_d = None if approach_guess is None else float(
        check_finite("approach_guess", approach_guess, "expected approach of the load minimum, length"))
    start_gap_stress = None
    if start_stress is not None:
        s_full = check_finite("start_stress", start_stress, "adhesive stress of the cold start, stress")
        if s_full.shape != grid.shape:
            raise ValueError(f"start_stress must have the grid shape {grid.shape}; got {s_full.shape}")
        start_gap_stress = np.clip(prob.to_work(s_full), 0.0, law.max_stress)
    t0 = time.perf_counter()
    prog = _Progress(progress, "path")
    records = []          # (state summary dict, phase)
    kept = []
    failures = []
    by_index = {}

    def run(delta, guess, phase):
        st = _solve(prob, float(delta), guess, tol, int(max_iter))
        rec = st.summary()
        rec["phase"] = phase
        rec["in_contact"] = st.in_contact
        records.append(rec)
        k = len(records) - 1
        by_index[k] = st
        if not st.converged:
            failures.append({"approach": float(delta), "residual": float(st.residual),
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
            guess = _Prediction(np.zeros_like(start_gap_stress), start_gap_stress.copy())
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
                g = _predict(prob, by_index[nxt[0]], last, d_new) if (predict and nxt) else last
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
            k, new = run(delta, _predict(prob, prev, st, delta) if predict else st, "unloading")
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
                k, new = run(dd, _predict(prob, prev, st, dd) if predict else st, "refine")
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
    if k_po not in by_index:
        k_po = max(by_index)
    arr = {key: np.array([r[key] for r in records]) for key in
           ("approach", "load", "a", "b", "c", "d", "contact_area", "phase", "converged", "iterations",
            "outer_iterations", "residual")}
    states = tuple(by_index[i] for i in range(len(records))) if keep_states else ()
    return UnloadingPath(arr["approach"], arr["load"], arr["a"], arr["b"], arr["c"], arr["d"],
                         arr["contact_area"], arr["phase"], arr["converged"].astype(bool),
                         arr["iterations"].astype(int), arr["outer_iterations"].astype(int),
                         arr["residual"], control, float(w_po), float(d_po), by_index[k_po],
                         tuple(failures), states, time.perf_counter() - t0, po_converged, prob.resolved,
                         int(getattr(warm_start, "states_solved", 0)), int(getattr(warm_start, "iterations", 0)),
                         pull_off_error=float(w_po_error), pull_off_note=po_note)


# ============================================================================ paper units
#: Half-width of the domain per expected semi-axis of the largest cohesive zone of
#: the path (the zone must lie inside the grid; DC-FFT needs no margin beyond it).
DOMAIN_MARGIN = 1.15
#: Default number of unloading steps from the start of unloading to the expected jump.
DEFAULT_STEPS = 20


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
        Approach at the analytic DH load-control pull-off [c_r^2/R]: where the
        bracket search of :func:`unloading_path` starts.
    pull_off_zone : (float, float)
        Semi-axes (c, d) of the analytic DH cohesive zone at that pull-off [c_r]:
        the zone of the bracket search's cold start.
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
    displacement-control pull-off.
    """
    from .. import model
    from ..geometry import radius_ratio, sin_skew_angle

    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    if int(n) != n or int(n) < 8 or int(n) % 2:
        raise ValueError(f"n must be an even integer >= 8 (cells per axis); got {n!r}")
    n = int(n)
    if int(n_steps) != n_steps or n_steps < 4:
        raise ValueError(f"n_steps must be an integer >= 4 (unloading steps); got {n_steps!r}")
    margin = float(check_positive("margin", margin, "domain half-width per zone semi-axis"))
    law_obj = law_from_name(law, mu, 1.0) if isinstance(law, str) else _check_law(law)
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
    # the analytic cohesive zone at the load-control pull-off (cold start of the bracket search)
    at_po = model.load_curve(mu, beta0, [max(float(po.a_star), 1e-3 * a_start)])
    zone = (float(at_po.c_star[0]), float(at_po.d_star[0]))
    return NondimensionalProblem(mu, beta0, grid, z, law_obj, float(sin_skew_angle(beta0)), d_max,
                                 (d_max - d_end) / int(n_steps), float(po.delta_star), zone)


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
        Displacement control: error estimate of ``W_star`` from the extrapolation
        to the fold (:func:`fold_of_branch`); NaN under load control.
    note : str
        Caveats on the pull-off (empty under load control): every
        displacement-control result carries :data:`DISPLACEMENT_CONTROL_NOTE`
        (its measured errors against Maugis-Dugdale), and says when no fold was
        bracketed.
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

    def as_dict(self) -> dict:
        """JSON-ready scalars (the path and failures summarised)."""
        out = {k: getattr(self, k) for k in (
            "mu", "beta0", "n", "law", "control", "W_star", "W_star_error", "a_star", "b_star", "c_star",
            "d_star", "beta_ab", "beta_cd", "delta_star", "converged", "resolved", "n_steps", "iterations",
            "residual", "half_width_x", "half_width_y", "elapsed", "note")}
        out["failures"] = [dict(f) for f in self.failures]
        out["iterations_per_step"] = self.iterations / max(self.n_steps, 1)
        return out


#: Coarsest grid (cells per axis) solved for nested warm starts (:class:`NestedWarmStart`).
NESTED_MIN_N = 64


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

    Attributes
    ----------
    states_solved, iterations : int
        Coarse states solved and their CG iterations, over all levels.
    """

    def __init__(self, mu, beta0, n, *, law="dugdale", margin=DOMAIN_MARGIN, tol=DEFAULT_TOL,
                 max_iter=DEFAULT_MAX_ITER, threads=None):
        fine = nondimensional_problem(mu, beta0, n, law=law, margin=margin)
        nc = int(n) // 2
        if nc < NESTED_MIN_N or nc % 2:
            raise ValueError(f"n must be even and >= {2 * NESTED_MIN_N} for nested warm starts; got {n!r}")
        coarse = nondimensional_problem(mu, beta0, nc, law=law, margin=margin)
        self.fine_grid = fine.grid
        self._prob = _Problem(coarse.initial_gap, coarse.grid, coarse.law, None, threads, 1.0)
        self._cold = _Prediction(np.zeros_like(self._prob.z), self._prob.to_work(coarse.start_stress()))
        self._tol, self._max_iter = float(tol), int(max_iter)
        self._inner = (NestedWarmStart(mu, beta0, nc, law=law, margin=margin, tol=tol, max_iter=max_iter,
                                       threads=threads) if nc // 2 >= NESTED_MIN_N and nc % 4 == 0 else None)
        self._states = {}
        self._own_iterations = 0

    @property
    def states_solved(self) -> int:
        return len(self._states) + (self._inner.states_solved if self._inner else 0)

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
            st = _solve(self._prob, d, guess, self._tol, self._max_iter)
            self._own_iterations += st.iterations
            self._states[d] = st
        return self._states[d]

    def __call__(self, approach):
        """Warm start on the fine grid, or None when the coarse state is not a converged contact state."""
        st = self.coarse_state(approach)
        if not (st.converged and st.in_contact):
            return None
        return interpolate_state(st, self.fine_grid)


def adhesive_pull_off(mu, beta0, n, *, law="dugdale", control="load", n_steps=DEFAULT_STEPS,
                      refine_levels=2, tol=DEFAULT_TOL, max_iter=DEFAULT_MAX_ITER,
                      margin=DOMAIN_MARGIN, threads=None, keep_states=False,
                      progress=None, search="bracket", nested=None) -> AdhesivePullOff:
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
        the last contact state before the jump.

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
    search : {'bracket', 'march'}
        Load control only.  'bracket' (default): cold-start at the analytic DH
        pull-off approach from the DH cohesive zone and bracket the load minimum
        there (a handful of states; :func:`unloading_path` with
        ``approach_guess``).  'march': unload from ``approach_max`` in uniform
        steps to the jump and refine the minimum's bracket (the path of
        dhfield <= the first session; ~5x more states, same pull-off).
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
    if search not in ("bracket", "march"):
        raise ValueError(f"search must be one of ('bracket', 'march') (load-control path); got {search!r}")
    prob = nondimensional_problem(mu, beta0, n, law=law, n_steps=n_steps, margin=margin)
    guess = {}
    if control == "load" and search == "bracket" and np.all(np.isfinite(prob.pull_off_zone)):
        guess = dict(approach_guess=prob.pull_off_approach, start_stress=prob.start_stress())
        if nested is None:
            nested = int(n) >= 2 * NESTED_MIN_N and int(n) % 4 == 0
        if nested:
            guess["warm_start"] = NestedWarmStart(mu, beta0, n, law=law, margin=margin, tol=tol,
                                                  max_iter=max_iter, threads=threads)
    path = unloading_path(prob.initial_gap, prob.grid, prob.law, prob.approach_max, prob.approach_step,
                          control=control, refine_levels=refine_levels, tol=tol, max_iter=max_iter,
                          threads=threads, keep_states=keep_states, progress=progress, **guess)
    return _pull_off_result(prob, int(n), path)


#: Caveat carried by every displacement-control pull-off (:attr:`AdhesivePullOff.note`).
#: Measured on the sphere against Maugis-Dugdale's displacement-control pull-off
#: (``adhesive_pull_off(mu, 1, n, control="displacement")`` vs ``dhfield.maugis_dugdale``,
#: 2026-11-23): lambda = 0.3: +0.10 / +0.08 % (N = 128 / 256, no fold bracketed: the last
#: converged state); lambda = 0.6: -6.0 / -6.2 %; lambda = 1: -0.23 / +2.8 %; lambda = 1.5:
#: +11.4 / +6.5 %; lambda = 2: +14.1 / +18.2 %; lambda = 3: +13.6 % (N = 128).  The error
#: estimate of the fold extrapolation (W_star_error) is often 2-4x smaller than these errors.
DISPLACEMENT_CONTROL_NOTE = (
    "the displacement-control pull-off is the fold of delta(W) extrapolated from the converged states "
    "before the jump; on the sphere it is -6 % to +18 % off Maugis-Dugdale for lambda = 0.6-3 "
    "(N = 128/256), often beyond W_star_error: use load control (within 0.05 % of MD) for reference values")


def _pull_off_result(prob: NondimensionalProblem, n: int, path: UnloadingPath) -> AdhesivePullOff:
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
        W_star_error=float(abs(path.pull_off_error * scale)), note=note)


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
    if int(n) != n or int(n) <= coarse.n:
        raise ValueError(f"n must be an integer > coarse.n = {coarse.n} (cells per axis); got {n!r}")
    for name, v, lo in (("window", window, 1), ("refine_levels", refine_levels, 0),
                        ("refine_factor", refine_factor, 2)):
        if int(v) != v or int(v) < lo:
            raise ValueError(f"{name} must be an integer >= {lo}; got {v!r}")
    prob_nd = nondimensional_problem(coarse.mu, coarse.beta0, int(n), law=coarse.law, n_steps=n_steps)
    grid = prob_nd.grid
    if not (math.isclose(0.5 * grid.nx * grid.dx, coarse.half_width_x, rel_tol=1e-9)
            and math.isclose(0.5 * grid.ny * grid.dy, coarse.half_width_y, rel_tol=1e-9)):
        raise ValueError("coarse must come from the same domain (adhesive_pull_off with the default margin)")
    prob = _Problem(prob_nd.initial_gap, grid, prob_nd.law, None, threads, 1.0)
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    h = prob_nd.approach_step / int(refine_factor) ** int(refine_levels)
    top = prob_nd.approach_max
    j_c = int(round((top - coarse.delta_star) / h))
    t0 = time.perf_counter()
    prog = _Progress(progress, f"refine N={int(n)}")
    solved = {}                       # lattice index -> ContactState

    def run(j, guess):
        st = _solve(prob, top - j * h, guess, tol, int(max_iter))
        solved[j] = st
        prog.update(len(solved), st, "refine")
        return st

    # downwards from the top of the window: warm start from the coarse state, then secant
    first = interpolate_state(coarse.path.pull_off_state, grid)
    lo_j, hi_j = j_c - int(window), j_c + int(window)
    prev, st = None, first
    for j in range(lo_j, hi_j + 1):
        new = run(j, first if st is first else _predict(prob, prev, st, top - j * h))
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
            run(j, _predict(prob, solved[js[1]], solved[js[0]], top - j * h))
        else:                         # at the bottom: continue unloading
            j = js[-1] + 1
            run(j, _predict(prob, solved[js[-2]], solved[js[-1]], top - j * h))
    prog.close()
    js, w, sm = minimum()
    states = [solved[j] for j in js]
    if sm is None:
        k_po, w_po, d_po = len(states) - 1, float("nan"), float("nan")
    else:
        k_po, w_po, d_po = sm.index, sm.y, sm.x
    recs = [s.summary() for s in states]
    failures = tuple({"approach": r["approach"], "residual": r["residual"], "iterations": r["iterations"],
                      "phase": "refine"} for r in recs if not r["converged"])
    arr = {key: np.array([r[key] for r in recs]) for key in
           ("approach", "load", "a", "b", "c", "d", "contact_area", "iterations", "outer_iterations",
            "residual")}
    path = UnloadingPath(arr["approach"], arr["load"], arr["a"], arr["b"], arr["c"], arr["d"],
                         arr["contact_area"], np.array(["refine"] * len(states)),
                         np.array([r["converged"] for r in recs], dtype=bool),
                         arr["iterations"].astype(int), arr["outer_iterations"].astype(int), arr["residual"],
                         "load", float(w_po), float(d_po), states[k_po], failures,
                         tuple(states) if keep_states else (), time.perf_counter() - t0,
                         not failures and sm is not None and not sm.at_boundary, prob.resolved)
    return _pull_off_result(prob_nd, int(n), path)
