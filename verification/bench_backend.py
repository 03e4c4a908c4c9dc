"""The BEM on another array backend (dhfield.bem.backend): the same answers, and what it costs.

Three stages, each printed with its differences and timings, each run even if an earlier one
failed (a traceback is printed and the exit status is 1):

1. ``operator``: the DC-FFT operator of the backend against the pyfftw one (random pressures, full
   grid and symmetric quadrant): largest difference relative to the largest displacement, time
   per call of each (side by side, same process).
2. ``state``: the predicted (high-mu) route's cold state of ``--beta0``, ``--mu`` on ``--n`` cells
   (:func:`dhfield.bem.pull_off.predicted_path`'s start), solved on both backends: load,
   iterations, wall time.  Skipped with ``--skip-reference`` on the fftw side.
3. ``pull-off`` (``--pull-off``): :func:`dhfield.bem.adhesive_pull_off` of each ``--pull-off``
   case on the backend (automatic grid unless ``--n``), its W* and stated error beside the
   recommended analytic model.

Usage::

    .venv/bin/python -m verification.bench_backend --backend numpy --beta0 1 --mu 3 --n 256
    # on a machine with a GPU and CuPy
    python -m verification.bench_backend --backend cupy --beta0 1 --mu 10 --n 1280 --pull-off 1:10

The ``numpy`` backend runs the same code as ``cupy`` on the CPU: the comparison with fftw is
then a check of the array code path, not a speed-up.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
import time
import traceback

import numpy as np


def _sync(xp):
    if xp is not np:
        xp.cuda.Device().synchronize()


def stage_operator(backend, threads) -> None:
    from dhfield.bem.backend import to_host
    from dhfield.bem.operator import Grid, get_operator

    rng = np.random.default_rng(20)
    for n, ny, sym in ((256, 256, True), (512, 128, True), (256, 256, False), (2048, 2048, True)):
        g = Grid(n, ny, 1.0 / n, 1.0 / n)
        ref = get_operator(g, symmetric=sym, threads=threads, backend="fftw")
        op = get_operator(g, symmetric=sym, threads=threads, backend=backend)
        p = rng.random(ref.input_shape)
        u_ref = ref(p)
        pd = op.xp.asarray(p)
        u = to_host(op(pd))
        err = float(np.abs(u - u_ref).max() / np.abs(u_ref).max())
        reps = 5
        t0 = time.perf_counter()
        for _ in range(reps):
            ref(p)
        t_ref = (time.perf_counter() - t0) / reps
        op(pd)
        _sync(op.xp)
        t0 = time.perf_counter()
        for _ in range(reps):
            op(pd)
        _sync(op.xp)
        t_op = (time.perf_counter() - t0) / reps
        print(f"  operator {n} x {ny} {'quadrant' if sym else 'full    '}: max |du|/max|u| = {err:.2e}  "
              f"fftw {1e3 * t_ref:8.2f} ms  {backend} {1e3 * t_op:8.2f} ms  ratio {t_ref / t_op:6.2f}", flush=True)
        if not err < 1e-12:
            raise AssertionError(f"operator {n} x {ny}: the backends differ by {err:.2e} (> 1e-12)")


def stage_state(backend, beta0, mu, n, threads, skip_reference) -> None:
    from dhfield.analysis.bem_start import plan_grid, predicted_problem
    from dhfield.bem import solver

    # the predicted route's first state: the lattice sample nearest the predicted pull-off
    plan = plan_grid(mu=mu, beta0=beta0)
    problem = predicted_problem(mu=mu, beta0=beta0, n=plan.n_needed if n is None else n,
                                ny=plan.ny_needed if n is None else None)
    delta = problem.lattice_approach(problem.pull_off_approach)
    g = problem.grid
    print(f"  state: beta0 = {beta0:g}, mu = {mu:g}, {g.nx} x {g.ny} cells, approach {delta:+.6f}, "
          f"tol {solver.DEFAULT_TOL:g}", flush=True)
    loads = {}
    for b in ((backend,) if skip_reference else ("fftw", backend)):
        os.environ["DHFIELD_BEM_BACKEND"] = b
        prob = problem.adhesive_problem(threads)
        cold = problem.path_start(prob).stress
        t0 = time.perf_counter()
        st = solver.solve_problem(prob, delta, solver.Prediction(np.zeros_like(cold), cold.copy()), solver.DEFAULT_TOL,
                                  solver.DEFAULT_MAX_ITER)
        wall = time.perf_counter() - t0
        loads[b] = st.load
        print(f"    {b:6s} converged = {st.converged!s:5s} Newton = {st.outer_iterations:3d} GMRES = {st.iterations:6d} "
              f"residual = {st.residual:.2g}  W = {st.load:+.8f}  wall {wall:7.1f} s", flush=True)
    if len(loads) == 2:
        rel = abs(loads[backend] - loads["fftw"]) / abs(loads["fftw"])
        print(f"    |dW|/|W| = {rel:.2e} between the backends", flush=True)


def stage_pull_off(backend, cases, n, threads) -> None:
    from dhfield.analysis.bem_start import adhesive_pull_off
    from dhfield.models.md_elliptic import pull_off_nondimensional

    os.environ["DHFIELD_BEM_BACKEND"] = backend
    for case in cases:
        beta0, mu = (float(v) for v in case.split(":"))
        t0 = time.perf_counter()
        rec = adhesive_pull_off(beta0=beta0, mu=mu, n=n, threads=threads)
        wall = time.perf_counter() - t0
        ana = float(pull_off_nondimensional(beta0, mu).W_star)
        print(f"  pull-off beta0 = {beta0:g}, mu = {mu:g} ({rec.n} cells along x): W* = {float(rec.W_star):+.6f} "
              f"+- {rec.W_star_error:.2g}  converged = {rec.converged}  (md-elliptic {ana:+.6f}, "
              f"{100 * (ana / rec.W_star - 1):+.3f} %)  wall {wall:.1f} s", flush=True)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.bench_backend", description=__doc__.split("\n")[0])
    p.add_argument("--backend", default="numpy", choices=["numpy", "cupy"])
    p.add_argument("--beta0", type=float, default=1.0)
    p.add_argument("--mu", type=float, default=3.0)
    p.add_argument("--n", type=int, default=256, help="cells along x of the state stage (default 256)")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--skip-reference", action="store_true", help="state stage: the backend only")
    p.add_argument("--pull-off", nargs="*", default=[], metavar="BETA0:MU", help="pull-off cases (stage 3)")
    p.add_argument("--pull-off-n", type=int, default=None, help="cells along x of stage 3 (default automatic)")
    p.add_argument("--stages", nargs="+", default=["operator", "state", "pull-off"],
                   choices=["operator", "state", "pull-off"])
    args = p.parse_args(argv)
    failed = 0
    stages = {"operator": lambda: stage_operator(args.backend, args.threads),
              "state": lambda: stage_state(args.backend, args.beta0, args.mu, args.n, args.threads,
                                           args.skip_reference),
              "pull-off": lambda: stage_pull_off(args.backend, args.pull_off, args.pull_off_n, args.threads)}
    for name in args.stages:
        if name == "pull-off" and not args.pull_off:
            continue
        print(f"[{name}] backend {args.backend}", flush=True)
        try:
            stages[name]()
        except Exception:          # report and go on to the next stage
            traceback.print_exc()
            sys.stdout.flush()
            failed = 1
    return failed


if __name__ == "__main__":
    sys.exit(main())
