"""One adhesive state by a semismooth Newton (primal-dual active-set) method on the DC-FFT operator.

Problem
-------
Unknown: the total surface traction ``q`` per cell (positive in compression), on the
working grid of :class:`dhfield.bem.solver.AdhesiveProblem` (the even-even quadrant in
symmetric mode).  With the DC-FFT operator K and the approach delta,

.. math::

    h = z - \\delta + K q, \\qquad p = q + \\sigma(h), \\qquad
    h \\ge 0,\\; p \\ge 0,\\; p\\,h = 0,

where ``p`` is the repulsive (contact) pressure and sigma the traction law.  These are the
stationarity conditions of the potential energy

.. math::

    \\Pi(u) = \\tfrac12 u^T K^{-1} u + \\sum_i \\phi(z_i - \\delta + u_i), \\quad u = K q,
    \\quad h \\ge 0, \\qquad \\phi(h) = -\\int_h^\\infty \\sigma,

so a state is a constrained critical point of Pi, stable when Pi's Hessian
``K^{-1} + diag(sigma'(h))`` is positive on the non-contact cells.

The law on a grid
-----------------
The Dugdale law (sigma0 for h < h0) is taken with its edge as a linear ramp of width
``w`` in the cell's own gap, centred on h0 (the work of adhesion sigma0 h0 is kept):

.. math:: \\sigma_w(h) = \\sigma_0\\,\\min\\!\\left(1, \\max\\!\\left(0,
          \\frac{h_0 + w/2 - h}{w}\\right)\\right).

``w`` is the edge width of :class:`~dhfield.bem.solver.AdhesiveProblem` (``min_spread``):
the smallest width for which a discrete edge state is energy-stable, capped at 2 h0; it
vanishes like dx ln(1/dx) under refinement.  Smooth laws (exponential) are used as they are.

Algorithm
---------
Semismooth Newton on the complementarity function ``F = min(c h, p)`` with
``c = sigma0/h0`` (gap scaled to a stress), i.e. a primal-dual active-set method:

* contact cells A = {c h < p}: the Newton row enforces ``h + K dq = 0``;
* edge cells E (out of contact, on the law's ramp): ``p + dq - |sigma'| K dq = 0``;
* the other cells: ``dq = -p`` (the traction is the law's plateau, or zero).

The generalised Jacobian restricted to A u E is solved matrix-free by GMRES, right-
preconditioned on A by the inverse of the operator's own symbol (the hypersingular
operator: a Calderon preconditioner, which keeps the iteration count nearly independent
of the grid), with a relative tolerance that tightens with the residual (inexact Newton,
superlinear).  A backtracking line search on the merit ``||F||^2`` makes every accepted
step decrease it, or, with the watchdog (``SolverOptions.watchdog``, [4]_), the best merit
decrease at least once in every few steps while full steps are taken between.  The pull-off sensitivity ``dq/d delta`` costs one more linear solve
with the same Jacobian (:func:`load_slope`).

References
----------
.. [1] M. Hintermueller, K. Ito, K. Kunisch (2002) The primal-dual active set strategy as
   a semismooth Newton method. SIAM J. Optim. 13:865-888. doi:10.1137/S1052623401383558
.. [2] O. Steinbach, W. L. Wendland (1998) The construction of some efficient
   preconditioners in the boundary element method. Adv. Comput. Math. 9:191-216.
   doi:10.1023/A:1018937506719
.. [3] D. Maugis (1992) J. Colloid Interface Sci. 150:243-269. doi:10.1016/0021-9797(92)90288-C
.. [4] R. M. Chamberlain, M. J. D. Powell, C. Lemarechal, H. C. Pedersen (1982) The watchdog
   technique for forcing convergence in algorithms for constrained optimization. Math.
   Programming Study 16:1-17. doi:10.1007/BFb0120945
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, asdict, replace

import numpy as np
import scipy.fft
from scipy.sparse.linalg import LinearOperator, gmres

from .laws import DugdaleLaw
from .operator import influence_coefficients

__all__ = ["SolverOptions", "NewtonResult", "solve_state", "solve_state_smoothed", "load_slope",
           "symbol_preconditioner", "problem_preconditioner", "load_minimum", "LoadMinimum", "cold_start", "cold_start_on", "ramp_stress", "solve_state_at_force",
           "CONVERGED", "DIVERGED_LINE_SEARCH", "DIVERGED_MAX_IT", "DIVERGED_LINEAR_SOLVE", "DIVERGED_STALL",
           "fgmres", "right_preconditioned_gmres", "contact_cg", "prolong", "prolong_state", "grid_ladder", "NESTED_OPTIONS", "LevelReport",
           "NestedResult", "solve_state_nested"]

#: Stop reasons (PETSc-style: positive converged, negative diverged).
CONVERGED = "converged_residual"
DIVERGED_LINE_SEARCH = "diverged_line_search"
DIVERGED_MAX_IT = "diverged_max_it"
DIVERGED_LINEAR_SOLVE = "diverged_linear_solve"
DIVERGED_STALL = "diverged_stall"


@dataclass(frozen=True)
class SolverOptions:
    """Tolerances and caps of the adhesive solve (one object for every route).

    Parameters
    ----------
    tol : float, default 1e-8
        Converged when ``max |min(h/h0, p/sigma0)| <= tol`` over the cells [-].
    max_newton : int, default 60
        Cap on Newton iterations of one state.
    max_krylov : int, default 2000
        Cap on GMRES iterations of one linear solve.
    forcing : float, default 0.1
        Largest relative GMRES tolerance (inexact Newton); the tolerance used is
        ``min(forcing, sqrt(||F|| / ||F_0||))`` relative [-].
    nonmonotone : int, default 1
        A step is accepted when it decreases the merit below the largest of the last this
        many merits (1: monotone).
    min_damping, max_damping : float, default 0.25, 1e4
        Range of the trust-region (Levenberg-Marquardt) damping of the non-contact rows: a
        rejected step is retried with the damping multiplied by 4 from ``4 min_damping``; beyond
        ``max_damping`` the last step is backtracked instead [-].
    stall : int, default 0
        Stop (:data:`DIVERGED_STALL`) when the merit fell by less than 1e-3 relative over the
        last this many accepted steps (0: never).
    contact_inner : int, default 0
        Inner iterations of the contact rows' preconditioner: 0 applies the inverse symbol
        (:func:`symbol_preconditioner`); k > 0 applies k iterations of conjugate gradients on
        the contact block ``K_AA`` itself, preconditioned by the inverse symbol, and the outer
        Krylov solver is the flexible GMRES (:func:`fgmres`).
    symbol_floor : bool, default True
        The inverse symbol with its spectrum floored at the highest frequencies' value
        (``symbol_preconditioner(floor=True)``), when the solve builds it.  Without the
        floor, cells that are not square leave near-zero or negative entries in the
        truncated kernel's spectrum, whose inverses swamp the preconditioner.
    watchdog : int, default 0
        Watchdog steps (0: none): up to this many full Newton steps are taken whatever their
        merit; when none of them has brought the merit below the best one so far (by 1e-4
        relative), the iteration returns to the best iterate and takes the safeguarded step
        from it (a step that decreases the merit, with the trust-region damping).  The best
        merit therefore falls at least once every ``watchdog + 1`` iterations (Chamberlain,
        Powell, Lemarechal & Pedersen 1982), and the full steps move the contact's rim by
        many cells at once, where a merit-decreasing step moves it by a fraction of a ring.
    """

    tol: float = 1e-8
    max_newton: int = 60
    max_krylov: int = 2000
    forcing: float = 0.1
    nonmonotone: int = 1
    min_damping: float = 0.25
    max_damping: float = 1e4
    stall: int = 0
    contact_inner: int = 0
    symbol_floor: bool = True
    watchdog: int = 0

    def as_dict(self) -> dict:
        """Return the options as a mapping (recorded with every result).

        Returns
        -------
        dict
            Field name to value.
        """
        return asdict(self)


@dataclass
class NewtonResult:
    """A solved (or flagged) adhesive state on the working grid.

    Parameters
    ----------
    traction : ndarray
        Total traction q per working cell, positive compressive [stress].
    gap : ndarray
        Gap h [length].
    contact : ndarray of bool
        Contact cells (the final active set).
    load : float
        Total load, sum(q) times the cell area (four quadrants in symmetric mode) [force].
    residual : float
        ``max |min(h/h0, p/sigma0)|`` [-].
    reason : str
        Why it stopped (:data:`CONVERGED` or a ``diverged_*`` reason).
    newton_iterations, krylov_iterations, operator_calls : int
        Work spent.
    merit_history : list of float
        ``||F||`` after each accepted step (decreasing by construction without the watchdog; with
        it, its running minimum falls at least once in every ``watchdog + 1`` entries).
    elapsed : float
        Wall time [s].
    """

    traction: np.ndarray
    gap: np.ndarray
    contact: np.ndarray
    load: float
    residual: float
    reason: str
    newton_iterations: int
    krylov_iterations: int
    operator_calls: int
    merit_history: list
    elapsed: float

    @property
    def converged(self) -> bool:
        """True when the residual met the tolerance."""
        return self.reason == CONVERGED


class _Law:
    """sigma(h) and its slope for the solve (the Dugdale edge as a ramp of width w)."""

    def __init__(self, law, width):
        self.law = law
        self.sigma0 = law.max_stress
        self.h0 = law.range
        self.dugdale = isinstance(law, DugdaleLaw)
        self.width = float(width) if self.dugdale else 0.0
        if self.dugdale and not self.width > 0.0:
            raise ValueError("the Dugdale law needs an edge width > 0 (AdhesiveProblem.min_spread)")

    def stress(self, h):
        if self.dugdale:
            w = self.width
            return self.sigma0 * np.clip((self.h0 + 0.5 * w - h) / w, 0.0, 1.0)
        return self.law.stress(np.maximum(h, 0.0))

    def slope(self, h):
        """|d sigma/dh| >= 0 per cell."""
        if self.dugdale:
            w = self.width
            on = np.abs(h - self.h0) < 0.5 * w
            return np.where(on, self.sigma0 / w, 0.0)
        return -self.law.stress_slope(np.maximum(h, 0.0))


def problem_preconditioner(problem, floor=True):
    """The :func:`symbol_preconditioner` of an adhesive problem, built once per problem and floor.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem (grid, symmetry, E*).
    floor : bool, default True
        As in :func:`symbol_preconditioner`.

    Returns
    -------
    callable
        ``apply(v) -> ndarray`` on the problem's working grid (cached on the problem: its
        spectrum and FFTW plans are not rebuilt for every state).
    """
    cache = problem.__dict__.setdefault("_symbol_preconditioners", {})
    key = bool(floor)
    if key not in cache:
        cache[key] = symbol_preconditioner(problem.grid, problem.symmetric, _modulus(problem), floor=key)
    return cache[key]


#: Cap on the FFTW planning time of each transform of :func:`symbol_preconditioner` [s].
PLANNING_SECONDS = 2.0


def symbol_preconditioner(grid, symmetric, reduced_modulus=1.0, workers=1, floor=True):
    """The inverse of the DC-FFT operator's own symbol, applied to a working-grid field.

    The operator is ``crop o T^-1 o diag(S) o T o pad`` with T the DFT (full grid) or the
    DCT-II (quadrant) of the zero-padded field; this returns
    ``v -> crop o T^-1 o diag(1/S) o T o pad v``: the inverse of the un-cropped (circulant)
    operator, a discrete hypersingular operator.  Restricted to the contact cells it is a
    Calderon preconditioner of the operator restricted to them.

    Parameters
    ----------
    grid : Grid
        The full grid.
    symmetric : bool
        Working on the even-even quadrant.
    reduced_modulus : float
        E* [stress].
    workers : int
        Threads of the transforms (FFTW in symmetric mode, scipy.fft otherwise).
    floor : bool, default True
        Raise the symbol to its smallest positive value on the highest frequencies (the row
        ``nx - 1`` and the column ``ny - 1`` of the DCT-I spectrum) everywhere.  On cells that
        are not square the truncated kernel's spectrum oscillates about zero at high
        frequencies along the zero frequency of the longer cell side (157 entries <= 0 at
        beta0 = 0.4826 on 1280^2, dx/dy = 1.73); without the floor their inverses are ~1e12
        times the others.

    Returns
    -------
    callable
        ``apply(v) -> ndarray`` on working-grid arrays.
    """
    nx, ny = grid.shape
    d = scipy.fft.dctn(influence_coefficients(grid, reduced_modulus), type=1, workers=workers)
    if floor:
        top = np.concatenate([d[nx - 1, :ny], d[:nx, ny - 1]])
        d = np.maximum(d, top[top > 0].min())
    if symmetric:
        spec = d[:nx, :ny]
        inv = 1.0 / (np.maximum(spec, 1e-300 + 1e-12 * spec.max()) * (4.0 * nx * ny))
        qx, qy = nx // 2, ny // 2
        # FFTW's REDFT10 / REDFT01 are scipy's unnormalised DCT-II / DCT-III.  The padded field is
        # zero beyond the quadrant and only the quadrant is kept, so the transforms along y run on
        # the quadrant's rows only (as the operator's own, :mod:`dhfield.bem.operator`)
        import pyfftw

        plan = dict(flags=("FFTW_MEASURE", "FFTW_DESTROY_INPUT"), threads=int(workers),
                    planning_timelimit=PLANNING_SECONDS)
        rows = pyfftw.zeros_aligned((qx, ny), dtype="float64")
        work = pyfftw.zeros_aligned((nx, ny), dtype="float64")
        back = pyfftw.empty_aligned((qx, ny), dtype="float64")
        out = pyfftw.empty_aligned((qx, ny), dtype="float64")
        y_fwd = pyfftw.FFTW(rows, work[:qx], axes=(1,), direction=["FFTW_REDFT10"], **plan)
        x_fwd = pyfftw.FFTW(work, work, axes=(0,), direction=["FFTW_REDFT10"], **plan)
        x_bwd = pyfftw.FFTW(work, work, axes=(0,), direction=["FFTW_REDFT01"], **plan)
        y_bwd = pyfftw.FFTW(back, out, axes=(1,), direction=["FFTW_REDFT01"], **plan)

        def apply(v):
            rows[...] = 0.0
            rows[:, :qy] = v
            work[qx:] = 0.0
            y_fwd()
            x_fwd()
            work[...] *= inv
            x_bwd()
            back[...] = work[:qx]
            y_bwd()
            return out[:, :qy].copy()

        return apply
    full = np.empty((2 * nx, ny + 1))
    full[: nx + 1] = d
    full[nx + 1:] = d[nx - 1:0:-1]
    inv = 1.0 / np.maximum(full, 1e-12 * full.max())
    buf = np.zeros((2 * nx, 2 * ny))

    def apply(v):
        buf[...] = 0.0
        buf[:nx, :ny] = v
        t = scipy.fft.rfft2(buf, workers=workers)
        t *= inv
        return scipy.fft.irfft2(t, s=buf.shape, workers=workers)[:nx, :ny]

    return apply


class _Jacobian:
    """The generalised Jacobian on the cells S = A u E, right-preconditioned on A."""

    def __init__(self, op, contact, edge, slope, precond, damping=0.0, gap_scale=1.0, inner=0):
        self.op = op
        self.inner = int(inner)
        self.c = float(gap_scale)
        self.damping = float(damping)
        self.contact = contact
        self.edge = edge
        self.slope_e = slope[edge]
        self.S = contact | edge
        self.idx = np.nonzero(self.S.ravel())[0]
        self.is_a = contact.ravel()[self.idx]
        self.is_e = ~self.is_a
        self.precond = precond
        self.shape = contact.shape
        self.calls = 0
        self._full = np.zeros(self.shape)

    def scatter(self, x):
        f = self._full
        f[...] = 0.0
        f.ravel()[self.idx] = x
        return f

    def right(self, v):
        """x = P v: the inverse symbol on A, identity on E."""
        out = v.copy()
        if self.is_a.any():
            va = np.where(self.is_a, v, 0.0)
            if self.inner > 0:
                out[self.is_a] = self.inner_solve(v[self.is_a]) / self.c
            else:
                pa = self.precond(self.scatter(va).copy()).ravel()[self.idx]
                out[self.is_a] = pa[self.is_a] / self.c
        return out

    def _on_a(self, f, xa):
        """f restricted to A of the field that is xa on A (zero elsewhere)."""
        v = np.zeros(self.idx.size)
        v[self.is_a] = xa
        return f(self.scatter(v).copy()).ravel()[self.idx][self.is_a]

    def inner_solve(self, ra):
        """``self.inner`` CG iterations on K_AA y = ra from zero, preconditioned by the inverse symbol."""
        return contact_cg(lambda x: self._on_a(self._count_op, x), lambda x: self._on_a(self.precond, x),
                          ra, self.inner)

    def _count_op(self, f):
        self.calls += 1
        return self.op(f)

    def matvec(self, x):
        """J x on S."""
        kx = self.op(self.scatter(x).copy()).ravel()[self.idx]
        self.calls += 1
        out = self.c * kx
        out[self.is_e] = (1.0 + self.damping) * x[self.is_e] - self.slope_e * kx[self.is_e]
        return out


def contact_cg(apply_k, apply_m, b, iterations):
    """A fixed number of preconditioned conjugate-gradient iterations on ``K y = b`` from ``y = 0``.

    Parameters
    ----------
    apply_k : callable
        ``x -> K x`` (symmetric positive definite).
    apply_m : callable
        ``r -> M r``, the preconditioner (symmetric positive definite).
    b : ndarray
        Right-hand side.
    iterations : int
        Iterations (each one ``K`` and one ``M``).

    Returns
    -------
    ndarray
        The iterate ``y``: a nonlinear function of ``b``, so the outer solver must be flexible.
    """
    y = np.zeros_like(b)
    r = b.copy()
    z = apply_m(r)
    d = z.copy()
    rz = float(r @ z)
    for _ in range(int(iterations)):
        if not rz > 0.0:
            break
        kd = apply_k(d)
        a = rz / float(d @ kd)
        y += a * d
        r -= a * kd
        z = apply_m(r)
        rz_new = float(r @ z)
        d = z + (rz_new / rz) * d
        rz = rz_new
    return y


def fgmres(matvec, precond, rhs, rtol, maxiter, restart=200, history=None):
    """Flexible GMRES (Saad 1993): right preconditioning by an operator that may change between iterations.

    Parameters
    ----------
    matvec : callable
        ``x -> A x``.
    precond : callable
        ``v -> M v`` (any function of v; stored per iteration).
    rhs : ndarray
        Right-hand side b; the start is ``x = 0``.
    rtol : float
        Stop when ``||b - A x|| <= rtol ||b||``.
    maxiter : int
        Cap on iterations (over all restarts).
    restart : int, default 200
        Krylov vectors per cycle.
    history : list, optional
        Appended with the relative residual after each iteration (the Arnoldi estimate).

    Returns
    -------
    x : ndarray
        The solution.
    iterations : int
        Iterations done.
    info : int
        0 when converged, else the iterations done.
    """
    n = rhs.size
    beta0 = float(np.linalg.norm(rhs))
    x = np.zeros(n)
    if beta0 == 0.0:
        return x, 0, 0
    its = 0
    r = rhs.copy()
    while True:
        beta = float(np.linalg.norm(r))
        m = min(restart, maxiter - its)
        V = np.empty((m + 1, n))
        Z = np.empty((m, n))
        H = np.zeros((m + 1, m))
        cs, sn = np.zeros(m), np.zeros(m)
        g = np.zeros(m + 1)
        g[0] = beta
        V[0] = r / beta
        k = 0
        done = False
        while k < m:
            Z[k] = precond(V[k])
            w = matvec(Z[k])
            for i in range(k + 1):           # modified Gram-Schmidt
                H[i, k] = float(w @ V[i])
                w -= H[i, k] * V[i]
            H[k + 1, k] = float(np.linalg.norm(w))
            breakdown = not H[k + 1, k] > 0.0
            if not breakdown:
                V[k + 1] = w / H[k + 1, k]
            for i in range(k):                # earlier Givens rotations
                t = cs[i] * H[i, k] + sn[i] * H[i + 1, k]
                H[i + 1, k] = -sn[i] * H[i, k] + cs[i] * H[i + 1, k]
                H[i, k] = t
            d = math.hypot(H[k, k], H[k + 1, k])
            cs[k], sn[k] = (H[k, k] / d, H[k + 1, k] / d) if d > 0.0 else (1.0, 0.0)
            H[k, k] = d
            H[k + 1, k] = 0.0
            g[k + 1] = -sn[k] * g[k]
            g[k] = cs[k] * g[k]
            k += 1
            its += 1
            rel = abs(g[k]) / beta0
            if history is not None:
                history.append(rel)
            if rel <= rtol or breakdown:
                done = True
                break
        yk = np.linalg.solve(np.triu(H[:k, :k]), g[:k]) if k else np.zeros(0)
        x += yk @ Z[:k]
        if done or its >= maxiter:
            return x, its, 0 if done else its
        r = rhs - matvec(x)


def right_preconditioned_gmres(matvec, right, rhs, rtol, maxiter):
    """Solve ``A x = rhs`` by restarted GMRES on ``A P y = rhs``, ``x = P y``.

    Parameters
    ----------
    matvec : callable
        ``v -> A v`` on 1-d arrays.
    right : callable
        ``v -> P v``, the right preconditioner.
    rhs : ndarray
        Right-hand side (1-d).
    rtol : float
        Relative tolerance on ``||A P y - rhs||`` [-].
    maxiter : int
        Cap on the matrix-vector products (restart length ``min(200, maxiter)``).

    Returns
    -------
    x : ndarray
        The solution ``P y``.
    iterations : int
        Matrix-vector products used.
    info : int
        The flag of scipy's ``gmres`` (0: converged).
    """
    n = rhs.size
    count = [0]

    def mv(v):
        count[0] += 1
        return matvec(right(v))

    A = LinearOperator((n, n), matvec=mv, dtype=float)
    restart = min(200, maxiter)
    y, info = gmres(A, rhs, rtol=rtol, atol=0.0, restart=restart, maxiter=max(1, maxiter // restart))
    return right(y), count[0], info


def _gmres(jac, rhs, rtol, maxiter):
    """Solve J x = rhs with right preconditioning; return (x, iterations, info)."""
    if getattr(jac, "inner", 0) > 0:
        return fgmres(jac.matvec, jac.right, rhs, rtol, maxiter)
    return right_preconditioned_gmres(jac.matvec, jac.right, rhs, rtol, maxiter)


def _state(problem, law, delta, q):
    h = problem.z - delta + problem.op(q)
    p = q + law.stress(h)
    return h, p


def _residual(h, p, c):
    return np.minimum(c * h, p)


def _active_sets(law, h, p, c):
    """The Newton step's cell sets of a state: (contact, edge, free, slope).

    Contact ``c h < p``; edge: off the contact, on the law's ramp (``slope = -sigma'(h) > 0``);
    free: the rest (the law's plateau, or zero stress).
    """
    contact = c * h < p
    slope = law.slope(h)
    edge = (~contact) & (slope > 0.0)
    return contact, edge, ~(contact | edge), slope


def _step_rhs(contact, slope, h, p, c, y0):
    """Right-hand side of the Newton rows, ``y0 = K dq`` of the free cells' step already moved."""
    return np.where(contact, -c * (h + y0), -p + slope * y0)


def _approach_column(contact, slope, c):
    """The rows' derivative in the approach (a rigid shift of the gap): ``c`` on the contact, ``-slope`` elsewhere."""
    return np.where(contact, c, -slope)


def solve_state(problem, delta, guess=None, options=SolverOptions(), precond=None, log=None):
    """Solve one adhesive state at the approach ``delta`` (displacement control).

    Parameters
    ----------
    problem : AdhesiveProblem
        Grid, initial gap, law and operator (:class:`dhfield.bem.solver.AdhesiveProblem`).
    delta : float
        Approach of distant points [length].
    guess : ndarray, optional
        Total traction on the working grid to start from [stress]; default zero.
    options : SolverOptions
        Tolerances and caps.
    precond : callable, optional
        :func:`symbol_preconditioner` of the problem (built when omitted).
    log : callable, optional
        Called with one line per Newton iteration.

    Returns
    -------
    NewtonResult
        The state, its residual and the reason it stopped.
    """
    t0 = time.perf_counter()
    law = _Law(problem.law, problem.min_spread)
    op = problem.op
    if precond is None:
        precond = problem_preconditioner(problem, floor=options.symbol_floor)
    sigma0, h0 = law.sigma0, law.h0
    c = sigma0 / h0
    q = np.zeros_like(problem.z) if guess is None else np.array(guess, dtype=float, copy=True)
    h, p = _state(problem, law, delta, q)
    calls = 1
    F = _residual(h, p, c)
    merit = float(np.linalg.norm(F))
    res = float(np.max(np.abs(F))) / sigma0
    history = [merit]
    krylov = 0
    reason = DIVERGED_MAX_IT
    it = 0
    lam = 0.0
    best = (merit, q, h, p, F, res)      # the watchdog's best iterate
    relaxed = 0                          # full steps taken since the best merit last fell
    while True:
        if res <= options.tol:
            reason = CONVERGED
            break
        if it >= options.max_newton:
            break
        if options.stall and len(history) > options.stall and history[-1] > (1.0 - 1e-3) * history[-1 - options.stall]:
            reason = DIVERGED_STALL
            break
        it += 1
        if options.watchdog and relaxed >= options.watchdog:
            # the full steps did not lower the best merit: back to the best iterate, a safeguarded step from it
            merit, q, h, p, F, res = best
            relaxed = -1
            if log is not None:
                log(f"newton {it:3d}: watchdog: back to the best iterate (|F| {merit:.3e})")
        contact, edge, free, slope = _active_sets(law, h, p, c)
        rtol = min(options.forcing, math.sqrt(merit / max(history[0], 1e-300)))
        if not options.watchdog:
            ref = max(history[-options.nonmonotone:])
        elif relaxed < 0:
            ref, lam = merit, max(lam, options.min_damping)
        else:
            ref, lam = math.inf, 0.0
        # Levenberg-Marquardt damping of the edge rows (a trust region on the zone's edge): lam -> inf
        # freezes the edge and leaves the convex contact step, lam = 0 is Newton's step
        alpha = 1.0
        while True:
            # the cells off the law's ramp move to its plateau (damped by the trust region)
            dq = np.zeros_like(q)
            dq[free] = -p[free] / (1.0 + lam)
            y0 = op(dq)
            calls += 1
            rhs_full = _step_rhs(contact, slope, h, p, c, y0)
            jac = _Jacobian(op, contact, edge, slope, precond, damping=lam, gap_scale=c, inner=options.contact_inner)
            x, kit, info = _gmres(jac, rhs_full.ravel()[jac.idx], rtol, options.max_krylov)
            krylov += kit
            calls += jac.calls
            step = dq.copy()
            step.ravel()[jac.idx] = x
            qt = q + step
            ht, pt = _state(problem, law, delta, qt)
            calls += 1
            Ft = _residual(ht, pt, c)
            mt = float(np.linalg.norm(Ft))
            if mt <= (1.0 - 1e-4) * ref and math.isfinite(mt):
                lam = lam / 4.0 if lam > options.min_damping else 0.0
                break
            if lam >= options.max_damping:
                # the trust region cannot shrink further: backtrack along this step
                while mt > (1.0 - 1e-4 * alpha) * ref and alpha > 1e-3:
                    alpha *= 0.5
                    qt = q + alpha * step
                    ht, pt = _state(problem, law, delta, qt)
                    calls += 1
                    Ft = _residual(ht, pt, c)
                    mt = float(np.linalg.norm(Ft))
                break
            if log is not None:
                log(f"newton {it:3d}: step rejected (|F| {mt:.3e} >= {ref:.3e}) with damping {lam:.3g}, gmres {kit}")
            lam = max(4.0 * lam, options.min_damping * 4.0)
        if not mt < ref:
            reason = DIVERGED_LINE_SEARCH
            break
        q, h, p, F, merit = qt, ht, pt, Ft, mt
        res = float(np.max(np.abs(F))) / sigma0
        history.append(merit)
        if options.watchdog:
            if merit <= (1.0 - 1e-4) * best[0]:
                best, relaxed = (merit, q, h, p, F, res), 0
            else:
                relaxed += 1
        if log is not None:
            log(f"newton {it:3d}: residual {res:.3e}  |F| {merit:.3e}  step {alpha:.3g} damping {lam:.3g} gmres {kit:4d} "
                f"(info {info})  contact {int(contact.sum())}  edge {int(edge.sum())}")
    if options.watchdog and reason != CONVERGED and best[0] < merit:
        merit, q, h, p, F, res = best
    load = float(np.sum(q)) * problem.weight
    return NewtonResult(q, h, c * h < p if reason == CONVERGED else p > 0, load, res, reason, it, krylov, calls,
                        history, time.perf_counter() - t0)


#: Largest relative GMRES tolerance of the bordered solve (:func:`solve_state_at_force`): the
#: approach's step is a ratio of sums over the edge cells of both solutions, which an inexact
#: solve perturbs.  Over six branches (sphere mu = 0.3, 1, 3; beta0 = 0.5 at mu = 1, 2; beta0 = 0.3
#: at mu = 1; ``python -m verification.bench_bordered_forcing``) 0.1 left 7 states unconverged on
#: two of them, and 1e-2, 1e-3 and 1e-4 converged every state; 1e-3 keeps a factor 10 inside that
#: range for about 7 % more GMRES iterations than 1e-2.
BORDERED_FORCING = 1e-3


def solve_state_at_force(problem, force, delta, guess, options=SolverOptions(), precond=None, log=None):
    """Solve one adhesive state at a prescribed adhesive force, the approach an unknown.

    The state equations of :func:`solve_state` bordered by the adhesive force
    ``F_a = sum sigma(h) dA = force``, with the approach ``delta`` as the extra unknown.  Each
    Newton step solves the generalised Jacobian twice (for the residual and for the approach's
    column, whose rows are ``-c`` on the contact and ``sigma'`` on the law's ramp: a rigid
    shift of the gap), to a relative tolerance of at most :data:`BORDERED_FORCING`, and the
    approach's step follows from the linearised force.  A step is
    accepted when it lowers the merit ``||F||^2 + G^2`` below the largest of the last
    ``options.nonmonotone`` merits (G the force's residual in the units of F), else halved.

    Parameters
    ----------
    problem : AdhesiveProblem
        Grid, initial gap, law and operator.
    force : float
        Adhesive force F_a > 0 [force].
    delta : float
        First guess of the approach [length].
    guess : ndarray
        Total traction on the working grid to start from (a state of the same branch) [stress].
    options : SolverOptions
        Tolerances and caps (``tol`` also bounds ``|F_a - force| / force``).
    precond : callable, optional
        :func:`symbol_preconditioner` of the problem (built when omitted).
    log : callable, optional
        One line per Newton iteration.

    Returns
    -------
    (NewtonResult, float)
        The state and its approach.
    """
    t0 = time.perf_counter()
    law = _Law(problem.law, problem.min_spread)
    op = problem.op
    if precond is None:
        precond = problem_preconditioner(problem, floor=options.symbol_floor)
    sigma0, h0 = law.sigma0, law.h0
    c = sigma0 / h0
    target = float(force)
    w = problem.weight
    g_scale = 1.0 / (w * math.sqrt(problem.z.size))        # G in the units of ||F|| (stress x sqrt(cells))
    q = np.array(guess, dtype=float, copy=True)
    delta = float(delta)

    def evaluate(q, d):
        h, p = _state(problem, law, d, q)
        F = _residual(h, p, c)
        fa = float(np.sum(law.stress(h))) * w
        return h, p, F, fa, math.hypot(float(np.linalg.norm(F)), (fa - target) * g_scale)

    h, p, F, fa, merit = evaluate(q, delta)
    history = [merit]
    krylov = calls = it = 0
    reason = DIVERGED_MAX_IT
    while True:
        res = max(float(np.max(np.abs(F))) / sigma0, abs(fa - target) / target)
        if res <= options.tol:
            reason = CONVERGED
            break
        if it >= options.max_newton:
            break
        it += 1
        contact, edge, free, slope = _active_sets(law, h, p, c)
        rtol = min(options.forcing, BORDERED_FORCING, math.sqrt(merit / max(history[0], 1e-300)))
        dq0 = np.zeros_like(q)
        dq0[free] = -p[free]
        y0 = op(dq0)
        rhs0 = _step_rhs(contact, slope, h, p, c, y0)
        r1 = _approach_column(contact, slope, c)
        jac = _Jacobian(op, contact, edge, slope, precond, gap_scale=c, inner=options.contact_inner)
        x0, k0, _ = _gmres(jac, rhs0.ravel()[jac.idx], rtol, options.max_krylov)
        x1, k1, _ = _gmres(jac, r1.ravel()[jac.idx], rtol, options.max_krylov)
        krylov += k0 + k1
        kx0 = op(jac.scatter(x0).copy())
        kx1 = op(jac.scatter(x1).copy())
        calls += jac.calls + 3
        # linearised force: fa + w sum_E (-slope) (-d_delta + y0 + K x0 + d_delta K x1) = target
        num = fa - target - w * float(np.sum(slope * (y0 + kx0)))
        den = w * float(np.sum(slope * (1.0 - kx1)))
        if not (den != 0.0 and math.isfinite(num / den)):
            reason = DIVERGED_LINEAR_SOLVE
            break
        dd = -num / den
        step = dq0.copy()
        step.ravel()[jac.idx] = x0 + dd * x1
        ref = max(history[-options.nonmonotone:])
        alpha = 1.0
        while True:
            qt, dt = q + alpha * step, delta + alpha * dd
            ht, pt, Ft, fat, mt = evaluate(qt, dt)
            calls += 1
            if mt < (1.0 - 1e-4 * alpha) * ref or alpha <= 1e-3:
                break
            alpha *= 0.5
        if not mt < ref:
            reason = DIVERGED_LINE_SEARCH
            break
        q, delta, h, p, F, fa, merit = qt, dt, ht, pt, Ft, fat, mt
        history.append(merit)
        if log is not None:
            log(f"newton {it:3d}: residual {res:.3e} merit {merit:.3e} step {alpha:.3g} approach {delta:.8f} "
                f"gmres {k0}+{k1}")
    load = float(np.sum(q)) * problem.weight
    state = NewtonResult(q, h, c * h < p if reason == CONVERGED else p > 0, load, res, reason, it, krylov, calls,
                         history, time.perf_counter() - t0)
    return state, delta


def _modulus(problem):
    """E* of the problem's operator [stress]."""
    return problem.op.reduced_modulus


def load_slope(problem, state, precond=None, options=SolverOptions(), rtol=1e-10):
    """Compute dW/d delta of a converged state: one linear solve with the state's Jacobian.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem.
    state : NewtonResult
        A converged state of it.
    precond : callable, optional
        :func:`symbol_preconditioner` of the problem.
    options : SolverOptions
        Caps.
    rtol : float, default 1e-10
        Relative tolerance of the linear solve (a predictor needs far less than the slope) [-].

    Returns
    -------
    slope : float
        The load's slope dW/d delta [force/length].
    dq : ndarray
        The traction's slope dq/d delta on the working grid [stress/length] (a tangent predictor).
    """
    law = _Law(problem.law, problem.min_spread)
    if precond is None:
        precond = problem_preconditioner(problem, floor=options.symbol_floor)
    h = state.gap
    p = state.traction + law.stress(h)
    c = law.sigma0 / law.h0
    contact, edge, _, slope = _active_sets(law, h, p, c)
    jac = _Jacobian(problem.op, contact, edge, slope, precond, gap_scale=c, inner=options.contact_inner)
    # d/d delta of the rows: A: h' = -1 + K dq = 0; E: dq - |s'| (K dq - 1) = 0; others: dq = 0
    rhs_full = _approach_column(contact, slope, c)
    rhs = rhs_full.ravel()[jac.idx]
    x, kit, info = _gmres(jac, rhs, rtol, options.max_krylov)
    dq = np.zeros_like(state.traction)
    dq.ravel()[jac.idx] = x
    return float(np.sum(dq)) * problem.weight, dq


@dataclass
class LoadMinimum:
    """The load-control pull-off: the minimum of the load along the displacement-controlled branch.

    Parameters
    ----------
    approach : float
        Approach at the fitted minimum [length].
    load : float
        The minimum load (the pull-off force, negative when tensile) [force].
    load_error : float
        Standard error of the fitted minimum (lattice noise of the samples) [force].
    state : NewtonResult
        The solved state nearest the minimum.
    approaches, loads : ndarray
        Every state solved (approach [length], load [force]).
    newton_iterations, krylov_iterations : int
        Work over all states.
    converged : bool
        Every state converged and the minimum lies inside the sampled window.
    reason : str
        Why the search stopped.
    elapsed : float
        Wall time [s].
    """

    approach: float
    load: float
    load_error: float
    state: "NewtonResult"
    approaches: np.ndarray
    loads: np.ndarray
    newton_iterations: int
    krylov_iterations: int
    converged: bool
    reason: str
    elapsed: float

    @property
    def states(self) -> int:
        """States solved."""
        return int(self.loads.size)


def _quadratic_vertex(x, y):
    """(vertex x, vertex y, standard error of vertex y, curvature) of a least-squares parabola."""
    x0 = float(np.mean(x))
    scale = float(np.ptp(x)) or 1.0
    t = (np.asarray(x) - x0) / scale
    A = np.vander(t, 3)
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    a, b, c0 = coef
    if not a > 0:
        return float("nan"), float("nan"), float("inf"), float(a)
    tv = -b / (2 * a)
    yv = c0 - b * b / (4 * a)
    dof = max(len(t) - 3, 1)
    resid = y - A @ coef
    s2 = float(resid @ resid) / dof
    cov = s2 * np.linalg.pinv(A.T @ A)
    # gradient of the vertex value c - b^2/(4a) w.r.t. (a, b, c)
    g = np.array([b * b / (4 * a * a), -b / (2 * a), 1.0])
    err = math.sqrt(max(float(g @ cov @ g), 0.0))
    return x0 + tv * scale, float(yv), err, float(a) / scale ** 2


def load_minimum(problem, approach, guess=None, half_window=None, samples=7, options=SolverOptions(),
                 max_rounds=6, log=None, method="plain"):
    """Locate the load-control pull-off: the minimum of the load W(delta) along the displacement-controlled branch.

    States are solved by :func:`solve_state` at ``samples`` approaches spread over
    ``approach +- half_window``, each warm-started from its solved neighbours (linear
    extrapolation in delta); a least-squares parabola through the loads gives the minimum.
    The window moves to the fitted vertex until the vertex lies in its middle third.  The
    standard error of the fitted minimum measures the loads' lattice noise (the edge moving
    through whole cells).

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem.
    approach : float
        First approach (an analytic prediction of the pull-off) [length].
    guess : ndarray, optional
        Traction to start the first state from (e.g. :func:`cold_start`).
    half_window : float, optional
        Half-width of the sampled window [length]; default 2 % of |approach|.
    samples : int
        States per window (odd, >= 3).
    options : SolverOptions
        Per-state options.
    max_rounds : int
        Cap on window moves.
    log : callable, optional
        One line per state.
    method : {"plain", "smoothed"}
        The state solve: :func:`solve_state` or :func:`solve_state_smoothed`.

    Returns
    -------
    LoadMinimum
        The minimum and its work.
    """
    t0 = time.perf_counter()
    precond = problem_preconditioner(problem, floor=options.symbol_floor)
    hw = 0.02 * abs(approach) if half_window is None else float(half_window)
    solved = {}
    work = [0, 0]

    def nearest(d):
        keys = sorted(solved, key=lambda k: abs(k - d))
        return keys[:2]

    def solve_at(d):
        if d in solved:
            return solved[d]
        near = nearest(d)
        if not near:
            q0 = guess
        elif len(near) == 1:
            q0 = solved[near[0]].traction
        else:
            a, b = near
            qa, qb = solved[a].traction, solved[b].traction
            q0 = qa + (d - a) / (b - a) * (qb - qa)
        solve = solve_state if method == "plain" else solve_state_smoothed
        st = solve(problem, d, q0, options, precond)
        work[0] += st.newton_iterations
        work[1] += st.krylov_iterations
        solved[d] = st
        if log is not None:
            log(f"state {len(solved):2d}: approach {d:.8f} load {st.load:.8f} newton {st.newton_iterations} "
                f"gmres {st.krylov_iterations} {st.reason} ({st.elapsed:.1f} s)")
        return st

    def result(d, load, err, ok, reason):
        ds = np.array(sorted(solved))
        best = solved[min(solved, key=lambda k: abs(k - d))] if np.isfinite(d) else solved[ds[0]]
        return LoadMinimum(float(d), float(load), float(err), best, ds, np.array([solved[k].load for k in ds]),
                           work[0], work[1], ok, reason, time.perf_counter() - t0)

    center = float(approach)
    st = solve_at(center)
    if not st.converged:
        return result(center, st.load, float("inf"), False, st.reason)
    for _ in range(max_rounds):
        ds = center + np.linspace(-hw, hw, samples)
        # solve outward from the centre, so every warm start has a near neighbour
        for d in sorted(ds, key=lambda v: abs(v - center)):
            st = solve_at(float(d))
            if not st.converged:
                return result(d, st.load, float("inf"), False, st.reason)
        window = [k for k in solved if abs(k - center) <= hw * (1 + 1e-9)]
        xv, yv, err, curv = _quadratic_vertex(np.array(window), np.array([solved[k].load for k in window]))
        if not np.isfinite(xv):
            center -= hw                 # no minimum in the window: the load still falls towards lower delta
            continue
        if abs(xv - center) <= hw / 3.0:
            return result(xv, yv, err, True, CONVERGED)
        center = float(np.clip(xv, center - 2 * hw, center + 2 * hw))
    return result(center, float("nan"), float("inf"), False, "diverged_window")


def ramp_stress(problem, gap):
    """The adhesive stress of the grid's law (its Dugdale edge a ramp of width ``min_spread``) at ``gap``.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem (law and edge width).
    gap : ndarray
        Gap on the working grid [length].

    Returns
    -------
    ndarray
        The stress sigma(h) per cell [stress].
    """
    return _Law(problem.law, problem.min_spread).stress(gap)


def cold_start_on(problem, delta, zone, tol=1e-3, max_iter=5000):
    """An analytic start: sigma0 on the full-grid cells ``zone``, and the contact pressure it implies.

    As :func:`cold_start`, with the zone given as a mask instead of an ellipse.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem.
    delta : float
        Approach [length].
    zone : ndarray of bool, shape (nx, ny)
        Cells of the start's adhesive zone (full grid).
    tol : float
        Tolerance of the contact solve (relative to the law's range) [-].
    max_iter : int
        Cap on its CG iterations.

    Returns
    -------
    ndarray
        The traction q on the working grid [stress].
    """
    from .solver import solve_contact_pressure

    s = problem.to_work(problem.law.max_stress * np.asarray(zone, dtype=float))
    sol = solve_contact_pressure(problem.op, problem.z - delta, np.zeros_like(s), problem.law.range, tol, max_iter,
                                 problem.k0, stress=s)
    return sol.pressure - s


def cold_start(problem, delta, zone_semi_axes, tol=1e-3, max_iter=5000):
    """An analytic start: sigma0 on a predicted cohesive ellipse, and the contact pressure it implies.

    The adhesive stress s = sigma0 on the ellipse with semi-axes (c, d) is held fixed and the
    (convex) non-adhesive contact problem with the gap ``z - delta - K s`` is solved for the
    repulsive pressure p by the Polonsky-Keer CG
    (:func:`dhfield.bem.solver.solve_contact_pressure`); the start is ``q = p - s``.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem.
    delta : float
        Approach [length].
    zone_semi_axes : (float, float)
        Semi-axes (c, d) of the predicted cohesive zone [length].
    tol : float
        Tolerance of the contact solve (relative to the law's range) [-].
    max_iter : int
        Cap on its CG iterations.

    Returns
    -------
    ndarray
        The traction q on the working grid [stress].
    """
    c, d = zone_semi_axes
    x, y = problem.grid.mesh()
    return cold_start_on(problem, delta, (x / c) ** 2 + (y / d) ** 2 < 1.0, tol, max_iter)


# ---------------------------------------------------------------------------------------------
# Smoothing Newton: both kinks (the complementarity min, the law's ramp ends) smoothed by one
# parameter s that is driven to zero with the residual (Chen-Harker-Kanzow-Smale smoothing).

def _softclip(x, s):
    """A smooth clip(x, 0, 1): softplus(x) - softplus(x - 1) with softness s (exact as s -> 0)."""
    if s <= 0.0:
        return np.clip(x, 0.0, 1.0), ((x > 0.0) & (x < 1.0)).astype(float)
    a = np.logaddexp(0.0, x / s) * s
    b = np.logaddexp(0.0, (x - 1.0) / s) * s
    da = 0.5 * (1.0 + np.tanh(0.5 * x / s))
    db = 0.5 * (1.0 + np.tanh(0.5 * (x - 1.0) / s))
    return a - b, da - db


class _SmoothLaw(_Law):
    def stress_and_slope(self, h, s):
        """(sigma, |d sigma/dh|) of the ramped law with its ends smoothed by s (ramp fractions)."""
        if not self.dugdale:
            return self.stress(h), self.slope(h)
        w = self.width
        x = (self.h0 + 0.5 * w - h) / w
        f, df = _softclip(x, s)
        return self.sigma0 * f, self.sigma0 * df / w


def _chks(a, b, eps):
    """Smoothed min(a, b) and its partial derivatives (CHKS): (a + b - sqrt((a - b)^2 + 4 eps^2))/2."""
    d = a - b
    r = np.sqrt(d * d + 4.0 * eps * eps)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(r > 0, d / np.where(r > 0, r, 1.0), 0.0)
    return 0.5 * (a + b - r), 0.5 * (1.0 - t), 0.5 * (1.0 + t)


class _SmoothJacobian:
    """Rows (fa c - fb |sigma'|) (K x)_i + fb x_i on the whole working grid, right-preconditioned."""

    def __init__(self, op, fa, fb, slope, c, precond):
        self.op = op
        self.kcoef = fa * c - fb * slope
        self.diag = fb
        self.mask = fa > fb                      # contact-like rows: the inverse symbol
        self.c = c
        self.precond = precond
        self.shape = fa.shape
        self.calls = 0

    def right(self, v):
        v = v.reshape(self.shape)
        out = np.where(self.mask, 0.0, v)
        if self.mask.any():
            out = out + np.where(self.mask, self.precond(np.where(self.mask, v, 0.0)) / self.c, 0.0)
        return out.ravel()

    def matvec(self, x):
        x = x.reshape(self.shape)
        self.calls += 1
        return (self.kcoef * self.op(np.ascontiguousarray(x)) + self.diag * x).ravel()


def solve_state_smoothed(problem, delta, guess=None, options=SolverOptions(), precond=None, log=None,
                         smoothing=0.1):
    """One adhesive state by a smoothing Newton method (see :func:`solve_state` for the system).

    ``min(c h, p)`` and the ramp's ends are smoothed by one parameter s (``eps = s sigma0`` for
    the min, softness s of the ramp in ramp fractions), which falls with the residual
    (``s <- min(s, res/2)``) so that the iterates follow the smoothed systems to the exact one.
    Every step is Newton's on the current smoothed system, with a backtracking line search on
    its merit.

    Parameters
    ----------
    problem : AdhesiveProblem
        Grid, initial gap, law and operator.
    delta : float
        Approach of distant points [length].
    guess : ndarray, optional
        Total traction on the working grid to start from [stress]; default zero.
    options : SolverOptions
        Tolerances and caps.
    precond : callable, optional
        :func:`symbol_preconditioner` of the problem (built when omitted).
    log : callable, optional
        Called with one line per Newton iteration.
    smoothing : float, default 0.1
        Largest smoothing s [-]; the start's own residual caps it further (``s <= res/2``).

    Returns
    -------
    NewtonResult
        The state, its (unsmoothed) residual and the reason it stopped.
    """
    t0 = time.perf_counter()
    law = _SmoothLaw(problem.law, problem.min_spread)
    op = problem.op
    if precond is None:
        precond = problem_preconditioner(problem, floor=options.symbol_floor)
    sigma0, h0 = law.sigma0, law.h0
    c = sigma0 / h0
    s = float(smoothing)
    q = np.zeros_like(problem.z) if guess is None else np.array(guess, dtype=float, copy=True)
    calls = 0

    def evaluate(q, s):
        nonlocal calls
        h = problem.z - delta + op(q)
        calls += 1
        sig, sl = law.stress_and_slope(h, s)
        p = q + sig
        F, fa, fb = _chks(c * h, p, s * sigma0)
        return h, p, sl, F, fa, fb

    def true_res(h, q):
        p = q + law.stress(h)
        return float(np.max(np.abs(np.minimum(c * h, p)))) / sigma0

    h, p, sl, F, fa, fb = evaluate(q, s)
    res = true_res(h, q)
    if 0.5 * res < s:                            # a warm start: smooth no more than its residual asks
        s = 0.5 * res
        h, p, sl, F, fa, fb = evaluate(q, s)
    merit = float(np.linalg.norm(F))
    history = [merit]
    krylov = 0
    it = 0
    reason = DIVERGED_MAX_IT
    while True:
        if res <= options.tol:
            reason = CONVERGED
            break
        if it >= options.max_newton:
            break
        it += 1
        jac = _SmoothJacobian(op, fa, fb, sl, c, precond)
        rtol = min(options.forcing, math.sqrt(merit / max(history[0], 1e-300)))
        x, kit, info = _gmres(jac, -F.ravel(), rtol, options.max_krylov)
        krylov += kit
        calls += jac.calls
        step = x.reshape(q.shape)
        alpha = 1.0
        while True:
            qt = q + alpha * step
            ht, pt, slt, Ft, fat, fbt = evaluate(qt, s)
            mt = float(np.linalg.norm(Ft))
            if mt <= (1.0 - 1e-4 * alpha) * merit or alpha < 1e-4:
                break
            alpha *= 0.5
        if not mt < merit:
            reason = DIVERGED_LINE_SEARCH
            break
        q, h = qt, ht
        res = true_res(h, q)
        s_new = min(s, 0.5 * res)
        if s_new < s:
            s = s_new
            h, p, sl, F, fa, fb = evaluate(q, s)
            merit = float(np.linalg.norm(F))
        else:
            p, sl, F, fa, fb, merit = pt, slt, Ft, fat, fbt, mt
        history.append(merit)
        if log is not None:
            log(f"newton {it:3d}: residual {res:.3e}  smoothing {s:.2e}  |F_s| {merit:.3e}  step {alpha:.3g}  "
                f"gmres {kit:4d} (info {info})")
    p = q + law.stress(h)
    load = float(np.sum(q)) * problem.weight
    return NewtonResult(q, h, c * h < p, load, res, reason, it, krylov, calls, history, time.perf_counter() - t0)


# ---------------------------------------------------------------------------------------------
# Nested iteration (grid sequencing): a state solved on grids 2x, 4x, ... coarser over the same
# domain, each level's state prolonged to start the next.

def _prolong_axis(a, axis):
    """Cell-centred linear interpolation onto twice the cells along ``axis`` (weights 3/4, 1/4).

    The neighbour beyond either end is the end cell itself: the even mirror at the symmetry
    plane of a quadrant, and a constant extension at the domain's outer edge.
    """
    a = np.moveaxis(np.asarray(a, dtype=float), axis, 0)
    pad = np.concatenate([a[:1], a, a[-1:]], axis=0)
    out = np.empty((2 * a.shape[0],) + a.shape[1:])
    out[0::2] = 0.75 * pad[1:-1] + 0.25 * pad[:-2]
    out[1::2] = 0.75 * pad[1:-1] + 0.25 * pad[2:]
    return np.moveaxis(out, 0, axis)


def prolong(field):
    """Bilinear prolongation of a working-grid field onto the grid with twice the cells per axis.

    Parameters
    ----------
    field : ndarray, shape (mx, my)
        Cell-centred field on a working grid (full grid, or its even-even quadrant, whose
        first row and column border the symmetry planes).

    Returns
    -------
    ndarray, shape (2 mx, 2 my)
        The field on the working grid of the same domain with half the cell size.
    """
    return _prolong_axis(_prolong_axis(field, 0), 1)


def prolong_state(state, coarse, fine, mode="gap"):
    """A converged state of ``coarse`` carried onto ``fine`` (same domain, twice the cells per axis) as a start.

    Parameters
    ----------
    state : NewtonResult
        A state of ``coarse``.
    coarse, fine : AdhesiveProblem
        The two problems (the fine grid's cells are the coarse cells halved per axis).
    mode : {"gap", "traction"}, default "gap"
        ``"gap"``: the repulsive pressure ``p = q + sigma(h)`` and the gap ``h`` are
        prolonged (each clipped at zero), and the traction is ``p - sigma_f(h)`` with the
        fine grid's own law (its narrower ramp), so the cohesive zone ends where the
        prolonged gap reaches h0.  ``"traction"``: the traction q itself is prolonged.

    Returns
    -------
    ndarray
        The traction on the fine working grid [stress].

    Raises
    ------
    ValueError
        If the fine working grid is not twice the coarse one per axis.
    """
    shape = tuple(2 * s for s in coarse.z.shape)
    if tuple(fine.z.shape) != shape:
        raise ValueError(f"the fine working grid must be {shape} (twice the coarse per axis); got {fine.z.shape}")
    if mode == "traction":
        return prolong(state.traction)
    if mode != "gap":
        raise ValueError(f"mode must be 'gap' or 'traction'; got {mode!r}")
    lc = _Law(coarse.law, coarse.min_spread)
    lf = _Law(fine.law, fine.min_spread)
    p = np.maximum(state.traction + lc.stress(state.gap), 0.0)
    h = np.maximum(prolong(state.gap), 0.0)
    return np.maximum(prolong(p), 0.0) - lf.stress(h)


def grid_ladder(problem, levels, threads=1):
    """The problems of a nested solve: ``problem`` on its grid and on grids 2, 4, ... times coarser.

    Parameters
    ----------
    problem : NondimensionalProblem
        The target (finest) problem (:func:`dhfield.bem.pull_off.paper_problem`).
    levels : int
        Grids in the ladder (1: the target only); every coarser grid halves both cell counts.
    threads : int
        FFTW threads of the operators.

    Returns
    -------
    list of AdhesiveProblem
        Coarsest first; the last is ``problem.adhesive_problem(threads)``.

    Raises
    ------
    ValueError
        If a coarser grid's cell counts are not even integers.
    """
    from .solver import AdhesiveProblem

    levels = int(levels)
    nx, ny = problem.grid.nx, problem.grid.ny
    k = 2 ** (levels - 1)
    if levels < 1 or nx % (2 * k) or ny % (2 * k):
        raise ValueError(f"{levels} levels need nx, ny divisible by {2 * k}; got {nx} x {ny}")
    out = []
    for j in range(levels - 1, 0, -1):
        nd = problem.coarser(nx // 2 ** j)
        out.append(AdhesiveProblem(nd.initial_gap, nd.grid, nd.law, None, threads, 1.0))
    out.append(problem.adhesive_problem(threads))
    return out


@dataclass
class LevelReport:
    """The work and outcome of one level of a nested solve.

    Parameters
    ----------
    shape : tuple of int
        Cells of the full grid (nx, ny).
    newton_iterations, krylov_iterations : int
        Work on this level.
    elapsed : float
        Wall time of this level, its prolongation included [s].
    residual : float
        Final ``max |min(h/h0, p/sigma0)|`` [-].
    contact_cells : int
        Contact cells of the final state (working grid).
    reason : str
        Why this level's solve stopped.
    """

    shape: tuple
    newton_iterations: int
    krylov_iterations: int
    elapsed: float
    residual: float
    contact_cells: int
    reason: str


@dataclass
class NestedResult:
    """A state solved by nested iteration: the finest level's state and every level's report.

    Parameters
    ----------
    state : NewtonResult
        The state on the finest grid (its work counts the finest level only).
    levels : list of LevelReport
        Coarsest first.
    elapsed : float
        Wall time over all levels [s].
    """

    state: NewtonResult
    levels: list
    elapsed: float

    @property
    def converged(self) -> bool:
        """True when the finest level converged."""
        return self.state.converged

    @property
    def newton_iterations(self) -> int:
        """Newton iterations over all levels."""
        return sum(r.newton_iterations for r in self.levels)

    @property
    def krylov_iterations(self) -> int:
        """GMRES iterations over all levels."""
        return sum(r.krylov_iterations for r in self.levels)


#: Options of :func:`solve_state_nested`, :func:`dhfield.bem.energy.pull_off_nested` and
#: :mod:`dhfield.bem.ladder`: the merit may rise over up to 4 steps (a prolonged start sits near the
#: state, where full semismooth steps that cross the ramp's kinks raise ``||F||`` before it falls), and
#: up to 8 full steps are taken whatever their merit (the watchdog: at Tabor parameters ~10 the
#: contact's rim moves by thousands of cells in a few full steps, by a fraction of a ring per
#: merit-decreasing step; 4 full steps were too few on the sphere at mu = 10, 1976^2, 8 converge).
NESTED_OPTIONS = SolverOptions(nonmonotone=4, watchdog=8)


def solve_state_nested(problems, delta, guess=None, options=NESTED_OPTIONS, coarse_tol=1e-6, mode="traction",
                       log=None, solve=None, coarsest_solve=None, coarse_stall=3, coarse_max_newton=10, require_coarse=False):
    """Solve one adhesive state by nested iteration: coarsest grid first, each state prolonged to start the next.

    Parameters
    ----------
    problems : list of AdhesiveProblem
        The ladder, coarsest first, on one domain, each grid twice the previous per axis
        (:func:`grid_ladder`).
    delta : float
        Approach [length].
    guess : ndarray, optional
        Traction on the coarsest working grid to start from (e.g. :func:`cold_start`).
    options : SolverOptions, default NESTED_OPTIONS
        Options of the finest level.
    coarse_tol : float, default 1e-6
        Tolerance of the coarser levels (their states are starts) [-].
    mode : {"traction", "gap"}
        Prolongation (:func:`prolong_state`).
    log : callable, optional
        One line per Newton iteration and per level.
    solve : callable, optional
        The state solve of the finer levels, ``solve(problem, delta, guess, options, precond, log)``;
        default :func:`solve_state`.
    coarsest_solve : callable, optional
        The state solve of the coarsest level (the global phase, from ``guess``); default ``solve``.
    coarse_stall : int, default 3
        ``SolverOptions.stall`` of the coarser levels whose grid does not resolve the edge
        (``resolved`` False): such a level stops once its merit stalls.  A coarser level that
        resolves it is solved to convergence, the coarsest with ``options.max_newton``: at
        Tabor parameters 0.1-0.3 a coarsest level stopped after 3 stalled iterations left the
        finest level 60 iterations short of convergence, where solved in full it converged in
        20-50 cheap iterations and each finer level in 5-8.
    coarse_max_newton : int, default 10
        Cap on Newton iterations of each coarser level but the coarsest (whose solve is the
        global phase): a prolonged start has its contact set in place after a few steps.
    require_coarse : bool, default False
        End the ladder at a coarser level that did not converge.  Otherwise its last iterate is
        prolonged all the same: a grid too coarse for its edge (``edge_width_ratio > 1``) has no
        stable discrete edge, and its Newton iteration stalls on the edge cells once the contact
        set is placed, which is what the finer level needs.

    Returns
    -------
    NestedResult
        The finest state (flagged by its reason when it did not converge).
    """
    t0 = time.perf_counter()
    solve = solve or solve_state
    reports = []
    q = guess
    st = None
    for j, prob in enumerate(problems):
        t1 = time.perf_counter()
        if j > 0:
            q = prolong_state(st, problems[j - 1], prob, mode)
        last = j == len(problems) - 1
        # a coarser grid that resolves its edge is solved to convergence (its state is the start the
        # finer Newton iteration converges from); one that does not has no stable discrete edge and
        # stops once its merit stalls
        stall = 0 if getattr(prob, "resolved", False) else coarse_stall
        opts = options if last else replace(options, tol=max(coarse_tol, options.tol), stall=stall,
                                            max_newton=options.max_newton if j == 0 else coarse_max_newton)
        st = ((coarsest_solve or solve) if j == 0 else solve)(prob, delta, q, opts, None, log)
        nx, ny = prob.grid.shape
        reports.append(LevelReport((nx, ny), st.newton_iterations, st.krylov_iterations, time.perf_counter() - t1,
                                   st.residual, int(np.count_nonzero(st.contact)), st.reason))
        if log is not None:
            log(f"level {nx}x{ny}: {st.reason} newton {st.newton_iterations} gmres {st.krylov_iterations} "
                f"residual {st.residual:.2e} contact {reports[-1].contact_cells} ({reports[-1].elapsed:.1f} s)")
        if not st.converged and (last or require_coarse):
            break
    return NestedResult(st, reports, time.perf_counter() - t0)
