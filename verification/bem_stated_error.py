"""The stated error of every BEM route against Maugis-Dugdale on the sphere (issue 42, findings 2-3).

Prints one table, the sphere (beta0 = 1, Dugdale law) at Tabor parameters mu and grids of
n x n cells, for the three routes of ``dhfield solve``:

* load control (``adhesive_pull_off(..., control="load")``) against the minimum of the MD load
  (:func:`dhfield.models.maugis_dugdale.pull_off_nondimensional`, Maugis 1992,
  doi:10.1016/0021-9797(92)90288-C);
* displacement control (``control="displacement"``) against the minimum of the MD approach, or
  its end a = 0 (the same function, ``control="displacement"``);
* a machine spring of stiffness K* (``dhfield solve --machine-stiffness K*``: the branch of
  :func:`dhfield.analysis.bem_spring.bem_unloading_branch`, the grid half as fine of
  :func:`dhfield.analysis.bem_spring.coarse_branch` where the jump is bracketed, and the record of
  :func:`dhfield.cli.solve.spring_record`) against MD's jump under the same spring
  (:func:`dhfield.analysis.spring.pull_off_under_spring`, model 'md': the first minimum of the
  machine position along MD's load-approach curve, continued on its separated branch).

Each case gets the exit status ``dhfield solve`` gives it (0 converged and resolved; 3 not
converged; 4 unresolved; 5 refused before solving: n far too coarse for the Dugdale edge), by
the same checks.  For every exit-0 case the table shows |W* - W*_MD| / W_star_error, the
ratio of the actual error to the stated one (<= 1: the answer is within its stated error).
The summary gives the exit-0 count per route, how many lie outside their stated error, and
the worst ratio; the script exits 1 when any exit-0 case lies outside, or fewer than
``--min-cases`` exit-0 cases were run.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_stated_error          # every route (~15 min)
    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_stated_error --controls spring --n 64 96 --mu 1
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
import warnings

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # before numpy: threaded BLAS stalls on a loaded machine

import numpy as np  # noqa: E402

from dhfield.analysis import spring as compliance
from dhfield.models import maugis_dugdale  # noqa: E402
from dhfield.analysis.bem_start import adhesive_pull_off, plan_grid  # noqa: E402
from dhfield.analysis.bem_spring import bem_pull_off_under_spring, bem_unloading_branch, coarse_branch  # noqa: E402
from dhfield.cli.solve import EXIT_UNCONVERGED, EXIT_UNRESOLVABLE, EXIT_UNRESOLVED, spring_record  # noqa: E402

MUS = (0.3, 0.5, 1.0, 2.0, 3.0, 5.0)
GRIDS = (32, 48, 64, 96, 128, 192, 256)
#: Grids of the spring cases (each solves two branches per grid, one serves every K*).
SPRING_GRIDS = (32, 48, 64, 96, 128)
STIFFNESSES = (0.0, 0.1, 1.0, 10.0)
CONTROLS = ("load", "displacement", "spring")
#: Fewest exit-0 cases for a pass (issue 42: "over at least 60 exit-0 cases").
MIN_CASES = 60


def _exit_status(converged, resolved) -> int:
    """The exit status of ``dhfield solve`` for a solved case."""
    return 0 if converged and resolved else EXIT_UNCONVERGED if not converged else EXIT_UNRESOLVED


def control_cases(control, mu, n):
    """One row (dict) of a load- or displacement-control case, as ``dhfield solve --n n --control control``."""
    t0 = time.perf_counter()
    ref = float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control=control).W_star)
    row = {"control": control, "K": float("nan"), "mu": mu, "n": n, "ref": ref}
    if plan_grid(beta0=1.0, mu=mu, n=n, control=control).too_coarse:
        return [{**row, "exit": EXIT_UNRESOLVABLE, "W": float("nan"), "err": float("inf"), "t": 0.0}]
    try:
        res = adhesive_pull_off(beta0=1.0, mu=mu, n=n, control=control, threads=1)
    except RuntimeError:
        return [{**row, "exit": EXIT_UNCONVERGED, "W": float("nan"), "err": float("inf"),
                 "t": time.perf_counter() - t0}]
    return [{**row, "exit": _exit_status(res.converged, res.resolved), "W": float(res.W_star),
             "err": float(res.W_star_error), "t": time.perf_counter() - t0}]


def spring_cases(mu, n, stiffnesses):
    """Rows of the spring cases at (mu, n), one per K*, as ``dhfield solve --n n --machine-stiffness K*``."""
    t0 = time.perf_counter()
    refs = [float(compliance.pull_off_under_spring("md", beta0=1.0, mu=mu, machine_stiffness=k)["W_star"])
            for k in stiffnesses]
    rows = [{"control": "spring", "K": k, "mu": mu, "n": n, "ref": r} for k, r in zip(stiffnesses, refs)]
    if plan_grid(beta0=1.0, mu=mu, n=n, control="spring", machine_stiffness=0.0).too_coarse:
        return [{**r, "exit": EXIT_UNRESOLVABLE, "W": float("nan"), "err": float("inf"), "t": 0.0} for r in rows]
    try:
        branch = bem_unloading_branch(beta0=1.0, mu=mu, n=n, threads=1)
    except RuntimeError:
        return [{**r, "exit": EXIT_UNCONVERGED, "W": float("nan"), "err": float("inf"),
                 "t": time.perf_counter() - t0} for r in rows]
    coarse, built = None, False
    out = []
    for r, k in zip(rows, stiffnesses):
        if bool(bem_pull_off_under_spring(branch, k).resolved) and not built:   # as the CLI: only when bracketed
            coarse, built = coarse_branch(branch, threads=1), True
        rec = spring_record(branch, k, None, coarse if bool(bem_pull_off_under_spring(branch, k).resolved) else None)
        out.append({**r, "exit": _exit_status(rec["converged"], rec["resolved"]), "W": rec["W_star"],
                    "err": rec["W_star_error"], "t": time.perf_counter() - t0})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--controls", nargs="+", choices=CONTROLS, default=list(CONTROLS), help="routes to run")
    ap.add_argument("--mu", type=float, nargs="+", default=list(MUS), help="Tabor parameters")
    ap.add_argument("--n", type=int, nargs="+", default=None,
                    help=f"grids (default {GRIDS}; for the spring {SPRING_GRIDS})")
    ap.add_argument("--k", type=float, nargs="+", default=list(STIFFNESSES), help="spring stiffnesses K*")
    ap.add_argument("--min-cases", type=int, default=MIN_CASES, help="fewest exit-0 cases for a pass")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore", RuntimeWarning)
    print("BEM stated error against Maugis-Dugdale, sphere (beta0 = 1, Dugdale law), 1 thread")
    head = (f"{'control':>12} {'K*':>5} {'mu':>4} {'n':>4} {'exit':>4} {'W* BEM':>10} {'W* MD':>10} "
            f"{'|error|':>9} {'stated':>9} {'ratio':>6} {'s':>6}")
    print(head)
    print("-" * len(head))
    rows = []
    t_all = time.perf_counter()
    for control in args.controls:
        grids = args.n or (SPRING_GRIDS if control == "spring" else GRIDS)
        for n in grids:
            for mu in args.mu:
                new = (spring_cases(mu, n, args.k) if control == "spring" else control_cases(control, mu, n))
                for r in new:
                    r["actual"] = abs(r["W"] - r["ref"])
                    r["ratio"] = r["actual"] / r["err"] if r["exit"] == 0 and r["err"] > 0 else float("nan")
                    k = "-" if math.isnan(r["K"]) else f"{r['K']:g}"
                    ratio = f"{r['ratio']:6.2f}" if r["exit"] == 0 else "     -"
                    print(f"{r['control']:>12} {k:>5} {r['mu']:>4g} {r['n']:>4} {r['exit']:>4} {r['W']:>10.5f} "
                          f"{r['ref']:>10.5f} {r['actual']:>9.2e} {r['err']:>9.2e} {ratio} {r['t']:>6.1f}",
                          flush=True)
                rows.extend(new)
    print("-" * len(head))
    ok = [r for r in rows if r["exit"] == 0]
    outside = [r for r in ok if not r["actual"] <= r["err"]]
    for control in args.controls:
        mine = [r for r in ok if r["control"] == control]
        worst = max((r["ratio"] for r in mine), default=float("nan"))
        print(f"{control:>12}: {len(mine)} exit-0 of {sum(r['control'] == control for r in rows)} cases, "
              f"{sum(not r['actual'] <= r['err'] for r in mine)} outside their stated error, worst ratio {worst:.3f}")
    worst = max(ok, key=lambda r: r["ratio"], default=None)
    if worst is not None:
        print(f"all routes: {len(ok)} exit-0 cases, {len(outside)} outside their stated error; worst ratio of actual "
              f"to stated error {worst['ratio']:.3f} ({worst['control']}, K* = {worst['K']:g}, mu = {worst['mu']:g}, "
              f"n = {worst['n']}); {time.perf_counter() - t_all:.0f} s")
    passed = not outside and len(ok) >= args.min_cases
    print("PASS" if passed else f"FAIL ({len(outside)} outside; {len(ok)} exit-0 cases, {args.min_cases} wanted)")
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
