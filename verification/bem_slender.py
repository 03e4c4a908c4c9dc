"""The adhesive BEM on slender contacts (crossing angles 10-45 deg): cell shapes measured, ground truth stored.

Two jobs (issue 20), both printing every case beside GVG
(:mod:`dhfield.models.jkr_elliptic_energy`) and the recommended DMT-to-JKR model ``md-elliptic``
(:mod:`dhfield.models.md_elliptic`), with the wall time, the CPU time and the CG and
outer iteration counts:

``measure`` (default)
    One case solved on two grids that resolve the same Dugdale edge: n x n cells
    (stretched along x, the automatic grid before issue 20: 480 x 480 at beta0 = 0.1806,
    mu = 5) and the automatic grid with about square cells
    (:func:`dhfield.analysis.bem_start.plan_grid`, 576 x 160 there).  Prints converged,
    resolved, unconverged states, W* and its stated error, and the cells across the zone
    along x and y.

``truth``
    The slender part of the extended ground truth: every (beta0, mu) at the automatic
    grid and route (level 1, as ``dhfield solve`` without ``--n``) and at twice its cells
    along each axis (level 2, an explicit grid), run one at a time,
    each case written at once as a JSON file under ``--work-dir`` (a rerun skips the cases
    there), then consolidated into ``--out`` (default ``data/adhesive_ground_truth_slender.nc``,
    dims ``(beta0, mu, level)``) with provenance: git commit, command line, per-case wall
    and CPU times, iterations, the grid (nx, ny), the flags and the stated errors.

The sweep (``dhfield sweep``, quantity ``adhesive``) takes a cells-per-axis ``n`` axis and
solves n x n grids: it cannot run the shaped nx x ny grids, hence this script.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_slender                       # ~2 + ~7 min
    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_slender measure --beta0 0.1806 --mu 5 --stretched 480
    DHFIELD_THREADS=1 .venv/bin/python -m verification.bem_slender truth --beta0 0.1806 0.3 --mu 0.3 1
    .venv/bin/python -m verification.bem_slender truth --consolidate-only

Measured with ``measure`` (2026-11-26, shared 2-core machine, DHFIELD_THREADS=1), beta0 =
0.1806, mu = 5: 480 x 480 (230k cells, 2.35 cells across the zone along x, 7.2 along y):
16 states, 13 unconverged, W* = -0.361569 (no error bound), 16230 CG and 1403 outer
iterations, 441 s wall / 202 s CPU; 576 x 160 (92k cells, 2.7 and 2.4 cells): 6 states, all
converged, resolved, W* = -0.361370 +- 0.0075, 3886 CG and 274 outer iterations, 28 s wall /
15 s CPU (GVG -0.358366; the candidate model of that time, md-elliptic before its Eq. T0, -0.359791;
md-elliptic -0.360362).  ``truth`` at level 2 (1152 x 320):
W* = -0.361064 +- 0.0037, located, 3 states, 1669 CG, 60 s wall / 22 s CPU.
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import json
import shlex
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUT = ROOT / "data" / "adhesive_ground_truth_slender.nc"
DEFAULT_WORK_DIR = ROOT / "out" / "adhesive_ground_truth_slender"
#: The slender part of the extended ground truth of issue 20 (crossing ~30 and ~45 deg).
BETA0 = (0.1806, 0.3)
MU = (0.3, 1.0)
LEVELS = (1, 2)


def references(beta0, mu) -> dict:
    """W* of GVG (JKR limit, :mod:`dhfield.models.jkr_elliptic_energy`) and of the recommended model at (beta0, mu).

    The stored dataset's ``W_star_candidate`` is the model of the time of the run (md-elliptic before
    its effective Tabor parameter, Eq. T0); a new run stores ``W_star_md_elliptic``.
    """
    from dhfield.models import md_elliptic as elliptic_transition, jkr_elliptic_energy

    gvg = float(jkr_elliptic_energy.pull_off_nondimensional(beta0, mu, control="load")["W_star"])
    rec = float(elliptic_transition.pull_off_nondimensional(beta0, mu)["W_star"])
    return {"W_star_gvg": gvg, "W_star_md_elliptic": rec}


def solve_case(beta0, mu, nx, ny, *, max_iter=None, automatic=False) -> dict:
    """One load-control BEM pull-off on nx x ny cells: the result's scalars, timings and iteration counts.

    ``automatic``: solve without ``n`` (the automatic grid, which must be nx x ny, and its route:
    the relaxed coarse-to-fine start where the grid half as fine cannot hold the Dugdale edge), as
    ``dhfield solve`` without ``--n`` does; else the explicit nx x ny grid.
    """
    from dhfield.analysis.bem_start import AdhesiveOptions, adhesive_pull_off

    kw = {} if max_iter is None else {"options": AdhesiveOptions(max_iter=int(max_iter))}
    t0, c0 = time.perf_counter(), time.process_time()
    if automatic:
        # the route the stored set was built with (the path routes; the Newton route is the default since 2026-12-02)
        res = adhesive_pull_off(mu=float(mu), beta0=float(beta0), progress=False, search="located", **kw)
    else:
        res = adhesive_pull_off(mu=float(mu), beta0=float(beta0), n=int(nx), ny=int(ny), progress=False, **kw)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    g = res.path.pull_off_state.grid if res.path.pull_off_state is not None else None
    if automatic and (g is None or g.shape != (int(nx), int(ny))):
        raise RuntimeError(f"the automatic grid is not {nx} x {ny}")
    dx, dy = (g.dx, g.dy) if g is not None else (float("nan"), float("nan"))
    rec = {"beta0": float(beta0), "mu": float(mu), "nx": int(nx), "ny": int(ny), "automatic": bool(automatic),
           "W_star": res.W_star,
           "W_star_error": res.W_star_error, "converged": bool(res.converged), "resolved": bool(res.resolved),
           "search": res.search, "states": int(res.n_steps), "unconverged": len(res.failures),
           "iterations": int(res.iterations), "outer_iterations": int(np.sum(res.path.outer_iterations)),
           "wall_s": wall, "cpu_s": cpu, "a_star": res.a_star, "b_star": res.b_star, "c_star": res.c_star,
           "d_star": res.d_star, "delta_star": res.delta_star, "zone_cells_x": (res.c_star - res.a_star) / dx,
           "zone_cells_y": (res.d_star - res.b_star) / dy, "note": res.note}
    rec.update(references(beta0, mu))
    return rec


def print_case(rec, label=""):
    """One line: the grid, the flags, W* with its error beside GVG and md-elliptic, the cost."""
    w, g, c = rec["W_star"], rec["W_star_gvg"], rec["W_star_md_elliptic"]
    print(f"{label}beta0 = {rec['beta0']:g}, mu = {rec['mu']:g}, {rec['nx']} x {rec['ny']}: W* = {w:.6f} "
          f"(error {rec['W_star_error']:.2g}) converged = {rec['converged']} resolved = {rec['resolved']} "
          f"[{rec['search']}, {rec['states']} states, {rec['unconverged']} unconverged] | GVG {g:.6f} "
          f"({100 * (w / g - 1):+.2f} %), md-elliptic {c:.6f} ({100 * (w / c - 1):+.2f} %) | zone cells "
          f"x {rec['zone_cells_x']:.2f}, y {rec['zone_cells_y']:.2f} | {rec['iterations']} CG, "
          f"{rec['outer_iterations']} outer, {rec['wall_s']:.0f} s wall, {rec['cpu_s']:.0f} s CPU", flush=True)


def auto_grid(beta0, mu, level=1):
    """(nx, ny) of the automatic grid (:func:`dhfield.analysis.bem_start.plan_grid`) times ``level`` per axis."""
    from dhfield.analysis.bem_start import plan_grid

    plan = plan_grid(mu=mu, beta0=beta0)
    return plan.n_needed * int(level), plan.ny_needed * int(level)


def measure(args) -> int:
    """The ``measure`` job: n x n (stretched) against the automatic shaped grid."""
    grids = [(n, n, False, "n x n cells (stretched)") for n in args.stretched]
    nx, ny = auto_grid(args.beta0, args.mu)
    grids.append((nx, ny, True, "automatic grid (about square cells)"))
    for nx, ny, auto, label in grids:
        print_case(solve_case(args.beta0, args.mu, nx, ny, max_iter=args.max_iter, automatic=auto), f"{label}: ")
    return 0


def _git_commit() -> str:
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "dhfield"], cwd=ROOT, capture_output=True,
                               text=True, check=True).stdout.strip()
    except Exception:  # noqa: BLE001 - provenance is best effort outside a checkout
        return "unknown"
    return head + (" (dhfield modified)" if dirty else "")


def _case_file(work_dir, beta0, mu, level) -> Path:
    return Path(work_dir) / f"beta0={beta0:g}_mu={mu:g}_level={level}.json"


def truth(args) -> int:
    """The ``truth`` job: run the missing cases (one at a time), then consolidate."""
    from dhfield.io import atomic_path

    work = Path(args.work_dir)
    work.mkdir(parents=True, exist_ok=True)
    if not args.consolidate_only:
        for level in args.levels:              # every coarse case first: an interrupted run covers the grid
            for beta0 in args.beta0:
                for mu in args.mu:
                    path = _case_file(work, beta0, mu, level)
                    if path.exists():
                        print_case(json.loads(path.read_text()), "(stored) ")
                        continue
                    nx, ny = auto_grid(beta0, mu, level)
                    rec = solve_case(beta0, mu, nx, ny, max_iter=args.max_iter, automatic=level == 1)
                    rec.update(level=int(level), commit=_git_commit(),
                               command=shlex.join([sys.executable, "-m", "verification.bem_slender", *sys.argv[1:]]),
                               threads=os.environ.get("DHFIELD_THREADS", ""),
                               finished=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()))
                    with atomic_path(path) as tmp:
                        Path(tmp).write_text(json.dumps(rec, indent=1, default=float))
                    print_case(rec)
    return consolidate(work, args.out)


#: Per-case fields stored in the dataset (numbers; the flags as 0/1 bytes).
NUMERIC_FIELDS = ("W_star", "W_star_error", "nx", "ny", "states", "unconverged", "iterations", "outer_iterations",
                  "wall_s", "cpu_s", "a_star", "b_star", "c_star", "d_star", "delta_star", "zone_cells_x",
                  "zone_cells_y")


def consolidate(work_dir, out) -> int:
    """Gather the JSON cases into the netCDF ground truth (atomic write); print a table."""
    import xarray as xr

    from dhfield.io import write_netcdf

    recs = [json.loads(p.read_text()) for p in sorted(Path(work_dir).glob("beta0=*_mu=*_level=*.json"))]
    if not recs:
        print(f"no cases under {work_dir}", file=sys.stderr)
        return 1
    b0 = sorted({r["beta0"] for r in recs})
    mus = sorted({r["mu"] for r in recs})
    lv = sorted({r["level"] for r in recs})
    shape = (len(b0), len(mus), len(lv))

    def idx(r):
        return b0.index(r["beta0"]), mus.index(r["mu"]), lv.index(r["level"])

    data = {k: np.full(shape, np.nan) for k in NUMERIC_FIELDS}
    flags = {k: np.zeros(shape, dtype="i1") for k in ("converged", "resolved", "present")}
    text = {k: np.full(shape, "", dtype=object) for k in ("search", "note", "commit", "command", "finished")}
    for r in recs:
        i = idx(r)
        for k in NUMERIC_FIELDS:
            data[k][i] = float(r[k])
        flags["converged"][i], flags["resolved"][i], flags["present"][i] = r["converged"], r["resolved"], 1
        for k in text:
            text[k][i] = str(r.get(k, ""))
    refs = {k: np.array([[references(b, m)[k] for m in mus] for b in b0])
            for k in ("W_star_gvg", "W_star_md_elliptic")}
    dims = ("beta0", "mu", "level")
    ds = xr.Dataset(
        {**{k: (dims, v) for k, v in data.items()}, **{k: (dims, v) for k, v in flags.items()},
         **{k: (dims, v.astype(str)) for k, v in text.items()},
         **{k: (("beta0", "mu"), v) for k, v in refs.items()}},
        coords={"beta0": b0, "mu": mus, "level": lv})
    ds.attrs.update(
        title="Adhesive BEM ground truth for slender elliptical contacts (Dugdale law, load control)",
        description=("BEM pull-off W* (Eq. 34 normalisation) at beta0 < 0.45 on the automatic grid with about "
                     "square cells (level 1: dhfield.analysis.bem_start.plan_grid's n_needed x ny_needed) and twice "
                     "its cells per axis (level 2); converged/resolved flags and the stated W_star_error of each "
                     "case; GVG (jkr_elliptic_energy) and the recommended model md-elliptic "
                     "(elliptic_transition) at the same points. dhfield output: never a test reference."),
        provenance="python -m verification.bem_slender truth (per case: commit, command, finished, wall_s, cpu_s)",
        consolidated=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), consolidate_commit=_git_commit())
    ds["W_star_error"].attrs["note"] = "stated error of W_star (search + discretisation); inf when not resolved"
    ds["wall_s"].attrs["note"] = "wall time on a shared 2-core machine, DHFIELD_THREADS=1 (load varies)"
    write_netcdf(ds, out)
    print(f"wrote {out}: {int(flags['present'].sum())} cases")
    for r in sorted(recs, key=lambda r: (r["beta0"], r["mu"], r["level"])):
        print_case(r, f"level {r['level']}: ")
    return 0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.bem_slender", description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="job")
    m = sub.add_parser("measure", help="n x n stretched cells against the automatic shaped grid")
    m.add_argument("--beta0", type=float, default=0.1806)
    m.add_argument("--mu", type=float, default=5.0)
    m.add_argument("--stretched", type=int, nargs="*", default=[480], help="n of the n x n grids (default 480)")
    m.add_argument("--max-iter", type=int, default=None)
    t = sub.add_parser("truth", help="the slender ground truth, two levels per case, stored")
    t.add_argument("--beta0", type=float, nargs="+", default=list(BETA0))
    t.add_argument("--mu", type=float, nargs="+", default=list(MU))
    t.add_argument("--levels", type=int, nargs="+", default=list(LEVELS))
    t.add_argument("--max-iter", type=int, default=None)
    t.add_argument("--work-dir", default=str(DEFAULT_WORK_DIR))
    t.add_argument("--out", default=str(DEFAULT_OUT))
    t.add_argument("--consolidate-only", action="store_true")
    args = p.parse_args(argv)
    if args.job is None:
        args = p.parse_args(["measure", *(argv or [])])
    if args.job == "truth":
        if any(not 0 < b < 1 for b in args.beta0) or any(not x > 0 for x in args.mu) or any(k < 1 for k in args.levels):
            p.error("--beta0 must be in (0, 1), --mu > 0, --levels >= 1")
        return truth(args)
    if not (0 < args.beta0 <= 1 and args.mu > 0) or any(n < 8 or n % 2 for n in args.stretched):
        p.error("--beta0 must be in (0, 1], --mu > 0, --stretched even integers >= 8")
    return measure(args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
