"""What quadrant symmetry, the box CG and a coarse-to-fine start buy, at one case (issue 20).

One state of the adhesive BEM at the analytic (two-axis) pull-off approach, solved

* cold (sigma0 on the two-axis zone), on the quadrant (the default) and on the full grid
  (``symmetric=False``);
* cold on the quadrant with the box CG switched off (``ACTIVE_BOX_MAX_FRACTION = 0``:
  every CG iteration on the whole working grid);
* warm, from the same approach solved on the grid half as fine, interpolated
  (:func:`dhfield.bem.pull_off.interpolate_state`): the coarse-to-fine start (the
  coarse solve's time is printed too);
* ``neighbour``: the state one lattice sample (``approach_step / 2``) above, warm-started
  from the cold-started one as it is, and ``dilated``: from it stretched about the centre by
  the contact change expected there (:func:`dhfield.bem.pull_off.dilate_state`, JKR's
  sphere d delta/d a: the predicted route's start of its first neighbour).

Prints wall and CPU seconds, CG and outer iterations and W per variant.  Usage::

    .venv/bin/python -m verification.measure_bem_savings --beta0 0.5 --mu 5 --n 384

Measured 2026-11-26 (2-core machine shared, load average 4.5), beta0 = 0.5, mu = 5, N = 384 (the
automatic grid), variants run in the order coarse-to-fine after quadrant: CPU 2.4 s quadrant
(654 CG, 45 outer), 8.8 s full grid (819 CG, 49 outer: the quadrant buys 3.7x), 2.9 s without
the box CG (704 CG: the box buys 1.2x), coarse-to-fine 0.7 s at N = 192 + 1.7 s at N = 384
(550 CG, 40 outer: nothing at this case).  At mu = 10, N = 1440 one cold state was not done
after 58 outer iterations / 1768 CG iterations (3.5 CPU minutes).

Measured 2026-11-26 (load average 6-7), sphere mu = 5, N = 256 (``--beta0 1 --mu 5 --n 256
--variants quadrant neighbour dilated``): the state one sample above from the cold one as it
is 675 CG / 52 outer (1.0 CPU s), dilated 336 CG / 27 outer (0.4 CPU s): the dilation buys 2x.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
import time

import numpy as np


def _timed(fn):
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - t0, time.process_time() - c0


def main(argv=None) -> int:
    from dhfield.analysis.bem_start import nondimensional_problem
    from dhfield.bem import solver
    from dhfield.bem.pull_off import interpolate_state
    from dhfield.bem.solver import AdhesiveProblem, Prediction, solve_problem

    p = argparse.ArgumentParser(prog="python -m verification.measure_bem_savings", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, default=0.5)
    p.add_argument("--mu", type=float, default=5.0)
    p.add_argument("--n", type=int, default=384)
    p.add_argument("--variants", nargs="+", default=["quadrant", "full", "no-box", "coarse-to-fine", "neighbour",
                                                     "dilated"])
    args = p.parse_args(argv)
    nd = nondimensional_problem(mu=args.mu, beta0=args.beta0, n=args.n)
    delta = nd.pull_off_approach
    g = nd.grid
    print(f"beta0 = {args.beta0:g}, mu = {args.mu:g}, N = {args.n} (dx = {g.dx:.5f}, dy = {g.dy:.5f}), "
          f"state at the two-axis pull-off approach {delta:+.5f}; load average {os.getloadavg()[0]:.1f}", flush=True)

    def cold(symmetric):
        prob = AdhesiveProblem(nd.initial_gap, g, nd.law, symmetric, None, 1.0)
        stress = np.clip(prob.to_work(nd.start_stress()), 0.0, nd.law.max_stress)
        return solve_problem(prob, delta, Prediction(np.zeros_like(prob.z), stress), solver.DEFAULT_TOL,
                             solver.DEFAULT_MAX_ITER)

    def report(name, st, wall, cpu, extra=""):
        print(f"  {name:15s} converged = {st.converged!s:5s} CG = {st.iterations:6d} outer = {st.outer_iterations:3d} "
              f"W = {st.load:+.6f}  wall {wall:6.1f} s  CPU {cpu:6.1f} s{extra}", flush=True)

    for v in args.variants:
        if v == "quadrant":
            report(v, *_timed(lambda: cold(True)))
        elif v == "full":
            report(v, *_timed(lambda: cold(False)))
        elif v == "no-box":
            keep = solver.ACTIVE_BOX_MAX_FRACTION
            solver.ACTIVE_BOX_MAX_FRACTION = 0.0
            try:
                report(v, *_timed(lambda: cold(True)))
            finally:
                solver.ACTIVE_BOX_MAX_FRACTION = keep
        elif v == "coarse-to-fine":
            coarse_nd = nd.coarser(args.n // 2)
            cprob = coarse_nd.adhesive_problem()
            cstress = np.clip(cprob.to_work(coarse_nd.start_stress()), 0.0, nd.law.max_stress)
            cst, cw, cc = _timed(lambda: solve_problem(cprob, delta, Prediction(np.zeros_like(cprob.z), cstress),
                                                       solver.DEFAULT_TOL, solver.DEFAULT_MAX_ITER))
            report(f"coarse N={args.n // 2}", cst, cw, cc, f"  (edge ratio {cprob.edge_width_ratio:.2f})")
            prob = nd.adhesive_problem()
            guess = interpolate_state(cst, g)
            report(v, *_timed(lambda: solve_problem(prob, delta, guess, solver.DEFAULT_TOL, solver.DEFAULT_MAX_ITER)),
                   "  (fine solve only)")
        elif v in ("neighbour", "dilated"):
            import math

            from dhfield.bem.pull_off import LOCATE_DIVISIONS, dilate_state

            prob = nd.adhesive_problem()
            base = cold(True)
            up = delta + nd.approach_step / LOCATE_DIVISIONS
            guess = base
            if v == "dilated":
                a, b = base.contact_semi_axes()
                m = math.sqrt(a * b)
                slope = 1.0 / (2.0 * m - 0.5 * math.sqrt(2.0 * math.pi / m))      # JKR sphere: da/d delta
                da = slope * (up - delta)
                guess = dilate_state(base, 1.0 + da / m, 1.0 + da / m)
            report(v, *_timed(lambda: solve_problem(prob, up, guess, solver.DEFAULT_TOL, solver.DEFAULT_MAX_ITER)),
                   f"  (state at {up:+.5f} from the one at {delta:+.5f})")
        else:
            p.error(f"unknown variant {v!r}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
