"""``dhfield pulloff``: the pull-off of any model, from --beta0/--mu or from physical inputs."""
from __future__ import annotations

import argparse

from ._common import validity_epilog as _epilog
from ._common import (add_model_arguments, add_physical_arguments, contact_parameters_from_args, model_names,
                      plain_record, print_json, print_warning)

_MODEL_HELP = ("model (default: md-elliptic, the recommended model, at every crossing angle and mu, warned outside "
               "the box of the stored BEM cases; "
               "dh-elliptic is the paper's, which under-predicts the adhesion of elliptical contacts and warns)")


def add_parser(sub) -> None:
    p = sub.add_parser("pulloff", help="pull-off force of any model (nondimensional W* or SI newtons)",
                       description="Pull-off of one model.  Inputs: --beta0 and --mu (nondimensional, "
                       "Eqs. 32-35), or physical inputs in SI units (output then in N and m).  Every model "
                       "gives the same keys in --json, null where a value is n/a; the text output leaves out "
                       "the quantities the model does not have (e.g. the adhesive zone of JKR) and prints nan "
                       "where the model has the quantity but gave no value.",
                       epilog=_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    add_model_arguments(p, required=False)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    from ..analysis.compare import DEFAULT_MODEL

    p.add_argument("--model", choices=model_names(), default=DEFAULT_MODEL, help=_MODEL_HELP)
    p.add_argument("--json", action="store_true", help="print one JSON object (with a 'units' entry)")
    p.add_argument("--machine-stiffness", type=float, default=None, metavar="K",
                   help="pull-off under a machine spring (control 'spring'): K >= 0 in N/m with physical inputs, "
                   "K* (paper's units) with --beta0/--mu; 0 is load control (dhfield.analysis.spring)")
    add_physical_arguments(p)
    p.set_defaults(func=run)


def pull_off_record(args) -> dict:
    """The pull-off record (schema PULL_OFF_KEYS or PULL_OFF_SI_KEYS) the arguments ask for."""
    from ..analysis.compare import pull_off
    from ..analysis.dimensional import pull_off_force

    params = contact_parameters_from_args(args)
    if getattr(args, "machine_stiffness", None) is not None:
        from ..analysis.spring import pull_off_force_under_spring, spring_pull_off_record

        if args.control != "load":
            raise ValueError("control goes with no machine spring; --machine-stiffness sets the machine itself")
        if params is None:
            return plain_record(spring_pull_off_record(args.model, mu=args.mu, beta0=args.beta0, machine_stiffness=args.machine_stiffness))
        return plain_record(pull_off_force_under_spring(params, args.machine_stiffness, model=args.model))
    if params is None:
        return plain_record(pull_off(args.model, mu=args.mu, beta0=args.beta0, control=args.control))
    return plain_record(pull_off_force(params, model=args.model, control=args.control))


#: SI key of each nondimensional quantity that a model may not have (:data:`dhfield.analysis.compare.ABSENT_KEYS`).
_SI_OF = {"c_star": "adhesive_semi_major", "d_star": "adhesive_semi_minor"}


def absent_keys(model) -> frozenset:
    """The keys the text output of a model's pull-off leaves out: NaN in every pull-off of that model.

    Parameters
    ----------
    model : str
        A name of :data:`dhfield.analysis.compare.MODEL_NAMES`.

    Returns
    -------
    frozenset of str
        :data:`dhfield.analysis.compare.ABSENT_KEYS` of the model and their SI keys (the adhesive zone's
        semi-axes in m); empty for an unknown name.  ``--json`` keeps every key (null).
    """
    from ..analysis.compare import ABSENT_KEYS

    keys = ABSENT_KEYS.get(model, ())
    return frozenset(keys) | {_SI_OF[k] for k in keys if k in _SI_OF}


def run(args) -> int:
    from ..core.schema import units

    rec = pull_off_record(args)
    nondim = args.beta0 is not None
    unit = {k: units(k, nondimensional=nondim) for k in rec}
    print_warning(rec)
    if args.json:
        print_json({**rec, "units": unit})
    else:
        absent = absent_keys(rec["model"])
        for k, v in rec.items():  # 10 significant digits, as curve, cycle and fit (no 0.49999999999999994)
            if k == "warning" and not v:  # an empty warning is not printed
                continue
            if k in absent:
                continue
            text = f"{v:.10g}" if isinstance(v, float) else str(v)
            print(f"{k:22s} {text:24s} {'' if unit[k] == '1' else unit[k]}".rstrip())
    return 0
