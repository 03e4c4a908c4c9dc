"""Command-line interface: ``dhfield <subcommand> ...``.

A thin layer: each subcommand parses its options and calls one library
function; no physics lives here.  Invalid input exits with status 2 and one line
on stderr (``dhfield: error: ...``), never a traceback.

To add a subcommand, write ``_add_<name>(subparsers)`` that creates the parser
and sets ``func`` to a ``_run_<name>(args) -> int`` function, and list it in
:data:`_SUBCOMMANDS`.
"""
from __future__ import annotations

import argparse
import json
import math
import sys

__all__ = ["main"]


class _OneLineParser(argparse.ArgumentParser):
    """argparse with usage errors reduced to one line and exit status 2."""

    def error(self, message):
        raise _UsageError(f"{self.prog}: {message}")


class _UsageError(Exception):
    pass


def _json_default(obj):
    import numpy as np

    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(type(obj))


def _print_json(payload) -> None:
    # NaN is not JSON: emit null for not-applicable quantities.
    def clean(x):
        if isinstance(x, float) and not math.isfinite(x):
            return None
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x

    print(json.dumps(clean(json.loads(json.dumps(payload, default=_json_default))), sort_keys=False))


def _add_model_arguments(p) -> None:
    p.add_argument("--beta0", type=float, required=True, help="initial ellipticity b/a in (0, 1]")
    p.add_argument("--mu", type=float, required=True, help="Tabor parameter (Eq. 35), > 0")


# --- curve ---------------------------------------------------------------------------------

def _add_curve(sub) -> None:
    p = sub.add_parser("curve", help="load curve of the elliptical DH model (nondimensional, Eqs. 32-36)")
    _add_model_arguments(p)
    p.add_argument("--ellipticity", type=float, default=None,
                   help="ellipticity of both ellipses if different from beta0")
    p.add_argument("--a-min", type=float, default=None, help="smallest contact semi-major axis a* (> 0)")
    p.add_argument("--a-max", type=float, default=None, help="largest contact semi-major axis a*")
    p.add_argument("--n", type=int, default=200, help="number of points (default 200)")
    p.add_argument("--out", default=None, help="write FILE.nc (netCDF) or FILE.csv; default: print a table")
    p.set_defaults(func=_run_curve)


def _run_curve(args) -> int:
    import numpy as np

    from .io.curves import CURVE_VARIABLES, write_load_curve
    from .model import DEFAULT_A_STAR, load_curve

    a_star = None
    if args.a_min is not None or args.a_max is not None:
        lo = DEFAULT_A_STAR[0] if args.a_min is None else args.a_min
        hi = DEFAULT_A_STAR[1] if args.a_max is None else args.a_max
        if not hi > lo:
            raise ValueError(f"a-max must be greater than a-min; got a-min={lo!r}, a-max={hi!r}")
        if args.n < 2:
            raise ValueError(f"n must be an integer >= 2; got {args.n!r}")
        a_star = np.linspace(lo, hi, args.n)
    curve = load_curve(args.mu, args.beta0, a_star, ellipticity=args.ellipticity, n=args.n)
    if args.out:
        path = write_load_curve(curve, args.out)
        print(f"wrote {path}")
        return 0
    names = list(CURVE_VARIABLES)
    print("\t".join(names))
    for row in zip(*(getattr(curve, n) for n in names)):
        print("\t".join(f"{x:.10g}" for x in row))
    return 0


# --- pulloff -------------------------------------------------------------------------------

def _add_pulloff(sub) -> None:
    p = sub.add_parser("pulloff", help="pull-off force W*max of the elliptical DH model")
    _add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    p.add_argument("--model", choices=_model_names(), default="dh-elliptic",
                   help="comparison model (default: dh-elliptic, the paper's model)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=_run_pulloff)


def _model_names():
    from .compare import MODEL_NAMES

    return MODEL_NAMES


def _compare_record(model, args) -> dict:
    from .compare import pull_off

    rec = pull_off(model, args.mu, args.beta0, args.control)
    return {k: (v if isinstance(v, str) else float(v)) for k, v in rec.items()}


def _pull_off_record(args) -> dict:
    from .model import pull_off

    if getattr(args, "model", "dh-elliptic") != "dh-elliptic":
        return _compare_record(args.model, args)
    r = pull_off(args.mu, args.beta0, control=args.control)
    return {"model": "dh-elliptic", "beta0": float(r.beta0), "mu": float(r.mu), "control": r.control,
            "W_star": float(r.W_star), "a_star": float(r.a_star), "c_star": float(r.c_star),
            "v": float(r.v), "delta_star": float(r.delta_star),
            "at_zero_contact": bool(r.at_zero_contact)}


def _run_pulloff(args) -> int:
    rec = _pull_off_record(args)
    if args.json:
        _print_json(rec)
    else:
        for k, v in rec.items():
            print(f"{k:16s} {v}")
    return 0


# --- compare -------------------------------------------------------------------------------

def _add_compare(sub) -> None:
    p = sub.add_parser("compare", help="pull-off of every comparison model side by side (Fig. 9 axes)")
    _add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    p.add_argument("--out", default=None, help="also write FILE.nc (netCDF, dimension 'model')")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=_run_compare)


def _run_compare(args) -> int:
    from .compare import MODEL_NAMES

    if args.out and not str(args.out).lower().endswith(".nc"):
        raise ValueError(f"output file must end in .nc; got {args.out!r}")
    recs = {name: _compare_record(name, args) for name in MODEL_NAMES}
    if args.out:
        from .io import write_netcdf
        from .io.compare import comparison_dataset

        write_netcdf(comparison_dataset(recs), args.out)
    if args.json:
        _print_json({"beta0": args.beta0, "mu": args.mu, "control": args.control, "models": list(recs.values())})
    else:
        cols = ("W_star", "a_star", "c_star", "v", "delta_star", "ellipticity")
        print(f"{'model':22s}" + "".join(f"{c:>13s}" for c in cols))
        for name, r in recs.items():
            print(f"{name:22s}" + "".join(f"{r[c]:13.6g}" for c in cols))
        if args.out:
            print(f"wrote {args.out}")
    return 0


# --- field ---------------------------------------------------------------------------------

def _add_field(sub) -> None:
    p = sub.add_parser("field", help="full-field BEM cross-check of one DH case, written to netCDF")
    _add_model_arguments(p)
    p.add_argument("--a-star", type=float, required=True, help="contact semi-major axis a* (> 0)")
    p.add_argument("--n", type=int, default=512, help="cells per axis (>= 8, default 512)")
    p.add_argument("--threads", type=int, default=None, help="FFTW threads (default $DHFIELD_THREADS or 1)")
    p.add_argument("--out", required=True, help="output netCDF file")
    p.set_defaults(func=_run_field)


def _run_field(args) -> int:
    from .io.field import compute_and_write_case

    path = compute_and_write_case(args.beta0, args.mu, args.a_star, args.n, args.out, threads=args.threads)
    print(f"wrote {path}")
    return 0


# --- periphery -----------------------------------------------------------------------------

def _add_periphery(sub) -> None:
    p = sub.add_parser("periphery", help="sigma0, zone width, edge separation and work of adhesion along "
                       "every ray theta_p at pull-off (the equal-beta test)")
    _add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="pull-off under load control (default) or displacement control")
    p.add_argument("--n-theta", type=int, default=10, help="rays in [0, pi/2] (default 10, >= 2)")
    p.add_argument("--out", default=None, help="also write FILE.nc (netCDF)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=_run_periphery)


def _run_periphery(args) -> int:
    import numpy as np

    from .io.periphery import pull_off_periphery_dataset, write_dataset
    from .periphery import pull_off_periphery

    if args.n_theta < 2:
        raise ValueError(f"n-theta must be an integer >= 2 (number of rays); got {args.n_theta!r}")
    if args.out and not str(args.out).lower().endswith(".nc"):
        raise ValueError(f"output file must end in .nc; got {args.out!r}")
    theta = np.linspace(0.0, 0.5 * np.pi, args.n_theta)
    beta0, mu = np.array([[args.beta0]]), np.array([[args.mu]])
    po, prof = pull_off_periphery(mu, beta0, theta, control=args.control)
    if args.out:
        ds = pull_off_periphery_dataset(mu[0], beta0[:, 0], po, prof, control=args.control)
        write_dataset(ds, args.out)
    cols = ("theta", "contact_radius", "adhesive_radius", "zone_width", "max_adhesive_stress",
            "edge_separation", "work_of_adhesion")
    rows = {c: np.asarray(getattr(prof, c))[0, 0] for c in cols}
    if args.json:
        _print_json({"beta0": args.beta0, "mu": args.mu, "control": args.control,
                     "W_star": float(po.W_star[0, 0]), "a_star": float(po.a_star[0, 0]),
                     "c_star": float(po.c_star[0, 0]), "v": float(po.v[0, 0]), "rays": rows})
        return 0
    print(f"pull-off ({args.control} control): W* = {float(po.W_star[0, 0]):.6g}, "
          f"a* = {float(po.a_star[0, 0]):.6g}, c* = {float(po.c_star[0, 0]):.6g}, v = {float(po.v[0, 0]):.6g}")
    print("".join(f"{c:>20s}" for c in cols))
    for i in range(theta.size):
        print("".join(f"{rows[c][i]:20.10g}" for c in cols))
    if args.out:
        print(f"wrote {args.out}")
    return 0


# --- entry point ---------------------------------------------------------------------------

_SUBCOMMANDS = [_add_curve, _add_pulloff, _add_field, _add_compare, _add_periphery]


def build_parser() -> argparse.ArgumentParser:
    from . import __version__

    parser = _OneLineParser(prog="dhfield", description="Extended double-Hertz model of an adhesive "
                            "elliptical contact (Zini et al. 2018, doi:10.1007/s11249-017-0976-8)")
    parser.add_argument("--version", action="version", version=f"dhfield {__version__}")
    sub = parser.add_subparsers(dest="command", parser_class=_OneLineParser, required=True)
    for add in _SUBCOMMANDS:
        add(sub)
    return parser


def main(argv=None) -> int:
    """Run the CLI; return the exit status (0 success, 2 bad input)."""
    try:
        args = build_parser().parse_args(argv)
        return int(args.func(args) or 0)
    except _UsageError as exc:
        print(f"dhfield: error: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"dhfield: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"dhfield: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
