"""Solve one first state by nested iteration and save it (traction, approach) for the Krylov measurements.

Usage::

    python -m verification.save_state 0.4826 10 1280 3 /tmp/state.npz
    python -m verification.save_state 1.0 5 320 3 /tmp/sph5_cg3.npz 3   # SolverOptions.contact_inner = 3
    python -m verification.save_state 0.4826 10 1280 3 /tmp/mu10_floor.npz 0 1   # symbol_floor = True
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from verification.bench_nested import _problem  # noqa: E402


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    beta0, mu, n, levels, path = float(argv[0]), float(argv[1]), int(argv[2]), int(argv[3]), argv[4]
    inner = int(argv[5]) if len(argv) > 5 else 0
    floor = bool(int(argv[6])) if len(argv) > 6 else False
    from dhfield.bem import newton

    P = _problem(beta0, mu, n)
    ladder = newton.grid_ladder(P, levels, threads=int(os.environ.get("DHFIELD_THREADS", "1")))
    print(f"grid {P.grid.nx}x{P.grid.ny} edge ratio {ladder[-1].edge_width_ratio:.3f}", flush=True)
    q0 = newton.cold_start(ladder[0], P.pull_off_approach, P.pull_off_zone)
    t0 = time.perf_counter()
    opts = newton.SolverOptions(nonmonotone=4, contact_inner=inner, symbol_floor=floor)
    r = newton.solve_state_nested(ladder, P.pull_off_approach, q0, opts,
                                  log=lambda s: print(s, flush=True))
    st = r.state
    print(f"{st.reason} newton {st.newton_iterations} gmres {st.krylov_iterations} load {st.load:.8f} "
          f"{time.perf_counter() - t0:.1f} s; per level (newton/gmres/wall): "
          + " | ".join(f"{v.newton_iterations}/{v.krylov_iterations}/{v.elapsed:.1f}s" for v in r.levels), flush=True)
    np.savez(path, traction=st.traction, delta=P.pull_off_approach, beta0=beta0, mu=mu, n=n,
             converged=st.converged, load=st.load)
    return 0


if __name__ == "__main__":
    sys.exit(main())
