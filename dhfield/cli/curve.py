"""``dhfield curve``: the load curve of a model, over contact sizes or (SI) over loads."""
from __future__ import annotations

import argparse

from ._common import UsageError, add_model_arguments, add_physical_arguments, contact_parameters_from_args
from ._common import print_json, print_warning
from ._common import validity_epilog as _epilog


def add_parser(sub) -> None:
    from ..analysis.compare import CURVE_MODEL_NAMES, DEFAULT_MODEL

    p = sub.add_parser("curve", help="load curve of a model (nondimensional, Eqs. 32-36, or SI)",
                       description="Load curve of one model.  Inputs: --beta0 and --mu (nondimensional; range "
                       "--a-min/--a-max in c_r), or physical inputs in SI units (range --semi-major-min/"
                       "--semi-major-max [m] or --load-min/--load-max [N] on the stable branch).",
                       epilog=_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    add_model_arguments(p, required=False)
    p.add_argument("--model", choices=CURVE_MODEL_NAMES, default=DEFAULT_MODEL,
                   help="model (default: md-elliptic, the recommended one; dh-elliptic is the paper's); "
                   "dh-elliptic-jkr-beta has no curve")
    p.add_argument("--ellipticity", type=float, default=None,
                   help="dh-elliptic only: ellipticity of both ellipses if different from beta0")
    p.add_argument("--a-min", type=float, default=None, help="smallest contact semi-major axis a* (> 0)")
    p.add_argument("--a-max", type=float, default=None, help="largest contact semi-major axis a*")
    p.add_argument("--semi-major-min", type=float, default=None, help="SI: smallest contact semi-major axis [m]")
    p.add_argument("--semi-major-max", type=float, default=None, help="SI: largest contact semi-major axis [m]")
    p.add_argument("--load-min", type=float, default=None,
                   help="SI: smallest load [N] (compressive positive; at least the pull-off force; write a negative "
                   "value as --load-min=-5e-4)")
    p.add_argument("--load-max", type=float, default=None, help="SI: largest load [N]")
    p.add_argument("--n", type=int, default=200, help="number of points (default 200)")
    p.add_argument("--out", default=None, help="write FILE.nc (netCDF) or FILE.csv; default: print a table")
    p.add_argument("--json", action="store_true", help="print one JSON object (arrays as lists, with 'units')")
    p.add_argument("--machine-stiffness", type=float, default=None, metavar="K",
                   help="add the column machine_displacement = approach + load/K of a machine spring: K > 0 in N/m "
                   "with physical inputs, K* (paper's units) with --beta0/--mu (dhfield.analysis.spring)")
    add_physical_arguments(p)
    p.set_defaults(func=run)


def _range(lo, hi, n, name_lo, name_hi):
    import numpy as np

    from ..core.validation import check_finite

    if lo is None or hi is None:
        raise UsageError(f"give both --{name_lo} and --{name_hi}")
    check_finite(name_lo, lo)  # name the option the user gave, not the grid
    check_finite(name_hi, hi)
    if not hi > lo:
        raise ValueError(f"{name_hi} must be greater than {name_lo}; got {name_lo}={lo!r}, {name_hi}={hi!r}")
    if n < 2:
        raise ValueError(f"n must be an integer >= 2; got {n!r}")
    return np.linspace(lo, hi, n)


def curve_record(args):
    """The load curve (a :class:`dhfield.core.records.LoadCurve`) the arguments ask for."""
    from ..analysis import compare, dimensional
    from ..models.dh_elliptic import DEFAULT_A_STAR, load_curve

    params = contact_parameters_from_args(args)
    si_range = [f for f in ("semi_major_min", "semi_major_max", "load_min", "load_max")
                if getattr(args, f) is not None]
    if params is None:
        if si_range:
            raise UsageError(f"--{si_range[0].replace('_', '-')} needs physical inputs; with --beta0/--mu use "
                             "--a-min/--a-max")
        a_star = None
        if args.a_min is not None or args.a_max is not None:
            lo = DEFAULT_A_STAR[0] if args.a_min is None else args.a_min
            hi = DEFAULT_A_STAR[1] if args.a_max is None else args.a_max
            from ..core.validation import check_contact_size_star
            check_contact_size_star("--a-min (smallest a_star)", lo)
            check_contact_size_star("--a-max (largest a_star)", hi)
            a_star = _range(lo, hi, args.n, "a-min", "a-max")
        if args.ellipticity is not None:
            if args.model != "dh-elliptic":
                raise UsageError(f"--ellipticity applies to --model dh-elliptic only (the paper's model, whose "
                                 f"ellipticity is a free parameter); got --model {args.model}, the default "
                                 "being md-elliptic: add --model dh-elliptic")
            # the paper's model's own curve: the registry's keys, then its free ellipticity
            return load_curve(mu=args.mu, beta0=args.beta0, a_star=a_star, ellipticity=args.ellipticity, n=args.n)
        return compare.load_curve(args.model, mu=args.mu, beta0=args.beta0, a_star=a_star, n=args.n)
    if args.a_min is not None or args.a_max is not None or args.ellipticity is not None:
        raise UsageError("--a-min/--a-max/--ellipticity go with --beta0/--mu; with physical inputs use "
                         "--semi-major-min/--semi-major-max or --load-min/--load-max")
    by_size = args.semi_major_min is not None or args.semi_major_max is not None
    by_load = args.load_min is not None or args.load_max is not None
    if by_size and by_load:
        raise UsageError("give a contact-size range or a load range, not both")
    if by_load:
        force = _range(args.load_min, args.load_max, args.n, "load-min", "load-max")
        return dimensional.load_curve_si(params, model=args.model, force=force)
    a = None
    if by_size:
        a = _range(args.semi_major_min, args.semi_major_max, args.n, "semi-major-min", "semi-major-max")
    return dimensional.load_curve_si(params, a, n=args.n, model=args.model)


def run(args) -> int:
    import numpy as np

    from ..core.schema import LOAD_CURVE_HEADER_KEYS, units

    from ..analysis.validity import validity_message

    rec = curve_record(args)
    if getattr(args, "machine_stiffness", None) is not None:
        from ..analysis.spring import add_machine_displacement

        rec = add_machine_displacement(rec, args.machine_stiffness)
    print_warning({"warning": validity_message(rec["model"], rec["mu"], rec["beta0"])})
    nondim = "force" not in rec
    cols = [k for k in rec if k not in LOAD_CURVE_HEADER_KEYS and np.ndim(rec[k]) == 1]
    if args.out:
        from ..io.curves import write_load_curve

        k = getattr(args, "machine_stiffness", None)   # the stiffness of machine_displacement (param_*)
        extra = {} if k is None else {("machine_stiffness" if not nondim else "machine_stiffness_star"): k}
        path = write_load_curve(rec, args.out, **extra)
        print(f"wrote {path}")
        return 0
    if args.json:
        print_json({**rec, "units": {k: units(k, nondimensional=nondim) for k in rec if k != "ellipticity"}})
        return 0
    print("\t".join(cols))
    for row in zip(*(rec[k] for k in cols)):
        print("\t".join(f"{x:.10g}" for x in row))
    return 0
