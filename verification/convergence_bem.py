"""Accuracy of the DC-FFT operator against the analytic displacement fields.

Prints, for N = 128 ... 2048 cells per axis, the relative L-infinity error of the
numerical surface displacement (dhfield.bem) against the analytic one (Eq. 13 for
Hertz, Eq. 26 for the extended DH model) at the cell centres, and the observed
order of convergence between successive grids.

Domain and sampling (stated in the output):

* Hertz ellipse a = 1, beta = 0.7 (R = E* = 1), square domain [-2a, 2a]^2 of
  N x N cells, pressure by exact cell averages (the default) and, for the record,
  by centre samples;
* DH case beta0 = 0.9, mu = 1, a* = 1.2 (c*, v from dhfield.models.dh_elliptic), domain
  [-1.5c, 1.5c]^2, cell averages.

Errors are max |omega_BEM - omega| / max |omega| over the whole grid ("L-inf"),
over the cells at least 0.1 a from the contact edge (and 0.1 c from the adhesive
edge for DH; "L-inf off edge"), and the root-mean-square error over the grid
divided by the same scale ("RMS").

Usage::

    .venv/bin/python verification/convergence_bem.py [--nmax 2048] [--threads 1]
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from dhfield.analysis import fields
from dhfield.core import refinement

#: Targets of issue 4.
TARGETS = {512: 1e-3, 1024: 3e-4}
TARGET_ORDER = 1.5
#: Width of the band around the ellipse edges excluded in the "off edge" column [units of a].
EDGE_BAND = 0.1

HERTZ = dict(semi_major=1.0, beta=0.7)
DH_CASE = dict(beta0=0.9, mu=1.0, a_star=1.2)


def _off_edge(case):
    x, y = case.grid.mesh()
    prm = case.parameters
    beta = prm["beta"]
    a = prm["semi_major"]
    keep = np.abs(np.hypot(x / a, y / (beta * a)) - 1.0) * a > EDGE_BAND * a
    c = prm.get("adhesive_semi_major")
    if c is not None:
        keep &= np.abs(np.hypot(x / c, y / (beta * c)) - 1.0) * c > EDGE_BAND * a
    return keep


def errors(case):
    """Relative L-inf (whole grid), L-inf off the edges, and RMS displacement errors."""
    err = case.displacement_numerical - case.displacement_analytic
    scale = np.max(np.abs(case.displacement_analytic))
    keep = _off_edge(case)
    return (np.max(np.abs(err)) / scale, np.max(np.abs(err[keep])) / scale,
            np.sqrt(np.mean(err**2)) / scale)


def study(make_case, ns):
    """Rows (n, h, linf, linf_off, rms) and their observed orders."""
    rows = []
    for n in ns:
        case = make_case(n)
        rows.append((n, case.grid.dx, *errors(case)))
    arr = np.array(rows)
    orders = [np.concatenate([[np.nan], refinement.observed_orders(arr[:, 1], arr[:, k])]) for k in (2, 3, 4)]
    return arr, np.array(orders).T


def dh_parameters():
    return fields.adhesive_state(DH_CASE["a_star"], mu=DH_CASE["mu"], beta0=DH_CASE["beta0"])


def format_table(arr, orders) -> str:
    lines = ["|    N |       h | rel L-inf | order | rel L-inf off edge | order |  rel RMS | order |",
             "|-----:|--------:|----------:|------:|-------------------:|------:|---------:|------:|"]
    for row, o in zip(arr, orders):
        n, h, e1, e2, e3 = row
        f = lambda v: "    -" if np.isnan(v) else f"{v:5.2f}"  # noqa: E731
        lines.append(f"| {int(n):4d} | {h:7.5f} | {e1:9.2e} | {f(o[0])} | {e2:18.2e} | {f(o[1])} | "
                     f"{e3:8.2e} | {f(o[2])} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nmax", type=int, default=2048)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args(argv)
    ns = [n for n in (128, 256, 512, 1024, 2048, 4096) if n <= args.nmax]
    t0 = time.perf_counter()
    ok = True

    a, beta = HERTZ["semi_major"], HERTZ["beta"]
    for sampling in ("average", "centre"):
        arr, orders = study(lambda n: fields.hertz_case(n, a, beta, sampling=sampling, threads=args.threads), ns)
        print(f"\nHertz ellipse a = {a}, beta = {beta}, domain [-2a, 2a]^2, N x N cells, "
              f"pressure sampling = {sampling}")
        print("errors of omega_BEM - omega_Eq.13 at the cell centres, relative to max|omega|")
        print(format_table(arr, orders))
        if sampling == "average":
            hertz_arr, hertz_orders = arr, orders

    c, v = dh_parameters()
    arr, orders = study(lambda n: fields.dh_case(n, 1.2, c, 0.9, v, threads=args.threads), ns)
    print(f"\nDH case beta0 = 0.9, mu = 1, a* = 1.2 -> c* = {c:.6f}, v = {v:.6f}; domain [-1.5c, 1.5c]^2, "
          "pressure sampling = average")
    print("errors of omega_BEM - omega_Eq.26 at the cell centres, relative to max|omega|")
    print(format_table(arr, orders))

    print("\nTargets (Hertz ellipse, cell averages, whole-grid relative L-inf):")
    for n, tol in TARGETS.items():
        if n in hertz_arr[:, 0]:
            e = hertz_arr[hertz_arr[:, 0] == n, 2][0]
            passed = e <= tol
            ok &= passed
            print(f"  N = {n}: {e:.2e} <= {tol:.0e}  {'PASS' if passed else 'FAIL'}")
    last = hertz_orders[-1]
    for k, name in enumerate(("L-inf whole grid", f"L-inf off edge (> {EDGE_BAND} a)", "RMS")):
        passed = last[k] >= TARGET_ORDER
        print(f"  observed order {name}, N = {int(hertz_arr[-2, 0])} -> {int(hertz_arr[-1, 0])}: "
              f"{last[k]:.2f} >= {TARGET_ORDER}  {'PASS' if passed else 'FAIL'}")
    print(f"\n(total time {time.perf_counter() - t0:.1f} s)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
