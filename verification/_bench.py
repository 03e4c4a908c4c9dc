"""Shared timing helpers of the benchmark scripts (medians of repeats, one table)."""
from __future__ import annotations

import os
import statistics
import sys
import time


def median_time(fn, repeats: int) -> float:
    """Median wall time [s] of ``fn()`` over ``repeats`` calls, after one warm-up call."""
    fn()  # warm-up: caches, lazy imports, FFTW plans
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def run_cases(title: str, cases, width: int = 56) -> int:
    """Time ``(name, fn, target_seconds_or_None, repeats)`` cases and print one table.

    Returns the exit status: 1 if any target is missed, else 0.
    """
    print(f"{title} on {os.cpu_count()} cores, python {sys.version.split()[0]}")
    print(f"{'case':{width}s} {'median':>10s} {'target':>10s} {'ratio':>7s}  verdict")
    ok = True
    for name, fn, target, repeats in cases:
        t = median_time(fn, repeats)
        if target is None:
            print(f"{name:{width}s} {t * 1e3:8.2f}ms {'-':>10s} {'-':>7s}  (reported)")
            continue
        passed = t <= target
        ok &= passed
        print(f"{name:{width}s} {t * 1e3:8.2f}ms {target * 1e3:8.1f}ms {t / target:7.3f}  "
              f"{'PASS' if passed else 'FAIL'}")
    return 0 if ok else 1
