"""Adhesive ground truth: BEM pull-off of the elliptical Dugdale contact over (beta0, mu, N).

For every case (beta0, mu) of the grid of issue 8,

    beta0 in {0.5, 0.6, 0.8, 0.9, 0.99, 1},  mu in {0.3, 0.5, 1, 2, 5},

and every N of a ladder (cells per axis, doubling), the self-consistent adhesive
BEM (:func:`dhfield.bem.adhesive_pull_off`, Dugdale law sigma0 = mu,
h0 = 1/mu in the paper's units) gives W*max (Eq. 34 normalisation), the
second-moment semi-axes a*, b*, c*, d* and beta_ab = b/a, beta_cd = d/c at the
pull-off.  The three finest N are Richardson-extrapolated
(:func:`dhfield.bem.richardson_extrapolation`); the result is stored next to
every analytic model of :mod:`dhfield.analysis.compare` at the same (beta0, mu): the
paper's closure (``dh-elliptic``), its JKR-beta variant, the ray-average and
two-axis closures, elliptical JKR (Johnson & Greenwood 2005) and Maugis-Dugdale
(a sphere with R = sqrt(R'R''), lambda = 1.1272 mu).

Resumable
---------
The cases live in the sweeps' resumable store (:class:`dhfield.sweep.store.CaseStore`)
under ``--work-dir``: every finished (beta0, mu, N) case is written at once,
atomically, as a small netCDF file named by its parameters, and a rerun reads the
cases already there.  A case whose path has unconverged states is recorded with its
status and message; a case that raised is recorded too (status 'failed', kept in the
consolidated file) and, as in a sweep, solved again by the next run.
The cases run N by N (all of the coarsest N first; mu = 5, the costly column, after
everything else), so an interrupted run still covers the grid at the coarser N.

Consolidation
-------------
``data/adhesive_ground_truth.nc`` (small: scalars per case, no fields), dims
``(beta0, mu, n)`` plus ``model`` for the analytic references, with
provenance: git commit, command line, per-case wall times, the N ladder, the
solver tolerances, and per case a status flag (ok / unconverged / failed /
missing) and message.  :func:`read_ground_truth` reads it back.

Usage::

    .venv/bin/python -m verification.study_adhesive                     # the whole study
    .venv/bin/python -m verification.study_adhesive --beta0 1 --mu 1 --n 64 128 256
    .venv/bin/python -m verification.study_adhesive --consolidate-only   # rebuild the .nc
"""
from __future__ import annotations

import os

# Before numpy loads OpenBLAS: its threads make the CG's dot products of 128 x 128 arrays take tens of
# ms instead of microseconds on a loaded 2-core machine (measured: Hertz N = 256 solve 7.2 s -> 0.9 s).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import functools
import json
import math
import shlex
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
#: The (beta0, mu) grid of issue 8.
BETA0 = (0.5, 0.6, 0.8, 0.9, 0.99, 1.0)
MU = (0.3, 0.5, 1.0, 2.0, 5.0)
#: Default N ladder (cells per axis): 3 levels for Richardson extrapolation, affordable
#: for all 30 cases in about an hour on 2 cores.
N_LADDER = (64, 128, 256)
#: CG iterations per state in the study: converged states take ~50 (measured: 1647 over 35
#: states at beta0 = 1, mu = 1, N = 128); the solver default (20000) lets a failing state
#: cost minutes.
STUDY_MAX_ITER = 3000
DEFAULT_WORK_DIR = ROOT / "out" / "adhesive_study"
DEFAULT_OUT = ROOT / "data" / "adhesive_ground_truth.nc"
#: Analytic models stored next to the BEM (names of dhfield.analysis.compare.MODEL_NAMES).
REFERENCE_MODELS = ("dh-elliptic", "dh-elliptic-jkr-beta", "dh-elliptic-ray-average",
                    "dh-elliptic-two-axis", "jkr-elliptic", "md", "dmt")
#: Status codes of a case (CF flag values in the dataset).  "unconverged_after_pull_off":
#: every unconverged state of the path lies beyond the pull-off (smaller approach, after
#: detachment), where it cannot move the reported minimum; such levels are used.
STATUSES = ("ok", "unconverged_after_pull_off", "unconverged", "failed", "missing")
#: Statuses whose values enter the extrapolation and the verdict.
USABLE = ("ok", "unconverged_after_pull_off")
#: Scalars of a case record that go into the dataset.
CASE_FLOATS = ("W_star", "a_star", "b_star", "c_star", "d_star", "beta_ab", "beta_cd", "delta_star",
               "residual", "elapsed", "iterations", "n_steps", "half_width_x", "half_width_y")


# --------------------------------------------------------------------------- one case
def case_name(beta0: float, mu: float, n: int, law: str = "dugdale", control: str = "load") -> str:
    """File stem of one case, e.g. ``b0.8_m1_n256_dugdale_load``."""
    return f"b{beta0:g}_m{mu:g}_n{int(n)}_{law}_{control}"


def _write_json(record: dict, path: Path) -> Path:
    from dhfield.io import atomic_path

    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(record, indent=1, default=_json_default))
    return path


def _json_default(obj):
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(type(obj))


def run_case(beta0, mu, n, *, law="dugdale", control="load", solver=None, start=None, **options) -> dict:
    """Solve one case; return its record (never raises for a solver failure).

    Parameters
    ----------
    beta0, mu : float
        Initial ellipticity and Tabor parameter (Eq. 35) [-].
    n : int
        Cells per axis [-].
    solver : callable, optional
        ``solver(mu, beta0, n, law=..., control=..., **options) -> dhfield.core.records.PullOff``;
        default :func:`dhfield.bem.adhesive_pull_off` (tests pass a stand-in).
    start : dhfield.core.records.PullOff, optional
        The same case at a coarser N: then only the states around its pull-off are
        solved at ``n`` (:func:`dhfield.bem.refine_pull_off`, coarse to fine).

    Returns
    -------
    dict
        The parameters, ``status`` ('ok', 'unconverged' or 'failed'), ``message``
        (empty when ok: otherwise the parameters and the reason), and the
        scalars of the pull-off (NaN when failed).
    """
    return _solve_case(beta0, mu, n, law=law, control=control, solver=solver, start=start, **options)[0]


def _gathered(options) -> dict:
    """The study's flat options as keyword arguments of the library's pull-offs: the numerical
    settings (the fields of :class:`dhfield.analysis.bem_start.AdhesiveOptions`) gathered as ``options``."""
    from dataclasses import fields

    from dhfield.analysis.bem_start import AdhesiveOptions

    numerics = {f.name for f in fields(AdhesiveOptions)}
    return {**{k: v for k, v in options.items() if k not in numerics},
            "options": AdhesiveOptions(**{k: v for k, v in options.items() if k in numerics})}


def _adhesive_pull_off(*, beta0, mu, n, law, control, progress, **options):
    """:func:`dhfield.bem.adhesive_pull_off` with the study's flat options (:func:`_gathered`)."""
    from dhfield.bem import adhesive_pull_off

    return adhesive_pull_off(beta0=beta0, mu=mu, n=n, law=law, control=control, progress=progress,
                             **_gathered(options))


def _solve_case(beta0, mu, n, *, law="dugdale", control="load", solver=None, start=None, **options):
    """(record, result or None) of one case: :func:`run_case` keeping the solver's result."""
    if solver is None:
        solver = _adhesive_pull_off
    rec = {"beta0": float(beta0), "mu": float(mu), "n": int(n), "law": law, "control": control,
           "max_iter": int(options.get("max_iter", -1)),
           "route": "full path" if start is None else f"coarse to fine from n={int(start.n)}",
           "search": str(options.get("search", "located")) if start is None else "refine"}
    where = f"beta0={beta0:g}, mu={mu:g}, n={int(n)}, law={law}, control={control}"
    t0 = time.perf_counter()
    try:
        if start is None:
            res = solver(mu=float(mu), beta0=float(beta0), n=int(n), law=law, control=control, progress=False, **options)
        else:
            from dhfield.bem import refine_pull_off

            res = refine_pull_off(start, int(n), progress=False, **_gathered(options))
    except Exception as exc:  # noqa: BLE001 - a failed case is recorded, never dropped
        rec.update({k: float("nan") for k in CASE_FLOATS})
        rec.update(status="failed", message=f"{where}: {type(exc).__name__}: {exc}",
                   elapsed=time.perf_counter() - t0, converged=False, failures=[])
        return rec, None
    d = dict(res)   # the BEM's pull-off record (dhfield.core.records.PullOff, a mapping)
    for stored, key in (("beta_ab", "ellipticity"), ("beta_cd", "adhesive_ellipticity")):
        if key in d:
            d[stored] = d[key]      # the study's case files and dataset keep their names
    if d.get("search"):
        rec["search"] = str(d["search"])    # the route actually taken (a search may fall back)
    rec.update({k: float(d[k]) for k in CASE_FLOATS if k in d})
    rec["converged"] = bool(d["converged"])
    rec["failures"] = [dict(f) for f in d.get("failures", ())]
    rec["solver_source"] = _solver_source()
    if not rec["failures"]:
        rec.update(status="ok", message="")
    else:
        worst = max((f.get("residual", float("nan")) for f in rec["failures"]), default=float("nan"))
        after = rec["converged"] or all(float(f.get("approach", np.inf)) < rec["delta_star"]
                                        for f in rec["failures"])
        rec.update(status="unconverged_after_pull_off" if after else "unconverged",
                   message=f"{where}: {len(rec['failures'])} unconverged state(s) on the path"
                           f"{' (all beyond the pull-off)' if after else ''}, "
                           f"worst residual {worst:.3g}")
    if not d.get("resolved", True):
        # the solver's note says why (too coarse for the edge, a physical bound broken, a collapsed zone)
        note = str(d.get("note", ""))
        why = note[note.index("unresolved: "):] if "unresolved: " in note else \
            "unresolved: grid too coarse for the Dugdale edge"
        rec["message"] = (rec["message"] + "; " if rec["message"] else f"{where}: ") + f"{why} (resolved=False)"
    return rec, res


#: Cases with mu >= DEFER_MU run after all the others (at mu = 5 the zone spans few cells of
#: the coarse grids and a path costs minutes: measured 100-290 s at N = 64 against 1-25 s
#: for mu <= 2), so a run cut short still covers the rest of the grid over the whole ladder.
DEFER_MU = 5.0


def cases(beta0s, mus, ns):
    """The cases in run order: mu < DEFER_MU first, then by N ascending, mu, beta0."""
    todo = [(b, m, int(n)) for n in ns for b in beta0s for m in mus]
    return sorted(todo, key=lambda c: (c[1] >= DEFER_MU, c[2], c[1], c[0]))


#: Fingerprint of the study's case store (:class:`dhfield.sweep.store.CaseStore`): the layout of a
#: record.  A case's parameters are in its key (:func:`case_name`), its options in its record.
STORE_FINGERPRINT = "verification.study_adhesive case records v1"


def case_store(work_dir=DEFAULT_WORK_DIR):
    """The study's resumable case store in ``work_dir`` (created if missing)."""
    from dhfield.sweep.store import CaseStore

    return CaseStore(work_dir, STORE_FINGERPRINT, {"study": "verification.study_adhesive"})


def _record_dataset(rec: dict):
    """A case record as a store Dataset: its scalars as variables, the rest as a JSON attribute."""
    import xarray as xr

    ds = xr.Dataset({k: ((), float(rec[k])) for k in CASE_FLOATS if k in rec})
    # the store's status: a case that raised goes to its failure file and is retried by the next run
    ds.attrs.update(status="failed" if rec["status"] == "failed" else "ok", message=str(rec.get("message", "")),
                    record=json.dumps({k: v for k, v in rec.items() if k not in CASE_FLOATS},
                                      default=_json_default))
    return ds


def _dataset_record(ds) -> dict:
    rec = json.loads(ds.attrs["record"])
    rec.update({k: float(ds[k].values) for k in CASE_FLOATS if k in ds})
    return rec


def run_study(beta0s=BETA0, mus=MU, ns=N_LADDER, *, work_dir=DEFAULT_WORK_DIR, law="dugdale",
              control="load", solver=None, progress=None, coarse_to_fine=None, **options) -> list[dict]:
    """Run every case not yet in ``work_dir``; return all records of the requested cases.

    Each finished case is written at once to the study's :func:`case_store`
    (atomic); finished cases are read, not recomputed (resume), and cases that
    raised are solved again.  With
    ``coarse_to_fine=N0`` every n > N0 of the ladder is solved coarse to fine
    (:func:`dhfield.bem.refine_pull_off`) from the next coarser level solved in
    this run (the level N0 is re-solved in memory when its file already exists);
    the record's ``route`` says which.
    """
    store = case_store(work_dir)
    if progress is None:
        progress = sys.stderr.isatty()
    todo = cases(beta0s, mus, ns)
    out = []
    t0 = time.perf_counter()
    solved = {}                                   # (beta0, mu) -> result at the last n (coarse to fine)
    for k, (b, m, n) in enumerate(todo, 1):
        key = case_name(b, m, n, law, control)
        fine = coarse_to_fine is not None and n > int(coarse_to_fine) and control == "load"
        if store.is_done(key):
            out.append(_dataset_record(store.read(key)))
            continue
        start = solved.get((b, m)) if fine else None
        if fine and start is None:
            # the coarsest level of the route, solved again in memory (its file is kept)
            _, start = _solve_case(b, m, int(coarse_to_fine), law=law, control=control, solver=solver,
                                   **options)
        rec, res = _solve_case(b, m, n, law=law, control=control, solver=solver,
                               start=start if (start is not None and np.isfinite(start.delta_star)) else None,
                               **options)
        if coarse_to_fine is not None and res is not None and n >= int(coarse_to_fine):
            solved[(b, m)] = res
        store.write(key, _record_dataset(rec))
        out.append(rec)
        msg = (f"[{k}/{len(todo)}] beta0={b:g} mu={m:g} n={n}: {rec['status']} W*={rec['W_star']:.5f} "
               f"beta_ab={rec['beta_ab']:.4f} beta_cd={rec['beta_cd']:.4f} ({rec['elapsed']:.1f} s; "
               f"total {time.perf_counter() - t0:.0f} s)")
        print(msg, file=sys.stderr, flush=True)
        if rec["status"] != "ok":
            print(f"  {rec['message']}", file=sys.stderr, flush=True)
    return out


def load_records(work_dir=DEFAULT_WORK_DIR, law="dugdale", control="load") -> list[dict]:
    """Every case record stored in ``work_dir`` for ``law`` and ``control``."""
    store = case_store(work_dir)
    failed = [p.name[:-len(".failed.nc")] for p in store.directory.glob("*.failed.nc")]
    keys = sorted(k for k in set(store.keys()) | set(failed) if k.endswith(f"_{law}_{control}"))
    return [_dataset_record(store.read(k)) for k in keys]


# --------------------------------------------------------------------------- consolidation
def _git_commit() -> str:
    from dhfield.io import git_commit

    return git_commit()


@functools.lru_cache(maxsize=1)
def _solver_source() -> str:
    """Commit of the solver and whether dhfield/bem had uncommitted changes (provenance).

    Taken once per process: the solver is imported once, so later edits of the
    tree do not change the code that runs.
    """
    from dhfield.io import git_commit

    return git_commit(paths=("dhfield/bem",))


#: Observed orders for which the Richardson value is used.  The sub-cell zone edge makes the
#: convergence in N non-monotone at the 1e-4 level; an order below 0.5 (or above 4) from three
#: such levels would extrapolate the noise (measured: q = 0.16 at beta0 = 0.8, mu = 2 moved W*
#: by 1.3 % beyond N = 256), so the finest value is kept there.
RICHARDSON_ORDERS = (0.5, 4.0)


def extrapolate(ns, values):
    """Richardson value over the three finest *converged* levels of one case.

    Returns ``(value, order, levels)``: with fewer than three finite levels the
    finest finite value, NaN order, and the number of levels used; with a
    non-monotone sequence or an order outside :data:`RICHARDSON_ORDERS`, the
    finest value, the order found, and 1.
    """
    from dhfield.bem import richardson_extrapolation

    ns = np.asarray(ns, dtype=float)
    v = np.asarray(values, dtype=float)
    ok = np.isfinite(v)
    ns, v = ns[ok], v[ok]
    if v.size == 0:
        return float("nan"), float("nan"), 0
    if v.size < 3:
        return float(v[-1]), float("nan"), int(v.size)
    n3, v3 = ns[-3:], v[-3:]
    if not math.isclose(n3[2] / n3[1], n3[1] / n3[0], rel_tol=1e-9):
        return float(v3[-1]), float("nan"), 1
    val, q = richardson_extrapolation(n3, v3)
    if not RICHARDSON_ORDERS[0] <= q <= RICHARDSON_ORDERS[1]:
        return float(v3[-1]), float(q), 1  # implausible order: the finest value, the order for information
    return float(val), float(q), 3


def reference_table(beta0s, mus, models=REFERENCE_MODELS, control="load") -> dict:
    """model -> {'W_star', 'ellipticity', 'adhesive_ellipticity'} arrays of shape (beta0, mu)."""
    from dhfield.analysis import compare

    b = np.asarray(beta0s, float)[:, None]
    m = np.asarray(mus, float)[None, :]
    out = {}
    for name in models:
        rec = compare.pull_off(name, mu=m, beta0=b, control=control)
        out[name] = {k: np.broadcast_to(np.asarray(rec.get(k, np.nan), float), (b.size, m.size)).copy()
                     for k in ("W_star", "ellipticity", "adhesive_ellipticity")}
    return out


def cached_reference_table(work_dir, beta0s, mus, control="load") -> dict:
    """:func:`reference_table`, cached per (model, beta0, mu) in ``work_dir/references_<control>.json``.

    The closures cost minutes over the grid, so the table is computed once,
    vectorised over the whole grid, and stored atomically.
    """
    path = Path(work_dir) / f"references_{control}.json"
    cache = json.loads(path.read_text()) if path.is_file() else {}
    out = {m: {k: np.full((len(beta0s), len(mus)), np.nan) for k in ("W_star", "ellipticity",
                                                                      "adhesive_ellipticity")}
           for m in REFERENCE_MODELS}
    keys = {(i, j): f"{float(b)!r},{float(m)!r}" for i, b in enumerate(beta0s) for j, m in enumerate(mus)}
    if any(k not in cache for k in keys.values()):
        tab = reference_table(beta0s, mus, control=control)  # vectorised over the grid: one call per model
        for (i, j), key in keys.items():
            cache[key] = {name: {k: float(v[i, j]) for k, v in rec.items()} for name, rec in tab.items()}
        Path(work_dir).mkdir(parents=True, exist_ok=True)
        _write_json(cache, path)
    for (i, j), key in keys.items():
        for name in REFERENCE_MODELS:
            for k in out[name]:
                out[name][k][i, j] = cache[key][name][k]
    return out


def ground_truth_dataset(records, *, ns=None, references=None, command="", tolerances=None):
    """Consolidate case records into one small Dataset (no fields).

    Parameters
    ----------
    records : list of dict
        From :func:`run_study` / :func:`load_records`.
    ns : sequence of int, optional
        The N ladder (default: every n in the records).
    references : dict, optional
        :func:`reference_table` output; computed when None.
    command : str
        The command line, stored as provenance.
    tolerances : dict, optional
        Solver tolerances to store (default: dhfield.bem defaults).

    Returns
    -------
    xarray.Dataset
        dims (beta0, mu, n) and (model, beta0, mu); see the module docstring.
    """
    import xarray as xr

    from dhfield.io import cf, provenance_attrs

    if not records:
        raise ValueError("records must hold at least one case; got none")
    beta0s = sorted({float(r["beta0"]) for r in records})
    mus = sorted({float(r["mu"]) for r in records})
    ns = sorted({int(r["n"]) for r in records}) if ns is None else sorted(int(n) for n in ns)
    laws = {r.get("law", "dugdale") for r in records}
    controls = {r.get("control", "load") for r in records}
    if len(laws) > 1 or len(controls) > 1:
        raise ValueError(f"records must share one law and one control; got {sorted(laws)}, {sorted(controls)}")
    shape = (len(beta0s), len(mus), len(ns))
    val = {k: np.full(shape, np.nan) for k in CASE_FLOATS}
    status = np.full(shape, STATUSES.index("missing"), dtype=np.int8)
    cap = np.zeros(shape, dtype=np.int32)  # records without the field were run with STUDY_MAX_ITER
    message = np.full(shape, "", dtype=object)
    source = np.full(shape, "", dtype=object)
    route = np.full(shape, "", dtype=object)
    search = np.full(shape, "", dtype=object)
    for r in records:
        if int(r["n"]) not in ns:
            continue
        i, j, k = beta0s.index(float(r["beta0"])), mus.index(float(r["mu"])), ns.index(int(r["n"]))
        for key in CASE_FLOATS:
            val[key][i, j, k] = float(r.get(key, np.nan))
        cap[i, j, k] = int(r.get("max_iter", -1)) if int(r.get("max_iter", -1)) > 0 else STUDY_MAX_ITER
        status[i, j, k] = STATUSES.index(r["status"])
        message[i, j, k] = r.get("message", "")
        source[i, j, k] = r.get("solver_source", "")
        route[i, j, k] = r.get("route", "full path")
        search[i, j, k] = r.get("search", "march")      # records before the bracket search marched
    dims = ("beta0", "mu", "n")
    data = {}
    for key in ("W_star", "a_star", "b_star", "c_star", "d_star", "beta_ab", "beta_cd", "delta_star"):
        data[key] = cf.variable(key, dims, val[key], nondimensional=True, qualifier="BEM at pull-off")
    data["residual"] = (dims, val["residual"], {"long_name": "largest solver residual on the path",
                                                "units": "1"})
    data["iterations"] = (dims, val["iterations"], {"long_name": "conjugate-gradient iterations on the path",
                                                    "units": "1"})
    data["n_steps"] = (dims, val["n_steps"], {"long_name": "solved states on the path", "units": "1"})
    data["elapsed"] = (dims, val["elapsed"], {"long_name": "wall time of the case", "units": "s"})
    data["max_iter"] = (dims, cap, {"long_name": "CG iteration cap per state of the case (0: not run)",
                                    "units": "1"})
    for key in ("half_width_x", "half_width_y"):
        data[key] = (dims, val[key], {"long_name": f"domain {key.replace('_', ' ')}, in c_r", "units": "1"})
    data["status"] = (dims, status, {"long_name": "case status", "flag_values": np.arange(len(STATUSES),
                                                                                          dtype=np.int8),
                                     "flag_meanings": " ".join(STATUSES)})
    data["message"] = (dims, message.astype(str), {"long_name": "failure message naming the parameters"})
    data["route"] = (dims, route.astype(str), {
        "long_name": "how the case was solved: the full path, or coarse to fine from a coarser n "
                     "(dhfield.bem.refine_pull_off: only the states around the pull-off)"})
    data["search"] = (dims, search.astype(str), {
        "long_name": "load-minimum search of the path: march (unload from approach_max in uniform steps), "
                     "bracket (from the analytic pull-off), located (bracket with the minimum located on "
                     "coarser grids) or refine (coarse to fine)"})
    data["solver_source"] = (dims, source.astype(str), {
        "long_name": "git commit of the solver that computed the case (and whether dhfield/bem was modified)"})
    # Richardson over the finest three levels, per (beta0, mu); unconverged/failed levels excluded
    usable = np.isin(status, [STATUSES.index(s) for s in USABLE])
    for key in ("W_star", "beta_ab", "beta_cd", "a_star", "c_star"):
        ext = np.full(shape[:2], np.nan)
        order = np.full(shape[:2], np.nan)
        levels = np.zeros(shape[:2], dtype=np.int8)
        for i in range(shape[0]):
            for j in range(shape[1]):
                v = np.where(usable[i, j], val[key][i, j], np.nan)
                ext[i, j], order[i, j], levels[i, j] = extrapolate(ns, v)
        data[f"{key}_extrapolated"] = cf.variable(key, ("beta0", "mu"), ext, nondimensional=True,
                                                  qualifier="BEM, Richardson-extrapolated over n")
        data[f"{key}_order"] = (("beta0", "mu"), order, {
            "long_name": f"observed order of convergence of {key} in n (error ~ n^-order)", "units": "1"})
        data[f"{key}_levels"] = (("beta0", "mu"), levels, {
            "long_name": f"converged levels of n used for {key}_extrapolated (3: Richardson; "
                         "fewer: finest value)", "units": "1"})
    if references is None:
        references = reference_table(beta0s, mus, control=next(iter(controls)))
    models = list(references)
    data["W_star_model"] = cf.variable("W_star", ("model", "beta0", "mu"),
                                       np.stack([references[m]["W_star"] for m in models]),
                                       nondimensional=True, qualifier="analytic model at pull-off")
    data["ellipticity_model"] = cf.variable("ellipticity", ("model", "beta0", "mu"),
                                            np.stack([references[m]["ellipticity"] for m in models]),
                                            qualifier="analytic model at pull-off")
    data["adhesive_ellipticity_model"] = cf.variable(
        "adhesive_ellipticity", ("model", "beta0", "mu"),
        np.stack([references[m]["adhesive_ellipticity"] for m in models]), qualifier="analytic model at pull-off")
    coords = {"beta0": cf.coordinate("beta0", beta0s), "mu": cf.coordinate("mu", mus),
              "n": ("n", np.asarray(ns, dtype=np.int32), {"long_name": "cells per axis of the BEM grid",
                                                         "units": "1"}),
              "model": cf.label_coordinate("model", models)}
    ds = xr.Dataset(data, coords=coords)
    if tolerances is None:
        from dhfield import bem as adhesive

        tolerances = {"tol": adhesive.DEFAULT_TOL, "max_iter": adhesive.DEFAULT_MAX_ITER,
                      "domain_margin": adhesive.DOMAIN_MARGIN, "unloading_steps": adhesive.DEFAULT_STEPS}
    ds.attrs.update(provenance_attrs(
        "dhfield adhesive ground truth: BEM (Dugdale) pull-off of the elliptical contact vs analytic closures",
        law=next(iter(laws)), control=next(iter(controls)), n_ladder=" ".join(str(n) for n in ns),
        git_commit=_git_commit(), command=command,
        **{f"solver_{k}": v for k, v in tolerances.items()}))
    ds.attrs["nondimensionalisation"] = ("R = E* = dgamma = 1 (Eqs. 32-35): lengths in c_r, W* = W sin(theta_skew)"
                                         "/(2 pi R dgamma) (Eq. 34), sigma0 = mu, h0 = 1/mu")
    ds.attrs["extrapolation"] = ("Richardson over the three finest converged n of the ladder "
                                 "(dhfield.bem.richardson_extrapolation) where the observed order is in "
                                 f"[{RICHARDSON_ORDERS[0]}, {RICHARDSON_ORDERS[1]}] and the differences are "
                                 "monotone (levels = 3); otherwise the finest converged value (levels = 1 or 2)")
    ds.attrs["case_seconds_total"] = float(np.nansum(val["elapsed"]))
    return cf.finalize(ds)


def consolidate(work_dir=DEFAULT_WORK_DIR, out=DEFAULT_OUT, *, ns=None, law="dugdale", control="load",
                command="", references=None, max_iter=None) -> Path:
    """Write :func:`ground_truth_dataset` of the records in ``work_dir`` to ``out`` (atomic)."""
    from dhfield.io import check_writable, write_netcdf

    check_writable(out)
    records = load_records(work_dir, law, control)
    if references is None and records:
        beta0s = sorted({float(r["beta0"]) for r in records})
        mus = sorted({float(r["mu"]) for r in records})
        references = cached_reference_table(work_dir, beta0s, mus, control)
    tolerances = None
    if max_iter is not None:
        from dhfield import bem as adhesive

        tolerances = {"tol": adhesive.DEFAULT_TOL, "max_iter": int(max_iter),
                      "domain_margin": adhesive.DOMAIN_MARGIN, "unloading_steps": adhesive.DEFAULT_STEPS}
    ds = ground_truth_dataset(records, ns=ns, references=references, command=command, tolerances=tolerances)
    return write_netcdf(ds, out)


def read_ground_truth(path=DEFAULT_OUT):
    """Read the consolidated dataset; ValueError naming ``path`` if it is not one."""
    from dhfield.io import read_netcdf

    ds = read_netcdf(path)
    missing = [v for v in ("W_star", "beta_ab", "beta_cd", "status", "W_star_model") if v not in ds]
    if missing:
        raise ValueError(f"path must be an adhesive ground-truth dataset; {str(path)!r} lacks {missing}")
    return ds


# --------------------------------------------------------------------------- command line
def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.study_adhesive", description=__doc__.split("\n")[0])
    p.add_argument("--beta0", type=float, nargs="+", default=list(BETA0), help="initial ellipticities (0, 1]")
    p.add_argument("--mu", type=float, nargs="+", default=list(MU), help="Tabor parameters (Eq. 35), > 0")
    p.add_argument("--n", type=int, nargs="+", default=list(N_LADDER), help="N ladder, cells per axis (even)")
    p.add_argument("--law", default="dugdale", choices=("dugdale", "exponential"))
    p.add_argument("--control", default="load", choices=("load", "displacement"))
    p.add_argument("--work-dir", type=Path, default=DEFAULT_WORK_DIR, help="per-case JSON files (resume)")
    p.add_argument("--out", type=Path, default=DEFAULT_OUT, help="consolidated netCDF")
    p.add_argument("--max-iter", type=int, default=STUDY_MAX_ITER,
                   help=f"CG iterations per state before it is flagged unconverged (default {STUDY_MAX_ITER})")
    p.add_argument("--coarse-to-fine", type=int, default=None, metavar="N0",
                   help="solve every n > N0 of the ladder only around the pull-off, from the next coarser n "
                        "(dhfield.bem.refine_pull_off)")
    p.add_argument("--consolidate-only", action="store_true", help="only rebuild --out from --work-dir")
    p.add_argument("--references-only", action="store_true",
                   help="only compute (and cache in --work-dir) the analytic references of the grid")
    args = p.parse_args(argv)
    for b in args.beta0:
        if not 0 < b <= 1:
            p.error(f"--beta0 must be in (0, 1]; got {b}")
    for m in args.mu:
        if not m > 0:
            p.error(f"--mu must be > 0; got {m}")
    for n in args.n:
        if n < 8 or n % 2:
            p.error(f"--n must be even integers >= 8; got {n}")
    from dhfield.io import check_writable

    try:
        check_writable(args.out)
    except ValueError as exc:
        p.error(str(exc))
    command = " ".join(shlex.quote(a) for a in [sys.executable, "-m", "verification.study_adhesive",
                                                 *(sys.argv[1:] if argv is None else argv)])
    if args.references_only:
        cached_reference_table(args.work_dir, sorted(args.beta0), sorted(args.mu), args.control)
        return 0
    if not args.consolidate_only:
        run_study(args.beta0, args.mu, args.n, work_dir=args.work_dir, law=args.law, control=args.control,
                  max_iter=args.max_iter, coarse_to_fine=args.coarse_to_fine)
    path = consolidate(args.work_dir, args.out, law=args.law, control=args.control, command=command,
                       max_iter=args.max_iter)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
