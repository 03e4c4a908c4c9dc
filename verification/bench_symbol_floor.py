"""The floored symbol preconditioner against the plain one: the nested first state, side by side.

For each case the first state (the analytic pull-off approach, from the analytic start) is solved
by :func:`dhfield.bem.newton.solve_state_nested` twice, with ``SolverOptions.symbol_floor`` off and
on; the table gives the stop reason, Newton and GMRES iterations, the load and the wall time.

Usage::

    python -m verification.bench_symbol_floor            # 20 deg mu = 1, sphere mu = 5, beta0 = 0.3 mu = 5
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

#: (beta0, mu, n or None for plan_grid's choice)
CASES = [(0.108, 1.0, None), (1.0, 5.0, 320), (0.3, 5.0, 400)]


def main(argv=None) -> int:
    from dhfield.bem import newton
    from verification.bench_nested import _problem

    print(f"{'beta0':>6} {'mu':>4} {'grid':>9} {'symbol':>7} {'reason':>20} {'newton':>6} {'gmres':>6} "
          f"{'load':>12} {'wall':>6}")
    for beta0, mu, n in CASES:
        prob = _problem(beta0, mu, n)
        ladder = newton.grid_ladder(prob, 2 if prob.grid.ny % 8 else 3, threads=1)
        first = newton.solve_state_smoothed if beta0 < 0.2 else None   # plain Newton fails cold at 20 deg
        for floor in (False, True):
            q0 = newton.cold_start(ladder[0], prob.pull_off_approach, prob.pull_off_zone)
            opts = newton.SolverOptions(nonmonotone=4, symbol_floor=floor)
            t0 = time.perf_counter()
            st = newton.solve_state_nested(ladder, prob.pull_off_approach, q0, opts, coarsest_solve=first).state
            print(f"{beta0:6.3f} {mu:4g} {prob.grid.nx:>4}x{prob.grid.ny:<4} {'floor' if floor else 'plain':>7} "
                  f"{st.reason:>20} {st.newton_iterations:6d} {st.krylov_iterations:6d} {st.load:12.8f} "
                  f"{time.perf_counter() - t0:5.1f}s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
