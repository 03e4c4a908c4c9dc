"""``dhfield fit``: the inverse problem, dgamma (and sigma0) from measurements."""
from __future__ import annotations

import re

from ._common import UsageError, add_physical_arguments, model_names, print_json, print_warning

#: Columns of ``--data``: schema name -> accepted aliases.
DATA_COLUMNS = {"force": ("force", "load"), "semi_major": ("semi_major", "contact_size"),
                "approach": ("approach",)}
#: Starting work of adhesion of a ``--data`` fit without --work-of-adhesion [J/m^2]
#: (a typical solid-solid value; the fit moves 4 decades either way).
DEFAULT_START_WORK = 0.05


def add_parser(sub) -> None:
    p = sub.add_parser(
        "fit", help="work of adhesion from a pull-off force, or dgamma and sigma0 from a load curve",
        description="The inverse problem, in SI units.  With --pull-off-force F and --adhesive-stress: the "
        "work of adhesion whose pull-off force is F (one root).  With --data FILE.csv (columns force [N] and "
        "semi_major [m], optionally approach [m]; aliases load, contact_size): dgamma and sigma0 by least "
        "squares, with standard errors.  Geometry and material as for 'dhfield pulloff'; with --data, "
        "--work-of-adhesion and --adhesive-stress are starting values (default 0.05 J/m^2 and mu = 1).")
    what = p.add_mutually_exclusive_group(required=True)
    what.add_argument("--pull-off-force", type=float, metavar="F", help="measured pull-off force [N] (negative)")
    what.add_argument("--data", metavar="FILE.csv", help="measured load curve (CSV with a header row)")
    p.add_argument("--model", choices=model_names(), default="dh-elliptic",
                   help="model (default: dh-elliptic, the paper's)")
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="loading mode of the pull-off measurement (default load)")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="with --data: write the fit and its residuals to FILE.png and FILE.svg")
    p.add_argument("--json", action="store_true", help="print one JSON object (with a 'units' entry)")
    add_physical_arguments(p)
    p.set_defaults(func=run, beta0=None, mu=None)
    # accept negative numbers in scientific notation as values (--pull-off-force -1.2e-3)
    p._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def _params(args):
    from ._common import contact_parameters_from_args

    # dgamma is what is fitted: a placeholder stands in where none is given (only the
    # geometry and material of the result are used, and the starting value of --data)
    given_work, given_stress = args.work_of_adhesion, args.adhesive_stress
    if args.youngs_modulus is None:
        raise UsageError("fit needs the geometry and material: --youngs-modulus, --poisson-ratio and one of "
                         "--cylinder-radius, --radii, --principal-radii")
    args.work_of_adhesion = DEFAULT_START_WORK if given_work is None else given_work
    if given_stress is None:
        args.adhesive_stress = 1.0
    params = contact_parameters_from_args(args)
    args.work_of_adhesion, args.adhesive_stress = given_work, given_stress
    return params


def _read_data(path):
    from ..io.table import read_table

    frame, _ = read_table(path)
    cols = {}
    for name, aliases in DATA_COLUMNS.items():
        found = [a for a in aliases if a in frame.columns]
        if found:
            cols[name] = found[0]
        elif name != "approach":
            raise ValueError(f"data file {str(path)!r} has no column {name!r} (or {', '.join(aliases[1:])}); "
                             f"columns: {', '.join(map(str, frame.columns))}")
    frame, _ = read_table(path, required=tuple(cols.values()))
    return {name: frame[col].to_numpy(dtype=float) for name, col in cols.items()}


def run(args) -> int:
    from .. import fit
    from ..schema import units

    if args.plot is not None and args.data is None:
        raise UsageError("--plot goes with --data")
    if args.plot is not None:
        from ..io import validate_output_path

        validate_output_path(args.plot, (".png",), "plot")
    if args.pull_off_force is not None:
        if args.adhesive_stress is None:
            raise UsageError("--pull-off-force needs --adhesive-stress (the fit finds dgamma at that sigma0)")
        params = _params(args)
        res = fit.fit_work_of_adhesion(args.pull_off_force, params, max_adhesive_stress=args.adhesive_stress,
                                       model=args.model, control=args.control)
        rec = res.as_record()
        print_warning(rec)
    else:
        data = _read_data(args.data)
        params = _params(args)
        stress = args.adhesive_stress if args.adhesive_stress is not None else \
            params.max_adhesive_stress / params.mu  # mu = 1 at the starting dgamma (Eq. 35)
        res = fit.fit_curve(data["force"], data["semi_major"], params, approach=data.get("approach"),
                            model=args.model, initial=(params.work_of_adhesion, stress))
        rec = res.as_record()
        if args.plot is not None:
            from ..io.fit import write_residual_plot

            write_residual_plot(res, args.plot)
    unit = {k: units(k.removesuffix("_stderr")) if k.removesuffix("_stderr") in _SCHEMA_KEYS else
            _EXTRA_UNITS.get(k, "1") for k in rec}
    if args.json:
        print_json({**rec, "units": {k: u for k, u in unit.items() if isinstance(rec[k], (float, int))
                                     and not isinstance(rec[k], bool)}})
    else:
        for k, v in rec.items():
            print(f"{k:28s} {v!s:24s} {'' if unit[k] == '1' else unit[k]}".rstrip())
        if args.plot is not None:
            print(f"wrote {args.plot} and {args.plot[:-4]}.svg")
    if args.data is not None and not res.success:
        import sys

        print(f"dhfield: warning: {res.message}", file=sys.stderr)
    return 0


_SCHEMA_KEYS = ("work_of_adhesion", "max_adhesive_stress", "mu", "beta0", "force")
#: Units of record keys that are not schema variables.
_EXTRA_UNITS = {"load_noise": "N", "approach_noise": "m"}
