"""``dhfield fit``: the inverse problem, dgamma (and sigma0) from measurements."""
from __future__ import annotations

import argparse
import math
import re

from ._common import UsageError, add_physical_arguments, model_names, print_json, print_warning

#: Starting work of adhesion of a ``--data`` fit without --work-of-adhesion [J/m^2]
#: (a typical solid-solid value; the fit moves 4 decades either way).
DEFAULT_START_WORK = 0.05
#: Uncertainty flags: dest of the input -> (flag, number of values).  One standard deviation
#: each, in the unit of the input; propagated linearly by dhfield.analysis.fit.propagate_input_uncertainty.
STD_FLAGS = {"adhesive_stress": ("--adhesive-stress-std", 1), "youngs_modulus": ("--youngs-modulus-std", 1),
             "poisson_ratio": ("--poisson-ratio-std", 1), "youngs_modulus_2": ("--youngs-modulus-2-std", 1),
             "poisson_ratio_2": ("--poisson-ratio-2-std", 1), "cylinder_radius": ("--cylinder-radius-std", 1),
             "radii": ("--radii-std", 2), "principal_radii": ("--principal-radii-std", 2),
             "skew_angle_deg": ("--skew-angle-deg-std", 1)}

_DESCRIPTION = """\
The inverse problem, in SI units.

With --pull-off-force F [F ...] and --adhesive-stress: the work of adhesion whose
pull-off force is each F (one root each); with several replicate forces, their
mean and its standard error.  The standard error is t-adjusted: +-1.96 of it
is the Student-t 95 % interval of the mean (for 3 replicates the plain s/sqrt(n)
would cover only 82 %); 'replicate_stderr' is the plain one.  Uncertain inputs
(--adhesive-stress-std, --youngs-modulus-std, ..., one standard deviation each,
in the input's unit) are propagated linearly (central differences) and
combined with the replicates' scatter (Welch-Satterthwaite degrees of freedom).

With --data FILE.csv (columns force [N] and semi_major [m], optionally
approach [m]; aliases load, contact_size; a unit in the header such as
'load [mN]' or 'contact_size [um]' is converted): dgamma and sigma0 by least
squares, with standard errors.  Where the data cannot identify one (or the
least squares did not converge) the fit is flagged: that estimate, and mu,
print as 'not identifiable' (null in --json, listed in 'not_identifiable'),
one line on stderr says why, and the exit status is 3.  With --data,
--work-of-adhesion and --adhesive-stress are starting values (default 0.05 J/m^2 and mu = 1).

With --data FILE.csv that has an angle column (skew_angle_deg, degrees): one fit
over every crossing angle (geometry from --cylinder-radius or --radii, without
--skew-angle-deg; mu changes with the angle, the material does not).  Rows
without a semi_major column are pull-off forces (negative): dgamma is fitted
at --adhesive-stress, or with sigma0 when it is left out (flagged, exit 3,
where the forces do not determine it); rows with one are load-curve points:
dgamma and sigma0.  work_of_adhesion_stderr is the standard error (s/sqrt(n)
for replicates), work_of_adhesion_ci95 the Student-t 95 % interval; --plot
draws the data against the fitted model, one curve per angle.

Geometry and material as for 'dhfield pulloff'.  Outside a model's validated
range, and for dh-elliptic where it departs from the recommended model
md-elliptic, the result carries the warning 'dhfield pulloff' gives."""


def add_parser(sub) -> None:
    p = sub.add_parser(
        "fit", help="work of adhesion from pull-off forces, or dgamma and sigma0 from a load curve",
        description=_DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    what = p.add_mutually_exclusive_group(required=True)
    what.add_argument("--pull-off-force", type=float, nargs="+", metavar="F",
                      help="measured pull-off force(s) [N] (negative); several values are replicates")
    what.add_argument("--data", metavar="FILE.csv", help="measured load curve (CSV with a header row)")
    from ..analysis.compare import DEFAULT_MODEL

    p.add_argument("--model", choices=model_names(), default=DEFAULT_MODEL,
                   help="model (default: md-elliptic, the recommended one; dh-elliptic is the paper's)")
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="loading mode of the pull-off measurement (default load)")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="with --data: write the fit and its residuals to FILE.png, FILE.svg and FILE.pdf")
    p.add_argument("--json", action="store_true", help="print one JSON object (with a 'units' entry)")
    add_physical_arguments(p)
    g = p.add_argument_group("input uncertainties (with --pull-off-force; one standard deviation each, in the "
                             "input's unit; body 2 follows body 1 when it has no flags of its own)")
    for dest, (flag, n) in STD_FLAGS.items():
        kw = {"nargs": 2} if n == 2 else {}
        g.add_argument(flag, type=float, dest=f"{dest}_std", metavar="STD", default=None, **kw,
                       help=f"standard deviation of {flag.removesuffix('-std')}")
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
    try:
        params = contact_parameters_from_args(args)
    finally:
        args.work_of_adhesion, args.adhesive_stress = given_work, given_stress
    return params


def _uncertain_inputs(args):
    """(inputs, input_std, build) of the --*-std flags, for dhfield.analysis.fit.propagate_input_uncertainty."""
    import copy

    from ._common import contact_parameters_from_args

    inputs, stds = {}, {}
    for dest, (flag, n) in STD_FLAGS.items():
        std = getattr(args, f"{dest}_std")
        if std is None:
            continue
        value = getattr(args, dest)
        for x in (std if n == 2 else [std]):
            if not (math.isfinite(x) and x >= 0.0):
                raise UsageError(f"{flag} must be a standard deviation >= 0 (finite, in the unit of "
                                 f"{flag.removesuffix('-std')}); got {x!r}")
        if value is None:
            raise UsageError(f"{flag} needs {flag.removesuffix('-std')} (the value it is the uncertainty of)")
        if n == 1:
            inputs[dest], stds[dest] = value, std
        else:
            for k in range(2):
                inputs[f"{dest}_{k + 1}"], stds[f"{dest}_{k + 1}"] = value[k], std[k]

    def build(**values):
        ns = copy.copy(args)
        ns.work_of_adhesion = DEFAULT_START_WORK  # a placeholder: dgamma is what is fitted
        for dest, (_, n) in STD_FLAGS.items():
            if n == 1 and dest in values:
                setattr(ns, dest, values[dest])
            elif n == 2 and f"{dest}_1" in values:
                pair = list(getattr(ns, dest))
                pair = [values.get(f"{dest}_{k + 1}", pair[k]) for k in range(2)]
                setattr(ns, dest, pair)
        return contact_parameters_from_args(ns)

    return inputs, stds, build


def run(args) -> int:
    from ..analysis import fit

    if args.plot is not None and args.data is None:
        raise UsageError("--plot goes with --data")
    if args.plot is not None:
        from ..io import validate_output_path

        validate_output_path(args.plot, (".png",), "plot")
    stds_given = [flag for dest, (flag, _) in STD_FLAGS.items() if getattr(args, f"{dest}_std") is not None]
    if args.pull_off_force is not None:
        if args.adhesive_stress is None:
            raise UsageError("--pull-off-force needs --adhesive-stress (the fit finds dgamma at that sigma0)")
        inputs, stds, build = _uncertain_inputs(args)
        params = _params(args)
        res = fit.fit_work_of_adhesion(args.pull_off_force, params, max_adhesive_stress=args.adhesive_stress,
                                       model=args.model, control=args.control)
        if stds:
            res = fit.propagate_input_uncertainty(res, build, inputs, stds)
        rec = res.as_record()
        print_warning(rec)
    else:
        if stds_given:
            raise UsageError(f"{stds_given[0]} goes with --pull-off-force (a --data fit estimates its own "
                             "standard errors)")
        from ..io.fit import has_angle_column

        if has_angle_column(args.data):
            return _run_joint(args)
        params = _params(args)
        from ..io.fit import read_curve_data

        data = read_curve_data(args.data, params)
        stress = args.adhesive_stress if args.adhesive_stress is not None else \
            params.max_adhesive_stress / params.mu  # mu = 1 at the starting dgamma (Eq. 35)
        import sys

        progress = sys.stderr.isatty() or data["force"].size >= PROGRESS_POINTS
        res = fit.fit_curve(data["force"], data["semi_major"], params, approach=data.get("approach"),
                            model=args.model, initial=(params.work_of_adhesion, stress), progress=progress)
        rec = _hide_not_identifiable(res.as_record())
        print_warning(rec)
        if args.plot is not None:
            from ..io.fit import write_residual_plot

            write_residual_plot(res, args.plot)
    _print_record(args, rec)
    if args.data is not None and not res.success:
        import sys

        print(f"dhfield: fit is not an answer: {res.message}", file=sys.stderr)
        return EXIT_NOT_AN_ANSWER
    return 0


def _run_joint(args) -> int:
    """``--data`` with a crossing-angle column: :func:`dhfield.analysis.fit.fit_joint` over the file's angles."""
    import copy
    import sys

    from ..analysis import fit
    from ..io.fit import read_joint_data

    if args.skew_angle_deg is not None:
        raise UsageError(f"--skew-angle-deg goes with a data file without an angle column; {args.data} gives "
                         "each row's angle in its skew_angle_deg column")
    if args.principal_radii is not None:
        raise UsageError("a data file with an angle column needs --cylinder-radius or --radii (the angle sets "
                         "the principal radii), not --principal-radii")
    data = read_joint_data(args.data)

    def contact_at(angle_deg):
        ns = copy.copy(args)
        ns.skew_angle_deg = float(angle_deg)
        return _params(ns)

    initial = None
    if args.work_of_adhesion is not None or "semi_major" in data:
        p0 = contact_at(float(data["skew_angle_deg"][0]))
        stress = args.adhesive_stress if args.adhesive_stress is not None else \
            p0.max_adhesive_stress / p0.mu  # mu = 1 at the starting dgamma (Eq. 35)
        initial = (p0.work_of_adhesion, stress)
    # with pull-off forces, --adhesive-stress holds sigma0 fixed; with load curves it is a starting value
    fixed = args.adhesive_stress if "semi_major" not in data else None
    res = fit.fit_joint(data["force"], data["skew_angle_deg"], contact_at, contact_size=data.get("semi_major"),
                        max_adhesive_stress=fixed, model=args.model, control=args.control, initial=initial)
    rec = _hide_not_identifiable(res.as_record())
    print_warning(rec)
    if args.plot is not None:
        from ..io.fit import write_joint_plot

        write_joint_plot(res, args.plot)
    _print_record(args, rec)
    if not res.success:
        print(f"dhfield: fit is not an answer: {res.message}", file=sys.stderr)
        return EXIT_NOT_AN_ANSWER
    return 0


def _print_record(args, rec) -> None:
    """Print a fit's record as JSON (``--json``) or as aligned text lines with units."""
    unit = {k: _unit(k) for k in rec}
    if args.json:
        print_json({**rec, "units": {k: u for k, u in unit.items()
                                     if not isinstance(rec[k], (str, bool)) and k not in ("not_identifiable", "fitted")}})
        return
    for k, v in rec.items():
        if k == "not_identifiable":
            continue
        shown = NOT_IDENTIFIABLE_TEXT if v is None else _text(v)
        print(f"{k:28s} {shown:24s} {'' if unit[k] == '1' or v is None else unit[k]}".rstrip())
    if args.plot is not None:
        print(f"wrote {args.plot}, {args.plot[:-4]}.svg and {args.plot[:-4]}.pdf")


#: Rows of a ``--data`` file from which a fit reports its progress on stderr even when stderr is not a
#: terminal (a line every :data:`dhfield.analysis.fit.PROGRESS_INTERVAL` seconds; nothing for a faster fit).
PROGRESS_POINTS = 10_000
#: Exit status of a ``--data`` fit that is flagged (``success`` false: a parameter not identifiable,
#: or the least squares did not converge); the result is still printed, as ``dhfield solve`` does
#: with its exit status 3 (:data:`dhfield.cli.solve.EXIT_UNCONVERGED`).
EXIT_NOT_AN_ANSWER = 3
#: How the text output shows an estimate the data do not determine (null in --json).
NOT_IDENTIFIABLE_TEXT = "not identifiable"


def _hide_not_identifiable(rec) -> dict:
    """``rec`` with the estimates the data do not determine, their standard errors, and the quantities
    computed from them (mu from sigma0 and dgamma, their correlation), set to None."""
    names = rec.get("not_identifiable") or []
    if not names:
        return rec
    hidden = {k for n in names for k in (n, f"{n}_stderr")} | {"mu", "correlation"}
    return {k: (None if k in hidden else v) for k, v in rec.items()}


def _text(v):
    if isinstance(v, float):
        return f"{v:.10g}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_text(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k}: {_text(x)}" for k, x in v.items()) + "}"
    return str(v)


def _unit(key):
    from ..core.schema import units

    if key in _EXTRA_UNITS:
        return _EXTRA_UNITS[key]
    base = key.removesuffix("_stderr")
    return units(base) if base in _SCHEMA_KEYS else "1"


_SCHEMA_KEYS = ("work_of_adhesion", "max_adhesive_stress", "mu", "beta0", "force")
#: Units of record keys that are not schema variables.
_EXTRA_UNITS = {"skew_angles_deg": "deg", "max_adhesive_stress_ci95": "Pa", "relative_noise": "1", "load_noise": "N", "approach_noise": "m", "work_of_adhesion_ci95": "J m-2", "forces": "N",
                "replicate_works": "J m-2", "replicate_stderr": "J m-2", "input_stderr": "J m-2",
                "input_contributions": "J m-2"}
