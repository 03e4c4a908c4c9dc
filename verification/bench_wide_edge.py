"""What the wide-edge start buys a high-mu state that stalls with the grid's own edge (issue 20).

The predicted (high-mu) route's first state (the lattice sample nearest GVG's pull-off), on a
grid of ``--n`` cells per axis, from the route's cold start (sigma0 on GVG's zone), solved to the
route's tolerance (``PREDICTED_TOL``) with a stretch step every ``PREDICTED_STRETCH_EVERY`` outer
iterations and the solver's default mixing (Anderson memory 6, restarted), as the route solves
its cold state, in three variants one after the other in one process:

* ``own``: the grid's own edge, from the cold start;
* ``wide``: the Dugdale edge over its cap 2 h0
  (:meth:`dhfield.bem.solver.AdhesiveProblem.with_widest_edge`), from the cold start;
* ``own from wide``: the grid's own edge, started from the ``wide`` state, with Anderson memory
  ``STRETCH_ANDERSON_MEMORY`` (the route's mixing for external starts;
  :meth:`dhfield.bem.branch.Branch.widest_edge_guess`).

Prints per variant: converged, outer iterations, residual, load and wall time, and the edge
widths (in h0).  Compare the variants' outer iterations, not the seconds.  Usage::

    .venv/bin/python -m verification.bench_wide_edge                  # beta0 0.5, mu 10, 1280^2
    .venv/bin/python -m verification.bench_wide_edge --beta0 1 --n 1280 --skip-own

Measured (2026-11-28, 1 thread, by /tmp copies of this script with the same calls): at
beta0 = 0.5, mu = 10, 1280^2 (own edge 1.89 h0): ``own`` wandered at residual 2e-3 to 4e-2 for
150 outer iterations (stopped by hand); ``wide`` converged in 120-130 (421-474 s, two runs);
``own from wide`` converged in 22 (memory 30; 28 with memory 6), load -4.679307 against the wide
state's -4.679256.  Each variant can take 5-20 min on one core.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
import time


def main(argv=None) -> int:
    import numpy as np

    from dhfield.analysis import bem_start as A
    from dhfield.bem import solver as S
    from dhfield.bem.pull_off import PREDICTED_STRETCH_EVERY

    ap = argparse.ArgumentParser(prog="python -m verification.bench_wide_edge", description=__doc__.split("\n")[0])
    ap.add_argument("--beta0", type=float, default=0.5, help="initial ellipticity in (0, 1] (default 0.5)")
    ap.add_argument("--mu", type=float, default=10.0, help="Tabor parameter > 0 (default 10)")
    ap.add_argument("--n", type=int, default=1280, help="cells along x (default 1280)")
    ap.add_argument("--ny", type=int, default=None, help="cells along y (default n)")
    ap.add_argument("--threads", type=int, default=1, help="FFTW threads (default 1)")
    ap.add_argument("--skip-own", action="store_true", help="skip the 'own' variant (the slowest)")
    args = ap.parse_args(argv)

    nd = A.predicted_problem(mu=args.mu, beta0=args.beta0, n=args.n, ny=args.ny)
    prob = nd.adhesive_problem(args.threads)
    wide = prob.with_widest_edge()
    cold = nd.path_start(prob).stress
    d = nd.lattice_approach(nd.pull_off_approach)
    h0 = prob.law.range
    print(f"beta0 {args.beta0:g}, mu {args.mu:g}, {prob.grid.nx} x {prob.grid.ny} cells, approach {d:.6f}; "
          f"edge: own {prob.min_spread / h0:.3f} h0, wide {wide.min_spread / h0:.3f} h0", flush=True)

    def cold_start():
        return S.Prediction(np.zeros_like(cold), cold.copy())

    def run(name, p, start, memory):
        t = time.perf_counter()
        st = S.solve_problem(p, d, start, A.PREDICTED_TOL, S.DEFAULT_MAX_ITER, stretch_every=PREDICTED_STRETCH_EVERY,
                             anderson_memory=memory)
        print(f"{name:14s} converged {st.converged!s:5s} outer {st.outer_iterations:4d} residual {st.residual:.2e} "
              f"load {st.load:.6f} {time.perf_counter() - t:7.1f} s", flush=True)
        return st

    if not args.skip_own:
        run("own", prob, cold_start(), None)
    st_wide = run("wide", wide, cold_start(), None)
    if st_wide.converged:
        run("own from wide", prob, st_wide, S.STRETCH_ANDERSON_MEMORY)
    return 0


if __name__ == "__main__":
    sys.exit(main())
