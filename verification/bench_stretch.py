"""What the stretch step buys the predicted (high-mu) route's cold state (issue 20).

The cold state of :func:`dhfield.bem.pull_off.predicted_path` (sigma0 on GVG's pull-off zone,
corrected by the sphere's Maugis-Dugdale, at the lattice sample nearest the predicted pull-off),
solved to the route's tolerance (``PREDICTED_TOL``) on the automatic grid (or ``--n``):

* ``anderson``: Anderson steps only (the solver before the stretch step);
* ``stretch``: a stretch step every ``PREDICTED_STRETCH_EVERY`` outer iterations
  (:func:`dhfield.bem.solver.stretch_step`), as the route now solves it.

Prints per variant: converged, outer and CG iterations, the residual, the load and wall/CPU
time.  Usage::

    .venv/bin/python -m verification.bench_stretch --beta0 1 --mu 10 [--n 1280] [--threads 2]

Each variant at mu = 10 takes 4-10 min on 2 cores (the Anderson one up to the solver's
300-iteration cap).
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
import time

import numpy as np


def predicted_cold_state(beta0, mu, n=None):
    """The predicted route's cold state: (its NondimensionalProblem, the approach it is solved at).

    The approach is the lattice sample nearest the predicted pull-off, as
    :func:`dhfield.bem.pull_off.predicted_path` solves first; ``n`` None: the automatic grid.
    """
    from dhfield.analysis.bem_start import plan_grid, predicted_problem
    from dhfield.bem.pull_off import LOCATE_DIVISIONS

    plan = plan_grid(mu=mu, beta0=beta0)
    problem = predicted_problem(mu=mu, beta0=beta0, n=plan.n_needed if n is None else n,
                                ny=plan.ny_needed if n is None else None)
    spacing = problem.approach_step / LOCATE_DIVISIONS
    j0 = int(round((problem.approach_max - problem.pull_off_approach) / spacing))
    return problem, problem.approach_max - j0 * spacing


def main(argv=None) -> int:
    from dhfield.analysis.bem_start import PREDICTED_TOL
    from dhfield.bem import solver
    from dhfield.bem.pull_off import PREDICTED_STRETCH_EVERY

    p = argparse.ArgumentParser(prog="python -m verification.bench_stretch", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, default=1.0)
    p.add_argument("--mu", type=float, default=10.0)
    p.add_argument("--n", type=int, default=None, help="cells along x (default: the automatic grid)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--variants", nargs="+", default=["stretch", "anderson"], choices=["stretch", "anderson"])
    args = p.parse_args(argv)
    problem, delta = predicted_cold_state(args.beta0, args.mu, args.n)
    prob = problem.adhesive_problem(args.threads)
    cold = problem.path_start(prob).stress
    g = problem.grid
    print(f"beta0 = {args.beta0:g}, mu = {args.mu:g}: the predicted route's cold state on {g.nx} x {g.ny} cells "
          f"(edge ratio {prob.edge_width_ratio:.3f}) at approach {delta:+.6f}, tol {PREDICTED_TOL:g}, "
          f"{args.threads} thread(s); load average {os.getloadavg()[0]:.1f}", flush=True)
    for v in args.variants:
        every = PREDICTED_STRETCH_EVERY if v == "stretch" else None
        t0, c0 = time.perf_counter(), time.process_time()
        st = solver.solve_problem(prob, delta, solver.Prediction(np.zeros_like(cold), cold.copy()), PREDICTED_TOL,
                                  solver.DEFAULT_MAX_ITER, stretch_every=every)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        print(f"  {v:9s} converged = {st.converged!s:5s} outer = {st.outer_iterations:3d} CG = {st.iterations:6d} "
              f"residual = {st.residual:.2g}  W = {st.load:+.6f}  wall {wall:6.1f} s  CPU {cpu:6.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
