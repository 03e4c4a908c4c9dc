"""The path routes by the one solver, side by side with any other commit's (issue 38).

Prints one row per case: the route (``located``, ``bracket``, ``march``, ``predicted`` of
:func:`dhfield.bem.adhesive_pull_off` with an explicit grid, displacement control, and the
machine spring of :mod:`dhfield.analysis.bem_spring`), W* and its stated error, and, on the
sphere, Maugis-Dugdale's W* (Maugis 1992, doi:10.1016/0021-9797(92)90288-C; under the same
spring: :func:`dhfield.analysis.spring.pull_off_under_spring`) with |W* - W*_MD| / stated; the
CPU seconds, the states and the iterations of the states (GMRES iterations since the one solver,
conjugate-gradient iterations of the former fixed point before it).  Run it here and in a
checkout of another commit (e.g. ``git worktree add ../old fc5636a``, then
``PYTHONPATH=../old python -m verification.bench_one_solver`` from there) on the same
machine, one after the other.  Exits 1 when a sphere case's answer lies outside its stated error.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.bench_one_solver          # ~1 min
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import time

#: (label, beta0, mu, n, route): route is a load-control search, 'displacement', or 'spring:K*'.
CASES = (
    ("sphere", 1.0, 1.0, 128, "located"),
    ("sphere", 1.0, 3.0, 256, "located"),
    ("sphere", 1.0, 2.0, 128, "predicted"),
    ("60 deg", 0.5, 1.0, 128, "bracket"),
    ("60 deg", 0.5, 0.3, 96, "march"),
    ("30 deg", 0.1806, 1.0, 256, "located"),
    ("sphere", 1.0, 1.0, 96, "displacement"),
    ("sphere", 1.0, 0.3, 64, "displacement"),
    ("sphere", 1.0, 1.0, 64, "spring:1"),
)


def _case(beta0, mu, n, route):
    from dhfield.analysis.bem_start import adhesive_pull_off
    from dhfield.models import maugis_dugdale

    if route.startswith("spring:"):
        from dhfield.analysis import spring
        from dhfield.analysis.bem_spring import bem_pull_off_under_spring, bem_unloading_branch

        k = float(route.split(":")[1])
        br = bem_unloading_branch(beta0=beta0, mu=mu, n=n)
        rec = bem_pull_off_under_spring(br, k)
        ref = (float(spring.pull_off_under_spring("md", beta0=1.0, mu=mu, machine_stiffness=k)["W_star"])
               if beta0 == 1.0 else float("nan"))
        return float(rec["W_star"]), float(rec["W_star_error"]), ref, len(br.W_star) + br.failures, -1
    control = "displacement" if route == "displacement" else "load"
    kw = {} if control == "displacement" else {"search": route}
    r = adhesive_pull_off(beta0=beta0, mu=mu, n=n, control=control, threads=1, progress=False, **kw)
    ref = (float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control=control).W_star)
           if beta0 == 1.0 else float("nan"))
    return float(r.W_star), float(r.W_star_error), ref, int(r.n_steps), int(r.iterations)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.bench_one_solver", description=__doc__.split("\n")[0])
    p.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    print(f"commit {commit}")
    print(f"{'case':8s} {'beta0':>6s} {'mu':>4s} {'n':>4s} {'route':13s} {'W*':>10s} {'stated':>8s} {'MD':>10s} "
          f"{'dev/st':>6s} {'cpu s':>6s} {'states':>6s} {'iter':>7s}")
    bad = 0
    for label, beta0, mu, n, route in CASES:
        c0 = time.process_time()
        w, e, ref, states, it = _case(beta0, mu, n, route)
        cpu = time.process_time() - c0
        ratio = abs(w - ref) / e if ref == ref and e > 0 else float("nan")
        bad += ratio > 1.0
        print(f"{label:8s} {beta0:6g} {mu:4g} {n:4d} {route:13s} {w:10.6f} {e:8.2e} {ref:10.6f} {ratio:6.2f} "
              f"{cpu:6.1f} {states:6d} {it:7d}", flush=True)
    print(f"sphere cases outside their stated error: {bad}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
