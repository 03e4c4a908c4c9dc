"""``dhfield pulloff``."""
from __future__ import annotations

from ._common import add_model_arguments, compare_record, model_names, print_json


def add_parser(sub) -> None:
    p = sub.add_parser("pulloff", help="pull-off force W*max of the elliptical DH model")
    add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="load control (default) or displacement control")
    p.add_argument("--model", choices=model_names(), default="dh-elliptic",
                   help="comparison model (default: dh-elliptic, the paper's model)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def _pull_off_record(args) -> dict:
    from ..model import pull_off

    if getattr(args, "model", "dh-elliptic") != "dh-elliptic":
        return compare_record(args.model, args)
    r = pull_off(args.mu, args.beta0, control=args.control)
    return {"model": "dh-elliptic", "beta0": float(r.beta0), "mu": float(r.mu), "control": r.control,
            "W_star": float(r.W_star), "a_star": float(r.a_star), "c_star": float(r.c_star),
            "v": float(r.v), "delta_star": float(r.delta_star),
            "at_zero_contact": bool(r.at_zero_contact)}


def run(args) -> int:
    rec = _pull_off_record(args)
    if args.json:
        print_json(rec)
    else:
        for k, v in rec.items():
            print(f"{k:16s} {v}")
    return 0
