"""Why an adhesive BEM case does not converge: cold starts, path states and outer residuals, printed.

Issue 8's unconverged study case (beta0 = 0.5, mu = 5, N = 512) and issue 20's
(beta0 = 0.1806, mu = 5, N = 480, 30 deg) were diagnosed with this script.  It prints

* the grid (cells along x and y, dx, dy), the smallest Dugdale edge spread and ``resolved``;
* for each cold start of the bracket search's first state, at the approach and
  with the cohesive zone (sigma0 on an ellipse c x d) of an analytic model: the
  paper's DH model (the start until commit 713551f), the same approach with the
  adhesive ellipticity of the two-axis closure, the two-axis closure's own
  pull-off approach and zone (the start of :func:`dhfield.bem.adhesive_pull_off`
  for 0.3 <= beta0 < 1 since then), and GVG's JKR pull-off ellipse widened by the
  expected zone (the start of slender contacts, beta0 < 0.3) -- converged flag, outer
  and CG iterations, residual, load and semi-axes reached, and the cells across the
  cohesive zone along x ((c - a)/dx) and y ((d - b)/dy);
* with ``--history``: the outer (Anderson) iteration's residual every few iterations,
  with the cell of the largest zone-fraction change (where the fixed point wanders)
  and the count of cells changing by more than 1e-3;
* with ``--path``: every state of the load-control path (phase, approach, load,
  converged, CG and outer iterations, residual, cells across the zone), and with
  ``--trace`` every state solved on every grid of it (the coarser grids of the located
  and nested searches included), as it is solved.

``--ny`` sets the cells along y (default ``--n``: n x n cells); without ``--n`` the
automatic grid of :func:`dhfield.analysis.bem_start.plan_grid` is used.

Usage::

    .venv/bin/python -m verification.diagnose_adhesive --beta0 0.5 --mu 5 --n 512          # ~4-5 min
    .venv/bin/python -m verification.diagnose_adhesive --beta0 0.5 --mu 5 --n 512 --path   # + ~11 min
    .venv/bin/python -m verification.diagnose_adhesive --beta0 0.1806 --mu 5 --n 480 --starts gvg --history
    .venv/bin/python -m verification.diagnose_adhesive --beta0 0.1806 --mu 5 --starts gvg --path --trace

What it showed at beta0 = 0.1806, mu = 5 (2026-11-26, DHFIELD_THREADS=1, shared 2-core machine):
with 480 x 480 cells (dx = 3.6 dy) the states wander for 100-175 outer iterations, the
largest residual in the cells at the contact's tips (x = 2.72-2.79, y < 0.13), and the
path's refine states stop after STALL_OUTER = 60 iterations without progress (13
unconverged, W* = -0.36157, exit 3); the located search's 240 x 240 grid (1.2 cells across
c - a along x) converged no state in 260 s.  With about square cells (576 x 160, the
automatic grid since issue 20) every state converges in 33-84 outer iterations.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import dataclasses
import sys
import time

import numpy as np

#: Cold starts of the first bracket state: name -> what the zone and approach come from.
STARTS = {
    "dh": "the paper's DH pull-off: its approach and cohesive zone (c, d = beta0 c) (adhesive_pull_off "
          "before commit 713551f)",
    "dh-approach-two-axis-ellipticity": "DH approach and c, d = c x the two-axis closure's adhesive ellipticity",
    "two-axis": "two-axis closure's pull-off: its approach and cohesive zone (adhesive_pull_off since 713551f, "
                "0.3 <= beta0 < 1)",
    "gvg": "GVG's JKR pull-off: its approach and contact ellipse widened by the expected zone 0.785/mu^2 "
           "(adhesive_pull_off for beta0 < 0.3)",
}


def _across(st, grid):
    a, b = st.contact_semi_axes()
    c, d = st.cohesive_semi_axes()
    return a, b, c, d, (c - a) / grid.dx, (d - b) / grid.dy


class OuterHistory:
    """Records the outer iteration's residual by wrapping :class:`dhfield.bem.solver.AndersonMixing.step`.

    Each step records max |f|/sigma0 (the zone-fraction change), the working-grid cell where it
    is largest and the count of cells with |f| > 1e-3 sigma0.  Used as a context manager.
    """

    def __init__(self, sigma0):
        self.sigma0 = float(sigma0)
        self.rows = []

    def __enter__(self):
        from dhfield.bem import solver

        self._solver, self._orig = solver, solver.AndersonMixing.step
        orig, rows, s0 = self._orig, self.rows, self.sigma0

        def step(mixer, x, f):
            a = np.abs(f)
            k = np.unravel_index(int(np.argmax(a)), a.shape)
            rows.append((float(a[k]) / s0, k, int(np.count_nonzero(a > 1e-3 * s0))))
            return orig(mixer, x, f)

        solver.AndersonMixing.step = step
        return self

    def __exit__(self, *exc):
        self._solver.AndersonMixing.step = self._orig
        return False

    def print(self, prob, every=10):
        """Print every ``every``-th row (and the last), the cell as (x, y) on the full grid."""
        g = prob.grid
        for j, (r, k, cnt) in enumerate(self.rows):
            if j % every == 0 or j == len(self.rows) - 1:
                if prob.symmetric:      # the quadrant x > 0, y > 0: index i is x = (i + 1/2) dx
                    x, y = (k[0] + 0.5) * g.dx, (k[1] + 0.5) * g.dy
                else:
                    x, y = g.x[k[0]], g.y[k[1]]
                print(f"    outer {j + 1:3d}: residual {r:.2e} largest at x = {x:+.4f}, y = {y:+.4f}; "
                      f"{cnt} cells change by > 1e-3")


def _problem(mu, beta0, n, ny):
    from dhfield.analysis.bem_start import nondimensional_problem, plan_grid

    if n is None:
        plan = plan_grid(mu=mu, beta0=beta0)
        n, ny = plan.n_needed, plan.ny_needed
    return nondimensional_problem(mu=mu, beta0=beta0, n=n, ny=ny)


def cold_start(mu, beta0, n, start, *, tol=1e-6, max_iter=8000, ny=None, history=False):
    """(approach, zone, state, seconds, problem, working problem, history) of the first bracket state from ``start``."""
    from dhfield.analysis import compare
    from dhfield.analysis.bem_start import expected_zone_width
    from dhfield.bem.solver import Prediction, solve_problem

    nd = _problem(mu, beta0, n, ny)
    if start == "gvg":
        from dhfield.models import jkr_elliptic_energy

        g = jkr_elliptic_energy.pull_off_nondimensional(beta0, mu, control="load")
        w = expected_zone_width(mu)
        approach, c, d = float(g["delta_star"]), float(g["a_star"]) + w, float(g["b_star"]) + w
    elif start == "two-axis":
        ta = compare.pull_off("dh-elliptic-two-axis", mu=mu, beta0=beta0, control="load")
        approach, c, d = float(ta["delta_star"]), float(ta["c_star"]), float(ta["d_star"])
    else:
        dh = compare.pull_off("dh-elliptic", mu=mu, beta0=beta0, control="load")
        approach, c, d = float(dh["delta_star"]), float(dh["c_star"]), float(dh["d_star"])
        if start != "dh":
            ta = compare.pull_off("dh-elliptic-two-axis", mu=mu, beta0=beta0, control="load")
            d = c * float(ta["adhesive_ellipticity"])
    # the library's cold start (sigma0 on the zone) from this start's approach and zone
    nd = dataclasses.replace(nd, pull_off_approach=approach, pull_off_zone=(c, d))
    prob = nd.adhesive_problem()
    cold = nd.path_start(prob)
    hist = OuterHistory(nd.law.max_stress)
    t0 = time.perf_counter()
    if history:
        with hist:
            st = solve_problem(prob, approach, Prediction(np.zeros_like(prob.z), cold.stress), tol, max_iter)
    else:
        st = solve_problem(prob, approach, Prediction(np.zeros_like(prob.z), cold.stress), tol, max_iter)
    return approach, (c, d), st, time.perf_counter() - t0, nd, prob, hist


class StateTrace:
    """Prints every state solved on every grid (wraps the solver's ``solve_problem``); a context manager."""

    def __enter__(self):
        from dhfield.bem import branch, solver

        self._mods, self._orig = (branch, solver), solver.solve_problem
        orig, t00 = self._orig, time.perf_counter()

        def traced(prob, delta, guess, tol, max_iter):
            t0 = time.perf_counter()
            st = orig(prob, delta, guess, tol, max_iter)
            a, b, c, d, nx, ny = _across(st, prob.grid)
            print(f"  [{time.perf_counter() - t00:6.1f} s] {prob.grid.nx} x {prob.grid.ny} (edge ratio "
                  f"{prob.edge_width_ratio:.2f}) approach {delta:+.5f} from {type(guess).__name__:12s} "
                  f"converged {st.converged!s:5s} outer {st.outer_iterations:3d} CG {st.iterations:5d} residual "
                  f"{st.residual:.1e} W {st.load:+.5f} (c - a)/dx {nx:.2f} (d - b)/dy {ny:.2f} tol {tol:g} "
                  f"({time.perf_counter() - t0:.1f} s)", flush=True)
            return st

        for m in self._mods:
            m.solve_problem = traced
        return self

    def __exit__(self, *exc):
        for m in self._mods:
            m.solve_problem = self._orig
        return False


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.diagnose_adhesive", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, default=0.5)
    p.add_argument("--mu", type=float, default=5.0)
    p.add_argument("--n", type=int, default=None, help="cells along x (default: the automatic grid, plan_grid)")
    p.add_argument("--ny", type=int, default=None, help="cells along y (default: --n, or the automatic grid's)")
    p.add_argument("--starts", nargs="+", default=None, choices=list(STARTS),
                   help="cold starts to try (default: gvg for beta0 < 0.3, else dh, dh-approach-two-axis-ellipticity "
                        "and two-axis)")
    p.add_argument("--max-iter", type=int, default=8000, help="CG iterations per state (the study's --max-iter)")
    p.add_argument("--history", action="store_true", help="print the outer residual history of each cold start")
    p.add_argument("--path", action="store_true", help="also solve and print the whole load-control path")
    p.add_argument("--trace", action="store_true", help="with --path: print every state solved on every grid")
    args = p.parse_args(argv)
    if not 0 < args.beta0 <= 1 or not args.mu > 0 or (args.n is not None and (args.n < 8 or args.n % 2)):
        p.error("--beta0 must be in (0, 1], --mu > 0, --n an even integer >= 8")
    if args.ny is not None and (args.ny < 8 or args.ny % 2):
        p.error("--ny must be an even integer >= 8")
    b, m, n, ny = args.beta0, args.mu, args.n, args.ny
    starts = args.starts or (["gvg"] if b < 0.3 else ["dh", "dh-approach-two-axis-ellipticity", "two-axis"])
    for name in starts:
        approach, (c, d), st, el, nd, prob, hist = cold_start(m, b, n, name, max_iter=args.max_iter, ny=ny,
                                                              history=args.history)
        if name == starts[0]:
            g = nd.grid
            print(f"beta0 = {b:g}, mu = {m:g}, N = {g.nx} x {g.ny} cells: dx = {g.dx:.5f}, dy = {g.dy:.5f} "
                  f"(dx/dy = {g.dx / g.dy:.3f}); Dugdale edge spread >= {prob.min_spread:.4f} "
                  f"(2 h0 = {2 * nd.law.range:.4f}, edge ratio {prob.edge_width_ratio:.3f}), "
                  f"resolved = {prob.resolved}")
        a_, b_, c_, d_, nx, nyc = _across(st, nd.grid)
        print(f"cold start '{name}' ({STARTS[name]}): approach {approach:+.5f}, zone c = {c:.4f}, d = {d:.4f} -> "
              f"converged = {st.converged}, outer = {st.outer_iterations}, CG = {st.iterations}, "
              f"residual = {st.residual:.2e}, W = {st.load:+.5f}, a = {a_:.4f}, b = {b_:.4f}, c = {c_:.4f}, "
              f"d = {d_:.4f}, (c - a)/dx = {nx:.2f}, (d - b)/dy = {nyc:.2f} ({el:.0f} s)", flush=True)
        if args.history:
            hist.print(prob)
    if args.path:
        from dhfield.bem import adhesive_pull_off
        from dhfield.analysis.bem_start import AdhesiveOptions

        t0, c0 = time.perf_counter(), time.process_time()
        if args.trace:
            print("every state solved, on every grid:")
            with StateTrace():
                res = adhesive_pull_off(mu=m, beta0=b, n=n, ny=ny, progress=False,
                                        options=AdhesiveOptions(max_iter=args.max_iter, keep_states=True))
        else:
            res = adhesive_pull_off(mu=m, beta0=b, n=n, ny=ny, progress=sys.stderr.isatty(),
                                    options=AdhesiveOptions(max_iter=args.max_iter, keep_states=True))
        path = res.path
        g = path.pull_off_state.grid
        print(f"path on {g.nx} x {g.ny}: W* = {res.W_star:.6f} (error {res.W_star_error:.2g}), converged = "
              f"{res.converged}, resolved = {res.resolved}, search = {res.search}, {res.n_steps} states, "
              f"{len(res.failures)} unconverged, {res.iterations} CG iterations "
              f"({time.perf_counter() - t0:.0f} s wall, {time.process_time() - c0:.0f} s CPU)")
        for i in range(len(path.approach)):
            print(f"  {path.phase[i]:9s} approach {path.approach[i]:+.5f} W {path.load[i]:+.5f} "
                  f"converged {bool(path.converged[i])!s:5s} CG {path.iterations[i]:5d} outer "
                  f"{path.outer_iterations[i]:3d} residual {path.residual[i]:.2e} (c - a)/dx "
                  f"{(path.c[i] - path.a[i]) / g.dx:.2f} (d - b)/dy {(path.d[i] - path.b[i]) / g.dy:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
