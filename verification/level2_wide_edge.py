"""Level 2 of a mu = 10 case with the Dugdale edge held at its widest (issue 20, convergence over N).

At mu = 10 the level-1 grids' own edges are 1.9-2.0 h0, at the cap 2 h0; level 2's own edges are
1.03-1.08 h0, and there the route's states stall (``docs/theory/bem.rst``).  This script solves the
pull-off of level 2 (``automatic_grid(beta0, 10, 2)``) by the study's route (the predicted route
with :class:`dhfield.bem.pull_off.CoarseRouteWarmStart`: level 1's route states as starts), with
the edge held at 2 h0 on every grid (:attr:`dhfield.analysis.bem_start.AdhesiveOptions.widest_edge`,
the option the study's parts ``high-mu-level2-widest-*`` set through ``[bem] widest_edge``), so
that level 2 against level 1 measures the grid's convergence at (nearly) the same edge in cells.
It prints one line and stores nothing; the study's parts store.  Usage::

    OMP_NUM_THREADS=2 .venv/bin/python -m verification.level2_wide_edge --beta0 0.1 --threads 2

Measured (2026-11-28, 2 threads, tenth session, with level 1's grid at its own edge, 1.97 h0, and
only level 2's widened): beta0 = 0.1, 5120 x 960: W* = -0.225547 +- 0.0018, converged, three
states (41-60 outer iterations each at level 2), 1443 s; the stored level 1 (2560 x 480) is
-0.225527 +- 0.0037 (that run passed a CG cap of 1e6 to level 1's route; this script now makes the
study's own call, whose cap is the route's; the study's part gave -0.225543 +- 0.0018).
"""
from __future__ import annotations

import argparse
import sys
import time


def main(argv=None) -> int:
    from dhfield.analysis.bem_start import PREDICTED_SEARCH, AdhesiveOptions, adhesive_pull_off
    from dhfield.sweep.tasks import automatic_grid

    ap = argparse.ArgumentParser(prog="python -m verification.level2_wide_edge", description=__doc__.split("\n")[0])
    ap.add_argument("--beta0", type=float, default=0.1, help="initial ellipticity in (0, 1] (default 0.1)")
    ap.add_argument("--mu", type=float, default=10.0, help="Tabor parameter > 0 (default 10)")
    ap.add_argument("--threads", type=int, default=1, help="FFTW threads (default 1)")
    args = ap.parse_args(argv)

    g = automatic_grid(args.beta0, args.mu, 2)
    t0 = time.perf_counter()
    # the call the study's level-2 case makes (dhfield.sweep.tasks.adhesive_case), on args.threads threads
    res = adhesive_pull_off(beta0=args.beta0, mu=args.mu, n=g["nx"], ny=g["ny"], search=PREDICTED_SEARCH,
                            threads=args.threads, progress=True, options=AdhesiveOptions(widest_edge=True))
    print(f"beta0 {args.beta0:g}, mu {args.mu:g}, level 2 ({g['nx']} x {g['ny']}), edge at 2 h0: "
          f"W* = {res.W_star:.6f} +- {res.W_star_error:.2g}, converged {res.converged}, "
          f"{time.perf_counter() - t0:.0f} s{'; ' + res.note if res.note else ''}", flush=True)
    return 0 if res.converged else 3


if __name__ == "__main__":
    sys.exit(main())
