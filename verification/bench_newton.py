"""Prototype table: the semismooth Newton adhesive solve (dhfield.bem.newton) against today's route.

Each case runs in its own process (peak memory per case), on the grid ``plan_grid`` chooses,
from the analytic start (the predicted route's cold start: sigma0 on the GVG x MD zone, the
contact pressure it implies) with no retry.  The load-control pull-off is the vertex of a
least-squares parabola through the loads of the states sampled around the minimum.

Today's route (``adhesive_pull_off``, the default search) is run side by side where it is
affordable (``--today``); otherwise its cost is the stored record's (level 1 of
``data/adhesive_ground_truth_extended.nc``: CG iterations, CPU seconds).

Usage::

    python -m verification.bench_newton                 # every case, prints the table
    python -m verification.bench_newton --cases sphere-1 sphere-5 --today
    python -m verification.bench_newton --json out.json
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
STORE = ROOT / "data" / "adhesive_ground_truth_extended.nc"
SLENDER = ROOT / "data" / "adhesive_ground_truth_slender.nc"

#: (name, beta0, mu): the issue's prototype cases.
CASES = [
    ("sphere-1", 1.0, 1.0),
    ("sphere-5", 1.0, 5.0),
    ("sphere-10", 1.0, 10.0),
    ("20deg-1", 0.108, 1.0),
    ("b0.1-10", 0.1, 10.0),
    ("b0.1806-10", 0.1806, 10.0),
    ("b0.3-10", 0.3, 10.0),
    ("b0.4826-10", 0.4826, 10.0),
    ("b0.5-10", 0.5, 10.0),
    ("b0.8-10", 0.8, 10.0),
]


def run_case(beta0, mu, n=None, ny=None, samples=7, method="smoothed", first_state=0):
    """Solve one case with the Newton solver; return a JSON-ready dict (in this process).

    ``first_state`` > 0: solve only the first state (at the analytic approach, from the analytic
    start), with at most that many Newton iterations, and return its residual history.
    """
    import numpy as np

    from dhfield.analysis.bem_start import nondimensional_problem, plan_grid, predicted_problem
    from dhfield.bem import newton

    plan = plan_grid(beta0=beta0, mu=mu, n=n)
    n = plan.n if n is None else n
    ny = getattr(plan, "ny", None) if ny is None else ny
    try:       # the predicted route's domain (GVG x MD zone, margin 1.15) ...
        P = predicted_problem(beta0=beta0, mu=mu, n=n, ny=ny)
    except ValueError:       # ... or the located route's, where that zone does not fit the planned domain
        P = nondimensional_problem(beta0=beta0, mu=mu, n=n, ny=ny)
    prob = P.adhesive_problem(threads=int(os.environ.get("DHFIELD_THREADS", "1")))
    t0 = time.perf_counter()
    c0 = time.process_time()
    q0 = newton.cold_start(prob, P.pull_off_approach, P.pull_off_zone)
    lines = []

    def echo(line):
        lines.append(line)
        print(line, file=sys.stderr, flush=True)

    if first_state:
        if method == "hybrid":
            from dhfield.bem import energy

            solve = energy.solve_state_hybrid
        else:
            solve = newton.solve_state if method == "plain" else newton.solve_state_smoothed
        st = solve(prob, P.pull_off_approach, q0, newton.SolverOptions(max_newton=first_state), log=echo)
        return {"method": method, "beta0": beta0, "mu": mu, "nx": P.grid.nx, "ny": P.grid.ny,
                "edge_ratio": prob.edge_width_ratio, "first_state": True, "converged": st.converged,
                "reason": st.reason, "residual": st.residual, "newton": st.newton_iterations,
                "gmres": st.krylov_iterations, "wall": time.perf_counter() - t0, "cpu": time.process_time() - c0,
                "maxrss_gib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20, "log": lines}
    if method == "hybrid":
        from dhfield.bem import energy

        res = energy.pull_off_search(prob, P.pull_off_approach, q0, step=0.5 * P.approach_step, log=echo)
        res.load_error = 0.0
    else:
        res = newton.load_minimum(prob, P.pull_off_approach, q0, half_window=0.5 * P.approach_step,
                                  samples=samples, log=lines.append, method=method)
    scale = P.sin_skew / (2.0 * math.pi)        # Eq. (34)
    return {
        "method": method, "beta0": beta0, "mu": mu, "nx": P.grid.nx, "ny": P.grid.ny, "edge_ratio": prob.edge_width_ratio,
        "W_star": res.load * scale, "W_star_fit_error": res.load_error * scale, "converged": res.converged,
        "reason": res.reason, "states": res.states, "newton": res.newton_iterations,
        "gmres": res.krylov_iterations, "wall": time.perf_counter() - t0, "cpu": time.process_time() - c0,
        "maxrss_gib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20, "log": lines,
        "approaches": [float(x) for x in res.approaches], "loads": [float(x) * scale for x in res.loads],
    }


def run_today(beta0, mu):
    """The path routes on the same case: ``adhesive_pull_off(search='located')`` (the default before the Newton route)."""
    from dhfield.analysis.bem_start import adhesive_pull_off

    t0 = time.perf_counter()
    c0 = time.process_time()
    r = adhesive_pull_off(beta0=beta0, mu=mu, search="located")
    return {"W_star": float(r.W_star), "W_star_error": float(r.W_star_error), "converged": bool(r.converged),
            "iterations": int(r.iterations), "wall": time.perf_counter() - t0, "cpu": time.process_time() - c0,
            "maxrss_gib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20, "n": int(r.n)}


def stored(beta0, mu):
    """The stored truth (W*, its error) and today's stored level-1 cost, or NaNs."""
    import xarray as xr

    nan = float("nan")
    out = {"truth": nan, "truth_error": nan, "stored_cpu": nan, "stored_iterations": nan, "stored_grid": ""}
    with xr.open_dataset(STORE) as ds:
        if beta0 in ds.beta0.values and mu in ds.mu.values:
            s = ds.sel(beta0=beta0, mu=mu)
            out.update(truth=float(s.W_star_truth), truth_error=float(s.W_star_truth_error),
                       stored_cpu=float(s.cpu_seconds.sel(level=1)),
                       stored_iterations=float(s.iterations.sel(level=1)),
                       stored_grid=f"{int(s.nx.sel(level=1))}x{int(s.ny.sel(level=1))}"
                       if math.isfinite(float(s.nx.sel(level=1))) else "")
    return out


def _child(args):
    kind, beta0, mu = args.child
    beta0, mu = float(beta0), float(mu)
    out = run_today(beta0, mu) if kind == "today" else run_case(beta0, mu, method=kind,
                                                                first_state=int(os.environ.get("BENCH_FIRST_STATE", "0")))
    print(json.dumps(out))


def _spawn(kind, beta0, mu, timeout):
    cmd = [sys.executable, "-m", "verification.bench_newton", "--child", kind, repr(beta0), repr(mu)]
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=None if os.environ.get("BENCH_STREAM") else subprocess.PIPE,
                           text=True, timeout=timeout, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return {"error": f"over {timeout} s"}
    if p.returncode:
        err = (p.stderr or "").strip()
        return {"error": err.splitlines()[-1] if err else f"exit {p.returncode}"}
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="*", default=[c[0] for c in CASES], help="case names (default: all)")
    ap.add_argument("--today", action="store_true", help="also run today's route side by side")
    ap.add_argument("--method", choices=("plain", "smoothed", "hybrid"), default="smoothed",
                    help="the state solve: dhfield.bem.newton.solve_state (plain), solve_state_smoothed, or "
                         "dhfield.bem.energy.solve_state_hybrid with the slope-zero search (hybrid)")
    ap.add_argument("--timeout", type=float, default=3600.0, help="per case and route [s]")
    ap.add_argument("--json", type=Path, help="write every row here")
    ap.add_argument("--first-state", type=int, default=0, metavar="N",
                    help="solve only the first state, with at most N Newton iterations, and print its history")
    ap.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        _child(args)
        return 0
    if args.first_state:
        os.environ["BENCH_FIRST_STATE"] = str(args.first_state)
    from dhfield.models import maugis_dugdale

    rows = []
    known = {c[0]: c for c in CASES}
    for name in args.cases:
        _, beta0, mu = known[name]
        row = {"case": name, **stored(beta0, mu)}
        row["new"] = _spawn(args.method, beta0, mu, args.timeout)
        if args.today:
            row["today"] = _spawn("today", beta0, mu, args.timeout)
        if beta0 == 1.0:
            row["md"] = float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control="load").W_star)
        rows.append(row)
        _print_row(row)
        sys.stdout.flush()
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    bad = [r["case"] for r in rows if not r["new"].get("converged")]
    if bad:
        print(f"not converged: {', '.join(bad)}", file=sys.stderr)
    return 1 if bad else 0


def _print_row(r):
    new = r["new"]
    if "error" in new:
        print(f"{r['case']:<12} new solver: {new['error']}")
        return
    if new.get("first_state"):
        print(f"{r['case']:<12} {new['nx']:>5}x{new['ny']:<5} first state ({new['method']}, edge ratio "
              f"{new['edge_ratio']:.2f}): {new['reason']} after {new['newton']} Newton / {new['gmres']} GMRES iterations,"
              f" residual {new['residual']:.2e}, {new['wall']:.0f} s wall {new['cpu']:.0f} s cpu {new['maxrss_gib']:.2f} GiB")
        for line in new["log"]:
            print(f"{'':<14}{line}")
        return
    ref = r.get("md", r["truth"])
    dev = new["W_star"] / ref - 1.0 if math.isfinite(ref) else float("nan")
    sig = abs(new["W_star"] - r["truth"]) / r["truth_error"] if math.isfinite(r["truth_error"]) else float("nan")
    line = (f"{r['case']:<12} {new['nx']:>5}x{new['ny']:<5} W* {new['W_star']:.6f} +- {new['W_star_fit_error']:.1e}"
            f"  ref {ref:.6f} ({'MD' if 'md' in r else 'stored'}) {dev:+.4%}  |new-stored|/err {sig:.2f}"
            f"  states {new['states']:>2} newton {new['newton']:>4} gmres {new['gmres']:>5}"
            f"  {new['wall']:7.1f} s wall {new['cpu']:7.1f} s cpu {new['maxrss_gib']:.2f} GiB"
            f"  {'converged' if new['converged'] else new['reason']}")
    print(line)
    if "today" in r:
        t = r["today"]
        if "error" in t:
            print(f"{'':<12} today's route: {t['error']}")
        else:
            print(f"{'':<12} today's route: n {t['n']} W* {t['W_star']:.6f} +- {t['W_star_error']:.1e}  CG {t['iterations']}"
                  f"  {t['wall']:.1f} s wall {t['cpu']:.1f} s cpu {t['maxrss_gib']:.2f} GiB"
                  f"  {'converged' if t['converged'] else 'NOT converged'}")
    elif math.isfinite(r["stored_cpu"]):
        print(f"{'':<12} today's route (stored level 1, {r['stored_grid']}): CG {r['stored_iterations']:.0f}, "
              f"{r['stored_cpu']:.0f} s cpu")


if __name__ == "__main__":
    sys.exit(main())
