"""Issue 20's extended adhesive ground truth: run through ``dhfield sweep``, merged with the stored cases.

The extended study is beta0 in {0.1, 0.1806, 0.3, 0.5, 0.8, 1} (crossing ~18, 30, 45, 61, 80,
90 deg; the issue's 0.18 is the stored slender case beta0 = 0.1806, a 30 deg crossing, kept
as stored) x mu in {0.1, 0.3, 1, 3, 10}, each on two grid levels (convergence over N).
Part of it is stored already:

* ``data/adhesive_ground_truth.nc`` (``verification.study_adhesive``): beta0 {0.5, 0.6, 0.8,
  0.9, 0.99, 1} x mu {0.3, 0.5, 1, 2, 5} on an N ladder 64-1024;
* ``data/adhesive_ground_truth_slender.nc`` (``verification.bem_slender``): beta0 {0.1,
  0.1806, 0.3} x mu {0.1, 0.3, 1, 5}, the automatic grid (level 1) and twice its cells per
  axis (level 2).

The rest runs here as ``dhfield sweep`` studies (quantity ``adhesive`` on the ``grid_level``
axis: level 1 the automatic grid and route, level 2 twice its cells per axis; Dugdale law,
load control) on dask, one part per TOML file written under ``--work-dir``
(:data:`PARTS`), each resumable (its case store beside its output):

``run PART ...``
    Write the part's TOML and run ``dhfield sweep PART.toml --scheduler processes --workers W``
    (a dask process pool) under an optional hard ``--timeout``; print every case with its
    grid, W*, stated error, flags and wall/CPU time, and the part's wall time.
``build``
    Merge the stored files, the sweep cases the previous build of the output holds (the parts
    earlier sessions ran: their work dirs are gone) and every part's sweep output found under
    ``--work-dir`` (replacing the same case held) into
    ``data/adhesive_ground_truth_extended.nc`` (atomic write; the stored files are read,
    never changed): dims ``(beta0, mu, level)``, per case the values, the grid (nx, ny,
    half-widths), W_star_error, converged/resolved, the status ('ok', 'not_converged',
    'unresolved', 'failed', 'not run' for a case of the extended study that no source
    holds, with what the case store of a part stopped at its timeout holds of it, if any:
    finished there, failed, or not finished; 'absent' outside it), the
    wall/CPU time and its provenance (``source``, ``commit``, ``command``, ``finished``);
    per (beta0, mu) the best value ``W_star_truth`` with its error and source.  Lists the
    cases not run.

Levels of the N-ladder set: its two finest usable N (status ok or unconverged only after the
pull-off), each twice the cells per axis of the other as levels 1 and 2 are; its whole ladder
is kept as ``W_star_ladder`` (dim ``n``) and its best value (Richardson over three N where
it applies) is its ``W_star_truth``.

Usage::

    nice -n 10 .venv/bin/python -m verification.study_extended run cheap-wide cheap-slender
    nice -n 10 .venv/bin/python -m verification.study_extended run high-mu-trial --timeout 600
    nice -n 10 .venv/bin/python -m verification.study_extended run high-mu-level2 --max-seconds 4000
    .venv/bin/python -m verification.study_extended build

On a machine with an NVIDIA GPU and CuPy (the parts ``*-gpu``; the dask workers inherit the
environment, and each case's ``command`` records the backend)::

    DHFIELD_BEM_BACKEND=cupy python -m verification.study_extended run high-mu-level2-gpu \\
        --workers 1 --max-seconds 100000 --timeout 540

Measured on an H100 (2026-11-26), when level 2 still took the located route on the larger domain
of an explicit grid: the first case did not finish in 540 s (one worker, the process at 100 % of
one CPU core); six cases on six workers finished none in 490 s.  The GPU route is bound by the
host's kernel launches (``python -m verification.bench_backend``): not yet a way to level 2.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
OLD = ROOT / "data" / "adhesive_ground_truth.nc"
SLENDER = ROOT / "data" / "adhesive_ground_truth_slender.nc"
DEFAULT_OUT = ROOT / "data" / "adhesive_ground_truth_extended.nc"
DEFAULT_WORK_DIR = ROOT / "out" / "study_extended"

#: The extended study of issue 20 (beta0 = 0.1806: the stored slender case at a 30 deg crossing).
BETA0 = (0.1, 0.1806, 0.3, 0.5, 0.8, 1.0)
MU = (0.1, 0.3, 1.0, 3.0, 10.0)
LEVELS = (1, 2)

#: The sweeps of the cases no stored file holds: name -> (beta0, mu, grid levels).  A sweep's
#: axes are a product, so the missing set is cut into products.  mu = 10 is costly (~6-15 min a
#: case at level 1 on this machine, level 2 ~4x more): it is a part of its own.
PARTS = {
    "cheap-wide": ((0.5, 0.8, 1.0), (0.1, 3.0), (1, 2)),
    "cheap-slender": ((0.1, 0.1806, 0.3), (3.0,), (1, 2)),
    "high-mu": (BETA0, (10.0,), (1, 2)),
    "high-mu-wide": ((0.5, 0.8), (10.0,), (1,)),            # the predicted route, n x n cells
    "high-mu-sphere": ((1.0,), (10.0,), (1,)),              # the predicted route on the sphere
    "high-mu-slender": ((0.1, 0.1806, 0.3), (10.0,), (1,)),  # the predicted route on shaped grids
    "high-mu-level2": (BETA0, (10.0,), (2,)),                # planned, refused if beyond memory/time
    # the cases the parts above left without an answer (trapped cold states, a timeout), run again
    # with the predicted route's stretch step; a later part's case replaces an earlier part's
    "high-mu-stretch": ((0.1, 0.8, 1.0), (10.0,), (1,)),
    "high-mu-level2-wide": ((0.5,), (10.0,), (2,)),          # one mu = 10 case at level 2 (then 2880^2 cells)
    "high-mu-trial": ((0.5,), (10.0,), (1,)),
    # on a GPU (DHFIELD_BEM_BACKEND=cupy, dhfield.bem.backend): level-2 cases a 2-core machine
    # cannot afford (~1.5-3 CPU-hours each), the sphere (MD exact) and 60 deg first, and beta0 0.1
    # at level 1 again
    "high-mu-level2-gpu": ((0.5, 1.0), (10.0,), (2,)),
    "high-mu-slender-gpu": ((0.1,), (10.0,), (1,)),
    # level 2 by level 1's route and domain (the predicted route refined, search='predicted'):
    # the sphere (MD exact) and 60 deg
    "high-mu-level2-route": ((0.5, 1.0), (10.0,), (2,)),
    # level 2 by the route whose states start from the lower mu (mu/2 on level 1's grid,
    # dhfield.bem.pull_off.LowerMuWarmStart): the sphere (MD exact) first
    "high-mu-level2-lower-mu": ((1.0,), (10.0,), (2,)),
    "high-mu-level2-lower-mu-wide": ((0.5, 0.8), (10.0,), (2,)),
    "high-mu-level2-lower-mu-slender": ((0.1806, 0.3), (10.0,), (2,)),
    # run when the automatic route took the lower-mu start first (commits 7a99f24-76286e6; since cdd2470
    # it is the retry after GVG's start): the sphere (stored, converged), beta0 0.1 (58688f9: stored
    # not_converged after all three tries), beta0 0.1806 and 0.3 (stopped unfinished after 53 CPU min)
    "high-mu-lower-mu-check-sphere": ((1.0,), (10.0,), (1,)),
    "high-mu-slender-lower-mu": ((0.1,), (10.0,), (1,)),
    "high-mu-slender-lower-mu-check": ((0.1806, 0.3), (10.0,), (1,)),
    # the route's states mixed with Anderson memory STRETCH_ANDERSON_MEMORY = 30, no periodic restarts
    # (seventh session; python -m verification.bench_anderson): beta0 0.1 at level 1, and level 2 of
    # the sphere (MD exact), then of the others.  From 7eee468 beta0 0.1 still failed (its third state,
    # from the lower-mu start); since the next commit the states after the first start from their
    # converged neighbour (Branch external_fallback), and the part was run again
    "high-mu-anderson-slender": ((0.1,), (10.0,), (1,)),
    "high-mu-level2-anderson-sphere": ((1.0,), (10.0,), (2,)),
    "high-mu-level2-anderson-wide": ((0.5, 0.8), (10.0,), (2,)),
    "high-mu-level2-anderson-slender": ((0.1806, 0.3), (10.0,), (2,)),
    # level 2 whose states start from the route's own state on level 1's grid (the same mu,
    # dhfield.bem.pull_off.CoarseRouteWarmStart; eighth session; every state since b423276, the first
    # only at 58a0056): from the lower-mu start the sphere's and beta0 0.8's first states were still at
    # residual 4e-4 and 1e-3 after 125 and 109 outer iterations (parts high-mu-level2-anderson-*,
    # stopped); from level 1's state beta0 0.8's converged in 18.  None of these parts finished in that
    # session: beta0 0.8's third state was at 1.2e-4 after 120 outer iterations when stopped, the
    # sphere's first stalled at 2-7e-3, and 0.5's and 0.1806's first level-1 states stalled
    "high-mu-level2-coarse-route-sphere": ((1.0,), (10.0,), (2,)),
    "high-mu-level2-coarse-route-wide": ((0.5, 0.8), (10.0,), (2,)),
    "high-mu-level2-coarse-route-slender": ((0.1806, 0.3), (10.0,), (2,)),
    "high-mu-level2-coarse-route-slenderest": ((0.1,), (10.0,), (2,)),
    "high-mu-level2-coarse-route-60deg": ((0.5,), (10.0,), (2,)),
    "high-mu-level2-coarse-route-30deg": ((0.1806,), (10.0,), (2,)),
    # level 2 with every state raced (ninth session, dhfield.bem.branch.Branch.race): from level 1's
    # state, then from the nearest converged level-2 state dilated, then from the lower-mu start of
    # the level-2 grid; the sphere (MD exact) and beta0 0.8 (whose first two states converged above)
    # Ninth session: -wide (at 4caa76d, before the give-up window) and -sphere (a9e0372) converged,
    # 61-63 CPU min each; -60deg's second state was still being raced when stopped for the final checks
    "high-mu-level2-race-sphere": ((1.0,), (10.0,), (2,)),
    "high-mu-level2-race-wide": ((0.8,), (10.0,), (2,)),
    "high-mu-level2-race-60deg": ((0.5,), (10.0,), (2,)),
    # tenth session: the slender cases, one part per core (beta0 0.1 holds the recommended model's
    # worst mu = 10 case).  Run then, nothing stored: -slenderest (109c033) lost its first level-2
    # state (given up, then the lower-mu alternative gave None: since mended, Branch.race); -45deg
    # and -60deg (8cc34c8, a7442c6) lost level 1's first state under level 2 and were stopped
    # (docs/theory/bem.rst)
    "high-mu-level2-race-slenderest": ((0.1,), (10.0,), (2,)),
    "high-mu-level2-race-30deg": ((0.1806,), (10.0,), (2,)),
    "high-mu-level2-race-45deg": ((0.3,), (10.0,), (2,)),
    # eleventh to fourteenth sessions: the parts high-mu-level2-widest-* ([bem] widest_edge),
    # high-mu-level2-retry-lattice-* and high-mu-level2-lattice2-60deg ([bem] base_lattice) solved
    # level 2 of the mu = 10 cases with the options removed on 2026-12-02 (CHANGELOG); their cases
    # stay in the dataset (held from the previous build, each with its commit and command)
}

_KEY = 6  # decimals of beta0 and mu when matching cases of different files


def part_config(name, max_seconds=None) -> str:
    """The TOML text of a part (quantity adhesive, Dugdale, load control, grid levels).

    ``max_seconds`` [s] goes to ``[bem] max_seconds`` (the estimated time allowed per case; default
    the library's): it is not in the sweep's fingerprint, so a part rerun with more resumes its store.
    """
    beta0, mu, levels = PARTS[name]
    fmt = lambda v: "[" + ", ".join(f"{x:g}" for x in v) + "]"  # noqa: E731
    keys = {} if max_seconds is None else {"max_seconds": float(max_seconds)}
    value = lambda v: ("true" if v else "false") if isinstance(v, bool) else repr(v)  # noqa: E731
    bem = "".join(f"{k} = {value(v)}\n" for k, v in keys.items())
    bem = f"\n[bem]\n{bem}" if bem else ""
    return (f"# issue 20 extended ground truth, part {name!r} (python -m verification.study_extended)\n"
            "[sweep]\nquantities = [\"adhesive\"]\ncontrol = \"load\"\n\n"
            f"[axes]\nbeta0 = {fmt(beta0)}\nmu = {fmt(mu)}\ngrid_level = {fmt(levels)}\nlaw = [\"dugdale\"]\n"
            + bem)


def _sweep_command(toml, out, workers):
    exe = Path(sys.executable).with_name("dhfield")
    head = [str(exe)] if exe.is_file() else [sys.executable, "-c", "import sys; from dhfield.cli import main; "
                                                                   "sys.exit(main(sys.argv[1:]))"]
    return head + ["sweep", str(toml), "--scheduler", "processes", "--workers", str(workers), "--out", str(out),
                   "--quiet"]


def run_part(name, work_dir, workers=1, timeout=None, max_seconds=None) -> int:
    """Run one part through ``dhfield sweep``; print its cases and wall time."""
    work = Path(work_dir)
    work.mkdir(parents=True, exist_ok=True)
    toml, out = work / f"{name}.toml", work / f"{name}.nc"
    toml.write_text(part_config(name, max_seconds))
    cmd = _sweep_command(toml, out, workers)
    print(f"[{name}] {shlex.join(cmd)}", flush=True)
    t0 = time.perf_counter()
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.Popen(cmd, start_new_session=True)   # its own group: a timeout stops its workers too
    try:
        rc = proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (cpu1.ru_utime + cpu1.ru_stime) - (cpu0.ru_utime + cpu0.ru_stime)
        wall = time.perf_counter() - t0
        write_attempt(work, name, timeout, wall, cpu, shlex.join(cmd))
        print(f"[{name}] stopped after the hard timeout of {timeout:g} s ({wall:.0f} s wall, {cpu:.0f} s CPU of the "
              "processes reaped); finished cases are in its store", flush=True)
        return 124
    print(f"[{name}] dhfield sweep exit {rc} after {time.perf_counter() - t0:.0f} s wall", flush=True)
    if out.is_file():
        print_sweep(out)
    return rc


def write_attempt(work_dir, name, timeout, wall, cpu, command) -> Path:
    """Record a part stopped at its hard timeout (read by :func:`build` for the cases it did not finish)."""
    from dhfield.io import atomic_path, git_commit

    path = Path(work_dir) / f"{name}.timeout.json"
    beta0, mu, levels = PARTS[name]
    rec = {"part": name, "beta0": list(beta0), "mu": list(mu), "levels": list(levels), "timeout_s": timeout,
           "wall_s": wall, "cpu_s": cpu, "command": command, "commit": git_commit(),
           "stopped": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "load_average": list(os.getloadavg())}
    with atomic_path(path) as tmp:
        Path(tmp).write_text(json.dumps(rec, indent=1))
    return path


def _store_state(store_dir, key):
    """What a part's case store holds of case ``key``: ("finished", status, message), ("failed", message) or None.

    The sweep writes ``<key>.nc`` when a case finishes (status ok, not_converged or unresolved) and
    ``<key>.failed.nc`` when it raises (:class:`dhfield.sweep.store.CaseStore`); a case it started
    and did not finish leaves nothing.
    """
    from dhfield.io import read_netcdf

    for suffix, state in ((".nc", "finished"), (".failed.nc", "failed")):
        path = Path(store_dir) / f"{key}{suffix}"
        if path.is_file():
            ds = read_netcdf(path)
            message = str(ds.attrs.get("message", ""))
            return (state, str(ds.attrs.get("status", "")), message) if state == "finished" else (state, message)
    return None


def _attempts(work_dir) -> dict:
    """(beta0, mu, level) -> one line about a case of a part stopped at its hard timeout.

    The part's case store (``<part>.nc.cases/``, read now) tells which of its cases had finished
    (or failed) and which had not; the sweep keeps no record of a case it started, so an unfinished
    case is said to be not finished, not attempted: with W workers, W of them at most were running
    at the stop (the sweep starts the costliest first) and the rest were not reached.
    """
    from dhfield.sweep.engine import case_key
    from dhfield.sweep.store import output_paths

    out = {}
    for p in sorted(Path(work_dir).glob("*.timeout.json")):
        r = json.loads(p.read_text())
        stop = (f"part {r['part']} stopped at its hard timeout of {r['timeout_s']:g} s on {r['stopped']} "
                f"({r['command']}; commit {r['commit']}; {r['wall_s']:.0f} s wall, {r['cpu_s']:.0f} s CPU, load "
                f"average {r['load_average'][0]:.1f} on this shared machine)")
        store_dir = output_paths(Path(work_dir) / f"{r['part']}.nc")[1]
        cases = [((ib, im, il), (b, m, lv)) for ib, b in enumerate(r["beta0"]) for im, m in enumerate(r["mu"])
                 for il, lv in enumerate(r["levels"])]
        states = {idx: _store_state(store_dir, case_key("adhesive", (*idx, 0))) for idx, _ in cases}
        ended = sum(st is not None for st in states.values())
        for idx, (b, m, lv) in cases:
            st = states[idx]
            if st is None:
                line = (f"not finished when {stop}: {ended} of the part's {len(cases)} cases had ended (finished or "
                        f"failed) in its case store {store_dir.name}/, not this one (the sweep solves the costliest "
                        "first, one per worker, and records no start: this case was running at the stop or was not "
                        "reached)")
            elif st[0] == "finished":
                line = (f"finished (status {st[1]}) in the case store {store_dir.name}/ before {stop}; the part's "
                        "sweep output was not written, so build reads the case from the store")
            else:
                line = f"failed in part {r['part']} ({st[1]}), before {stop}"
            out[(round(float(b), _KEY), round(float(m), _KEY), int(lv))] = line
    return out


def print_sweep(path) -> None:
    """One line per case of a part's sweep output."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        ds = ds.isel(law=0)
        w = ds["W_star"].sel(model="bem-adhesive")
        st = ds["status"].sel(model="bem-adhesive")
        for b in ds["beta0"].values:
            for m in ds["mu"].values:
                for lv in ds["grid_level"].values:
                    c = dict(beta0=b, mu=m, grid_level=lv)
                    nx, ny = (float(ds[k].sel(c)) for k in ("nx", "ny"))
                    grid = f"{nx:.0f} x {ny:.0f}" if np.isfinite(nx) and np.isfinite(ny) else "no grid"
                    print(f"  beta0 {b:g} mu {m:g} level {lv}: {grid} "
                          f"W* = {float(w.sel(c)):.6f} +- {float(ds['W_star_error'].sel(c)):.2g} status "
                          f"{int(st.sel(c))} [{str(ds['adhesive_search'].sel(c).values)}] "
                          f"{float(ds['wall_seconds'].sel(c)):.1f} s wall, {float(ds['cpu_seconds'].sel(c)):.1f} s CPU"
                          + (f" | {str(ds['adhesive_message'].sel(c).values)}" if str(
                              ds["adhesive_message"].sel(c).values) else ""), flush=True)


# --------------------------------------------------------------------------- merge
#: Per-case numbers of the merged dataset.
NUMERIC = ("W_star", "W_star_error", "a_star", "b_star", "c_star", "d_star", "delta_star", "nx", "ny",
           "half_width_x", "half_width_y", "iterations", "n_steps", "wall_seconds", "cpu_seconds")
#: Per-case text of the merged dataset.
TEXT = ("status", "search", "message", "source", "commit", "command", "finished")
_STATUS_SWEEP = {0: "ok", 1: "not_converged", 2: "failed", 3: "unresolved"}


def _case(**kw) -> dict:
    rec = {k: float("nan") for k in NUMERIC}
    rec.update({k: "" for k in TEXT}, converged=-1, resolved=-1)
    rec.update(kw)
    return rec


def _old_cases():
    """(beta0, mu) -> {level: case} of the N-ladder set, its truth and its ladder."""
    import xarray as xr

    cases, truth, ladder = {}, {}, {}
    with xr.open_dataset(OLD) as ds:
        command = str(ds.attrs.get("param_command", ""))
        created = str(ds.attrs.get("history", "")).split(" ")[0]
        ns = [int(n) for n in ds["n"].values]
        for b in ds["beta0"].values:
            for m in ds["mu"].values:
                c = ds.sel(beta0=b, mu=m)
                key = (round(float(b), _KEY), round(float(m), _KEY))
                st = c["status"].values
                ladder[key] = (c["W_star"].values.astype(float), st.astype(np.int8))
                usable = [i for i in range(len(ns)) if st[i] in (0, 1) and np.isfinite(c["W_star"].values[i])]
                chosen = usable[-2:]
                if len(chosen) == 2 and ns[chosen[1]] != 2 * ns[chosen[0]]:
                    chosen = chosen[-1:]   # levels are twice the cells per axis apart
                per = {}
                for level, i in zip(range(3 - len(chosen), 3), chosen):
                    n = ns[i]
                    per[level] = _case(
                        W_star=float(c["W_star"].values[i]), a_star=float(c["a_star"].values[i]),
                        b_star=float(c["b_star"].values[i]), c_star=float(c["c_star"].values[i]),
                        d_star=float(c["d_star"].values[i]), delta_star=float(c["delta_star"].values[i]),
                        nx=float(n), ny=float(n), half_width_x=float(c["half_width_x"].values[i]),
                        half_width_y=float(c["half_width_y"].values[i]), iterations=float(c["iterations"].values[i]),
                        n_steps=float(c["n_steps"].values[i]), wall_seconds=float(c["elapsed"].values[i]),
                        converged=1, status="ok", search=str(c["search"].values[i]),
                        message=("states after the pull-off did not converge (the pull-off did)" if st[i] == 1
                                 else str(c["message"].values[i])),
                        source=f"adhesive_ground_truth.nc (verification.study_adhesive, N ladder, n = {n})",
                        commit=str(c["solver_source"].values[i]),
                        command=("python -m verification.study_adhesive (per-case command not recorded; the file's "
                                 f"last: {command})"), finished=created)
                cases[key] = per
                w_best = float(c["W_star_extrapolated"].values)
                if np.isfinite(w_best):
                    levels = int(c["W_star_levels"].values)
                    ws = [float(c["W_star"].values[i]) for i in usable]
                    err = abs(w_best - ws[-1]) if levels == 3 else (abs(ws[-1] - ws[-2]) if len(ws) > 1 else np.nan)
                    how = "Richardson over three N" if levels == 3 else "finest converged N"
                    truth[key] = (w_best, err, f"adhesive_ground_truth.nc W_star_extrapolated ({how})")
    return cases, truth, ladder, ns


def _slender_cases():
    import xarray as xr

    cases = {}
    with xr.open_dataset(SLENDER) as ds:
        for b in ds["beta0"].values:
            for m in ds["mu"].values:
                key = (round(float(b), _KEY), round(float(m), _KEY))
                per = {}
                for lv in ds["level"].values:
                    c = ds.sel(beta0=b, mu=m, level=lv)
                    if not int(c["present"]):
                        continue
                    conv, res = int(c["converged"]), int(c["resolved"])
                    per[int(lv)] = _case(
                        **{k: float(c[k]) for k in ("W_star", "W_star_error", "a_star", "b_star", "c_star", "d_star",
                                                    "delta_star", "nx", "ny", "iterations")},
                        n_steps=float(c["states"]), wall_seconds=float(c["wall_s"]), cpu_seconds=float(c["cpu_s"]),
                        converged=conv, resolved=res,
                        status="ok" if conv and res else "not_converged" if not conv else "unresolved",
                        search=str(c["search"].values), message=str(c["note"].values),
                        source=f"adhesive_ground_truth_slender.nc (verification.bem_slender, level {int(lv)})",
                        commit=str(c["commit"].values), command=str(c["command"].values),
                        finished=str(c["finished"].values))
                cases[key] = per
    return cases


#: Values of a case the sweep stores (on the dim ``model`` for :data:`_SWEEP_MODEL_VALUES`), read by
#: :func:`_sweep_cases` from a part's output and by :func:`_stored_cases` from its case store.
_SWEEP_MODEL_VALUES = ("W_star", "a_star", "c_star", "delta_star")
_SWEEP_VALUES = (*_SWEEP_MODEL_VALUES, "W_star_error", "b_star", "d_star", "nx", "ny", "half_width_x", "half_width_y",
                 "iterations", "n_steps", "wall_seconds", "cpu_seconds")


def _sweep_cases(work_dir):
    """Cases of every part's sweep output under ``work_dir``: (beta0, mu) -> {level: case}.

    Parts are read in the order of :data:`PARTS`; a case in a later part replaces the same case of
    an earlier one (a part that runs again the cases others left without an answer comes later).
    A case's message is the sweep's (why it is not an answer) or, for an answer, the solver's note
    (e.g. :data:`dhfield.analysis.bem_start.WIDEST_EDGE_NOTE`, a lattice retry).
    """
    import xarray as xr

    cases = {}
    for name in PARTS:
        path = Path(work_dir) / f"{name}.nc"
        if not path.is_file():
            for key, lv, case in _stored_cases(work_dir, name):
                cases.setdefault(key, {})[lv] = case
            continue
        with xr.open_dataset(path) as ds:
            ds = ds.sel(law="dugdale")
            for b in ds["beta0"].values:
                for m in ds["mu"].values:
                    key = (round(float(b), _KEY), round(float(m), _KEY))
                    for lv in ds["grid_level"].values:
                        c = ds.sel(beta0=b, mu=m, grid_level=lv)
                        a = c.sel(model="bem-adhesive")
                        if not str(c["adhesive_finished"].values):
                            continue   # not computed (an interrupted sweep)
                        st = _STATUS_SWEEP[int(a["status"])]
                        cases.setdefault(key, {})[int(lv)] = _case(
                            **{k: float(a[k]) for k in _SWEEP_MODEL_VALUES},
                            **{k: float(c[k]) for k in _SWEEP_VALUES if k not in _SWEEP_MODEL_VALUES},
                            converged=int(c["converged"]), resolved=int(c["resolved"]), status=st,
                            search=str(c["adhesive_search"].values),
                            message=str(c["adhesive_message"].values) or str(c["adhesive_note"].values),
                            source=f"dhfield sweep (verification.study_extended part {name}, grid_level {int(lv)})",
                            commit=str(c["adhesive_commit"].values), command=str(c["adhesive_command"].values),
                            finished=str(c["adhesive_finished"].values))
    return cases


def _stored_cases(work_dir, name):
    """Cases a part stopped at its timeout had finished: ``(key, level, case)`` from its case store.

    A part that hits its hard timeout writes no sweep output, but each case it finished is in its
    case store (``<key>.nc``, :class:`dhfield.sweep.store.CaseStore`) with the same values and
    provenance the output would hold; the store's key indexes the part's axes (beta0, mu,
    grid_level, law) of :data:`PARTS`.  Nothing without the part's ``<name>.timeout.json``.
    """
    from dhfield.io import read_netcdf
    from dhfield.sweep.engine import case_key
    from dhfield.sweep.store import output_paths

    if not (Path(work_dir) / f"{name}.timeout.json").is_file():
        return []
    store_dir = output_paths(Path(work_dir) / f"{name}.nc")[1]
    beta0, mu, levels = PARTS[name]
    out = []
    for ib, b in enumerate(beta0):
        for im, m in enumerate(mu):
            for il, lv in enumerate(levels):
                path = store_dir / (case_key("adhesive", (ib, im, il, 0)) + ".nc")
                if not path.is_file():
                    continue
                ds = read_netcdf(path)
                a = ds.attrs
                num = {k: float(ds[k]) if k in ds else float("nan") for k in _SWEEP_VALUES}
                flags = {k: int(ds[k]) if k in ds and np.isfinite(float(ds[k])) else -1 for k in ("converged", "resolved")}
                out.append(((round(float(b), _KEY), round(float(m), _KEY)), int(lv), _case(
                    **num, **flags, status=str(a.get("status", "")),
                    search=str(a.get("case_search", "")),
                    message=str(a.get("message", "")) or str(a.get("case_note", "")),
                    source=(f"dhfield sweep (verification.study_extended part {name}, grid_level {int(lv)}; read "
                            f"from its case store {store_dir.name}/: the part stopped at its timeout)"),
                    commit=str(a.get("case_commit", "")), command=str(a.get("case_command", "")),
                    finished=str(a.get("case_finished", "")))))
    return out


#: Marks the source of a case read back from the previous build (:func:`_previous_cases`).
_HELD = "held from the previous build"


def _previous_cases(path):
    """Cases of the sweep parts that the previous build at ``path`` holds: (beta0, mu) -> {level: case}.

    A part's sweep output and case store live under ``--work-dir`` (``out/``, not in git), so a
    later session's work dir holds only the parts it ran; the cases earlier sessions ran are held
    in the dataset itself.  Every case of it whose source is a ``dhfield sweep`` part (the N-ladder
    and slender files are read again from themselves) is kept, with its values and provenance as
    stored and its source marked; a part's output in the work dir replaces it (:func:`build`).
    None of it when no file is there.
    """
    import xarray as xr

    path = Path(path)
    cases = {}
    if not path.is_file():
        return cases
    with xr.open_dataset(path) as ds:
        built = f"{ds.attrs.get('built', '?')}, build commit {str(ds.attrs.get('build_commit', '?'))[:12]}"
        for i, b in enumerate(ds["beta0"].values):
            for j, m in enumerate(ds["mu"].values):
                for k, lv in enumerate(ds["level"].values):
                    src = str(ds["source"].values[i, j, k])
                    if not src.startswith("dhfield sweep"):
                        continue
                    if _HELD not in src:
                        src = f"{src} [{_HELD} of {path.name}, {built}]"
                    num = {key: float(ds[key].values[i, j, k]) for key in NUMERIC}
                    text = {key: str(ds[key].values[i, j, k]) for key in TEXT}
                    text["source"] = src
                    cases.setdefault((round(float(b), _KEY), round(float(m), _KEY)), {})[int(lv)] = _case(
                        **num, **text, converged=int(ds["converged"].values[i, j, k]),
                        resolved=int(ds["resolved"].values[i, j, k]))
    return cases


def _truth_of_levels(per):
    """Best W* of a two-level case: the finest answer, its error max(stated, |level 2 - level 1|)."""
    ok = {lv: c for lv, c in per.items() if c["status"] == "ok" and np.isfinite(c["W_star"])}
    if not ok:
        return None
    top = max(ok)
    w, err = ok[top]["W_star"], ok[top]["W_star_error"]
    err = err if np.isfinite(err) else 0.0
    if len(ok) > 1:
        err = max(err, abs(ok[max(ok)]["W_star"] - ok[min(ok)]["W_star"]))
    elif not np.isfinite(ok[top]["W_star_error"]):
        err = float("nan")
    return w, err, f"{ok[top]['source']} (finest level answering)"


def build(work_dir, out) -> int:
    """Merge the stored files and the sweep outputs into the extended dataset; list the cases not run."""
    import xarray as xr

    from dhfield.io import git_commit, write_netcdf

    old, old_truth, ladder, ns = _old_cases()
    swept = _previous_cases(out)          # the parts earlier sessions ran, as the last build holds them
    held = sum(len(per) for per in swept.values())
    for key, per in _sweep_cases(work_dir).items():
        swept.setdefault(key, {}).update(per)   # a part's output in the work dir replaces the held case
    sources = [("adhesive_ground_truth.nc", old), ("adhesive_ground_truth_slender.nc", _slender_cases()),
               ("dhfield sweep", swept)]
    merged, duplicates = {}, []
    for label, cases in sources:
        for key, per in cases.items():
            for lv, c in per.items():
                if lv in merged.get(key, {}):
                    duplicates.append(f"beta0 {key[0]:g} mu {key[1]:g} level {lv}: kept "
                                      f"{merged[key][lv]['source']}, not {c['source']}")
                    continue
                merged.setdefault(key, {})[lv] = c
    study = {(round(b, _KEY), round(m, _KEY)) for b in BETA0 for m in MU}
    b0 = sorted({k[0] for k in merged} | {k[0] for k in study})
    mus = sorted({k[1] for k in merged} | {k[1] for k in study})
    shape = (len(b0), len(mus), len(LEVELS))
    num = {k: np.full(shape, np.nan) for k in NUMERIC}
    flags = {k: np.full(shape, -1, dtype=np.int8) for k in ("converged", "resolved")}
    text = {k: np.full(shape, "", dtype=object) for k in TEXT}
    truth = {k: np.full(shape[:2], np.nan) for k in ("W_star_truth", "W_star_truth_error")}
    truth_src = np.full(shape[:2], "", dtype=object)
    in_study = np.zeros(shape[:2], dtype=np.int8)
    w_ladder = np.full(shape[:2] + (len(ns),), np.nan)
    st_ladder = np.full(shape[:2] + (len(ns),), -1, dtype=np.int8)
    not_run, attempts = [], _attempts(work_dir)
    for i, b in enumerate(b0):
        for j, m in enumerate(mus):
            key = (b, m)
            per = merged.get(key, {})
            in_study[i, j] = key in study
            for li, lv in enumerate(LEVELS):
                c = per.get(lv)
                if c is None:
                    text["status"][i, j, li] = "not run" if key in study else "absent"
                    text["message"][i, j, li] = attempts.get((b, m, lv), "")
                    if key in study:
                        not_run.append((b, m, lv))
                    continue
                for k in NUMERIC:
                    num[k][i, j, li] = c[k]
                for k in flags:
                    flags[k][i, j, li] = c[k]
                for k in TEXT:
                    text[k][i, j, li] = c[k]
            best = old_truth.get(key) or _truth_of_levels(per)
            if best is not None:
                truth["W_star_truth"][i, j], truth["W_star_truth_error"][i, j], truth_src[i, j] = best
            if key in ladder:
                w_ladder[i, j], st_ladder[i, j] = ladder[key]
    dims = ("beta0", "mu", "level")
    units = {"nx": "1", "ny": "1", "wall_seconds": "s", "cpu_seconds": "s"}
    long = {
        "W_star": "normalised load W sin(theta_skew)/(2 pi R dgamma) (Eq. 34), BEM at pull-off (load control)",
        "W_star_error": "stated error of W_star (search + discretisation); NaN: the source states none; inf: none "
                        "possible (not resolved)",
        "a_star": "contact semi-major axis a/c_r (Eq. 32)", "b_star": "contact semi-minor axis b/c_r (Eq. 32)",
        "c_star": "adhesive semi-major axis c/c_r (Eq. 32)", "d_star": "adhesive semi-minor axis d/c_r (Eq. 32)",
        "delta_star": "approach delta R/c_r^2 at pull-off", "nx": "BEM cells along x", "ny": "BEM cells along y",
        "half_width_x": "domain half-width along x, in c_r", "half_width_y": "domain half-width along y, in c_r",
        "iterations": "conjugate-gradient iterations of the case", "n_steps": "states solved on the load path",
        "wall_seconds": "wall time of the case on a shared 2-core machine (load varies)",
        "cpu_seconds": "CPU time of the case (NaN: not recorded by its source)",
        "converged": "1: every state down to the pull-off converged; 0: not; -1: no case or not recorded",
        "resolved": "1: the grid resolves the cohesive zone and the contact; 0: not; -1: no case or not recorded",
        "status": "ok, not_converged, unresolved, failed, 'not run' (a case of the extended study that no source "
                  "holds) or absent (outside the extended study)",
        "search": "route that gave the pull-off (the solver's search)",
        "message": "why the case is not an answer, or the source's note on it; for a case not run, what the case "
                   "store of a part stopped at its hard timeout holds of it, if any (empty: none)",
        "source": "file and script (or dhfield sweep part) that produced the case",
        "commit": "git commit of the code that solved the case",
        "command": "command line that solved the case",
        "finished": "UTC time the case finished (N-ladder set: the file's creation date)",
    }
    data = {k: (dims, v, {"long_name": long[k], "units": units.get(k, "1")}) for k, v in num.items()}
    data.update({k: (dims, v, {"long_name": long[k]}) for k, v in flags.items()})
    data.update({k: (dims, v.astype(str), {"long_name": long[k]}) for k, v in text.items()})
    data["W_star_truth"] = (("beta0", "mu"), truth["W_star_truth"], {
        "long_name": "best BEM W* of the point: the N-ladder set's W_star_extrapolated where it has the point, "
                     "else the finest level answering (status ok)", "units": "1"})
    data["W_star_truth_error"] = (("beta0", "mu"), truth["W_star_truth_error"], {
        "long_name": "error estimate of W_star_truth: max(stated error, |level 2 - level 1|); N-ladder set: the "
                     "Richardson correction, or the difference of its two finest N", "units": "1"})
    data["truth_source"] = (("beta0", "mu"), truth_src.astype(str), {"long_name": "where W_star_truth comes from"})
    data["extended_study"] = (("beta0", "mu"), in_study, {"long_name": "1: a point of issue 20's extended study "
                                                                         "(beta0 x mu grid)"})
    data["W_star_ladder"] = (("beta0", "mu", "n"), w_ladder, {
        "long_name": "W_star of the N-ladder set (adhesive_ground_truth.nc) on its whole ladder, as stored",
        "units": "1"})
    data["status_ladder"] = (("beta0", "mu", "n"), st_ladder, {
        "long_name": "status of the N-ladder set's cases as stored (-1: no such point)",
        "flag_values": np.array([-1, 0, 1, 2, 3, 4], dtype=np.int8),
        "flag_meanings": "absent ok unconverged_after_pull_off unconverged failed missing"})
    ds = xr.Dataset(data, coords={
        "beta0": ("beta0", np.asarray(b0), {"long_name": "Hertz ellipticity b/a of the geometry (Eq. 9)",
                                            "units": "1"}),
        "mu": ("mu", np.asarray(mus), {"long_name": "Tabor parameter (Eq. 35)", "units": "1"}),
        "level": ("level", np.asarray(LEVELS, dtype=np.int32), {
            "long_name": "grid level: 1 the coarser, 2 twice its cells per axis (sweep and slender set: 1 the "
                         "automatic grid and route; N-ladder set: its two finest usable N)", "units": "1"}),
        "n": ("n", np.asarray(ns, dtype=np.int32), {"long_name": "cells per side of the N-ladder set", "units": "1"})})
    ds.attrs.update(
        title="Adhesive BEM ground truth, extended (issue 20): Dugdale law, load control",
        description=("The stored N-ladder set (adhesive_ground_truth.nc), the slender set "
                     "(adhesive_ground_truth_slender.nc) and the cases run through dhfield sweep "
                     "(verification.study_extended) on one (beta0, mu, level) grid, with per-case provenance. "
                     "Extended study: beta0 " + " ".join(f"{b:g}" for b in BETA0) + " x mu "
                     + " ".join(f"{m:g}" for m in MU) + " (beta0 0.1806: the stored 30 deg slender case, for the "
                     "issue's 0.18). dhfield output: never a test reference."),
        not_run_cases="; ".join(f"beta0 {b:g} mu {m:g} level {lv}" for b, m, lv in not_run) or "none",
        attempts_stopped="; ".join(f"beta0 {b:g} mu {m:g} level {lv}: {line}" for (b, m, lv), line in
                                   sorted(attempts.items())) or "none",
        duplicates_skipped="; ".join(duplicates) or "none",
        nondimensionalisation="R = E* = dgamma = 1 (Eqs. 32-35): lengths in c_r, W* = W sin(theta_skew)/(2 pi R "
                              "dgamma) (Eq. 34), sigma0 = mu, h0 = 1/mu",
        built=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), build_commit=git_commit(),
        build_command=shlex.join([sys.executable, "-m", "verification.study_extended", *sys.argv[1:]]))
    write_netcdf(ds, out)
    print(f"read {held} sweep cases held by the previous build of {Path(out).name}; the work dir's parts replace "
          "the same cases")
    print(f"wrote {out}: {len(b0)} beta0 x {len(mus)} mu x {len(LEVELS)} levels; "
          f"{int(np.sum(text['status'] != 'absent') - len(not_run))} cases held, {len(not_run)} of the extended "
          "study not run")
    for line in duplicates:
        print(f"  duplicate skipped: {line}")
    print("extended study (beta0 x mu): W*_truth +- error [source]")
    for i, b in enumerate(b0):
        for j, m in enumerate(mus):
            if in_study[i, j]:
                print(f"  beta0 {b:6g} mu {m:5g}: {truth['W_star_truth'][i, j]:+.6f} +- "
                      f"{truth['W_star_truth_error'][i, j]:.2g}  [{truth_src[i, j] or 'none'}]")
    for line in _not_run_lines(not_run, attempts):
        print(line)
    return 0


def _not_run_lines(not_run, attempts) -> list:
    """The build's closing lines: the cases not run, each with what a stopped part's record says of it,
    then the cases held (read from a stopped part's case store, or answered by a later part) with what the
    stopped part's record says of them, under their own header, not as 'not run'."""
    missing = {(round(float(b), _KEY), round(float(m), _KEY), int(lv)) for b, m, lv in not_run}
    lines = [f"not run ({len(not_run)}): " + ("; ".join(f"beta0 {b:g} mu {m:g} level {lv}" for b, m, lv in not_run)
                                             or "none")]
    lines += [f"  beta0 {k[0]:g} mu {k[1]:g} level {k[2]}: {line}" for k, line in sorted(attempts.items())
              if k in missing]
    read = [(k, line) for k, line in sorted(attempts.items()) if k not in missing]
    if read:
        lines.append(f"cases held, with what the timeout record of a stopped part says of them ({len(read)}):")
        lines += [f"  beta0 {k[0]:g} mu {k[1]:g} level {k[2]}: {line}" for k, line in read]
    return lines


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.study_extended", description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="job", required=True)
    r = sub.add_parser("run", help="run parts of the study through dhfield sweep")
    r.add_argument("parts", nargs="+", choices=sorted(PARTS))
    r.add_argument("--workers", type=int, default=1, help="dask worker processes (default 1)")
    r.add_argument("--timeout", type=float, default=None, help="hard wall-clock limit per part [s]")
    r.add_argument("--max-seconds", type=float, default=None,
                   help="estimated time allowed per case [s] ([bem] max_seconds of the part; default the library's "
                        "1800 s: e.g. 4000 for the mu = 10 level-2 cases, estimated 42-57 min)")
    r.add_argument("--work-dir", default=str(DEFAULT_WORK_DIR))
    b = sub.add_parser("build", help="merge the stored files and the sweep outputs into the extended dataset")
    b.add_argument("--work-dir", default=str(DEFAULT_WORK_DIR))
    b.add_argument("--out", default=str(DEFAULT_OUT))
    args = p.parse_args(argv)
    if args.job == "run":
        if args.workers < 1 or (args.timeout is not None and not args.timeout > 0):
            p.error("--workers must be >= 1 and --timeout > 0")
        if args.max_seconds is not None and not (np.isfinite(args.max_seconds) and args.max_seconds > 0):
            p.error("--max-seconds must be a finite number > 0 (estimated time allowed per case, s)")
        rc = 0
        for name in args.parts:
            rc = max(rc, run_part(name, args.work_dir, args.workers, args.timeout, args.max_seconds))
        return rc
    return build(args.work_dir, args.out)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
