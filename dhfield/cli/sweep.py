"""``dhfield sweep``: a study over a grid of model inputs, on dask, resumable.

Two forms::

    dhfield sweep CONFIG.toml [--scheduler ADDRESS] [--workers N] [--out PATH] [--quiet]
    dhfield sweep --beta0 0.8 0.9 1 --mu-geomspace 0.1 10 200 --models dh-elliptic md --out s.nc

The TOML layout is documented in :mod:`dhfield.sweep.config`.  Flags given with
a config file override its ``[run]`` table and ``--max-seconds`` its ``[bem] max_seconds``
(the time allowed per adhesive case decides only whether a case is refused, never its
value: a rerun with a larger one resumes the same store), nothing else.
"""
from __future__ import annotations

import os
import sys

#: Exit status when every case ran but some BEM cases are stored flagged (status
#: not_converged or unresolved: their values are not answers).
EXIT_FLAGGED = 3

_EPILOG = ("exit status: 0 every case ok; 1 some cases failed (recorded with their message; a rerun retries "
           f"them); {EXIT_FLAGGED} some BEM cases are stored flagged, status not_converged or unresolved (the "
           "grid does not resolve the cohesive zone): their values are not answers; 2 invalid input.  "
           "A summary line goes to stderr, and with --quiet only when cases failed or are flagged.")

_AXIS_FLAGS = (("beta0", float), ("skew_angle_deg", float), ("mu", float), ("a_star", float), ("n", int),
               ("grid_level", int), ("law", str))


def add_parser(sub) -> None:
    p = sub.add_parser("sweep", help="sweep a grid of inputs (pull-offs, BEM checks) on dask; resumable",
                       description="Sweep a grid of model inputs (analytic pull-offs, load curves, forward BEM "
                                   "checks, the adhesive BEM) on dask; resumable.", epilog=_EPILOG)
    p.add_argument("config", nargs="?", default=None, help="TOML sweep file (see dhfield.sweep.config)")
    for name, typ in _AXIS_FLAGS:
        flag = name.replace("_", "-")
        p.add_argument(f"--{flag}", dest=name, nargs="+", type=typ, default=None, metavar="V",
                       help=f"values of the {name} axis")
        if typ is float:
            for kind in ("linspace", "geomspace"):
                p.add_argument(f"--{flag}-{kind}", dest=f"{name}_{kind}", nargs=3, type=float, default=None,
                               metavar=("START", "STOP", "NUM"), help=f"{name} axis as numpy.{kind}")
    p.add_argument("--quantities", nargs="+", default=None,
                   help="pull_off (default), load_curve, bem_field, adhesive")
    p.add_argument("--models", nargs="+", default=None, help="comparison models of pull_off")
    p.add_argument("--control", choices=("load", "displacement"), default=None)
    p.add_argument("--chunk-points", type=int, default=None, help="analytic grid points per task (2048)")
    p.add_argument("--curve-a-star", nargs=2, type=float, default=None, metavar=("FROM", "TO"),
                   help="load_curve: contact sizes a/c_r, evenly spaced (default 0.02 3)")
    p.add_argument("--curve-points", type=int, default=None, help="load_curve: points per curve (200)")
    p.add_argument("--half-width", type=float, default=None, help="fixed BEM domain half-width [c_r]")
    p.add_argument("--max-seconds", type=float, default=None, metavar="S",
                   help="adhesive: estimated time allowed per case [s], > 0 (default 1800); a grid level estimated "
                        "to take longer is refused before solving ([bem] max_seconds; overrides a config file's)")
    p.add_argument("--scheduler", default=None,
                   help="dask.distributed scheduler address tcp://host:port, or 'synchronous'/'processes'")
    p.add_argument("--workers", type=int, default=None, help="local worker processes, one core each (default: every core; 1 runs in this "
                   "process, which is quicker for sweeps of a few seconds: workers take a few seconds to start)")
    p.add_argument("--out", default=None, help="output FILE.nc (cases in FILE.nc.cases/) or DIR")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def _flag_mapping(args) -> dict:
    axes = {}
    for name, typ in _AXIS_FLAGS:
        given = [(k, getattr(args, k, None)) for k in (name, f"{name}_linspace", f"{name}_geomspace")]
        given = [(k, v) for k, v in given if v is not None]
        if len(given) > 1:
            raise ValueError(f"give the {name} axis once (one of --{name.replace('_', '-')}, "
                             f"--{name.replace('_', '-')}-linspace, --{name.replace('_', '-')}-geomspace)")
        if given:
            k, v = given[0]
            if k == name:
                axes[name] = list(v)
            else:
                start, stop, num = v
                if num != int(num):
                    raise ValueError(f"--{k.replace('_', '-')} NUM must be an integer >= 1; got {num!r}")
                axes[name] = {k.rsplit("_", 1)[1]: [start, stop, int(num)]}
    sweep = {}
    for key in ("quantities", "models", "control", "chunk_points", "curve_a_star", "curve_points"):
        if getattr(args, key) is not None:
            sweep[key] = getattr(args, key)
    bem = {} if args.half_width is None else {"half_width": args.half_width}
    if args.max_seconds is not None:
        bem["max_seconds"] = args.max_seconds
    return {"axes": axes, "sweep": sweep, "bem": bem}


def _from_flags(build, mapping, flags):
    """``build(mapping)``; an error about a value that came from a flag names the flag before its config key.

    The config's checks word their errors with the key (``bem.max_seconds must be ...``); a user who typed
    ``--max-seconds 0`` reads ``--max-seconds (bem.max_seconds) must be ...``.
    """
    try:
        return build(mapping)
    except ValueError as e:
        msg = str(e)
        for section, keys in flags.items():
            for key in keys:
                name = f"{section}.{key}"
                if msg.startswith((name + " ", name + ".")):
                    token = msg.split(" ", 1)[0]   # e.g. axes.mu.geomspace
                    value = keys[key]   # an axis given as --mu-geomspace is {'geomspace': [...]}
                    flag = key + (f"_{next(iter(value))}" if isinstance(value, dict) and len(value) == 1 else "")
                    raise ValueError(f"--{flag.replace('_', '-')} ({token}){msg[len(token):]}") from None
        raise


def run(args) -> int:
    from ..sweep import config_from_mapping, load_config, run_sweep
    from ..sweep.config import check_scheduler_address

    flag_mapping = _flag_mapping(args)
    if args.config is not None:
        if flag_mapping["axes"] or flag_mapping["sweep"] or set(flag_mapping["bem"]) - {"max_seconds"}:
            raise ValueError("give the axes and quantities either in CONFIG.toml or as flags, not both")
        config = load_config(args.config)
        if args.max_seconds is not None:   # validated as the config's [bem] max_seconds
            mapping = config.as_dict()
            mapping["bem"]["max_seconds"] = args.max_seconds
            config = _from_flags(config_from_mapping, mapping, {"bem": {"max_seconds": args.max_seconds}})
    else:
        if not flag_mapping["axes"]:
            raise ValueError("give a CONFIG.toml or the axes as flags (e.g. --beta0 0.9 1 --mu-geomspace 0.1 10 50)")
        config = _from_flags(config_from_mapping, flag_mapping, flag_mapping)
    from ..sweep.config import WORKERS_PER_CPU, max_workers

    if args.workers is not None and not 1 <= args.workers <= max_workers():
        raise ValueError(f"--workers must be an integer in 1..{max_workers()} ({WORKERS_PER_CPU} local processes "
                         f"per CPU); got {args.workers}")
    scheduler = args.scheduler if args.scheduler is not None else config.scheduler
    if scheduler not in (None, "synchronous", "processes"):
        check_scheduler_address(scheduler)
    out = args.out if args.out is not None else config.out
    if out is not None and not str(out).strip():
        raise ValueError(f"out (output path) must be a non-empty path; got {out!r}")
    if out is not None:
        from ..io import require_utf8_path

        require_utf8_path(os.path.abspath(out))   # the sweep and its cases are netCDF files
    if out is None:
        raise ValueError("--out is required (an output FILE.nc or DIR), or run.out in the config")
    res = run_sweep(config, out=out, scheduler=scheduler, workers=args.workers,
                    progress=False if args.quiet else None)
    flagged = list(getattr(res, "flagged", ()))
    summary = (f"wrote {res.path}: {len(res.computed)} cases computed, {len(res.reused)} reused, "
               f"{len(res.failed)} failed")
    if flagged:
        summary += f", {len(flagged)} flagged (not converged or unresolved: see status and adhesive_message)"
    warned = int(getattr(res, "warned", 0))
    if warned:
        summary += f", {warned} pull-off point(s) outside their model's validated range (see the warning variable)"
    if not args.quiet or res.failed or flagged:
        print(summary, file=sys.stderr)
    return 1 if res.failed else EXIT_FLAGGED if flagged else 0
