"""Why an adhesive BEM case does not converge: cold starts and path states, printed.

Issue 8's unconverged study case (beta0 = 0.5, mu = 5, N = 512) was diagnosed with
this script.  It prints

* the grid (cells per axis, dx, dy), the smallest Dugdale edge spread and ``resolved``;
* for each cold start of the bracket search's first state, at the approach and
  with the cohesive zone (sigma0 on an ellipse c x d) of an analytic model: the
  paper's DH model (the start until commit 713551f), the same approach with the
  adhesive ellipticity of the two-axis closure, and the two-axis closure's own
  pull-off approach and zone (the start of :func:`dhfield.bem.adhesive_pull_off`
  for beta0 < 1 since then) -- converged flag, outer and CG
  iterations, residual, load and semi-axes reached, and the cells across the
  cohesive zone along x ((c - a)/dx) and y ((d - b)/dy);
* with ``--path``: every state of the load-control path (phase, approach, load,
  converged, CG and outer iterations, residual, cells across the zone).

Usage::

    .venv/bin/python -m verification.diagnose_adhesive --beta0 0.5 --mu 5 --n 512          # ~4-5 min
    .venv/bin/python -m verification.diagnose_adhesive --beta0 0.5 --mu 5 --n 512 --path   # + ~11 min
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
                "beta0 < 1)",
}


def _across(st, grid):
    a, b = st.contact_semi_axes()
    c, d = st.cohesive_semi_axes()
    return a, b, c, d, (c - a) / grid.dx, (d - b) / grid.dy


def cold_start(mu, beta0, n, start, *, tol=1e-6, max_iter=8000):
    """(approach, zone, state, seconds) of the first bracket state solved from ``start``."""
    from dhfield import compare
    from dhfield.adhesive_start import nondimensional_problem
    from dhfield.bem.solver import Prediction, solve_problem

    nd = nondimensional_problem(mu, beta0, n)
    dh = compare.pull_off("dh-elliptic", mu=mu, beta0=beta0, control="load")
    ta = compare.pull_off("dh-elliptic-two-axis", mu=mu, beta0=beta0, control="load")
    if start == "two-axis":
        approach, c, d = float(ta["delta_star"]), float(ta["c_star"]), float(ta["d_star"])
    else:
        approach, c, d = float(dh["delta_star"]), float(dh["c_star"]), float(dh["d_star"])
        if start != "dh":
            d = c * float(ta["adhesive_ellipticity"])
    # the library's cold start (sigma0 on the zone) from this start's approach and zone
    nd = dataclasses.replace(nd, pull_off_approach=approach, pull_off_zone=(c, d))
    prob = nd.adhesive_problem()
    cold = nd.path_start(prob)
    t0 = time.perf_counter()
    st = solve_problem(prob, approach, Prediction(np.zeros_like(prob.z), cold.stress), tol, max_iter)
    return approach, (c, d), st, time.perf_counter() - t0, nd, prob


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.diagnose_adhesive", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, default=0.5)
    p.add_argument("--mu", type=float, default=5.0)
    p.add_argument("--n", type=int, default=512)
    p.add_argument("--starts", nargs="+", default=list(STARTS), choices=list(STARTS))
    p.add_argument("--max-iter", type=int, default=8000, help="CG iterations per state (the study's --max-iter)")
    p.add_argument("--path", action="store_true", help="also solve and print the whole load-control path")
    args = p.parse_args(argv)
    if not 0 < args.beta0 <= 1 or not args.mu > 0 or args.n < 8 or args.n % 2:
        p.error("--beta0 must be in (0, 1], --mu > 0, --n an even integer >= 8")
    b, m, n = args.beta0, args.mu, args.n
    for name in args.starts:
        approach, (c, d), st, el, nd, prob = cold_start(m, b, n, name, max_iter=args.max_iter)
        if name == args.starts[0]:
            g = nd.grid
            print(f"beta0 = {b:g}, mu = {m:g}, N = {n}: dx = {g.dx:.5f}, dy = {g.dy:.5f} (dx/dy = {g.dx / g.dy:.3f}); "
                  f"Dugdale edge spread >= {prob.min_spread:.4f} (2 h0 = {2 * nd.law.range:.4f}), "
                  f"resolved = {prob.resolved}")
        a_, b_, c_, d_, nx, ny = _across(st, nd.grid)
        print(f"cold start '{name}' ({STARTS[name]}): approach {approach:+.5f}, zone c = {c:.4f}, d = {d:.4f} -> "
              f"converged = {st.converged}, outer = {st.outer_iterations}, CG = {st.iterations}, "
              f"residual = {st.residual:.2e}, W = {st.load:+.5f}, a = {a_:.4f}, b = {b_:.4f}, c = {c_:.4f}, "
              f"d = {d_:.4f}, (c - a)/dx = {nx:.2f}, (d - b)/dy = {ny:.2f} ({el:.0f} s)", flush=True)
    if args.path:
        from dhfield.bem import adhesive_pull_off
        from dhfield.adhesive_start import AdhesiveOptions

        t0 = time.perf_counter()
        res = adhesive_pull_off(mu=m, beta0=b, n=n, progress=sys.stderr.isatty(), options=AdhesiveOptions(max_iter=args.max_iter, keep_states=True))
        path = res.path
        print(f"path: W* = {res.W_star:.6f}, converged = {res.converged}, resolved = {res.resolved}, "
              f"{res.n_steps} states, {res.iterations} CG iterations ({time.perf_counter() - t0:.0f} s)")
        g = path.pull_off_state.grid
        for i in range(len(path.approach)):
            print(f"  {path.phase[i]:9s} approach {path.approach[i]:+.5f} W {path.load[i]:+.5f} "
                  f"converged {bool(path.converged[i])!s:5s} CG {path.iterations[i]:5d} outer "
                  f"{path.outer_iterations[i]:3d} residual {path.residual[i]:.2e} (c - a)/dx "
                  f"{(path.c[i] - path.a[i]) / g.dx:.2f} (d - b)/dy {(path.d[i] - path.b[i]) / g.dy:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
