"""Memory and speed of ``dhfield sweep`` (issue 11), measured side by side in one run.

Prints:

* **Analytic map.**  A ``--map-n`` x ``--map-n`` (beta0, mu) pull-off map of the
  paper's model (``dh-elliptic``; beta0 in [0.3, 1], mu in [0.1, 10]) run as
  ``dhfield sweep ... --workers 2`` in a subprocess: wall time and the peak
  resident memory of the whole process tree (the CLI and its worker
  processes, summed, sampled every 20 ms with psutil).  Targets (200 x 200):
  <= 10 s and <= 1 GiB.
* **BEM speed-up, 1 -> 2 workers** (target >= 1.7), the same ``run_sweep`` on the
  default scheduler (local worker processes, :meth:`dhfield.sweep.Executor.start`
  spawns them single-threaded beforehand) with 1 and with 2 workers.  Timed: the
  whole ``run_sweep`` call (graph, tasks, per-case netCDF store, consolidation,
  final netCDF).  Not timed: the pool start-up (spawn + imports), printed apart.
  (a) forward BEM: 8 cases at N = 256 (beta0 in {0.7, 0.9} x mu in {0.5, 1, 2,
  4}, a* = 1, one fixed grid so one operator per worker); a first round builds
  the operators (printed), then ``--repeats`` rounds, 1 and 2 workers
  alternating, medians.  (b) the same sweep as a cold ``dhfield sweep``
  command, everything included (reported).  (c) the adhesive ground truth: 8
  cases at N = 256 (beta0 in {0.8, 1} x mu in {0.3, 0.5, 1, 2}), the sweep users
  wait for; with the per-case seconds and the best speed-up any split of those
  cases over 2 workers allows.  (d) a control without dask or store: the
  forward-BEM cases in one plain process and in two at once, the speed-up the
  (shared) machine offers at that moment.  (e) with ``--distributed``: the
  forward-BEM sweep on a dask.distributed LocalCluster (reported).

The machine is shared during development: the load average is printed with
the figures; rerun on a quiet machine for the record.  With the kernel's
autogroup scheduling (``/proc/sys/kernel/sched_autogroup_enabled`` = 1) every
session gets one fair share of the CPUs, so while others run, 2 workers of one
session get no more CPU than 1: the controls (d) and (f) show what the machine
offers at that moment, and the adhesive part also prints the makespan of the
engine's order simulated from the measured case times.

Usage::

    .venv/bin/python -m verification.bench_sweep [--map-n 200] [--repeats 3] [--skip-map] [--skip-bem | --map-only]
    .venv/bin/python -m verification.bench_sweep --bem-only [--skip-adhesive] [--distributed]   # ~3-4 min
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
        import resource

        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        wall, peak, rc = run_measured(argv)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)  # the CLI and its reaped workers
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    gib = peak / 2**30
    ok_t, ok_m = wall <= TARGET_MAP_SECONDS, peak <= TARGET_MAP_BYTES
    print(f"analytic map {n}x{n} = {n * n} points, dh-elliptic, {workers} worker processes (exit {rc})")
    print(f"  wall time          {wall:9.2f} s    target <= {TARGET_MAP_SECONDS:g} s  "
          f"{'PASS' if ok_t else 'FAIL'}  ({1e3 * wall / (n * n):.2f} ms per point)")
    print(f"  CPU time (tree)    {cpu:9.2f} s    (all processes, user + system: what a loaded machine "
          f"cannot inflate; {1e3 * cpu / (n * n):.2f} ms per point)")
    print(f"  peak RSS (tree)    {gib:9.3f} GiB  target <= 1 GiB  {'PASS' if ok_m else 'FAIL'}")
    return ok_t and ok_m and rc == 0


#: The adhesive sweep of issue 11 (the one users wait for): 8 ground-truth cases at N = 256.
ADHESIVE_CONFIG = {"axes": {"beta0": [0.8, 1.0], "mu": [0.3, 0.5, 1.0, 2.0], "n": [256]},
                   "sweep": {"quantities": ["adhesive"]}}


#: Most tasks in flight at once in the last timed local sweep (one per worker when tasks go out one by one).
IN_FLIGHT = {"now": 0, "most": 0}


def _timed_sweep(config, executor, out):
    """Wall time of one ``run_sweep`` on a started Executor: everything but the pool start-up."""
    from dask.callbacks import Callback

    from dhfield.sweep import config_from_mapping, run_sweep

    IN_FLIGHT.update(now=0, most=0)

    def pretask(key, dsk, state):
        IN_FLIGHT["now"] += 1
        IN_FLIGHT["most"] = max(IN_FLIGHT["most"], IN_FLIGHT["now"])

    def posttask(key, result, dsk, state, worker_id):
        IN_FLIGHT["now"] -= 1

    t0 = time.perf_counter()
    with Callback(pretask=pretask, posttask=posttask):  # parent-side bookkeeping of dask's local scheduler
        run_sweep(config_from_mapping(config), out=out, scheduler=executor, progress=False)
    return time.perf_counter() - t0


def _verdict(s):
    return f"target >= {TARGET_SPEEDUP}  {'PASS' if s >= TARGET_SPEEDUP else 'FAIL'}"


def _pools(quantity, workers=(1, 2)):
    """Started local pools (same scheduler, same code path for 1 and 2 workers) and their start-up [s]."""
    from dhfield.sweep import connect
    from dhfield.sweep.engine import QUANTITY_MODULES

    pools, start = {}, {}
    for w in workers:
        pools[w] = connect("processes", w)
        start[w] = pools[w].start(preload=QUANTITY_MODULES[quantity])  # as run_sweep would
    return pools, start


def _alternating_rounds(config, quantity, rounds, tag, after=None):
    """Wall times {workers: [s per round]} of ``rounds`` sweeps on started pools of 1 and 2 workers,
    alternating, and the pools' start-up [s]; ``after(workers, round, out)`` sees each output file."""
    pools, start = _pools(quantity)
    times = {1: [], 2: []}
    try:
        with tempfile.TemporaryDirectory() as tmp:
            _warm_parent(Path(tmp))
            for r in range(rounds):
                for w in (1, 2):
                    out = Path(tmp) / f"{tag}{w}_{r}.nc"
                    times[w].append(_timed_sweep(config, pools[w], out))
                    if after is not None:
                        after(w, r, out)
    finally:
        for ex in pools.values():
            ex.close()
    return times, start


def _case_seconds(out):
    """Wall time [s] of every case, from the case files of a finished sweep (attribute ``seconds``)."""
    from dhfield.io import read_netcdf
    from dhfield.sweep import output_paths

    _, store = output_paths(out)
    return {p.name[:-3]: float(read_netcdf(p).attrs["seconds"]) for p in sorted(store.glob("*__*.nc"))}


def _best_two_way(costs):
    """Smallest makespan of the cases on 2 workers, one case per task (exhaustive partition)."""
    total, best = sum(costs), float("inf")
    for mask in range(1 << (len(costs) - 1)):
        a = sum(c for i, c in enumerate(costs) if mask >> i & 1)
        best = min(best, max(a, total - a))
    return best


def _warm_parent(tmp: Path) -> None:
    """A tiny serial sweep, so that this process's own imports (xarray, netCDF, the adhesive solver that
    run_sweep checks for) fall outside every timing: else the first timed run, with 1 worker, pays them."""
    from dhfield.sweep import config_from_mapping, run_sweep
    from dhfield.sweep.tasks import adhesive_solver

    adhesive_solver()
    run_sweep(config_from_mapping({"axes": {"beta0": [1.0], "mu": [1.0]}, "sweep": {"models": ["jkr"]}}),
              out=tmp / "warm-up.nc", scheduler="synchronous", progress=False)


def _list_schedule(cfg, cases, workers=2):
    """Makespan [s] of the measured adhesive cases handed out in the engine's order to ``workers``."""
    from dhfield.sweep.tasks import expected_seconds

    def cost(key):
        ib, im, i_n = (int(t) for t in key.split("__")[1].split("_")[:3])
        ax = cfg["axes"]
        return expected_seconds("adhesive", {"beta0": ax["beta0"][ib], "mu": ax["mu"][im], "n": ax["n"][i_n]})

    free = [0.0] * workers
    for key in sorted(cases, key=cost, reverse=True):
        i = free.index(min(free))
        free[i] += cases[key]
    return max(free)


def bench_bem(repeats: int) -> bool:
    """Forward-BEM sweep of 8 cases at N = 256 on started pools of 1 and 2 workers, rounds alternating."""
    n_cases = 8
    print(f"forward-BEM sweep: {n_cases} cases at N = 256 (8 load paths, one grid), local worker processes; "
          f"medians of {repeats} rounds, 1 and 2 workers alternating")
    print("  timed: the whole run_sweep call (graph, tasks, per-case netCDF store, consolidation, final "
          "netCDF); not timed: the worker-pool start-up, printed apart")
    # round 0: each worker builds its operator (reported, not in the median)
    times, start = _alternating_rounds(BEM_CONFIG, "bem_field", repeats + 1, "f")
    t1, t2 = statistics.median(times[1][1:]), statistics.median(times[2][1:])
    print(f"  pool start-up       1 worker {start[1]:7.2f} s   2 workers {start[2]:7.2f} s   (spawn + imports)")
    print(f"  first round         1 worker {times[1][0]:7.2f} s   2 workers {times[2][0]:7.2f} s   speed-up "
          f"{times[1][0] / times[2][0]:5.2f}  (reported: each worker builds its operator; not in the medians)")
    print(f"  (a) warm workers    1 worker {t1:7.2f} s   2 workers {t2:7.2f} s   speed-up {t1 / t2:5.2f}  "
          f"{_verdict(t1 / t2)}")
    print("      rounds [s]: 1 worker " + " ".join(f"{t:.2f}" for t in times[1][1:]) + "; 2 workers "
          + " ".join(f"{t:.2f}" for t in times[2][1:]))
    return t1 / t2 >= TARGET_SPEEDUP


def bench_bem_cli() -> None:
    """The same forward-BEM sweep as a cold command, start-up of everything included (reported)."""
    cold = {}
    with tempfile.TemporaryDirectory() as tmp:
        for w in (1, 2):
            cold[w] = run_measured(_CLI + ["sweep", "--beta0", "0.7", "0.9", "--mu", "0.5", "1", "2", "4",
                                           "--a-star", "1", "--n", "256", "--quantities", "bem_field",
                                           "--half-width", "3", "--workers", str(w), "--quiet", "--out",
                                           str(Path(tmp) / f"c{w}.nc")])[0]
    print(f"  (b) cold command    1 worker {cold[1]:7.2f} s   2 workers {cold[2]:7.2f} s   speed-up "
          f"{cold[1] / cold[2]:5.2f}  (reported: 'dhfield sweep ... --workers W', interpreter, imports and "
          "worker spawn included; --workers 1 runs in the command's own process)")


def bench_adhesive(repeats: int, n: int = 256) -> bool:
    """The adhesive ground-truth sweep of 8 cases at N = ``n`` on started pools of 1 and 2 workers."""
    cfg = {**ADHESIVE_CONFIG, "axes": {**ADHESIVE_CONFIG["axes"], "n": [n]}}
    print(f"adhesive sweep: 8 ground-truth cases at N = {n} (beta0 {cfg['axes']['beta0']} x mu "
          f"{cfg['axes']['mu']}), local worker processes, costliest first; {repeats} round(s)")
    print("  timed: the whole run_sweep call; not timed: the worker-pool start-up, printed apart and added "
          "back in the last line")
    first = {}

    def keep_case_seconds(w, r, out):
        if w == 1 and r == 0:
            first.update(_case_seconds(out))

    times, start = _alternating_rounds(cfg, "adhesive", repeats, "a", after=keep_case_seconds)
    cases = first
    t1, t2 = statistics.median(times[1]), statistics.median(times[2])
    in_flight = IN_FLIGHT["most"]
    costs = sorted(cases.values(), reverse=True)
    best = _best_two_way(costs)

    def label(key):  # adhesive__<i_beta0>_<i_mu>_<i_n>_<i_law>
        ib, im = (int(t) for t in key.split("__")[1].split("_")[:2])
        return f"({cfg['axes']['beta0'][ib]:g}, {cfg['axes']['mu'][im]:g})"

    print("  case seconds, 1 worker, (beta0, mu): " + ", ".join(f"{label(k)} {v:.1f}" for k, v in cases.items()))
    print(f"  sum {sum(costs):.1f} s, largest {costs[0]:.1f} s: the best 2-worker split of these cases takes "
          f"{best:.1f} s, a speed-up of at most {sum(costs) / best:.2f}")
    lpt = _list_schedule(cfg, cases)
    print(f"  the engine's order (costliest first by tasks.expected_seconds, next case to the first free "
          f"worker) on 2 free cores: {lpt:.1f} s, speed-up {sum(costs) / lpt:.2f} (simulated from these case "
          "seconds; no overheads)")
    print(f"  pool start-up       1 worker {start[1]:7.2f} s   2 workers {start[2]:7.2f} s;  tasks in flight "
          f"at once with 2 workers: at most {in_flight} (one per worker)")
    print(f"  (c) warm workers    1 worker {t1:7.2f} s   2 workers {t2:7.2f} s   speed-up {t1 / t2:5.2f}  "
          f"{_verdict(t1 / t2)}")
    s_cold = (t1 + start[1]) / (t2 + start[2])
    print(f"      with start-up   1 worker {t1 + start[1]:7.2f} s   2 workers {t2 + start[2]:7.2f} s   "
          f"speed-up {s_cold:5.2f}  (reported)")
    return t1 / t2 >= TARGET_SPEEDUP


def store_cost() -> None:
    """Seconds to write and to read one case file of the store (netCDF), against one forward-BEM case."""
    import xarray as xr

    from dhfield.sweep import CaseStore, tasks

    rec = xr.Dataset({k: ((), 0.5, {"units": "1"}) for k in tasks.BEM_FIELD_FIELDS},
                     attrs={"status": "ok", "message": "", "seconds": 0.1})  # a forward-BEM case record
    with tempfile.TemporaryDirectory() as tmp:
        store = CaseStore(Path(tmp) / "cases", "bench")
        store.write("warm-up", rec)
        t0 = time.perf_counter()
        for i in range(20):
            store.write(f"case{i}", rec)
        t1 = time.perf_counter()
        for i in range(20):
            store.read(f"case{i}")
        t2 = time.perf_counter()
    print(f"  store: one case file written in {(t1 - t0) / 20 * 1e3:.1f} ms, read in {(t2 - t1) / 20 * 1e3:.1f} ms "
          "(netCDF; written by the worker, in the parallel part)")


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
    """Speed-up the machine offers right now: 4 + 4 cases in 1 process vs 4 and 4 in 2 processes at once."""
    import multiprocessing

    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(1) as pool:
        t1 = sum(pool.map(_raw_cases, [0, 1]))  # 8 cases, one after the other
    with ctx.Pool(2) as pool:
        t2 = max(pool.map(_raw_cases, [0, 1]))  # the same 8 cases, two processes
    print(f"  (d) control, plain multiprocessing, no dask, no store: the 8 forward-BEM cases in 1 process "
          f"{t1:6.2f} s, in 2 processes {t2:6.2f} s: the machine offers a speed-up of {t1 / t2:5.2f} now")
    return t1 / t2


def _raw_adhesive(case):
    """Control without dask: one adhesive case (beta0, mu, n) in this process, after a small warm-up; seconds."""
    from dhfield.sweep import tasks

    tasks.adhesive_case(1.0, 1.0, 32, "dugdale")
    t0 = time.perf_counter()
    tasks.adhesive_case(*case, "dugdale")
    return time.perf_counter() - t0


def raw_adhesive_parallelism(n: int) -> float:
    """Speed-up the machine offers for adhesive cases: 2 cases one after the other vs in 2 processes at once."""
    import multiprocessing

    cases = [(0.8, 1.0, n), (1.0, 1.0, n)]
    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(1) as pool:
        t1 = sum(pool.map(_raw_adhesive, cases, chunksize=1))
    with ctx.Pool(2) as pool:
        t2 = max(pool.map(_raw_adhesive, cases, chunksize=1))
    print(f"  (f) control, plain multiprocessing, no dask: adhesive (beta0, mu) = (0.8, 1) and (1, 1) at N = {n} "
          f"in 1 process {t1:6.2f} s, in 2 at once {t2:6.2f} s (slower of the two): the machine offers "
          f"{t1 / t2:5.2f} now")
    return t1 / t2


def _distributed(repeats: int) -> None:
    """The forward-BEM sweep on a dask.distributed LocalCluster of 1 and 2 single-threaded workers (reported)."""
    import logging

    from distributed import Client, LocalCluster

    logging.getLogger("distributed").setLevel(logging.ERROR)
    times, clusters, clients = {1: [], 2: []}, {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        try:
            for w in (1, 2):
                clusters[w] = LocalCluster(n_workers=w, threads_per_worker=1, processes=True, host="127.0.0.1",
                                           dashboard_address=":0", silence_logs=logging.ERROR)
                clients[w] = Client(clusters[w])
                clients[w].run(_warm_worker)
            for r in range(repeats):
                for w in (1, 2):
                    times[w].append(_timed_sweep(BEM_CONFIG, clients[w], Path(tmp) / f"d{w}_{r}.nc"))
        finally:
            for w in clusters:
                clients[w].close()
                clusters[w].close()
    t1, t2 = statistics.median(times[1]), statistics.median(times[2])
    print(f"  (e) LocalCluster    1 worker {t1:7.2f} s   2 workers {t2:7.2f} s   speed-up {t1 / t2:5.2f}  "
          "(reported; connected client, warm workers)")


def _warm_worker():
    """Import the BEM stack and build the operator of the benchmark grid in this worker."""
    from dhfield import bem

    grid = bem.Grid.centered(BEM_CONFIG["axes"]["n"][0], BEM_CONFIG["bem"]["half_width"])
    bem.get_operator(grid, 1.0, symmetric=True, threads=1)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--map-n", type=int, default=200, help="points per axis of the analytic map (200)")
    p.add_argument("--workers", type=int, default=2, help="worker processes of the analytic map (2)")
    p.add_argument("--repeats", type=int, default=3, help="rounds of the BEM speed-up (3)")
    p.add_argument("--skip-map", action="store_true")
    p.add_argument("--skip-bem", action="store_true")
    p.add_argument("--map-only", action="store_true", help="the analytic map only (same as --skip-bem)")
    p.add_argument("--bem-only", action="store_true", help="the BEM speed-ups only (same as --skip-map)")
    p.add_argument("--adhesive-repeats", type=int, default=2, help="rounds of the adhesive speed-up (2)")
    p.add_argument("--skip-adhesive", action="store_true", help="no adhesive sweep (saves ~1-2 min)")
    p.add_argument("--adhesive-n", type=int, default=256, help="cells per side of the adhesive sweep (256; "
                   "smaller for a quick check of this script, not for the record)")
    p.add_argument("--distributed", action="store_true",
                   help="also time the forward-BEM sweep on a dask.distributed LocalCluster")
    args = p.parse_args(argv)
    args.skip_bem |= args.map_only
    args.skip_map |= args.bem_only
    print(f"bench_sweep on {os.cpu_count()} cores, python {sys.version.split()[0]}, load average "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    ok = True
    if not args.skip_map:
        ok &= bench_map(args.map_n, args.workers)
    if not args.skip_bem:
        t0 = time.perf_counter()
        ok &= bench_bem(args.repeats)
        store_cost()
        bench_bem_cli()
        raw_parallelism()
        if args.distributed:
            _distributed(args.repeats)
        if not args.skip_adhesive:
            ok &= bench_adhesive(args.adhesive_repeats, args.adhesive_n)
            raw_adhesive_parallelism(args.adhesive_n)
        print(f"BEM part of the benchmark: {time.perf_counter() - t0:.0f} s")
    print("load average at the end " + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
