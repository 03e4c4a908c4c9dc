"""``dhfield compare``: the pull-off of every model side by side."""
from __future__ import annotations

from ._common import add_model_arguments, add_physical_arguments, contact_parameters_from_args, plain_record
from ._common import print_json, print_warning


def add_parser(sub) -> None:
    p = sub.add_parser("compare", help="pull-off of every comparison model side by side (Fig. 9 axes)",
                       description="The pull-off of every model of dhfield.compare side by side, one row per "
                       "model.  Inputs: --beta0 and --mu (table in the paper's units, Eqs. 32-35) or the "
                       "physical inputs in SI units of 'dhfield pulloff' (table in N and m, with W*).  The "
                       "table's second row gives each column's unit; --json gives every record with a 'units' "
                       "entry, --out a netCDF file on the dimension 'model'.  Models outside their validated "
                       "range are named on stderr.")
    add_model_arguments(p, required=False)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    p.add_argument("--out", default=None, help="also write FILE.nc (netCDF, dimension 'model')")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    add_physical_arguments(p)
    p.set_defaults(func=run)


#: What the columns of the nondimensional table are in (the paper's units, Eqs. 32-35).
_NONDIM_UNITS_LINE = ("# paper's units (Eqs. 32-35): W* = W sin(theta_skew)/(2 pi R dgamma) (Eq. 34); a*, b*, c*, d* "
                      "in c_r = (R^2 dgamma/E*)^(1/3); delta* in c_r^2/R; v dimensionless")
#: Short unit labels of the nondimensional columns (their scale, :mod:`dhfield.schema`).
_NONDIM_LABELS = {"W_star": "[Eq. 34]", "a_star": "[c_r]", "b_star": "[c_r]", "c_star": "[c_r]", "d_star": "[c_r]",
                  "v": "[1]", "delta_star": "[c_r^2/R]"}


def _unit_label(key, nondim) -> str:
    """The units row's entry of a column: its scale in the paper's units, or its SI unit (schema)."""
    from ..schema import units

    if nondim or key == "W_star":
        return _NONDIM_LABELS[key]
    return f"[{units(key)}]"


def run(args) -> int:
    from ..compare import compare
    from ..dimensional import pull_off_record_si
    from ..schema import PULL_OFF_KEYS, PULL_OFF_SI_KEYS, units

    if args.out and not str(args.out).lower().endswith(".nc"):
        raise ValueError(f"output file must end in .nc; got {args.out!r}")
    params = contact_parameters_from_args(args)
    if params is None:
        recs = {name: plain_record(r) for name, r in compare(mu=args.mu, beta0=args.beta0, control=args.control).items()}
        keys, nondim = PULL_OFF_KEYS, True
    else:
        recs = {name: plain_record(pull_off_record_si(r, params))
                for name, r in compare(mu=params.mu, beta0=params.beta0, control=args.control).items()}
        keys, nondim = PULL_OFF_SI_KEYS, False
    first = next(iter(recs.values()))
    print_warning(recs.get("dh-elliptic", {}))
    others = [n for n, r in recs.items() if n != "dh-elliptic" and r["warning"]]
    if others:
        print_warning({"warning": f"outside their validated range or failed (see 'warning' in --json, ranges in "
                                  f"pulloff --help): {', '.join(others)}"})
    if args.out:
        from ..io import write_netcdf
        from ..io.compare import comparison_dataset

        write_netcdf(comparison_dataset(recs), args.out)
    if args.json:
        print_json({"beta0": first["beta0"], "mu": first["mu"], "control": args.control,
                    "models": list(recs.values()), "units": {k: units(k, nondimensional=nondim) for k in keys}})
    else:
        cols = ("W_star", "a_star", "b_star", "c_star", "d_star", "v", "delta_star") if nondim else \
            ("force", "semi_major", "semi_minor", "adhesive_semi_major", "approach", "W_star")
        w = 13 if nondim else 21
        if nondim:
            print(_NONDIM_UNITS_LINE)
        print(f"{'model':24s}" + "".join(f"{c:>{w}s}" for c in cols))
        print(f"{'units':24s}" + "".join(f"{_unit_label(c, nondim):>{w}s}" for c in cols))
        for name, r in recs.items():
            print(f"{name:24s}" + "".join(f"{r[c]:{w}.6g}" for c in cols))
        if args.out:
            print(f"wrote {args.out}")
    return 0
