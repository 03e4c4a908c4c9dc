"""Slender crossings by the Newton route: W*(mu) at 4.8 and 10 deg, the recommended model beside it, the JKR limit.

For each (beta0, mu) the load-control pull-off as ``dhfield solve --beta0 B --mu M`` computes it
(:func:`dhfield.analysis.bem_start.adhesive_pull_off` on its automatic grid: the Newton route,
:mod:`dhfield.bem.ladder`), with its stated error, the answer's grid, the CPU seconds, and the
recommended model ``md-elliptic`` (:mod:`dhfield.models.md_elliptic`) against it.  Per beta0, the
BEM's W*(mu) extrapolated to mu -> infinity (:func:`verification.jkr_limit.extrapolate_jkr_limit`:
the sphere's Maugis-Dugdale approach to JKR, no elliptical-shape assumption) beside GVG's
elliptical JKR (:mod:`dhfield.models.jkr_elliptic_energy`).

Each case is written at once under ``--work-dir`` (JSON; a rerun skips the cases there) and the
whole table to ``--out`` (netCDF on (beta0, mu), with provenance: commit, command, per-case CPU
seconds).  Exits 1 when a case is not an answer (unconverged or unresolved).

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.slender_newton      # ~15 min (mu = 5 dominates)
    DHFIELD_THREADS=1 .venv/bin/python -m verification.slender_newton --mu 1 2 3   # ~1 min
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

BETA0 = (0.02, 0.047)
MU = (1.0, 2.0, 3.0, 5.0)
OUT = Path(__file__).resolve().parent.parent / "data" / "slender_newton.nc"


def solve_case(beta0, mu):
    """One case, as a JSON-ready dict."""
    from dhfield.analysis.bem_start import adhesive_pull_off
    from dhfield.models import md_elliptic

    t0 = time.process_time()
    r = adhesive_pull_off(beta0=beta0, mu=mu, progress=False, threads=1)
    cpu = time.process_time() - t0
    md = float(md_elliptic.pull_off_nondimensional(beta0, mu).W_star)
    nx, ny = (int(c) for c in r.path.pull_off_state.grid.shape)
    return dict(beta0=beta0, mu=mu, W_star=float(r.W_star), W_star_error=float(r.W_star_error),
                converged=bool(r.converged), resolved=bool(r.resolved), nx=nx, ny=ny, search=str(r.search),
                note=str(r.note), cpu_seconds=cpu, md_elliptic=md)


def main(argv=None) -> int:
    import numpy as np
    import xarray as xr

    from dhfield.core.geometry import sin_skew_angle, skew_angle
    from dhfield.io import git_commit, provenance_attrs, write_netcdf
    from dhfield.models import jkr_elliptic_energy as gvg
    from verification.jkr_limit import extrapolate_jkr_limit

    p = argparse.ArgumentParser(prog="python -m verification.slender_newton", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, nargs="+", default=list(BETA0))
    p.add_argument("--mu", type=float, nargs="+", default=list(MU))
    p.add_argument("--work-dir", type=Path, default=Path("out/slender_newton"))
    p.add_argument("--out", type=Path, default=OUT)
    args = p.parse_args(argv)
    args.work_dir.mkdir(parents=True, exist_ok=True)
    rows = {}
    for b in args.beta0:
        for m in args.mu:
            f = args.work_dir / f"case_{b:g}_{m:g}.json"
            if f.exists():
                rows[b, m] = json.loads(f.read_text())
            else:
                rows[b, m] = solve_case(b, m)
                tmp = f.with_suffix(".tmp")
                tmp.write_text(json.dumps(rows[b, m]))
                tmp.replace(f)
            r = rows[b, m]
            print(f"beta0 {b:g} ({math.degrees(float(skew_angle(b))):.1f} deg) mu {m:g}: W* {r['W_star']:.6f} "
                  f"+- {r['W_star_error'] / abs(r['W_star']):.2%} on {r['nx']} x {r['ny']} "
                  f"(converged {r['converged']}, resolved {r['resolved']}), md-elliptic {r['md_elliptic']:.6f} "
                  f"({r['md_elliptic'] / r['W_star'] - 1:+.2%}), {r['cpu_seconds']:.0f} s CPU", flush=True)
    bad = [k for k, r in rows.items() if not (r["converged"] and r["resolved"])]
    print("\nThe JKR limit (mu -> infinity) per beta0, beside GVG's elliptical JKR:")
    for b in args.beta0:
        mu = np.array([m for m in args.mu if (b, m) not in bad])
        w = np.array([rows[b, m]["W_star"] for m in mu])
        e = np.array([rows[b, m]["W_star_error"] for m in mu])
        w_gvg = float(gvg.pull_off_nondimensional(beta0=b, mu=1.0).W_star)
        try:
            lim = extrapolate_jkr_limit(mu, w, float(sin_skew_angle(b)), e)
        except ValueError as exc:
            print(f"  beta0 {b:g}: no limit ({exc})")
            continue
        print(f"  beta0 {b:g}: W*_inf = {lim.w_inf:.5f} +- {lim.error:.5f} ({lim.error / abs(lim.w_inf):.1%}; "
              f"from mu = {', '.join(f'{m:g}' for m in lim.mu_used)}); GVG {w_gvg:.5f} "
              f"({w_gvg / lim.w_inf - 1:+.2%}, {abs(w_gvg - lim.w_inf) / lim.error:.1f} errors)")
    shape = (len(args.beta0), len(args.mu))

    def grid(key, dtype=float):
        return np.array([[rows[b, m][key] for m in args.mu] for b in args.beta0], dtype=dtype).reshape(shape)

    ds = xr.Dataset(
        {"W_star": (("beta0", "mu"), grid("W_star"), {"long_name": "BEM load-control pull-off W* (Eq. 34)",
                                                       "units": "1"}),
         "W_star_error": (("beta0", "mu"), grid("W_star_error"), {"long_name": "stated error of W*", "units": "1"}),
         "W_star_md_elliptic": (("beta0", "mu"), grid("md_elliptic"),
                                {"long_name": "recommended model md-elliptic's W*", "units": "1"}),
         "answer": (("beta0", "mu"), (grid("converged", bool) & grid("resolved", bool)).astype("i1"),
                    {"long_name": "1 when converged and resolved", "units": "1"}),
         "nx": (("beta0", "mu"), grid("nx", int), {"long_name": "cells along x of the answer's grid", "units": "1"}),
         "cpu_seconds": (("beta0", "mu"), grid("cpu_seconds"), {"long_name": "CPU time of the case (1 thread)",
                                                                "units": "s"})},
        coords={"beta0": ("beta0", np.array(args.beta0), {"long_name": "Hertz ellipticity", "units": "1"}),
                "mu": ("mu", np.array(args.mu), {"long_name": "Tabor parameter (Eq. 35)", "units": "1"})})
    ds.attrs.update(provenance_attrs("dhfield: slender crossings by the Newton route (verification.slender_newton)",
                                     command=" ".join([sys.executable, "-m", "verification.slender_newton",
                                                       *(argv if argv is not None else sys.argv[1:])])))
    ds.attrs["commit"] = str(git_commit())
    write_netcdf(ds, args.out)
    print(f"\nwritten {args.out}")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
