"""What a longer Anderson memory buys the high-mu route's hardest states (issue 20).

One state of the predicted (high-mu) route, on its automatic grid (``--level 2``: twice the
cells per axis), started from the lower-mu warm start
(:class:`dhfield.bem.pull_off.LowerMuWarmStart`: the same approach at mu/2 on the grid half as
fine), solved to the route's tolerance (``PREDICTED_TOL``) and CG cap (``DEFAULT_MAX_ITER``) with a stretch step every
``PREDICTED_STRETCH_EVERY`` outer iterations, once per variant from the same start:

* ``memory 6``: Anderson memory ``ANDERSON_MEMORY``, restarted every ``ANDERSON_RESTART``
  outer iterations (the solver's default, and the route's before issue 20's seventh session);
* ``memory M``: ``anderson_memory=M`` (default ``STRETCH_ANDERSON_MEMORY``), no periodic restart
  (the route's mixing now).

Prints per variant: converged, outer and CG iterations, the residual, the load and the wall
time; the variants run one after the other in one process (compare their ratio, not the
seconds).  Usage::

    .venv/bin/python -m verification.bench_anderson                       # beta0 0.1, mu 10
    .venv/bin/python -m verification.bench_anderson --beta0 1 --mu 10 --approach -0.7567441645072825 --level 2

The default case is the state that left beta0 = 0.1, mu = 10 unanswered (approach -0.68669 on
2560 x 480).  Measured (2026-11-28, 1 thread): the start 8 s; memory 6 stalled (109 outer
iterations, residual 7.47e-4, 193 s), memory 30 converged (92, 6.09e-5, 184 s).
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
import time


def main(argv=None) -> int:
    from dhfield.analysis import bem_start as A
    from dhfield.bem import solver as S
    from dhfield.bem.pull_off import PREDICTED_STRETCH_EVERY, LowerMuWarmStart

    ap = argparse.ArgumentParser(prog="python -m verification.bench_anderson", description=__doc__.split("\n")[0])
    ap.add_argument("--beta0", type=float, default=0.1)
    ap.add_argument("--mu", type=float, default=10.0)
    ap.add_argument("--approach", type=float, default=-0.6866873460068601,
                    help="approach of the state [c_r units] (default: beta0 0.1, mu 10's unconverged state)")
    ap.add_argument("--level", type=int, default=1, choices=(1, 2), help="grid level (2: twice the cells per axis)")
    ap.add_argument("--memory", type=int, nargs="+", default=[S.STRETCH_ANDERSON_MEMORY],
                    help="Anderson memories to compare with the default (6, restarted)")
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args(argv)
    plan = A.plan_grid(mu=args.mu, beta0=args.beta0, max_seconds=1e9)
    nd = A.predicted_problem(mu=args.mu, beta0=args.beta0, n=plan.n_needed * args.level,
                             ny=plan.ny_needed * args.level)
    t0 = time.perf_counter()
    ws = LowerMuWarmStart(nd, tol=A.PREDICTED_TOL, max_iter=S.DEFAULT_MAX_ITER, threads=args.threads)
    guess = ws(args.approach)
    print(f"beta0 {args.beta0:g}, mu {args.mu:g}, level {args.level}: {nd.grid.nx} x {nd.grid.ny} cells, "
          f"approach {args.approach:.6g}; lower-mu start {time.perf_counter() - t0:.0f} s "
          f"({ws.states_solved} states, {ws.iterations} CG iterations)", flush=True)
    if guess is None:
        print("the lower-mu state did not converge: no start to compare from", flush=True)
        return 1
    prob = nd.adhesive_problem(args.threads)
    print(f"{'variant':>10} {'converged':>9} {'outer':>6} {'CG':>7} {'residual':>9} {'load':>12} {'wall s':>7}")
    for memory in [None] + list(args.memory):
        t = time.perf_counter()
        st = S.solve_problem(prob, args.approach, guess, A.PREDICTED_TOL, S.DEFAULT_MAX_ITER,
                             stretch_every=PREDICTED_STRETCH_EVERY, anderson_memory=memory)
        name = f"memory {memory or S.ANDERSON_MEMORY}"
        print(f"{name:>10} {str(st.converged):>9} {st.summary().get('outer_iterations', -1):>6} {st.iterations:>7} "
              f"{st.residual:>9.2e} {st.load:>12.7f} {time.perf_counter() - t:>7.0f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
