"""One adhesive state as a local minimum of the potential energy, and the load-control pull-off from it.

Problem
-------
At a fixed approach ``delta`` (displacement control) the state of the DC-FFT half-space
minimises the potential energy in the total traction ``q`` per working cell (positive in
compression), with the surface displacement ``u = K q`` and the gap ``h = z - delta + u``:

.. math::

    \\Pi(q) = \\tfrac12\\, q^T K q + \\sum_i \\phi(h_i), \\qquad
    \\phi(h) = -\\int_h^\\infty \\sigma_w, \\quad h \\ge 0,

with ``sigma_w`` the Dugdale law with its edge as a ramp of width ``w`` centred on h0
(:class:`dhfield.bem.newton` explains the width).  Pi is bounded below, and its gradient is
``K p`` with ``p = q + sigma_w(h)`` the repulsive pressure, so a stationary point is an
equilibrium with ``p = 0`` off contact.  The contact constraint ``h >= 0`` is a linear
constraint on q through the dense K; it is imposed by a quadratic penalty ``k h^2/2`` for
``h < 0``, with the stiffness ``k`` so large that the penetration ``p/k`` lies a factor
``penalty`` below the complementarity tolerance (``k = c/(tol penalty)``, ``c = sigma0/h0``).
The penalised Pi is C^1 and piecewise quadratic in q.

The load-control pull-off is the minimum over delta of the load ``W(delta)`` along the
displacement-stable branch, whose states are local minima of Pi: the load-control pull-off
(the fold of ``delta(W)``) is reached before the displacement-control jump.

Algorithm
---------
Newton's method on the gradient (semismooth: its Jacobian is piecewise constant), globalised
by the energy.  The Newton rows are those of :func:`dhfield.bem.newton.solve_state` with the
penalty in the contact rows; written on the cells S = A u E (contact, ramp) they form the
symmetric matrix

.. math:: M = K_{SS} + \\mathrm{diag}(1/k \\text{ on } A,\\; -(1+\\lambda)/|\\sigma'| \\text{ on } E),

solved by right-preconditioned restarted GMRES (MINRES, the short recurrence M's symmetry
allows, needs a stopping test on the true residual: scipy's measures against ``||M|| ||x||``)
with the block-diagonal SPD preconditioner (the inverse of the operator's own symbol on A,
``|sigma'|/(1+lambda)`` on E).  ``lambda >= 0`` damps the ramp rows (a trust region on the
non-convex part).  A step is taken only along a descent direction of Pi, with an Armijo
line search on Pi itself; Pi is piecewise quadratic along the step, so the line search needs
no operator product beyond ``K dq``.  When the damped Newton step is not a descent direction
the natural gradient ``-p`` is (``(K p)^T (-p) < 0``), so every iteration decreases Pi: the
iteration cannot cycle between active sets, and it converges to a stationary point.

References
----------
.. [1] M. Hintermueller, K. Ito, K. Kunisch (2002) The primal-dual active set strategy as
   a semismooth Newton method. SIAM J. Optim. 13:865-888. doi:10.1137/S1052623401383558
.. [2] C. C. Paige, M. A. Saunders (1975) Solution of sparse indefinite systems of linear
   equations. SIAM J. Numer. Anal. 12:617-629. doi:10.1137/0712047 (MINRES)
.. [3] J. Nocedal, S. J. Wright (2006) Numerical Optimization, 2nd ed., Springer, ch. 3.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from .laws import DugdaleLaw
from .newton import (CONVERGED, DIVERGED_LINE_SEARCH, DIVERGED_MAX_IT, NewtonResult, SolverOptions,
                     problem_preconditioner, right_preconditioned_gmres)

__all__ = ["RampPotential", "solve_state_energy", "energy", "PullOff", "pull_off_search", "NestedPullOff",
           "pull_off_nested"]


class RampPotential:
    """The ramped Dugdale law as a potential, with the contact penalty.

    Parameters
    ----------
    law : DugdaleLaw
        The Dugdale law: sigma0 (``max_stress``) and h0 (``range``).
    width : float
        Width w of the ramp, ``0 < w <= 2 h0`` [length].
    penalty_stiffness : float
        The stiffness k of the contact penalty ``k h^2/2`` for ``h < 0`` [stress/length].
    """

    def __init__(self, law, width, penalty_stiffness):
        if not isinstance(law, DugdaleLaw):
            raise TypeError("the energy solve takes the Dugdale law")
        self.sigma0 = law.max_stress
        self.h0 = law.range
        self.width = float(width)
        if not 0.0 < self.width <= 2.0 * self.h0 * (1 + 1e-12):
            raise ValueError("the ramp width must lie in (0, 2 h0]")
        self.lo = max(self.h0 - 0.5 * self.width, 0.0)
        self.hi = self.h0 + 0.5 * self.width
        self.k = float(penalty_stiffness)

    def stress(self, h):
        """Return the ramped Dugdale stress sigma_w(h), continued as sigma_w(0) below h = 0.

        Parameters
        ----------
        h : ndarray
            Gap [length].

        Returns
        -------
        ndarray
            The stress sigma_w(h) >= 0, tensile [stress].
        """
        return self.sigma0 * np.clip((self.hi - h) / self.width, 0.0, 1.0)

    def slope(self, h):
        """Return |d sigma_w/dh|: sigma0/w on the ramp, zero elsewhere.

        Parameters
        ----------
        h : ndarray
            Gap [length].

        Returns
        -------
        ndarray
            The slope's magnitude [stress/length].
        """
        return np.where((h > self.lo) & (h < self.hi), self.sigma0 / self.width, 0.0)

    def gradient(self, q, h):
        """Return the energy's gradient per cell, ``q + phi'(h)``.

        Parameters
        ----------
        q : ndarray
            Total traction [stress].
        h : ndarray
            Gap [length].

        Returns
        -------
        ndarray
            ``q + sigma_w(h) + k min(h, 0)``: zero where the traction balances the law and the
            penalty [stress].
        """
        return q + self.stress(h) + self.k * np.minimum(h, 0.0)

    def phi(self, h):
        """Return the potential phi(h) = -int_h^inf sigma_w, plus ``k h^2/2`` for h < 0.

        Parameters
        ----------
        h : ndarray
            Gap [length].

        Returns
        -------
        ndarray
            The potential phi(h), -sigma0 h0 at h = 0 [stress length].
        """
        s0, w = self.sigma0, self.width
        hp = np.maximum(h, 0.0)
        ramp = s0 * np.clip(self.hi - hp, 0.0, w) ** 2 / (2.0 * w)
        flat = s0 * np.maximum(self.hi - w - hp, 0.0)            # sigma0 (lo - h) on the plateau
        hn = np.minimum(h, 0.0)
        return -(ramp + flat) + s0 * hn + 0.5 * self.k * hn * hn


def energy(problem, potential, delta, q, u=None):
    """Potential energy Pi(q) per working-cell area (the sum over cells, without the cell area).

    Parameters
    ----------
    problem : AdhesiveProblem
        Grid, initial gap and operator.
    potential : RampPotential
        The law and the penalty.
    delta : float
        Approach [length].
    q : ndarray
        Total traction [stress].
    u : ndarray, optional
        ``K q`` when known [length].

    Returns
    -------
    float
        ``q.u/2 + sum phi(z - delta + u)`` [stress length].
    """
    if u is None:
        u = problem.op(q)
    return 0.5 * float(np.dot(q.ravel(), u.ravel())) + float(np.sum(potential.phi(problem.z - delta + u)))


class _Symmetric:
    """M = K_SS + diag(e) on the cells S, with the block-diagonal preconditioner."""

    def __init__(self, op, S, diag_e, contact, prec_e, precond):
        self.op = op
        self.idx = np.nonzero(S.ravel())[0]
        self.shape = S.shape
        self.diag = diag_e
        self.is_a = contact.ravel()[self.idx]
        self.prec_e = prec_e
        self.precond = precond
        self.calls = 0
        self._full = np.zeros(self.shape)

    def scatter(self, x):
        f = self._full
        f[...] = 0.0
        f.ravel()[self.idx] = x
        return f.copy()

    def matvec(self, x):
        self.calls += 1
        return self.op(self.scatter(x)).ravel()[self.idx] + self.diag * x

    def prec(self, v):
        out = self.prec_e * v
        if self.is_a.any():
            pa = self.precond(self.scatter(np.where(self.is_a, v, 0.0))).ravel()[self.idx]
            out[self.is_a] = pa[self.is_a]
        return out

    def solve(self, rhs, rtol, maxiter, x0=None):
        """x with ``||M P y - rhs|| <= rtol ||rhs||``, ``x = P y`` (right-preconditioned GMRES).

        scipy's MINRES measures its tolerance against ``||M|| ||x||``, which the large ramp
        diagonal makes meaningless here (it stops after one iteration), so the symmetric system
        is solved by restarted GMRES with the same preconditioner.
        """
        return right_preconditioned_gmres(self.matvec, self.prec, rhs, rtol, maxiter)


def _system(op, potential, h, damping, precond, contact=None):
    """The Newton matrix's cell sets and diagonal at the gap h (damping lambda on the ramp rows)."""
    contact = h < 0.0 if contact is None else contact
    slope = potential.slope(h)
    edge = (~contact) & (slope > 0.0)
    S = contact | edge
    idx = np.nonzero(S.ravel())[0]
    is_a = contact.ravel()[idx]
    sl = np.maximum(slope.ravel()[idx], 1e-300)
    diag = np.where(is_a, 1.0 / potential.k, -(1.0 + damping) / sl)
    prec_e = np.where(is_a, 0.0, sl / (1.0 + damping))
    return contact, edge, S, _Symmetric(op, S, diag, contact, prec_e, precond)


def _complementarity(potential, q, h):
    """max |min(c h, p)|/sigma0 with the exact (unpenalised) pressure p = q + sigma_w(max(h, 0))."""
    c = potential.sigma0 / potential.h0
    p = q + potential.stress(np.maximum(h, 0.0))
    return float(np.max(np.abs(np.minimum(c * h, p)))) / potential.sigma0


def _potential(problem, options, penalty):
    law = problem.law
    c = law.max_stress / law.range
    return RampPotential(law, problem.min_spread, c / (options.tol * penalty))


def solve_state_energy(problem, delta, guess=None, options=SolverOptions(), precond=None, log=None,
                       penalty=100.0, stage_ratio=1e3, stages=None):
    """Solve one adhesive state at the approach ``delta`` as a local minimum of the potential energy.

    The contact penalty is stiffened in stages, from the cells' own stiffness ``1/k0`` by the
    factor ``stage_ratio`` per stage up to its final value; each stage minimises its own
    energy (Newton, energy line search) from the previous stage's minimiser, and the last
    stage runs until the complementarity residual meets the tolerance.

    Parameters
    ----------
    problem : AdhesiveProblem
        Grid, initial gap, Dugdale law and operator (:class:`dhfield.bem.solver.AdhesiveProblem`);
        its ``min_spread`` is the ramp width.
    delta : float
        Approach of distant points [length].
    guess : ndarray, optional
        Total traction on the working grid to start from [stress]; default zero.
    options : SolverOptions
        Tolerances and caps (``max_krylov`` caps GMRES; ``max_newton`` caps the Newton
        iterations of all stages together).
    precond : callable, optional
        :func:`dhfield.bem.newton.symbol_preconditioner` of the problem (built when omitted).
    log : callable, optional
        Called with one line per Newton iteration.
    penalty : float, default 100
        The final contact penalty's penetration lies this factor below ``options.tol``
        (relative to h0 at a pressure sigma0) [-].
    stage_ratio : float, default 1e3
        Stiffening of the penalty from one stage to the next [-].
    stages : int, optional
        Number of penalty stages; default as many as ``stage_ratio`` needs to reach the final
        penalty from the cells' own stiffness.

    Returns
    -------
    NewtonResult
        The state; ``merit_history`` holds the energy after each accepted step (decreasing
        within each stage by construction).
    """
    t0 = time.perf_counter()
    op = problem.op
    pot = _potential(problem, options, penalty)
    k_final = pot.k
    pot.k = min(k_final, 1.0 / problem.k0)
    if precond is None:
        precond = problem_preconditioner(problem)
    sigma0 = pot.sigma0
    q = np.zeros_like(problem.z) if guess is None else np.array(guess, dtype=float, copy=True)
    u = op(q)
    h = problem.z - delta + u
    calls = 1
    p = pot.gradient(q, h)
    E = 0.5 * float(np.dot(q.ravel(), u.ravel())) + float(np.sum(pot.phi(h)))
    res = _complementarity(pot, q, h)
    history = [E]
    krylov = 0
    it = 0
    lam = 0.0
    reason = DIVERGED_MAX_IT
    stage = 1
    grad0 = None
    while True:
        grad = float(np.max(np.abs(p))) / sigma0          # the stage's own stationarity
        if pot.k < k_final and grad <= max(options.tol, 1e-3 * res):
            if stages is not None and stage >= stages:
                reason = "stage_converged"
                break
            stage += 1
            grad0 = None
            pot.k = min(k_final, pot.k * stage_ratio)       # next stage
            p = pot.gradient(q, h)
            E = 0.5 * float(np.dot(q.ravel(), u.ravel())) + float(np.sum(pot.phi(h)))
            history.append(E)
            if log is not None:
                log(f"penalty stage: stiffness {pot.k:.3e}  residual {res:.3e}")
            continue
        if pot.k >= k_final and res <= options.tol:
            reason = CONVERGED
            break
        if it >= options.max_newton:
            break
        it += 1
        grad0 = grad if grad0 is None else grad0
        rtol = min(options.forcing, grad / grad0)
        phi_h = pot.phi(h)
        while True:
            contact, edge, S, M = _system(op, pot, h, lam, precond)
            free = ~S
            dq = np.zeros_like(q)
            dq[free] = -p[free] / (1.0 + lam)
            y0 = op(dq)
            calls += 1
            rhs_full = np.where(contact, -p / pot.k - y0, p / np.maximum(pot.slope(h), 1e-300) - y0)
            kit, info = 0, 0
            if M.idx.size:
                x, kit, info = M.solve(rhs_full.ravel()[M.idx], rtol, options.max_krylov)
                dq.ravel()[M.idx] = x
            krylov += kit
            calls += M.calls
            kd = op(dq)
            calls += 1
            slope0 = float(np.dot(p.ravel(), kd.ravel()))          # dPi/dalpha at alpha = 0
            if slope0 < 0.0 or lam >= options.max_damping:
                break
            lam = max(4.0 * lam, 4.0 * options.min_damping)
        if not slope0 < 0.0:
            dq = -p                                              # natural gradient: always a descent direction
            kd = op(dq)
            calls += 1
            slope0 = float(np.dot(p.ravel(), kd.ravel()))
        qkd = float(np.dot(q.ravel(), kd.ravel()))
        dkd = float(np.dot(dq.ravel(), kd.ravel()))
        alpha = 1.0
        scale = 1e-13 * (abs(E) + float(np.sum(np.abs(phi_h))))     # the energy's rounding
        while True:
            dE = alpha * qkd + 0.5 * alpha * alpha * dkd + float(np.sum(pot.phi(h + alpha * kd) - phi_h))
            if dE <= 1e-4 * alpha * slope0 or (alpha == 1.0 and abs(dE) <= scale and abs(slope0) <= scale):
                break
            if alpha < 1e-10:
                break
            # minimiser of the quadratic through dE(0), dE'(0), dE(alpha), safeguarded
            a_new = -slope0 * alpha * alpha / (2.0 * (dE - slope0 * alpha))
            alpha = min(max(a_new, 0.1 * alpha), 0.5 * alpha)
        if alpha < 1e-10:
            reason = DIVERGED_LINE_SEARCH
            break
        q = q + alpha * dq
        u = op(q)
        calls += 1
        h = problem.z - delta + u
        p = pot.gradient(q, h)
        E = E + dE
        res = _complementarity(pot, q, h)
        history.append(E)
        if alpha == 1.0:
            lam = lam / 4.0 if lam > options.min_damping else 0.0
        if log is not None:
            log(f"newton {it:3d}: residual {res:.3e}  gradient {float(np.max(np.abs(p))) / sigma0:.3e}  "
                f"energy {E:.12e}  step {alpha:.3g}  damping {lam:.3g}  krylov {kit:4d} (info {info})  "
                f"contact {int(contact.sum())}  ramp {int(edge.sum())}  {time.perf_counter() - t0:.1f} s")
    load = float(np.sum(q)) * problem.weight
    pe = q + pot.stress(np.maximum(h, 0.0))
    c = sigma0 / pot.h0
    return NewtonResult(q, h, c * h < pe, load, res, reason, it, krylov, calls, history, time.perf_counter() - t0)


def load_tangent(problem, state, options=SolverOptions(), precond=None, penalty=100.0):
    """dW/d delta and dq/d delta of a converged state: one linear solve with its Newton matrix.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem.
    state : NewtonResult
        A converged state of :func:`solve_state_energy`.
    options : SolverOptions
        Caps (the solve is taken to 1e-10 relative).
    precond : callable, optional
        :func:`dhfield.bem.newton.symbol_preconditioner` of the problem.
    penalty : float
        As in :func:`solve_state_energy`.

    Returns
    -------
    slope : float
        dW/d delta [force/length].
    dq : ndarray
        dq/d delta on the working grid [stress/length].
    iterations : int
        Krylov iterations.
    """
    pot = _potential(problem, options, penalty)
    if precond is None:
        precond = problem_preconditioner(problem)
    contact, edge, S, M = _system(problem.op, pot, state.gap, 0.0, precond, state.contact)
    # d/d delta of the rows: contact K dq' + dq'/k = 1; ramp K dq' - dq'/|s'| = 1; others dq' = 0
    dq = np.zeros_like(state.traction)
    kit = 0
    if M.idx.size:
        x, kit, _ = M.solve(np.ones(M.idx.size), 1e-10, options.max_krylov)
        dq.ravel()[M.idx] = x
    return float(np.sum(dq)) * problem.weight, dq, kit


@dataclass
class PullOff:
    """The load-control pull-off found as the zero of dW/d delta along the displacement-stable branch.

    Parameters
    ----------
    approach : float
        Approach of the minimum [length].
    load : float
        The minimum load (negative when tensile) [force].
    state : NewtonResult
        The state at ``approach``.
    approaches, loads, slopes : ndarray
        Every state solved, in order (approach [length], load [force], dW/d delta [force/length]).
    newton_iterations, krylov_iterations : int
        Work over all states and tangents.
    converged : bool
        Every state converged and the slope's zero is bracketed and located.
    reason : str
        Why the search stopped.
    elapsed : float
        Wall time [s].
    """

    approach: float
    load: float
    state: NewtonResult
    approaches: np.ndarray
    loads: np.ndarray
    slopes: np.ndarray
    newton_iterations: int
    krylov_iterations: int
    converged: bool
    reason: str
    elapsed: float

    @property
    def states(self) -> int:
        """States solved."""
        return int(self.loads.size)


def pull_off_search(problem, approach, guess=None, step=None, options=SolverOptions(), rtol=2e-5,
                    max_states=25, log=None, solve=None, max_substeps=0):
    """Locate the load-control pull-off: the zero of dW/d delta, by a safeguarded secant.

    Each state is solved by :func:`solve_state_energy`, warm-started from the nearest solved
    state moved along its exact tangent ``dq/d delta`` (:func:`load_tangent`), which also
    gives the slope.  The next approach is the secant zero of the slope through the last two
    states, kept inside the bracket of a sign change once one is found (bisection when the
    secant leaves it); before a bracket exists each step goes downhill and doubles.

    Parameters
    ----------
    problem : AdhesiveProblem
        The problem.
    approach : float
        First approach (an analytic prediction of the pull-off) [length].
    guess : ndarray, optional
        Traction to start the first state from (e.g. :func:`dhfield.bem.newton.cold_start`).
    step : float, optional
        First step in approach [length]; default 1 % of |approach| (at least h0).
    options : SolverOptions
        Per-state options.
    rtol : float, default 2e-5
        Stop when the load's distance to the minimum, estimated from the slope and the
        secant curvature (``s^2/(2 W'')``), or bounded by the bracket (``max|s| (hi - lo)``;
        the slope is jagged on the lattice), is below ``rtol |W|`` [-].
    max_states : int
        Cap on states.
    log : callable, optional
        One line per state.
    solve : callable, optional
        The state solve, ``solve(problem, delta, guess, options, precond)``; default
        :func:`solve_state_hybrid`.
    max_substeps : int, default 0
        A state that does not converge from its neighbour's tangent is retried after a state
        half-way to that neighbour (recursively, up to this many halvings); the states
        half-way join the search's states.

    Returns
    -------
    PullOff
        The minimum and its work.
    """
    t0 = time.perf_counter()
    precond = problem_preconditioner(problem)
    if step is None:
        step = max(0.01 * abs(approach), problem.law.range)
    solved = []                       # (delta, state, slope, tangent)
    work = [0, 0]

    def solve_at(d, depth=0):
        conv = [r for r in solved if r[1].converged]
        if conv:
            d0, st0, _, t0_ = min(conv, key=lambda r: abs(r[0] - d))
            q0 = st0.traction + (d - d0) * t0_
        else:
            d0, q0 = None, guess
        st = (solve or solve_state_hybrid)(problem, d, q0, options, precond)
        work[0] += st.newton_iterations
        work[1] += st.krylov_iterations
        if not st.converged and d0 is not None and depth < max_substeps:
            # the tangent's start was too far: a state half-way first, then this one from its tangent
            mid, _ = solve_at(0.5 * (d0 + d), depth + 1)
            if mid.converged:
                return solve_at(d, depth + 1)
        s, tang, kit = load_tangent(problem, st, options, precond) if st.converged else (float("nan"), None, 0)
        work[1] += kit
        solved.append((d, st, s, tang))
        if log is not None:
            log(f"state {len(solved):2d}: approach {d:.10f} load {st.load:.10f} slope {s:.6e} newton "
                f"{st.newton_iterations} krylov {st.krylov_iterations}+{kit} {st.reason} ({st.elapsed:.1f} s, "
                f"total {time.perf_counter() - t0:.1f} s)")
        return st, s

    def result(ok, reason):
        best = min(solved, key=lambda r: r[1].load if r[1].converged else np.inf)
        return PullOff(best[0], best[1].load, best[1], np.array([r[0] for r in solved]),
                       np.array([r[1].load for r in solved]), np.array([r[2] for r in solved]),
                       work[0], work[1], ok, reason, time.perf_counter() - t0)

    d = float(approach)
    st, s = solve_at(d)
    if not st.converged:
        return result(False, st.reason)
    lo = hi = None                    # approaches with slope < 0 and > 0
    prev = None
    while len(solved) < max_states:
        if s < 0:
            lo = d if lo is None or d > lo else lo
        else:
            hi = d if hi is None or d < hi else hi
        if prev is not None:
            dp, sp = prev
            curv = (s - sp) / (d - dp)
            if curv > 0 and s * s / (2.0 * curv) <= rtol * abs(st.load):
                return result(True, CONVERGED)
            nxt = d - s / curv if curv > 0 else None
        else:
            nxt = None
        if lo is not None and hi is not None:
            # W is flat at its minimum: any state inside the bracket is within max|s| (hi - lo) of it
            if abs(hi - lo) * max(abs(r[2]) for r in solved if min(lo, hi) <= r[0] <= max(lo, hi)) \
                    <= rtol * abs(st.load):
                return result(True, CONVERGED)
            if nxt is None or not (min(lo, hi) < nxt < max(lo, hi)):
                nxt = 0.5 * (lo + hi)
        elif nxt is None or abs(nxt - d) > 4.0 * step:
            nxt = d - math.copysign(step, s)
            step *= 2.0
        prev = (d, s)
        d = float(nxt)
        st, s = solve_at(d)
        if not st.converged:
            return result(False, st.reason)
    return result(False, DIVERGED_MAX_IT)


def solve_state_hybrid(problem, delta, guess=None, options=SolverOptions(), precond=None, log=None, stages=1,
                       stage_ratio=1e2):
    """One adhesive state: the energy minimisation with a soft contact penalty, then the exact active-set Newton.

    The global phase (placing the cohesive zone's edge) is :func:`solve_state_energy` with
    ``stages`` penalty stages from the cells' own stiffness ``1/k0`` (each stage decreases its
    energy at every step); its minimiser differs from the exact state only by the penetration
    ``p/k`` of the contact, which :func:`dhfield.bem.newton.solve_state` (semismooth Newton on
    ``min(c h, p)``) removes in its local, superlinear phase.

    Parameters
    ----------
    problem, delta, guess, options, precond, log
        As in :func:`solve_state_energy`.
    stages : int, default 1
        Penalty stages of the global phase (beyond the first, the stiff penalty truncates the
        line search at every cell that enters contact).
    stage_ratio : float, default 100
        Stiffening of the penalty per stage [-].

    Returns
    -------
    NewtonResult
        The exact state, with the work of both phases.
    """
    from .newton import solve_state

    t0 = time.perf_counter()
    if precond is None:
        precond = problem_preconditioner(problem)
    a = solve_state_energy(problem, delta, guess, options, precond, log, stages=stages, stage_ratio=stage_ratio)
    # the contact's penetration p/k closes in the first step, which raises ||min(c h, p)|| before it falls:
    # the polish's merit is non-monotone over a few steps
    b = solve_state(problem, delta, a.traction, replace(options, nonmonotone=max(options.nonmonotone, 4)), precond, log)
    return NewtonResult(b.traction, b.gap, b.contact, b.load, b.residual, b.reason,
                        a.newton_iterations + b.newton_iterations, a.krylov_iterations + b.krylov_iterations,
                        a.operator_calls + b.operator_calls, a.merit_history + b.merit_history,
                        time.perf_counter() - t0)


@dataclass
class NestedPullOff:
    """The load-control pull-off located by nested iteration: one :class:`PullOff` per grid, coarsest first.

    Parameters
    ----------
    levels : list of PullOff
        The search on each searched grid, coarsest first; the last is the answer's.
    first_state : NestedResult
        The first state, solved up the grids too coarse to search to the first searched grid.
    elapsed : float
        Wall time over all levels [s].
    complete : bool
        The ladder reached its finest grid.
    """

    levels: list
    first_state: object
    elapsed: float
    complete: bool = True

    @property
    def result(self) -> PullOff:
        """The finest level's search."""
        return self.levels[-1]

    @property
    def converged(self) -> bool:
        """True when the ladder reached its finest grid and that grid's search converged."""
        return self.complete and bool(self.levels) and self.result.converged

    @property
    def load(self) -> float:
        """The minimum load on the finest grid [force]."""
        return self.result.load


def pull_off_nested(problems, approach, guess=None, step=None, options=None, rtol=2e-5, coarse_rtol=1e-3,
                    step_ratio=0.25, max_substeps=3, log=None, solve=None, first_solve=None):
    """Locate the load-control pull-off by nested iteration: the slope-zero search on each grid of a ladder.

    A grid too coarse for the Dugdale edge (``edge_width_ratio > 1``: no stable discrete
    edge, so no converged states and no slopes) serves only the first state: the state at
    ``approach`` is solved up the ladder by :func:`dhfield.bem.newton.solve_state_nested`
    from ``guess`` to the coarsest resolved grid (on that grid alone when it is the coarsest).  There the slope-zero search
    (:func:`pull_off_search`) starts; each finer grid's search starts at the coarser grid's
    minimum, from its state prolonged (:func:`dhfield.bem.newton.prolong_state`), with the
    first step shrunk by ``step_ratio``.

    Parameters
    ----------
    problems : list of AdhesiveProblem
        The ladder, coarsest first (:func:`dhfield.bem.newton.grid_ladder`).
    approach : float
        First approach [length].
    guess : ndarray, optional
        Traction on the coarsest working grid to start from.
    step : float, optional
        First step of the coarsest search [length] (as in :func:`pull_off_search`).
    options : SolverOptions, optional
        Per-state options; default :data:`dhfield.bem.newton.NESTED_OPTIONS`.
    rtol : float, default 2e-5
        Stopping tolerance of the finest search (as in :func:`pull_off_search`).
    coarse_rtol : float, default 1e-3
        Stopping tolerance of the coarser searches [-].
    step_ratio : float, default 0.25
        First step of a grid per first step of the grid below it [-].
    max_substeps : int, default 3
        As in :func:`pull_off_search`.
    log : callable, optional
        One line per state and per level.
    solve : callable, optional
        The state solve, ``solve(problem, delta, guess, options, precond, log)``; default
        :func:`dhfield.bem.newton.solve_state`.
    first_solve : callable, optional
        The solve of the first state on the coarsest grid (the global phase, from ``guess``),
        e.g. :func:`dhfield.bem.newton.solve_state_smoothed`; default ``solve``.

    Returns
    -------
    NestedPullOff
        Every searched level's result and the first state's levels; a search that does not
        converge ends the ladder there (as does a first state that does not converge).
    """
    from .newton import NESTED_OPTIONS, prolong_state, solve_state, solve_state_nested

    t0 = time.perf_counter()
    options = NESTED_OPTIONS if options is None else options
    solve = solve or solve_state
    first = next((j for j, p in enumerate(problems) if p.edge_width_ratio <= 1.0), len(problems) - 1)
    d, q = float(approach), guess
    start = solve_state_nested(problems[:first + 1], d, guess, options, log=log, solve=solve, coarsest_solve=first_solve)
    q = start.state.traction
    levels = []
    if not start.converged:
        return NestedPullOff(levels, start, time.perf_counter() - t0, False)
    if step is None:
        step = max(0.01 * abs(approach), problems[0].law.range)
    for j in range(first, len(problems)):
        prob = problems[j]
        if j > first:
            q = prolong_state(levels[-1].state, problems[j - 1], prob, "traction")
            d = levels[-1].approach
            step *= step_ratio
        last = j == len(problems) - 1
        res = pull_off_search(prob, d, q, step, options, rtol if last else max(rtol, coarse_rtol), log=log,
                              solve=solve, max_substeps=max_substeps)
        levels.append(res)
        if log is not None:
            nx, ny = prob.grid.shape
            log(f"level {nx}x{ny}: {res.reason} approach {res.approach:.8f} load {res.load:.8f} states {res.states} "
                f"newton {res.newton_iterations} krylov {res.krylov_iterations} ({res.elapsed:.1f} s)")
        if not res.converged:
            break
    return NestedPullOff(levels, start, time.perf_counter() - t0, len(levels) == len(problems) - first)
