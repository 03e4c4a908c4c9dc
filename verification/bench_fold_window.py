"""The fold fit's half-window (``dhfield.bem.continuation.FOLD_WINDOW``) against Maugis-Dugdale on the sphere.

Under displacement control the pull-off is the fold of the approach along the branch sampled at
prescribed adhesive force (:func:`dhfield.bem.continuation.fold_by_adhesive_force`), fitted over
``window`` samples each side of the smallest approach.  This script solves the sphere's
displacement-control pull-off (``adhesive_pull_off(control="displacement")``) with each window
and prints W*/W*_MD - 1 against Maugis-Dugdale's exact displacement-control pull-off (Maugis 1992,
doi:10.1016/0021-9797(92)90288-C; :mod:`dhfield.models.maugis_dugdale`), the stated relative
error and the CPU seconds, then the largest |W*/W*_MD - 1| per window.  The script exits 1 when
an answer lies outside its stated error.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.bench_fold_window        # ~1 min
"""
from __future__ import annotations

import argparse
import time

#: (mu, n) of the sphere: both sides of the transition.
CASES = ((0.3, 96), (1.0, 128), (2.0, 128), (3.0, 128), (3.0, 256))


def main(argv=None) -> int:
    from dhfield.bem import adhesive_pull_off, continuation
    from dhfield.models import maugis_dugdale

    p = argparse.ArgumentParser(prog="python -m verification.bench_fold_window", description=__doc__.split("\n")[0])
    p.add_argument("--windows", type=int, nargs="+", default=[1, 2, 3, 4])
    args = p.parse_args(argv)
    fit = continuation.fold_by_adhesive_force
    real = fit.__kwdefaults__["window"]
    print(f"(the library's window: {real})")
    print(f"{'mu':>4} {'n':>4} {'window':>6} {'W*/W*_MD - 1':>13} {'stated':>8} {'cpu s':>6}")
    worst, outside = {}, 0
    try:
        for mu, n in CASES:
            ref = float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control="displacement").W_star)
            for w in args.windows:
                fit.__kwdefaults__["window"] = w
                t0 = time.process_time()
                r = adhesive_pull_off(beta0=1.0, mu=mu, n=n, control="displacement", progress=False)
                dev = r.W_star / ref - 1.0
                stated = r.W_star_error / abs(r.W_star)
                outside += int(abs(r.W_star - ref) > r.W_star_error)
                worst[w] = max(worst.get(w, 0.0), abs(dev))
                print(f"{mu:4g} {n:4d} {w:6d} {dev:+13.2e} {stated:8.1e} {time.process_time() - t0:6.1f}")
    finally:
        fit.__kwdefaults__["window"] = real
    print("largest |W*/W*_MD - 1| per window: " + ", ".join(f"{w}: {v:.2e}" for w, v in worst.items()))
    print(f"answers outside their stated error: {outside}")
    return 1 if outside else 0


if __name__ == "__main__":
    raise SystemExit(main())
