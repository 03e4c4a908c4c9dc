"""Nested iteration (grid sequencing) of the semismooth Newton adhesive solve, against the single-grid solve.

Each run is its own process (peak memory per run).  A run solves one case on a ladder of
grids over the same domain, each halving the next one's cells per axis (``--levels 1``: the
target grid alone, from the analytic cold start).  The coarsest grid starts from the
analytic cold start (sigma0 on the predicted zone, the contact pressure it implies); each
finer grid from the coarser state prolonged (:func:`dhfield.bem.newton.prolong_state`).

``--kind state`` solves the first state (the analytic pull-off approach) by
:func:`dhfield.bem.newton.solve_state_nested`; ``--kind pull-off`` locates the load-control
pull-off by :func:`dhfield.bem.energy.pull_off_nested` (the zero of dW/d delta on every grid,
each grid's search started at the coarser grid's minimum) and compares W* with Maugis-Dugdale
(sphere) or the stored truth.

Usage::

    python -m verification.bench_nested --cases sphere-5 --levels 1 3
    python -m verification.bench_nested --cases b0.4826-10 --levels 3 --kind state --log /tmp/run.log
    python -m verification.bench_nested --cases sphere-1 sphere-5 --kind pull-off --levels 1 3
"""
from __future__ import annotations

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from verification.bench_newton import CASES, stored  # noqa: E402


def _problem(beta0, mu, n=None):
    from dhfield.analysis.bem_start import nondimensional_problem, plan_grid, predicted_problem

    plan = plan_grid(beta0=beta0, mu=mu)
    ny = getattr(plan, "ny", None) or plan.n
    if n is None:
        n = plan.n
    else:
        ny = max(8, 2 * round(ny * n / plan.n / 2))       # the planned cell shape
    try:
        return predicted_problem(beta0=beta0, mu=mu, n=n, ny=ny)
    except ValueError:
        return nondimensional_problem(beta0=beta0, mu=mu, n=n, ny=ny)


def run(beta0, mu, n, levels, kind, log_path=None, coarsest="plain", nonmonotone=4):
    """One run in this process; return a JSON-ready dict."""
    from dhfield.bem import energy, newton

    P = _problem(beta0, mu, n)
    out = open(log_path, "a") if log_path else sys.stderr

    def echo(line):
        print(line, file=out, flush=True)

    echo(f"== beta0 {beta0} mu {mu} grid {P.grid.nx}x{P.grid.ny} levels {levels} kind {kind}")
    t0 = time.perf_counter()
    ladder = newton.grid_ladder(P, levels, threads=int(os.environ.get("DHFIELD_THREADS", "1")))
    q0 = newton.cold_start(ladder[0], P.pull_off_approach, P.pull_off_zone)
    row = {"beta0": beta0, "mu": mu, "grids": [list(p.grid.shape) for p in ladder], "kind": kind, "coarsest": coarsest,
           "edge_ratio": ladder[-1].edge_width_ratio}
    if kind == "state":
        first = newton.solve_state_smoothed if coarsest == "smoothed" else None
        r = newton.solve_state_nested(ladder, P.pull_off_approach, q0, newton.SolverOptions(nonmonotone=nonmonotone),
                                      log=echo, coarsest_solve=first)
        row["levels"] = [{"newton": v.newton_iterations, "gmres": v.krylov_iterations, "wall": v.elapsed,
                          "residual": v.residual, "contact": v.contact_cells, "reason": v.reason} for v in r.levels]
        row.update(converged=r.converged, load=r.state.load)
    else:
        r = energy.pull_off_nested(ladder, P.pull_off_approach, q0, step=0.5 * P.approach_step,
                                   options=newton.SolverOptions(nonmonotone=nonmonotone), log=echo,
                                   first_solve=newton.solve_state_smoothed if coarsest == "smoothed" else None)
        scale = P.sin_skew / (2.0 * math.pi)        # Eq. (34)
        pre = r.first_state.levels[:-1]
        row["levels"] = [{"newton": v.newton_iterations, "gmres": v.krylov_iterations, "wall": v.elapsed,
                          "states": 0, "reason": v.reason} for v in pre]
        row["levels"] += [{"newton": v.newton_iterations, "gmres": v.krylov_iterations, "wall": v.elapsed,
                           "states": v.states, "W_star": v.load * scale, "approach": v.approach,
                           "reason": v.reason} for v in r.levels]
        if r.levels:                       # the first searched grid's first state came up the ladder
            v = r.first_state.levels[-1]
            row["levels"][len(pre)]["newton"] += v.newton_iterations
            row["levels"][len(pre)]["gmres"] += v.krylov_iterations
            row["levels"][len(pre)]["wall"] += v.elapsed
        if not r.levels:
            row["levels"].append({"newton": r.first_state.levels[-1].newton_iterations, "states": 0,
                                  "gmres": r.first_state.levels[-1].krylov_iterations, "wall": r.first_state.elapsed,
                                  "reason": r.first_state.state.reason})
        row.update(converged=bool(r.levels) and r.converged, W_star=r.load * scale if r.levels else float("nan"))
    row["wall"] = time.perf_counter() - t0
    row["maxrss_gib"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20
    return row


def _reference(beta0, mu):
    if beta0 == 1.0:
        from dhfield.models import maugis_dugdale

        return float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control="load").W_star), "MD"
    return stored(beta0, mu)["truth"], "stored"


def _print_row(name, row):
    if "error" in row:
        print(f"{name:<12} levels {row.get('nlevels', '?')}: {row['error']}")
        return
    grids = "->".join(f"{nx}x{ny}" for nx, ny in row["grids"])
    if row.get("coarsest") == "smoothed" and len(row["grids"]) > 1:
        grids += " (s)"
    work = " | ".join(f"{v['newton']}/{v['gmres']} {v['wall']:.1f}s" for v in row["levels"])
    line = f"{name:<12} {grids:<26} newton/gmres per level: {work:<44} {row['wall']:7.1f} s {row['maxrss_gib']:.2f} GiB"
    if row["kind"] == "state":
        v = row["levels"][-1]
        line += f"  residual {v['residual']:.1e} contact {v['contact']}  load {row['load']:.6f}"
    else:
        ref, src = _reference(row["beta0"], row["mu"])
        states = "+".join(str(v["states"]) if v["states"] else "s" for v in row["levels"])
        dev = row["W_star"] / ref - 1.0 if math.isfinite(ref) else float("nan")
        line += f"  states {states}  W* {row['W_star']:.6f} ref {ref:.6f} ({src}) {dev:+.4%}"
    print(line + ("" if row["converged"] else f"  NOT converged ({row['levels'][-1]['reason']})"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="*", default=["sphere-5", "20deg-1"], help="case names of bench_newton")
    ap.add_argument("--levels", nargs="*", type=int, default=[1, 3], help="grids per ladder (1: single grid)")
    ap.add_argument("--n", type=int, help="target cells along x (default: plan_grid's)")
    ap.add_argument("--kind", choices=("state", "pull-off"), default="state")
    ap.add_argument("--timeout", type=float, default=600.0, help="per run [s]")
    ap.add_argument("--log", help="append every Newton line here")
    ap.add_argument("--coarsest", choices=("plain", "smoothed"), default="plain",
                    help="the coarsest level's solve: solve_state or solve_state_smoothed (its global phase)")
    ap.add_argument("--json", type=Path, help="write every row here")
    ap.add_argument("--nonmonotone", type=int, default=4, help="SolverOptions.nonmonotone of every state")
    ap.add_argument("--child", nargs=4, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        b, m, n, lv = args.child
        print(json.dumps(run(float(b), float(m), None if n == "None" else int(n), int(lv), args.kind, args.log,
                             args.coarsest, args.nonmonotone)))
        return 0
    known = {c[0]: c for c in CASES}
    rows = []
    for name in args.cases:
        _, beta0, mu = known[name]
        for lv in args.levels:
            cmd = [sys.executable, "-m", "verification.bench_nested", "--kind", args.kind, "--coarsest", args.coarsest,
                   "--nonmonotone", str(args.nonmonotone),
                   "--child", repr(beta0), repr(mu), str(args.n), str(lv)] + (["--log", args.log] if args.log else [])
            try:
                p = subprocess.run(cmd, stdout=subprocess.PIPE, text=True, timeout=args.timeout, cwd=ROOT)
                row = json.loads(p.stdout.strip().splitlines()[-1]) if p.returncode == 0 else {"error": f"exit {p.returncode}"}
            except subprocess.TimeoutExpired:
                row = {"error": f"over {args.timeout:.0f} s"}
            row.update(case=name, nlevels=lv)
            rows.append(row)
            _print_row(name, row)
            sys.stdout.flush()
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
