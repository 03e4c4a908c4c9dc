"""The prototype table of issue 38: the load-control pull-off by the Newton solver on two grids, against the path routes.

Each case runs in its own process (peak memory per case) under a wall-clock cap, by
:func:`dhfield.bem.ladder.ladder_pull_off`: the check grid and the answer's grid from
:func:`dhfield.bem.ladder.ladder_grids` (the planned grid at least, the edge resolved with the
margin), each grid's first state by nested iteration from the analytic cold start, the
load's minimum from parabolas through states warm-started along their exact tangents.  No
case has options of its own.

Columns: the two grids; states and Newton/GMRES iterations over both; wall and CPU time;
peak memory; W* on the answer's grid and its stated error; the reference (Maugis-Dugdale
for the sphere, else the stored truth of ``data/adhesive_ground_truth_extended.nc``) and the
deviation from it; the path routes' stored CPU time for the same case (its level-1 grid).  The
problem is the route's own (:func:`dhfield.analysis.bem_start.newton_problem`).

Usage::

    python -m verification.bench_ladder --cases sphere-1 sphere-5 20deg-1 --today
    python -m verification.bench_ladder --cases b0.4826-10 --threads 2 --json /tmp/rows.json
    python -m verification.bench_ladder --cases sphere-5 --margins 1 1.5
    python -m verification.bench_ladder --cases sphere-10 --start tangent
    python -m verification.bench_ladder --cases sphere-5 --n 544 720 960 1280
    python -m verification.bench_ladder --cases sphere-5 --target 2e-3 --refinements 2
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

from verification.bench_nested import _problem, _reference  # noqa: E402
from verification.bench_newton import CASES, run_today, stored  # noqa: E402


def _route_problem(beta0, mu, n=None):
    """The Newton route's problem (:func:`dhfield.analysis.bem_start.newton_problem`) on the planned or ``n`` cells."""
    from dhfield.analysis.bem_start import newton_problem

    ref = _problem(beta0, mu, n)           # the planned cell counts (or n with the planned cell shape)
    return newton_problem(beta0=beta0, mu=mu, n=ref.grid.nx, ny=ref.grid.ny)


def run(beta0, mu, margin, threads, log_path=None, start="nested", n=None, target=None, refinements=0):
    """One case in this process; return a JSON-ready dict."""
    from dhfield.bem import ladder

    out = open(log_path, "a") if log_path else sys.stderr

    def echo(line):
        print(line, file=out, flush=True)

    t0 = time.perf_counter()
    c0 = time.process_time()
    P = _route_problem(beta0, mu, n)
    nc, nf = ladder.ladder_grids(P, margin)
    echo(f"== beta0 {beta0} mu {mu} planned {P.grid.nx}x{P.grid.ny} grids {nc} -> {nf} margin {margin} start {start}")
    k = 2 ** 3
    fine = P.on_cells(nf, P.cells_y(nf, k))
    r = ladder.ladder_pull_off(fine, nc, edge_margin=margin, threads=threads, log=echo, start=start,
                               target_error=target, max_refinements=refinements)
    scale = P.sin_skew / (2.0 * math.pi)           # Eq. (34)
    return {"beta0": beta0, "mu": mu, "margin": margin, "start": start, "grids": [list(g.shape) for g in r.grids],
            "states": sum(g.states for g in r.grids),
            "newton": sum(g.newton_iterations for g in r.grids),
            "gmres": sum(g.krylov_iterations for g in r.grids),
            "W_star_check": r.coarse.load * scale, "W_star": r.load * scale, "stated_error": r.stated_error,
            "converged": r.converged, "reason": r.reason, "wall": time.perf_counter() - t0,
            "cpu": time.process_time() - c0,
            "maxrss_gib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20}


def _print_row(name, row):
    if "error" in row:
        print(f"{name:<12} {row['error']}")
        return
    ref, src = _reference(row["beta0"], row["mu"])
    old = stored(row["beta0"], row["mu"])
    dev = row["W_star"] / ref - 1.0 if math.isfinite(ref) else float("nan")
    grids = "->".join(f"{nx}x{ny}" for nx, ny in row["grids"])
    print(f"{name:<12} {row['margin']:>4} {grids:<22} {row['states']:>3} {row['newton']:>5}/{row['gmres']:<6} "
          f"{row['wall']:7.1f} {row['cpu']:7.1f} {row['maxrss_gib']:5.2f}  {row['W_star']:.6f} "
          f"{row['stated_error']:8.3%}  {ref:.6f} {src:<6} {dev:+.4%}   {old['stored_cpu']:8.0f} {old['stored_grid']}"
          + ("" if row["converged"] else f"  NOT converged ({row['reason']})"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="*", default=[c[0] for c in CASES], help="case names of bench_newton")
    ap.add_argument("--margins", nargs="*", type=float, default=[1.5], help="edge margins (dhfield.bem.ladder)")
    ap.add_argument("--threads", type=int, default=1, help="FFTW threads per case")
    ap.add_argument("--n", type=int, nargs="*", default=[None],
                    help="smallest answer grids (cells along x; default the planned grid)")
    ap.add_argument("--target", type=float, help="relative stated error wanted (refine the grids while above)")
    ap.add_argument("--refinements", type=int, default=0, help="cap on refinements for --target")
    ap.add_argument("--start", choices=("nested", "tangent"), default="nested",
                    help="start of the states after each grid's first (dhfield.bem.ladder.grid_minimum)")
    ap.add_argument("--timeout", type=float, default=1800.0, help="per case [s]")
    ap.add_argument("--log", help="append every state line here")
    ap.add_argument("--json", type=Path, help="write every row here")
    ap.add_argument("--today", action="store_true",
                    help="also run the path routes (adhesive_pull_off(search='located'), the default before the "
                         "Newton route) on each case, side by side")
    ap.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    ap.add_argument("--today-child", nargs=2, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.today_child:
        print(json.dumps(run_today(float(args.today_child[0]), float(args.today_child[1]))))
        return 0
    if args.child:
        b, m, g = args.child
        print(json.dumps(run(float(b), float(m), float(g), args.threads, args.log, args.start, args.n[0], args.target,
                             args.refinements)))
        return 0
    known = {c[0]: c for c in CASES}
    print(f"{'case':<12} {'marg':>4} {'grids':<22} {'st':>3} {'newton/gmres':<12} {'wall s':>7} {'cpu s':>7} "
          f"{'GiB':>5}  {'W*':>9} {'stated':>8}  {'ref':>9} {'src':<6} {'dev':>8}   {'today cpu s'} (grid)")
    rows = []
    for name in args.cases:
        _, beta0, mu = known[name]
        for g, n in ((g, n) for g in args.margins for n in args.n):
            cmd = [sys.executable, "-m", "verification.bench_ladder", "--threads", str(args.threads), "--start", args.start,
                   *(["--n", str(n)] if n else []), "--refinements", str(args.refinements),
                   *(["--target", repr(args.target)] if args.target else []),
                   "--child", repr(beta0), repr(mu), repr(g)] + (["--log", args.log] if args.log else [])
            env = dict(os.environ, DHFIELD_THREADS=str(args.threads))
            try:
                p = subprocess.run(cmd, stdout=subprocess.PIPE, text=True, timeout=args.timeout, cwd=ROOT, env=env)
                row = json.loads(p.stdout.strip().splitlines()[-1]) if p.returncode == 0 else {"error": f"exit {p.returncode}"}
            except subprocess.TimeoutExpired:
                row = {"error": f"over {args.timeout:.0f} s"}
            row.update(case=name)
            rows.append(row)
            _print_row(name, row)
            sys.stdout.flush()
        if args.today:
            cmd = [sys.executable, "-m", "verification.bench_ladder", "--today-child", repr(beta0), repr(mu)]
            env = dict(os.environ, DHFIELD_THREADS=str(args.threads))
            try:
                p = subprocess.run(cmd, stdout=subprocess.PIPE, text=True, timeout=args.timeout, cwd=ROOT, env=env)
                t = json.loads(p.stdout.strip().splitlines()[-1]) if p.returncode == 0 else {"error": f"exit {p.returncode}"}
            except subprocess.TimeoutExpired:
                t = {"error": f"over {args.timeout:.0f} s"}
            t.update(case=name, route="today")
            rows.append(t)
            if "error" in t:
                print(f"{'  today':<12} {t['error']}")
            else:
                print(f"{'  today':<12} {'':>4} {t['n']:<22} {'':>3} {t['iterations']:>5} CG      {t['wall']:7.1f} "
                      f"{t['cpu']:7.1f} {t['maxrss_gib']:5.2f}  {t['W_star']:.6f} "
                      f"{t['W_star_error'] / abs(t['W_star']):8.3%}" + ("" if t["converged"] else "  NOT converged"))
            sys.stdout.flush()
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))
    return 0 if all(r.get("converged") for r in rows if r.get("route") != "today") else 1


if __name__ == "__main__":
    sys.exit(main())
