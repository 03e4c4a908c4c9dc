"""Speed and memory of the DC-FFT operator (dhfield.bem), measured side by side in one run.

Prints, for one displacement evaluation on an N = 1024 grid (N x N cells, padded
to 2048^2):

* the time of ``HalfSpaceOperator`` (full grid) divided by the time of a raw
  pyfftw ``rfft2`` + ``irfft2`` pair on the 2048^2 padded grid (FFTW plans built
  beforehand with the same planner effort and threads, ``execute()`` only);
  target <= 1.15;
* the same ratio for the even-even symmetry mode (quadrant in, quadrant out);
  target <= 0.5;
* the time of the full-grid operator divided by ContactMechanics'
  ``FreeFFTElasticHalfSpace.evaluate_disp`` on the same grid (optional
  benchmark extra ``bench``); target <= 0.35;
* the peak memory of building and applying the operator at N = 2048, in fresh
  subprocesses (tracemalloc peak of the Python/numpy allocations and the
  process's peak resident set size, VmHWM from /proc/self/status).

Each timing is the median of ``--repeats`` calls, with the methods interleaved
round by round so that they see the same machine state.

Usage::

    .venv/bin/python verification/bench_bem.py [--n 1024] [--threads 1] [--repeats 21]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np
import pyfftw

from dhfield import bem
from dhfield.analysis import field_sampling

TARGET_RAW = 1.15
TARGET_SYMMETRIC = 0.5
TARGET_CONTACTMECHANICS = 0.35

_MEMORY_SCRIPT = r"""
import json, sys, tracemalloc
import numpy as np
from dhfield import bem

def hwm():
    # VmHWM: peak resident set size of this process image (reset by exec, unlike ru_maxrss)
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")

n, symmetric, threads = int(sys.argv[1]), sys.argv[2] == "1", int(sys.argv[3])
grid = bem.Grid.centered(n, 2.0)
p = np.ones(grid.quadrant_grid_shape() if symmetric else grid.shape)
before = hwm()
tracemalloc.start()
op = bem.HalfSpaceOperator(grid, symmetric=symmetric, threads=threads)
u = op(p)
peak = tracemalloc.get_traced_memory()[1]
steady = tracemalloc.get_traced_memory()[0]
tracemalloc.stop()
print(json.dumps({"tracemalloc_peak_MiB": peak / 2**20, "tracemalloc_steady_MiB": steady / 2**20,
                  "hwm_MiB": hwm(), "hwm_before_MiB": before}))
"""


def _memory(n, symmetric, threads):
    res = subprocess.run([sys.executable, "-c", _MEMORY_SCRIPT, str(n), "1" if symmetric else "0", str(threads)],
                         capture_output=True, text=True, timeout=600, env=dict(os.environ))
    if res.returncode != 0:
        raise RuntimeError(res.stderr)
    return json.loads(res.stdout)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--repeats", type=int, default=21)
    ap.add_argument("--memory-n", type=int, default=2048)
    args = ap.parse_args(argv)
    n, thr = args.n, args.threads
    effort = "FFTW_MEASURE"

    grid = bem.Grid.centered(n, 2.0)
    p = field_sampling.hertz_pressure(grid, 1.0, 0.7)
    pq = bem.quadrant(p)

    t0 = time.perf_counter()
    full = bem.HalfSpaceOperator(grid, threads=thr, planner_effort=effort)
    t_build_full = time.perf_counter() - t0
    t0 = time.perf_counter()
    sym = bem.HalfSpaceOperator(grid, symmetric=True, threads=thr, planner_effort=effort)
    t_build_sym = time.perf_counter() - t0

    # the raw pair: plans on the padded grid, execute() only
    rin = pyfftw.empty_aligned((2 * n, 2 * n), dtype="float64")
    cplx = pyfftw.empty_aligned((2 * n, n + 1), dtype="complex128")
    rout = pyfftw.empty_aligned((2 * n, 2 * n), dtype="float64")
    fwd = pyfftw.FFTW(rin, cplx, axes=(0, 1), flags=(effort,), threads=thr)
    bwd = pyfftw.FFTW(cplx, rout, axes=(0, 1), direction="FFTW_BACKWARD", flags=(effort, "FFTW_DESTROY_INPUT"),
                      threads=thr)
    bem.save_wisdom()
    rin[...] = 0.0
    rin[:n, :n] = p

    def raw_pair():
        fwd.execute()
        bwd.execute()

    out_full = np.empty(grid.shape)
    out_sym = np.empty(pq.shape)
    methods = {"raw": raw_pair, "full": lambda: full(p, out=out_full), "sym": lambda: sym(pq, out=out_sym)}

    try:
        from ContactMechanics import FreeFFTElasticHalfSpace
    except ImportError:
        FreeFFTElasticHalfSpace = None
        cm_msg = ("ContactMechanics is not installed: skipping that comparison "
                  "(install the optional extra: pip install -e '.[bench]')")
    if FreeFFTElasticHalfSpace is not None:
        hs = FreeFFTElasticHalfSpace((n, n), 1.0, (4.0, 4.0))
        forces = p * grid.dx * grid.dy
        methods["cm"] = lambda: hs.evaluate_disp(forces)
        # same discrete operator: ContactMechanics returns -omega for compressive forces
        u_cm = hs.evaluate_disp(forces)
        u_us = full(p)
        cm_diff = float(np.max(np.abs(u_cm + u_us)) / np.max(np.abs(u_us)))

    for f in methods.values():  # warm-up
        f()
    times = {k: [] for k in methods}
    for _ in range(args.repeats):
        for k, f in methods.items():
            t = time.perf_counter()
            f()
            times[k].append(time.perf_counter() - t)
    med = {k: float(np.median(v)) for k, v in times.items()}

    print(f"dhfield.bem benchmark: N = {n} cells per axis (padded {2 * n}^2), threads = {thr}, "
          f"planner = {effort}, median of {args.repeats} interleaved calls")
    print(f"  pyfftw {pyfftw.__version__}; operator build (plans + kernel spectrum): full {t_build_full:.2f} s, "
          f"symmetric {t_build_sym:.2f} s")
    print(f"  raw pyfftw rfft2 + irfft2 pair on {2 * n}^2: {1e3 * med['raw']:8.2f} ms")
    print(f"  dhfield full grid (N^2 in, N^2 out):      {1e3 * med['full']:8.2f} ms")
    print(f"  dhfield symmetry mode (quadrant in/out):   {1e3 * med['sym']:8.2f} ms")
    if "cm" in med:
        print(f"  ContactMechanics FreeFFTElasticHalfSpace:  {1e3 * med['cm']:8.2f} ms "
              f"(results agree with dhfield to {cm_diff:.1e}, opposite sign convention)")
    ok = True
    r1 = med["full"] / med["raw"]
    r2 = med["sym"] / med["raw"]
    print("\nRatios (target in brackets):")
    print(f"  full grid / raw pair          = {r1:.3f}  (<= {TARGET_RAW})  {'PASS' if r1 <= TARGET_RAW else 'FAIL'}")
    print(f"  symmetry mode / raw pair      = {r2:.3f}  (<= {TARGET_SYMMETRIC})  "
          f"{'PASS' if r2 <= TARGET_SYMMETRIC else 'FAIL'}")
    ok &= r1 <= TARGET_RAW and r2 <= TARGET_SYMMETRIC
    if "cm" in med:
        r3 = med["full"] / med["cm"]
        r4 = med["sym"] / med["cm"]
        print(f"  full grid / ContactMechanics  = {r3:.3f}  (<= {TARGET_CONTACTMECHANICS})  "
              f"{'PASS' if r3 <= TARGET_CONTACTMECHANICS else 'FAIL'}")
        print(f"  symmetry mode / ContactMechanics = {r4:.3f}  (for information)")
        ok &= r3 <= TARGET_CONTACTMECHANICS
    else:
        print(f"  {cm_msg}")

    if args.memory_n:
        print(f"\nPeak memory at N = {args.memory_n} (fresh process, build + one evaluation):")
        for symmetric in (False, True):
            m = _memory(args.memory_n, symmetric, thr)
            print(f"  {'symmetry mode' if symmetric else 'full grid    '}: tracemalloc peak "
                  f"{m['tracemalloc_peak_MiB']:7.1f} MiB (held after the call {m['tracemalloc_steady_MiB']:6.1f} MiB); "
                  f"process peak RSS (VmHWM) {m['hwm_MiB']:7.1f} MiB, of which {m['hwm_before_MiB']:.1f} MiB "
                  "before building the operator")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
