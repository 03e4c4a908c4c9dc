"""The adhesive BEM at high mu with an automatic grid: W* against its reference, time and iterations (issue 20).

Runs :func:`dhfield.analysis.bem_start.adhesive_pull_off` without ``n`` (the grid of
:func:`dhfield.analysis.bem_start.plan_grid`) and prints, per case: N, the route, W*, its stated
error, ``converged``/``resolved``, the reference and the deviation from it, the fine states,
CG iterations (fine and coarse), wall and CPU seconds, and the load average.  The reference is
exact on the sphere (Maugis-Dugdale, :mod:`dhfield.models.maugis_dugdale`) and, for beta0 < 1, GVG
corrected by the sphere's MD/JKR ratio (:mod:`dhfield.models.md_elliptic`), the must-show
reference of issue 20.

``--route`` forces a route of the automatic grid: ``auto`` (what ``dhfield solve`` does),
or ``predicted`` (fine lattice samples around GVG's pull-off, :func:`dhfield.bem.pull_off.predicted_path`);
``--n`` another grid than the automatic one (same routes).  Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_high_mu --beta0 1 --mu 10
    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_high_mu --beta0 0.4826 --mu 10

Measured 2026-11-26 on the shared 2-core machine (CPU seconds and iteration counts compare; wall
seconds depend on the load):

* ``dhfield solve --beta0 0.4826 --mu 10`` (auto N = 1200, predicted route): W* = -0.644437 +- 0.016,
  converged and resolved, 3 fine states, 7733 CG, 366 s CPU (16:44 wall at load ~6); GVG x MD/JKR
  -0.644178: +0.04 %.  Before (N = 1440, the relaxed half grid stalling, then the fine bracket
  search): its first fine state alone took 669.5 s and 8443 CG; the command did not finish.
* ``--beta0 1 --mu 7.5`` (N = 640): W* = -0.751323 +- 0.015, MD +0.025 %, 4 fine states, 7399 CG
  (the 4th, an extension below the minimum towards the fold, 3271 CG / 169 outer), 104 s CPU.
* ``--beta0 1 --mu 5 --route predicted`` (N = 256): MD +0.13 %, 3 states, 1226 CG, 1.9 s CPU;
  ``--beta0 0.5 --mu 5 --route predicted`` (N = 288): +0.06 % of the stored N = 1024, 4.5 s CPU.
* ``dhfield solve --beta0 1 --mu 10`` (N = 1280) was stopped unfinished after 675 s CPU.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
import time


def reference(mu, beta0):
    """(name, W*) of the reference: MD on the sphere, GVG x MD/JKR otherwise."""
    from dhfield.models import jkr_elliptic_energy, maugis_dugdale

    md = float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control="load").W_star)
    if beta0 == 1.0:
        return "Maugis-Dugdale", md
    # GVG's exact-energy elliptical JKR times the sphere's MD/JKR ratio at the same mu (JKR sphere: -3/4)
    gvg = float(jkr_elliptic_energy.pull_off_nondimensional(beta0, mu, control="load").W_star)
    return "GVG x MD/JKR", gvg * md / -0.75


def run(mu, beta0, route, n=None, progress=False):
    """Solve one case by ``route``; returns (the BEM's dhfield.core.records.PullOff, wall s, CPU s)."""
    from dhfield.analysis import bem_start as ast
    from dhfield.bem.path import PathOptions

    t0, c0 = time.perf_counter(), time.process_time()
    if route == "auto":
        res = ast.adhesive_pull_off(mu=mu, beta0=beta0, n=n, progress=progress, search="located")   # (the path routes)
    else:
        n = n or ast.plan_grid(mu=mu, beta0=beta0, predicted=route == "predicted").n_needed
        opts = PathOptions(progress=progress)
        res = ast._predicted_pull_off(ast.predicted_problem(mu=mu, beta0=beta0, n=n), opts)
    return res, time.perf_counter() - t0, time.process_time() - c0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.bem_high_mu", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, default=1.0)
    p.add_argument("--mu", type=float, default=10.0)
    p.add_argument("--n", type=int, default=None, help="cells per axis (default: plan_grid's)")
    p.add_argument("--route", choices=("auto", "predicted"), default="auto")
    p.add_argument("--progress", action="store_true")
    args = p.parse_args(argv)
    load0 = os.getloadavg()[0]
    res, wall, cpu = run(args.mu, args.beta0, args.route, args.n, args.progress)
    name, ref = reference(args.mu, args.beta0)
    fine = int(res.iterations)
    coarse = int(getattr(res.path, "coarse_iterations", 0))
    print(f"beta0 = {args.beta0:g}, mu = {args.mu:g}, N = {res.n}, route {args.route} -> {res.search}: "
          f"W* = {res.W_star:.6f} +- {res.W_star_error:.2g} (converged {res.converged}, resolved {res.resolved}); "
          f"{name} {ref:.6f}: {100 * (res.W_star / ref - 1):+.3f} %; fine states {res.n_steps}, CG {fine} fine + "
          f"{coarse} coarse; wall {wall:.1f} s, CPU {cpu:.1f} s; load average {load0:.1f} -> {os.getloadavg()[0]:.1f}")
    if res.note:
        print("  note:", res.note)
    pa = res.path
    for k in range(len(pa.approach)):
        print(f"   state {k}: approach {pa.approach[k]:+.5f} load {pa.load[k]:+.6f} phase {pa.phase[k]} "
              f"converged {bool(pa.converged[k])} CG {int(pa.iterations[k])} outer {int(pa.outer_iterations[k])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
