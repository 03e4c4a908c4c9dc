"""``dhfield cycle``: the loading-unloading cycle of a model under a machine spring."""
from __future__ import annotations

import argparse

from ._common import UsageError, add_model_arguments, add_physical_arguments, contact_parameters_from_args
from ._common import print_json, print_warning
from ._common import validity_epilog as _epilog


def add_parser(sub) -> None:
    from ..compare import CURVE_MODEL_NAMES, DEFAULT_MODEL

    p = sub.add_parser("cycle", help="loading-unloading cycle: jump in, jump out, energy lost per cycle",
                       description="Approach from separation, jump into contact, unload to the jump out, under a "
                       "machine spring of stiffness K (default: a rigid machine, i.e. displacement control).  "
                       "Inputs: --beta0 and --mu (nondimensional; K* in the paper's units, dW*/d(delta*) = -K* "
                       "at the jump) or physical inputs in SI units (K in N/m).  See dhfield.compliance.",
                       epilog=_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    add_model_arguments(p, required=False)
    p.add_argument("--model", choices=CURVE_MODEL_NAMES, default=DEFAULT_MODEL,
                   help="model (default: md-elliptic, the recommended one; dh-elliptic is the paper's); "
                   "dh-elliptic-jkr-beta has no curve")
    p.add_argument("--machine-stiffness", type=float, default=None, metavar="K",
                   help="machine stiffness, >= 0: N/m with physical inputs, K* (paper's units) with --beta0/--mu; "
                   "0 is load control; default: a rigid machine (displacement control)")
    p.add_argument("--json", action="store_true", help="print one JSON object (with a 'units' entry)")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="draw force against approach with both jumps and the energy lost shaded")
    add_physical_arguments(p)
    p.set_defaults(func=run)


def run(args) -> int:
    import math

    from .. import compliance
    from ..io import validate_output_path

    if args.plot is not None:
        validate_output_path(args.plot, (".png",), "plot")
    if args.machine_stiffness is not None:
        compliance.check_machine_stiffness("machine-stiffness", args.machine_stiffness)
    params = contact_parameters_from_args(args)
    if params is None:
        rec = compliance.loading_cycle(args.model, args.mu, args.beta0, args.machine_stiffness)
        k_star, mu, beta0 = args.machine_stiffness, args.mu, args.beta0
    else:
        rec = compliance.loading_cycle_si(params, args.machine_stiffness, model=args.model)
        k_star, mu, beta0 = (None if args.machine_stiffness is None else rec["machine_stiffness_star"],
                             params.mu, params.beta0)
    print_warning(rec)
    units = {k: compliance.CYCLE_UNITS.get(k, "1") for k in rec
             if k not in ("model", "geometry", "jump_in_rule", "warning")}
    if args.json:
        print_json({**rec, "units": units})
    else:
        for k, v in rec.items():
            if k == "warning":
                continue
            text = f"{v:.10g}" if isinstance(v, float) and math.isfinite(v) else str(v)
            u = units.get(k, "1")
            print(f"{k:26s} {text:24s} {'' if u == '1' else u}".rstrip())
    if args.plot is not None:
        from ..io.cycle import write_cycle_plot

        data = compliance.cycle_path(args.model, mu, beta0, k_star)
        data["record"].update(rec)
        if params is None:
            write_cycle_plot(data, args.plot)
        else:
            from .._adhesion import load_unit

            force = float(load_unit(params.effective_radius, params.work_of_adhesion, rec["sin_skew"]))
            write_cycle_plot(data, args.plot, force_unit=force, approach_unit=float(params.approach_unit))
        print(f"wrote {args.plot}")
    return 0
