"""Speed of the analytic elliptical DH model (issue 2).

Run:  .venv/bin/python -m verification.bench_analytic

Prints the median wall time of
  * a 200-point load curve                     (target <= 50 ms)
  * one pull-off under load control            (target <= 30 ms)
  * one pull-off under displacement control    (reported)
  * the Fig. 9a dataset: 60 mu in [0.05, 20] x beta0 in {0.8, 0.9, 0.99}, vectorised (target <= 2 s)
"""
from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np

from dhfield import model


def _median_time(fn, repeats):
    fn()  # warm-up (caches, lazy imports)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> int:
    mu60 = np.geomspace(0.05, 20.0, 60)
    beta3 = np.array([0.8, 0.9, 0.99])
    cases = [
        ("load curve, 200 points (mu=1, beta0=0.9)", lambda: model.load_curve(1.0, 0.9, n=200), 0.050, 20),
        ("pull-off, load control (mu=1, beta0=0.9)", lambda: model.pull_off(1.0, 0.9), 0.030, 20),
        ("pull-off, displacement control (mu=1, beta0=0.9)",
         lambda: model.pull_off(1.0, 0.9, control="displacement"), None, 20),
        ("Fig. 9a dataset: 60 mu x 3 beta0 pull-offs", lambda: model.pull_off(mu60[:, None], beta3[None, :]),
         2.0, 5),
    ]
    print(f"dhfield analytic benchmark on {os.cpu_count()} cores, python {sys.version.split()[0]}")
    print(f"{'case':52s} {'median':>10s} {'target':>10s} {'ratio':>7s}  verdict")
    ok = True
    for name, fn, target, reps in cases:
        t = _median_time(fn, reps)
        if target is None:
            print(f"{name:52s} {t * 1e3:8.2f}ms {'-':>10s} {'-':>7s}  (reported)")
            continue
        passed = t <= target
        ok &= passed
        print(f"{name:52s} {t * 1e3:8.2f}ms {target * 1e3:8.0f}ms {t / target:7.3f}  {'PASS' if passed else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
