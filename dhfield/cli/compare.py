"""``dhfield compare``: the pull-off of every model side by side."""
from __future__ import annotations

from ._common import add_model_arguments, add_physical_arguments, contact_parameters_from_args, plain_record
from ._common import print_json, print_warning


def add_parser(sub) -> None:
    p = sub.add_parser("compare", help="pull-off of every comparison model side by side (Fig. 9 axes)",
                       description="The pull-off of every model of dhfield.analysis.compare side by side, one row per "
                       "model.  Inputs: --beta0 and --mu (table in the paper's units, Eqs. 32-35) or the "
                       "physical inputs in SI units of 'dhfield pulloff' (table in N and m, with W*).  The "
                       "table's second row gives each column's unit; --json gives every record with a 'units' "
                       "entry, --out a netCDF file on the dimension 'model'.  The recommended model's row is "
                       "marked '*'; 'vs <recommended>' is each model's W*/W*_recommended - 1, 'error' its estimated "
                       "error against the stored BEM ground truth (dhfield.analysis.model_error; n/a outside the box of the "
                       "stored cases, beta0 0.1-1, mu 0.1-10, load control), 'status' says whether a model is off "
                       "the recommended one by more than 2 %, outside its validated range or gave no answer, and "
                       "the notes under the table say why.  The flagged models are also named on stderr.")
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
#: Short unit labels of the nondimensional columns (their scale, :mod:`dhfield.core.schema`).
_NONDIM_LABELS = {"W_star": "[Eq. 34]", "a_star": "[c_r]", "b_star": "[c_r]", "c_star": "[c_r]", "d_star": "[c_r]",
                  "v": "[1]", "delta_star": "[c_r^2/R]"}


def _unit_label(key, nondim) -> str:
    """The units row's entry of a column: its scale in the paper's units, or its SI unit (schema)."""
    from ..core.schema import units

    if nondim or key == "W_star":
        return _NONDIM_LABELS[key]
    return f"[{units(key)}]"


def row_status(name, rec, departure) -> str:
    """The 'status' entry of a model's row: recommended, off, outside range, no answer, unverified or ok.

    Parameters
    ----------
    name : str
        The model.
    rec : dict
        Its plain pull-off record (with the trust group).
    departure : float
        Its W*/W*_recommended - 1 [-].

    Returns
    -------
    str
        Comma-separated: 'recommended' for :data:`dhfield.analysis.compare.RECOMMENDED_MODEL`; 'no answer'
        where W* is not finite; 'off' where the departure exceeds
        :data:`dhfield.analysis.validity.WARNING_THRESHOLD`; 'outside range' outside the model's
        validated range (:data:`dhfield.analysis.validity.VALIDITY_RANGES`); 'unverified' where no
        stored BEM case checks the point; 'ok' where none applies.
    """
    import math

    from ..analysis.compare import RECOMMENDED_MODEL
    from ..analysis.validity import WARNING_THRESHOLD, validity_message

    words = ["recommended"] if name == RECOMMENDED_MODEL else []
    if not math.isfinite(rec["W_star"]):
        words.append("no answer")
    elif abs(departure) > WARNING_THRESHOLD:
        words.append("off")
    if validity_message(name, rec["mu"], rec["beta0"]):
        words.append("outside range")
    if not rec.get("bem_verified", False) and "no answer" not in words:
        words.append("unverified")
    return ", ".join(words) or "ok"


def _percent(x, width) -> str:
    import math

    return f"{100 * x:+{width}.2f}" if math.isfinite(x) else f"{'nan':>{width}s}"


def _error_text(x, width) -> str:
    import math

    return f"{100 * x:{width}.2g}" if math.isfinite(x) else f"{'n/a':>{width}s}"


def run(args) -> int:
    from ..analysis.compare import RECOMMENDED_MODEL, compare, departure_from_recommended
    from ..analysis.dimensional import pull_off_record_si
    from ..core.schema import PULL_OFF_KEYS, PULL_OFF_SI_KEYS, PULL_OFF_TRUST_KEYS, units

    if args.out and not str(args.out).lower().endswith(".nc"):
        raise ValueError(f"output file must end in .nc; got {args.out!r}")
    params = contact_parameters_from_args(args)
    if params is None:
        records = compare(mu=args.mu, beta0=args.beta0, control=args.control)
        recs = {name: plain_record(r) for name, r in records.items()}
        keys, nondim = PULL_OFF_KEYS + PULL_OFF_TRUST_KEYS, True
    else:
        records = compare(mu=params.mu, beta0=params.beta0, control=args.control)
        recs = {name: plain_record(pull_off_record_si(r, params)) for name, r in records.items()}
        keys, nondim = PULL_OFF_SI_KEYS + PULL_OFF_TRUST_KEYS, False
    first = next(iter(recs.values()))
    departure = {name: float(d) for name, d in departure_from_recommended(records).items()}
    status = {name: row_status(name, r, departure[name]) for name, r in recs.items()}
    print_warning(recs.get("dh-elliptic", {}))
    groups = {"off": "depart from the recommended model by more than 2 %", "no answer": "gave no answer",
              "outside range": "outside their validated range"}
    named = [f"{text}: {', '.join(n for n in recs if n != 'dh-elliptic' and word in status[n].split(', '))}"
             for word, text in groups.items()
             if any(word in status[n].split(", ") for n in recs if n != "dh-elliptic")]
    if named:
        print_warning({"warning": "; ".join(named) + " (the notes under the table, or 'warning' in --json, say why; "
                                  "ranges in pulloff --help)"})
    if args.out:
        from ..io import write_netcdf
        from ..io.compare import comparison_dataset

        write_netcdf(comparison_dataset(recs), args.out)
    if args.json:
        print_json({"beta0": first["beta0"], "mu": first["mu"], "control": args.control,
                    "recommended_model": RECOMMENDED_MODEL,
                    "departure_from_recommended": departure, "status": status,
                    "models": list(recs.values()), "units": {k: units(k, nondimensional=nondim) for k in keys}})
    else:
        cols = ("W_star", "a_star", "b_star", "c_star", "d_star", "v", "delta_star") if nondim else \
            ("force", "semi_major", "semi_minor", "adhesive_semi_major", "approach", "W_star")
        w = 13 if nondim else 21
        if nondim:
            print(_NONDIM_UNITS_LINE)
        vs = f"vs {RECOMMENDED_MODEL}"
        print(f"{'model':26s}" + "".join(f"{c:>{w}s}" for c in cols) + f"{vs:>16s}{'error':>8s}  status")
        print(f"{'units':26s}" + "".join(f"{_unit_label(c, nondim):>{w}s}" for c in cols) + f"{'[%]':>16s}{'[%]':>8s}")
        for name, r in recs.items():
            label = f"{name} *" if name == RECOMMENDED_MODEL else name
            print(f"{label:26s}" + "".join(f"{r[c]:{w}.6g}" for c in cols)
                  + f"{_percent(departure[name], 16)}{_error_text(r['model_error'], 8)}  {status[name]}")
        print(f"* the recommended model ({RECOMMENDED_MODEL}).  error: estimated error of W* against the stored BEM "
              "ground truth (dhfield.analysis.model_error); n/a where no stored case checks the point.")
        notes = [(name, " ".join(str(r["warning"]).split())) for name, r in recs.items() if r["warning"]]
        if notes:
            print("notes:")
            for name, text in notes:  # most warnings start with the model's name already
                print(f"  {text}" if text.startswith(name) else f"  {name}: {text}")
        if args.out:
            print(f"wrote {args.out}")
    return 0
