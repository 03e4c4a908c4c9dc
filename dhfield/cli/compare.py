"""``dhfield compare``: the pull-off of every model side by side."""
from __future__ import annotations

from ._common import add_model_arguments, plain_record, print_json, print_warning


def add_parser(sub) -> None:
    p = sub.add_parser("compare", help="pull-off of every comparison model side by side (Fig. 9 axes)")
    add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    p.add_argument("--out", default=None, help="also write FILE.nc (netCDF, dimension 'model')")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..compare import compare
    from ..schema import PULL_OFF_KEYS, units

    if args.out and not str(args.out).lower().endswith(".nc"):
        raise ValueError(f"output file must end in .nc; got {args.out!r}")
    recs = {name: plain_record(r) for name, r in compare(args.mu, args.beta0, args.control).items()}
    for r in recs.values():
        print_warning(r)
    if args.out:
        from ..io import write_netcdf
        from ..io.compare import comparison_dataset

        write_netcdf(comparison_dataset(recs), args.out)
    if args.json:
        print_json({"beta0": args.beta0, "mu": args.mu, "control": args.control, "models": list(recs.values()),
                    "units": {k: units(k, nondimensional=True) for k in PULL_OFF_KEYS}})
    else:
        cols = ("W_star", "a_star", "b_star", "c_star", "d_star", "v", "delta_star")
        print(f"{'model':24s}" + "".join(f"{c:>13s}" for c in cols))
        for name, r in recs.items():
            print(f"{name:24s}" + "".join(f"{r[c]:13.6g}" for c in cols))
        if args.out:
            print(f"wrote {args.out}")
    return 0
