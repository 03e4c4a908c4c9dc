"""The bordered Newton solve's GMRES tolerance (``dhfield.bem.newton.BORDERED_FORCING``) over several branches.

The continuation in adhesive force (:func:`dhfield.bem.newton.solve_state_at_force`) solves each
Newton step's two linear systems to a relative tolerance of at most ``BORDERED_FORCING``.  This
script samples whole unloading branches at prescribed adhesive force
(:func:`dhfield.analysis.bem_spring.bem_unloading_branch`, the states of displacement control
and of the machine spring) with the constant set to each value given, and prints per branch and
value: the states that did not converge, the GMRES iterations of the branch, its CPU seconds, and the load minimum W*min of the converged states.  A value is
acceptable where every state of every branch converges; the library's is kept a factor 10 inside
that range (a margin for branches not sampled here), and the script exits 1 when a branch at the
library's value has an unconverged state.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.bench_bordered_forcing        # ~1 min
"""
from __future__ import annotations

import argparse
import math
import time

#: (beta0, mu, n): branches of the sphere and of ellipses, on both sides of the transition.
CASES = ((1.0, 0.3, 64), (1.0, 1.0, 96), (1.0, 3.0, 128), (0.5, 2.0, 64), (0.5, 1.0, 96), (0.3, 1.0, 96))


def main(argv=None) -> int:
    import numpy as np

    import dhfield.bem.newton as newton
    from dhfield.analysis.bem_spring import bem_unloading_branch

    p = argparse.ArgumentParser(prog="python -m verification.bench_bordered_forcing",
                                description=__doc__.split("\n")[0])
    p.add_argument("--values", type=float, nargs="+", default=[1e-1, 1e-2, 1e-3, 1e-4])
    args = p.parse_args(argv)
    real = newton.BORDERED_FORCING
    print(f"(the library's value: {real:g})")
    print(f"{'beta0':>6} {'mu':>5} {'n':>4} {'forcing':>8} {'unconv':>6} {'states':>6} "
          f"{'gmres':>7} {'cpu s':>6} {'W*min':>10}")
    worst = {}
    try:
        for beta0, mu, n in CASES:
            for value in args.values:
                newton.BORDERED_FORCING = value
                t0 = time.process_time()
                br = bem_unloading_branch(beta0=beta0, mu=mu, n=n)
                cpu = time.process_time() - t0
                w = float(np.min(br.W_star)) if np.size(br.W_star) else math.nan
                states = int(np.size(br.adhesive_force)) + int(br.failures)
                print(f"{beta0:6g} {mu:5g} {n:4d} {value:8.0e} {br.failures:6d} {states:6d} "
                      f"{br.iterations:7d} {cpu:6.2f} {w:10.6f}")
                worst[value] = worst.get(value, 0) + int(br.failures)
    finally:
        newton.BORDERED_FORCING = real
    print("unconverged states over every branch: " + ", ".join(f"{v:g}: {k}" for v, k in worst.items()))
    return 1 if worst.get(real, 0) else 0


if __name__ == "__main__":
    raise SystemExit(main())
