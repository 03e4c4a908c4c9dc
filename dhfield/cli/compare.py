"""``dhfield compare``."""
from __future__ import annotations

from ._common import add_model_arguments, compare_record, print_json


def add_parser(sub) -> None:
    p = sub.add_parser("compare", help="pull-off of every comparison model side by side (Fig. 9 axes)")
    add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    p.add_argument("--out", default=None, help="also write FILE.nc (netCDF, dimension 'model')")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..compare import MODEL_NAMES

    if args.out and not str(args.out).lower().endswith(".nc"):
        raise ValueError(f"output file must end in .nc; got {args.out!r}")
    recs = {name: compare_record(name, args) for name in MODEL_NAMES}
    if args.out:
        from ..io import write_netcdf
        from ..io.compare import comparison_dataset

        write_netcdf(comparison_dataset(recs), args.out)
    if args.json:
        print_json({"beta0": args.beta0, "mu": args.mu, "control": args.control, "models": list(recs.values())})
    else:
        cols = ("W_star", "a_star", "c_star", "v", "delta_star", "ellipticity")
        print(f"{'model':22s}" + "".join(f"{c:>13s}" for c in cols))
        for name, r in recs.items():
            print(f"{name:22s}" + "".join(f"{r[c]:13.6g}" for c in cols))
        if args.out:
            print(f"wrote {args.out}")
    return 0
