"""Every stored adhesive case recomputed by the Newton route (issue 38): W*, stated error, iterations, CPU time.

The cases are the 57 (beta0, mu) of ``data/adhesive_ground_truth_extended.nc`` with a stored
truth (``W_star_truth``; the slender file's twelve are among them).  Each is solved as
``dhfield solve --beta0 B --mu M --search newton`` solves it: no ``n``, one start policy, no
retry (:func:`dhfield.analysis.bem_start.adhesive_pull_off` with ``search='newton'``), in its
own process with one FFTW thread, so that its peak memory and CPU time are its own.

Each finished case is one JSON file in the work directory (written atomically), so a run
stopped at any point resumes where it stopped; ``build`` merges them into one CF dataset
(``data/adhesive_ground_truth_newton.nc``) with each case's provenance (commit, command,
finish time, wall and CPU seconds, peak memory) and the stored truth beside it; ``table``
prints the per-case table (states, GMRES iterations, CPU time, memory, W* against the stored
truth and both stated errors).

Usage::

    python -m verification.study_newton run [--work-dir out/study_newton] [--shard 0/2] [--mu 0.1 0.3]
    python -m verification.study_newton build [--work-dir out/study_newton]
    python -m verification.study_newton table [--path data/adhesive_ground_truth_newton.nc]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import resource
import shlex
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

STORED = ROOT / "data" / "adhesive_ground_truth_extended.nc"
OUT = ROOT / "data" / "adhesive_ground_truth_newton.nc"
WORK = ROOT / "out" / "study_newton"


def stored_cases(path=STORED):
    """[(beta0, mu, W*, stated error)] of the stored truth, cheapest first (by mu, then beta0 descending)."""
    import numpy as np
    import xarray as xr

    with xr.open_dataset(path) as ds:
        t = ds["W_star_truth"].load()
        e = ds["W_star_truth_error"].load()
    rows = []
    for b in t["beta0"].values:
        for m in t["mu"].values:
            w = float(t.sel(beta0=b, mu=m))
            if np.isfinite(w):
                rows.append((float(b), float(m), w, float(e.sel(beta0=b, mu=m))))
    rows.sort(key=lambda r: (r[1], -r[0]))
    return rows


def _case_file(work_dir, beta0, mu):
    return Path(work_dir) / f"case_b{beta0:g}_m{mu:g}.json"


def solve_case(beta0, mu) -> dict:
    """One case in this process, as ``dhfield solve --search newton`` solves it; a JSON-ready dict."""
    from dhfield.analysis.bem_start import adhesive_pull_off
    from dhfield.io import git_commit

    t0, c0 = time.perf_counter(), time.process_time()
    res = adhesive_pull_off(beta0=beta0, mu=mu, search="newton", threads=1)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    path = res.path
    st = getattr(path, "pull_off_state", None)
    grid = getattr(st, "grid", None)
    return {
        "beta0": beta0, "mu": mu, "W_star": float(res.W_star), "W_star_error": float(res.W_star_error),
        "a_star": float(res.a_star), "b_star": float(res.b_star), "c_star": float(res.c_star),
        "d_star": float(res.d_star), "delta_star": float(res.delta_star),
        "converged": bool(res.converged), "resolved": bool(res.resolved),
        "nx": int(res.n), "ny": int(grid.ny) if grid is not None else -1,
        "states": int(res.n_steps) + int(getattr(path, "coarse_states", 0)),
        "gmres": int(res.iterations) + int(getattr(path, "coarse_iterations", 0)),
        "wall_seconds": wall, "cpu_seconds": cpu,
        "peak_rss_gib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20,
        "note": str(res.note or ""), "commit": git_commit(),
        "command": f"dhfield solve --beta0 {beta0:g} --mu {mu:g} --search newton",
        "finished": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }


def _write_json(path, obj):
    from dhfield.io import atomic_path

    with atomic_path(path, "case record") as tmp:
        Path(tmp).write_text(json.dumps(obj, indent=1))


def run(work_dir=WORK, shard=(0, 1), mus=None, beta0s=None, timeout=None) -> int:
    """Solve every stored case not yet in ``work_dir`` (this shard's share), each in its own process."""
    work_dir = Path(work_dir)
    work_dir.mkdir(parents=True, exist_ok=True)
    cases = [c for c in stored_cases() if (mus is None or c[1] in mus) and (beta0s is None or c[0] in beta0s)]
    k, of = shard
    mine = cases[k::of]
    failed = 0
    for beta0, mu, w_ref, e_ref in mine:
        out = _case_file(work_dir, beta0, mu)
        if out.exists():
            continue
        cmd = [sys.executable, "-m", "verification.study_newton", "case", repr(beta0), repr(mu), "--out", str(out)]
        t0 = time.perf_counter()
        env = dict(os.environ, DHFIELD_THREADS="1", OMP_NUM_THREADS="1")
        try:
            proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)
            rc, tail = proc.returncode, (proc.stderr.strip().splitlines() or [""])[-1]
        except subprocess.TimeoutExpired:
            rc, tail = 124, f"stopped at the hard timeout {timeout} s"
        wall = time.perf_counter() - t0
        if rc != 0 or not out.exists():
            failed += 1
            _write_json(out, {"beta0": beta0, "mu": mu, "error": tail, "wall_seconds": wall,
                              "command": f"dhfield solve --beta0 {beta0:g} --mu {mu:g} --search newton",
                              "finished": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())})
            print(f"beta0 {beta0:<6g} mu {mu:<4g} FAILED ({wall:.0f} s): {tail}", flush=True)
            continue
        rec = json.loads(out.read_text())
        dev = (rec["W_star"] - w_ref) / abs(w_ref)
        print(f"beta0 {beta0:<6g} mu {mu:<4g} W* {rec['W_star']:.6f} stated {rec['W_star_error']:.2e} "
              f"stored {w_ref:.6f}±{e_ref:.1e} dev {100 * dev:+.3f}% conv {rec['converged']} res {rec['resolved']} "
              f"{rec['nx']}x{rec['ny']} cpu {rec['cpu_seconds']:.0f}s", flush=True)
    return 1 if failed else 0


def build(work_dir=WORK, out=OUT):
    """Merge the case records into one dataset (atomic write) and return it."""
    import numpy as np
    import xarray as xr
    from dhfield.io import git_commit, write_netcdf
    from dhfield.io.cf import variable_attrs

    cases = stored_cases()
    recs = {}
    for p in sorted(Path(work_dir).glob("case_*.json")):
        r = json.loads(p.read_text())
        recs[(r["beta0"], r["mu"])] = r
    beta0s = sorted({c[0] for c in cases})
    mus = sorted({c[1] for c in cases})
    shape = (len(beta0s), len(mus))
    num = {k: np.full(shape, np.nan) for k in
           ("W_star", "W_star_error", "a_star", "b_star", "c_star", "d_star", "delta_star", "nx", "ny", "states",
            "gmres", "wall_seconds", "cpu_seconds", "peak_rss_gib", "W_star_stored", "W_star_stored_error")}
    status = np.full(shape, "absent", dtype=object)
    text = {k: np.full(shape, "", dtype=object) for k in ("note", "commit", "command", "finished")}
    for b, m, w, e in cases:
        i, j = beta0s.index(b), mus.index(m)
        num["W_star_stored"][i, j], num["W_star_stored_error"][i, j] = w, e
        r = recs.get((b, m))
        if r is None:
            status[i, j] = "not run"
            continue
        for k in text:
            text[k][i, j] = str(r.get(k, ""))
        if "error" in r:
            status[i, j], text["note"][i, j] = "failed", r["error"]
            continue
        for k in num:
            if k in r:
                num[k][i, j] = float(r[k])
        status[i, j] = ("ok" if r["converged"] and r["resolved"] else
                        "not_converged" if not r["converged"] else "unresolved")
    # the schema's quantities take their attributes from the one table (dhfield.core.schema); the
    # study's own numbers have theirs here
    schema_vars = ("W_star", "a_star", "b_star", "c_star", "d_star", "delta_star")
    own = {"W_star_error": ("1", "stated error of W_star (grid ladder and search; inf: unresolved)"),
           "nx": ("1", "cells along x of the answer's grid"), "ny": ("1", "cells along y of the answer's grid"),
           "states": ("1", "states solved over all grids"),
           "gmres": ("1", "GMRES iterations over all grids (operator products)"),
           "wall_seconds": ("s", "wall time of the case"),
           "cpu_seconds": ("s", "CPU time of the case (1 FFTW thread)"),
           "peak_rss_gib": ("GiB", "peak resident memory of the case's process"),
           "W_star_stored": ("1", "stored truth W_star_truth of adhesive_ground_truth_extended.nc"),
           "W_star_stored_error": ("1", "stated error of the stored truth")}

    def attrs(k):
        if k in schema_vars:
            return variable_attrs(k, nondimensional=True, qualifier="BEM pull-off by the Newton route")
        return {"units": own[k][0], "long_name": own[k][1]}

    dims = ("beta0", "mu")
    data = {k: (dims, v, attrs(k)) for k, v in num.items()}
    data["status"] = (dims, status.astype(str), {"long_name": "ok / not_converged / unresolved / failed / not run"})
    for k, v in text.items():
        data[k] = (dims, v.astype(str), {"long_name": f"case provenance: {k}"})
    ds = xr.Dataset(data, coords={"beta0": ("beta0", beta0s, variable_attrs("beta0")),
                                  "mu": ("mu", mus, variable_attrs("mu"))})
    ds.attrs.update(title="Adhesive BEM ground truth recomputed by the Newton route (issue 38): Dugdale law, load "
                          "control",
                    description="Each stored case of adhesive_ground_truth_extended.nc solved as dhfield solve "
                                "--search newton solves it (automatic grids, one start policy, no retry); "
                                "per-case provenance in commit/command/finished",
                    nondimensionalisation="R = E* = dgamma = 1 (Eqs. 32-35); W* = W sin(theta_skew)/(2 pi R dgamma)",
                    built=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), build_commit=git_commit(),
                    build_command="python -m verification.study_newton " + " ".join(map(shlex.quote, sys.argv[1:])))
    write_netcdf(ds, out)
    return ds


def table(path=OUT) -> int:
    """Print the per-case table; return 1 when a case is not an answer or misses the stored truth."""
    import numpy as np
    import xarray as xr

    with xr.open_dataset(path) as ds:
        ds = ds.load()
    print(f"{'beta0':>6} {'mu':>5} {'grid':>11} {'st':>3} {'gmres':>6} {'cpu s':>7} {'GiB':>5} {'W*':>10} "
          f"{'stated':>8} {'stored':>10} {'+-':>8} {'dev %':>7} agree")
    bad = 0
    cpu_total = 0.0
    for b in ds.beta0.values:
        for m in ds.mu.values:
            c = ds.sel(beta0=b, mu=m)
            s = str(c.status.values)
            if s == "absent":
                continue
            w, e = float(c.W_star), float(c.W_star_error)
            ws, es = float(c.W_star_stored), float(c.W_star_stored_error)
            if s != "ok":
                bad += 1
                print(f"{b:6g} {m:5g} {s}: {str(c.note.values)[:110]}")
                continue
            cpu_total += float(c.cpu_seconds)
            dev = w - ws
            tol = e + (es if np.isfinite(es) else 0.0)
            agree = abs(dev) <= tol
            bad += not agree
            print(f"{b:6g} {m:5g} {int(c.nx):>5}x{int(c.ny):<5} {int(c.states):>3} {int(c.gmres):>6} "
                  f"{float(c.cpu_seconds):7.1f} {float(c.peak_rss_gib):5.2f} {w:10.6f} {e:8.1e} {ws:10.6f} "
                  f"{es:8.1e} {100 * dev / abs(ws):+7.3f} {'yes' if agree else 'NO'}")
    print(f"total CPU of the answered cases: {cpu_total / 60:.1f} min; cases not answered or not agreeing: {bad}")
    return 1 if bad else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m verification.study_newton", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="solve the cases not yet in the work directory")
    r.add_argument("--work-dir", default=str(WORK))
    r.add_argument("--shard", default="0/1", help="k/n: this process solves every n-th case from the k-th")
    r.add_argument("--mu", type=float, nargs="*", help="only these mu")
    r.add_argument("--beta0", type=float, nargs="*", help="only these beta0")
    r.add_argument("--timeout", type=float, help="hard wall-clock limit per case [s]")
    c = sub.add_parser("case", help="one case in this process (used by run)")
    c.add_argument("beta0", type=float)
    c.add_argument("mu", type=float)
    c.add_argument("--out", required=True)
    b = sub.add_parser("build", help="merge the case records into the dataset")
    b.add_argument("--work-dir", default=str(WORK))
    b.add_argument("--out", default=str(OUT))
    t = sub.add_parser("table", help="print the per-case table of the dataset")
    t.add_argument("--path", default=str(OUT))
    a = ap.parse_args(argv)
    if a.cmd == "run":
        k, n = (int(x) for x in a.shard.split("/"))
        return run(a.work_dir, (k, n), set(a.mu) if a.mu else None, set(a.beta0) if a.beta0 else None, a.timeout)
    if a.cmd == "case":
        _write_json(a.out, solve_case(a.beta0, a.mu))
        return 0
    if a.cmd == "build":
        build(a.work_dir, a.out)
        return 0
    return table(a.path)


if __name__ == "__main__":
    sys.exit(main())
