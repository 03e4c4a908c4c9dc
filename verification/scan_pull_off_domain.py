"""Scan the (beta0, mu) domain for impossible pull-offs (issue 9, items 1-2).

Run:  .venv/bin/python -m verification.scan_pull_off_domain [--n 100]

On an n x n grid, beta0 log-spaced over [1e-3, 1] and mu over [1e-2, 1e4], computes
the load- and displacement-controlled pull-off of ``dhfield.models.dh_elliptic.pull_off`` row by
row (bounded memory) and prints the counts of

* non-finite or failing points (an exception in a row counts the whole row);
* W*load >= 0 (a pull-off must be tensile);
* |W*load| < |W*disp| (impossible: load control passes the fixed-grips minimum);
* |W*load| increasing with mu between neighbours (the DMT -> JKR transition lowers
  the adhesion force monotonically).

A relative slack of 1e-9 absorbs rounding.  Runs against whatever ``dhfield`` is on
the path (e.g. an older checkout via PYTHONPATH) to give before/after numbers.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

SLACK = 1e-9


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100, help="grid points per axis (default 100)")
    args = ap.parse_args(argv)
    import dhfield
    from dhfield.models import dh_elliptic as model

    beta0 = np.geomspace(1e-3, 1.0, args.n)
    mu = np.geomspace(1e-2, 1e4, args.n)
    w_load = np.full((args.n, args.n), np.nan)
    w_disp = np.full((args.n, args.n), np.nan)
    failed = 0
    t0 = time.perf_counter()
    for i, b in enumerate(beta0):
        try:
            w_load[i] = model.pull_off(mu=mu, beta0=b).W_star
            w_disp[i] = model.pull_off(mu=mu, beta0=b, control="displacement").W_star
        except Exception as exc:  # noqa: BLE001 - counted and reported, the scan goes on
            failed += 1
            print(f"beta0 = {b:.4g}: {type(exc).__name__}: {exc}", file=sys.stderr)
    wall = time.perf_counter() - t0
    finite = np.isfinite(w_load) & np.isfinite(w_disp)
    bad_order = finite & (np.abs(w_load) < np.abs(w_disp) * (1 - SLACK))
    positive = finite & (w_load >= 0)
    mono = np.isfinite(w_load[:, 1:]) & np.isfinite(w_load[:, :-1]) & (
        np.abs(w_load[:, 1:]) > np.abs(w_load[:, :-1]) * (1 + SLACK))
    print(f"dhfield from {dhfield.__file__}")
    print(f"grid {args.n} x {args.n}: beta0 in [1e-3, 1], mu in [1e-2, 1e4] (log), {wall:.0f} s")
    print(f"rows failing with an exception: {failed}")
    print(f"non-finite points:              {int((~finite).sum())}")
    print(f"W*load >= 0:                    {int(positive.sum())}")
    print(f"|W*load| < |W*disp|:            {int(bad_order.sum())}")
    print(f"|W*load| increasing in mu:      {int(mono.sum())} (neighbour pairs)")
    if bad_order.any():
        print(f"  violations at beta0 <= {beta0[np.nonzero(bad_order)[0]].max():.3g}, mu in "
              f"[{mu[np.nonzero(bad_order)[1]].min():.3g}, {mu[np.nonzero(bad_order)[1]].max():.3g}]")
    return 0 if not (failed or (~finite).any() or positive.any() or bad_order.any() or mono.any()) else 1


if __name__ == "__main__":
    sys.exit(main())
