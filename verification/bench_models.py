"""Speed of the comparison models (issue 3).

Run:  .venv/bin/python -m verification.bench_models

Prints the median wall time (over repeats, after a warm-up) of
  * one Maugis-Dugdale pull-off (load control, lambda = 1)     (target <= 20 ms)
  * one elliptical-JKR pull-off (load control, beta0 = 0.9)     (target <= 50 ms)
and, for information, the displacement-controlled variants, a vectorised MD
pull-off over 100 lambda in [0.01, 100], the circular DH pull-off and a full
``dhfield.compare.compare`` row.  Exits 1 if a target is missed.
"""
from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np

from dhfield import compare, dh_circular, jkr_elliptic, maugis_dugdale


def _median_time(fn, repeats):
    fn()  # warm-up
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> int:
    lam100 = np.geomspace(0.01, 100.0, 100)
    cases = [
        ("MD pull-off, load control (lambda = 1)", lambda: maugis_dugdale._pull_off_maugis(1.0), 0.020, 30),
        ("MD pull-off, displacement control (lambda = 1)",
         lambda: maugis_dugdale._pull_off_maugis(1.0, "displacement"), None, 30),
        ("MD pull-off, 100 lambda in [0.01, 100], vectorised", lambda: maugis_dugdale._pull_off_maugis(lam100),
         None, 10),
        ("elliptical JKR pull-off, load control (beta0 = 0.9)", lambda: jkr_elliptic._pull_off(0.9), 0.050, 30),
        ("elliptical JKR pull-off, displacement control (beta0 = 0.9)",
         lambda: jkr_elliptic._pull_off(0.9, "displacement"), None, 30),
        ("circular DH pull-off, load control (mu = 1)", lambda: dh_circular._pull_off(1.0), None, 30),
        ("compare(mu = 5, beta0 = 0.9): all 7 models", lambda: compare.compare(5.0, 0.9), None, 10),
    ]
    print(f"dhfield comparison-model benchmark on {os.cpu_count()} cores, python {sys.version.split()[0]}")
    print(f"{'case':62s} {'median':>10s} {'target':>10s}  verdict")
    ok = True
    for name, fn, target, reps in cases:
        t = _median_time(fn, reps)
        if target is None:
            print(f"{name:62s} {t * 1e3:8.2f}ms {'-':>10s}  (reported)")
            continue
        good = t <= target
        ok &= good
        print(f"{name:62s} {t * 1e3:8.2f}ms {target * 1e3:8.1f}ms  {'PASS' if good else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
