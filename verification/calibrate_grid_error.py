"""The constant of the path routes' grid error, K of :func:`dhfield.bem.pull_off.discretisation_error`, against Maugis-Dugdale.

For the sphere (beta0 = 1, Dugdale law) at Tabor parameters mu and grids of n x n cells, the
located route's pull-off W* (``adhesive_pull_off(..., search="located")``) against the exact
Maugis-Dugdale W* (:func:`dhfield.models.maugis_dugdale.pull_off_nondimensional`, Maugis 1992,
doi:10.1016/0021-9797(92)90288-C): one row per case with ``|W* - W*_MD| / |W*|`` times the cells
across the narrowest length the state resolves (:func:`dhfield.bem.pull_off.resolving_cells`),
the measured K.  The last line gives the largest, and 1.5 times it, the value that
:data:`dhfield.bem.pull_off.DISCRETISATION_ERROR_PER_CELL` must reach; the script exits 1 when
the constant is below it.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.calibrate_grid_error        # ~2 min
"""
from __future__ import annotations

import argparse
import sys


def main(argv=None) -> int:
    from dhfield.analysis.bem_start import adhesive_pull_off
    from dhfield.bem.operator import Grid
    from dhfield.bem.pull_off import DISCRETISATION_ERROR_PER_CELL, resolving_cells
    from dhfield.models import maugis_dugdale

    p = argparse.ArgumentParser(prog="python -m verification.calibrate_grid_error", description=__doc__.split("\n")[0])
    p.add_argument("--mu", type=float, nargs="+", default=[0.3, 0.5, 1.0, 2.0])
    p.add_argument("--n", type=int, nargs="+", default=[16, 24, 32, 48, 64, 96, 128])
    args = p.parse_args(argv)
    worst = 0.0
    print(f"{'mu':>5} {'n':>4} {'W*':>10} {'W*_MD':>10} {'rel err':>9} {'cells':>6} {'K':>7}")
    for mu in args.mu:
        md = float(maugis_dugdale.pull_off_nondimensional(1.0, mu).W_star)
        for n in args.n:
            r = adhesive_pull_off(beta0=1.0, mu=mu, n=n, search="located", threads=1, progress=False)
            if not (r.converged and r.resolved):
                print(f"{mu:5g} {n:4d}  flagged (converged {r.converged}, resolved {r.resolved}): no K")
                continue
            cells = resolving_cells((r.a_star, r.b_star, r.c_star, r.d_star), Grid.centered(n, r.half_width_x), True)
            k = abs(r.W_star - md) / abs(r.W_star) * cells
            worst = max(worst, k)
            print(f"{mu:5g} {n:4d} {r.W_star:10.6f} {md:10.6f} {abs(r.W_star - md) / abs(md):9.2e} {cells:6.2f} "
                  f"{k:7.4f}", flush=True)
    print(f"largest K {worst:.4f}; 1.5 x it = {1.5 * worst:.4f}; DISCRETISATION_ERROR_PER_CELL = "
          f"{DISCRETISATION_ERROR_PER_CELL}")
    return 0 if DISCRETISATION_ERROR_PER_CELL >= 1.5 * worst else 1


if __name__ == "__main__":
    sys.exit(main())
