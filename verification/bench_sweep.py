"""Memory and speed of ``dhfield sweep`` (issue 11), measured side by side in one run.

Prints:

* **Analytic map.**  A ``--map-n`` x ``--map-n`` (beta0, mu) pull-off map of the
  paper's model (``dh-elliptic``; beta0 in [0.3, 1], mu in [0.1, 10]) run as
  ``dhfield sweep ... --workers 2`` in a subprocess: wall time and the peak
  resident memory of the whole process tree (the CLI and its worker
  processes, summed, sampled every 20 ms with psutil).  Targets (200 x 200):
  <= 10 s and <= 1 GiB.
* **BEM speed-up.**  A forward-BEM sweep of 8 cases at N = 256 (8 load paths:
  beta0 in {0.7, 0.9} x mu in {0.5, 1, 2, 4}, a* = 1, one fixed grid so one
  operator per worker), timed (a) on a warm dask.distributed LocalCluster of
  1 and of 2 single-threaded worker processes (imports done and the operator
  built in every worker beforehand, as in a long study) and (b) with the local-process
  scheduler, ``--workers 1`` vs ``--workers 2``, process start-up included;
  (c) a control without dask: the same cases in one plain process and in two
  at once, i.e. the speed-up the (shared) machine offers at that moment.
  The 1- and 2-worker runs alternate round by round so that both see the same
  machine state; medians of ``--repeats`` rounds.  Target for (a): >= 1.7.

The machine is shared during development: the load average is printed with
the figures; rerun on a quiet machine for the record.

Usage::

    .venv/bin/python verification/bench_sweep.py [--map-n 200] [--repeats 3] [--skip-map] [--skip-bem]
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET_MAP_SECONDS = 10.0
TARGET_MAP_BYTES = 1 << 30
TARGET_SPEEDUP = 1.7
BEM_CONFIG = {"axes": {"beta0": [0.7, 0.9], "mu": [0.5, 1.0, 2.0, 4.0], "a_star": [1.0], "n": [256]},
              "sweep": {"quantities": ["bem_field"]}, "bem": {"half_width": 3.0}}
_CLI = [sys.executable, "-c", "import sys; from dhfield.cli import main; sys.exit(main(sys.argv[1:]))"]


def _tree_rss(proc) -> int:
    import psutil

    total = 0
    try:
        procs = [proc] + proc.children(recursive=True)
    except psutil.NoSuchProcess:
        return 0
    for p in procs:
        try:
            total += p.memory_info().rss
        except psutil.NoSuchProcess:
            pass
    return total


def run_measured(argv) -> tuple[float, int, int]:
    """Run a command; return (wall seconds, peak summed RSS of its process tree [bytes], exit status)."""
    import psutil

    t0 = time.perf_counter()
    popen = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    proc = psutil.Process(popen.pid)
    peak = 0
    while popen.poll() is None:
        peak = max(peak, _tree_rss(proc))
        time.sleep(0.02)
    wall = time.perf_counter() - t0
    if popen.returncode:
        sys.stderr.write(popen.stderr.read().decode())
    return wall, peak, popen.returncode


def bench_map(n: int, workers: int) -> bool:
    with tempfile.TemporaryDirectory() as tmp:
        argv = _CLI + ["sweep", "--beta0-linspace", "0.3", "1", str(n), "--mu-geomspace", "0.1", "10", str(n),
                       "--models", "dh-elliptic", "--workers", str(workers), "--quiet", "--out",
                       str(Path(tmp) / "map.nc")]
        wall, peak, rc = run_measured(argv)
    gib = peak / 2**30
    ok_t, ok_m = wall <= TARGET_MAP_SECONDS, peak <= TARGET_MAP_BYTES
    print(f"analytic map {n}x{n} = {n * n} points, dh-elliptic, {workers} worker processes (exit {rc})")
    print(f"  wall time          {wall:9.2f} s    target <= {TARGET_MAP_SECONDS:g} s  "
          f"{'PASS' if ok_t else 'FAIL'}  ({1e3 * wall / (n * n):.2f} ms per point)")
    print(f"  peak RSS (tree)    {gib:9.3f} GiB  target <= 1 GiB  {'PASS' if ok_m else 'FAIL'}")
    return ok_t and ok_m and rc == 0


def _sweep_once(scheduler, workers, tmp, tag):
    from dhfield.sweep import config_from_mapping, run_sweep

    t0 = time.perf_counter()
    run_sweep(config_from_mapping(BEM_CONFIG), out=Path(tmp) / f"{tag}.nc", scheduler=scheduler, workers=workers,
              progress=False)
    return time.perf_counter() - t0


def _warm_worker():
    """Import the BEM stack and build the operator of the benchmark grid in this worker."""
    from dhfield import bem

    grid = bem.Grid.centered(BEM_CONFIG["axes"]["n"][0], BEM_CONFIG["bem"]["half_width"])
    bem.get_operator(grid, 1.0, symmetric=True, threads=1)


def _raw_cases(seed):
    """Control without dask: warm up, then time 4 of the benchmark's cases in this process."""
    from dhfield.sweep import tasks

    half_width, n = BEM_CONFIG["bem"]["half_width"], BEM_CONFIG["axes"]["n"][0]
    tasks.bem_field_case(0.8, 1.0, 1.0, n, half_width=half_width)
    t0 = time.perf_counter()
    for mu in BEM_CONFIG["axes"]["mu"]:
        tasks.bem_field_case(BEM_CONFIG["axes"]["beta0"][seed % 2], mu, 1.0, n, half_width=half_width)
    return time.perf_counter() - t0


def raw_parallelism() -> float:
    """Speed-up the machine offers right now: 4 cases in 1 process vs 4 + 4 in 2 processes at once."""
    import multiprocessing

    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(1) as pool:
        t1 = 2 * pool.map(_raw_cases, [0])[0]  # 8 cases, one after the other
    with ctx.Pool(2) as pool:
        t2 = max(pool.map(_raw_cases, [0, 1]))  # 8 cases, two processes
    print(f"  (c) control, plain multiprocessing, no dask: 8 cases in 1 process {t1:6.2f} s, in 2 processes "
          f"{t2:6.2f} s: the machine offers a speed-up of {t1 / t2:5.2f} now")
    return t1 / t2


def bench_bem(repeats: int) -> bool:
    import logging

    from distributed import Client, LocalCluster

    logging.getLogger("distributed").setLevel(logging.ERROR)  # no INFO lines at cluster close

    n_cases = 8
    print(f"BEM sweep: {n_cases} forward-BEM cases at N = 256 (8 load paths, one grid), medians of {repeats}")
    times = {1: [], 2: []}
    with tempfile.TemporaryDirectory() as tmp:
        clusters = {}
        try:
            for w in (1, 2):
                clusters[w] = LocalCluster(n_workers=w, threads_per_worker=1, processes=True, host="127.0.0.1",
                                           dashboard_address=":0", silence_logs=logging.ERROR)
                with Client(clusters[w]) as client:  # warm workers: imports done, one operator built in each
                    client.run(_warm_worker)
            for r in range(repeats):
                for w in (1, 2):
                    times[w].append(_sweep_once(clusters[w].scheduler_address, None, tmp, f"d{w}_{r}"))
            with Client(clusters[2]) as client:  # both workers took part (tasks per worker, last round)
                per_worker = client.run(lambda dask_worker: len(dask_worker.data) + len(dask_worker.state.log))
            print("  tasks seen per worker of the 2-worker cluster (log entries):", list(per_worker.values()))
        finally:
            for c in clusters.values():
                c.close()
        t1, t2 = statistics.median(times[1]), statistics.median(times[2])
        ok = t1 / t2 >= TARGET_SPEEDUP
        print(f"  (a) warm LocalCluster   1 worker {t1:7.2f} s   2 workers {t2:7.2f} s   speed-up {t1 / t2:5.2f}  "
              f"target >= {TARGET_SPEEDUP}  {'PASS' if ok else 'FAIL'}")
        cold = {1: [], 2: []}
        for r in range(repeats):
            for w in (1, 2):
                cold[w].append(run_measured(_CLI + ["sweep", "--beta0", "0.7", "0.9", "--mu", "0.5", "1", "2", "4",
                                                    "--a-star", "1", "--n", "256", "--quantities", "bem_field",
                                                    "--half-width", "3", "--scheduler", "processes", "--workers",
                                                    str(w), "--quiet", "--out", str(Path(tmp) / f"c{w}_{r}.nc")])[0])
        c1, c2 = statistics.median(cold[1]), statistics.median(cold[2])
        print(f"  (b) local processes CLI 1 worker {c1:7.2f} s   2 workers {c2:7.2f} s   speed-up {c1 / c2:5.2f}  "
              "(start-up of the worker processes included; reported)")
    raw_parallelism()
    return ok


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--map-n", type=int, default=200, help="points per axis of the analytic map (200)")
    p.add_argument("--workers", type=int, default=2, help="worker processes of the analytic map (2)")
    p.add_argument("--repeats", type=int, default=3, help="rounds of the BEM speed-up (3)")
    p.add_argument("--skip-map", action="store_true")
    p.add_argument("--skip-bem", action="store_true")
    args = p.parse_args(argv)
    print(f"bench_sweep on {os.cpu_count()} cores, python {sys.version.split()[0]}, load average "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    ok = True
    if not args.skip_map:
        ok &= bench_map(args.map_n, args.workers)
    if not args.skip_bem:
        ok &= bench_bem(args.repeats)
    print("load average at the end " + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
