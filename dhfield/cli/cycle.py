"""``dhfield cycle``: the loading-unloading cycle of a model under a machine spring."""
from __future__ import annotations

import argparse

from ._common import UsageError, add_model_arguments, add_physical_arguments, contact_parameters_from_args
from ._common import command_threads, print_json, print_warning
from ._common import validity_epilog as _epilog
from .solve import EXIT_UNCONVERGED, EXIT_UNRESOLVABLE, EXIT_UNRESOLVED  # --model bem: those of solve


def add_parser(sub) -> None:
    from ..analysis.compare import CURVE_MODEL_NAMES, DEFAULT_MODEL

    p = sub.add_parser("cycle", help="loading-unloading cycle: jump in, jump out, energy lost per cycle",
                       description="Approach from separation, jump into contact, unload to the jump out, under a "
                       "machine spring of stiffness K (default: a rigid machine, i.e. displacement control).  "
                       "Inputs: --beta0 and --mu (nondimensional; K* in the paper's units, dW*/d(delta*) = -K* "
                       "at the jump) or physical inputs in SI units (K in N/m).  The energy lost is printed to the digits "
                       "its uncertainty supports: energy_lost_uncertainty = energy_lost_error (quadrature) + "
                       "energy_lost_convention, which for a model without a force out of contact (the DH models, "
                       "md-elliptic, dmt) is the spread between ending the force-free approach at the contact "
                       "curve's end (the convention used) and where the central gap reaches the Dugdale range "
                       "(delta* = -1/mu, the rule of md and the BEM); --json keeps every digit.  See dhfield.analysis.spring.",
                       epilog=_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    add_model_arguments(p, required=False)
    p.add_argument("--model", choices=(*CURVE_MODEL_NAMES, "bem"), default=DEFAULT_MODEL,
                   help="model (default: md-elliptic, the recommended one; dh-elliptic is the paper's); "
                   "dh-elliptic-jkr-beta has no curve; bem: the "
                   "self-consistent adhesive BEM (Dugdale law) on an N x N grid, its unloading branch sampled at "
                   "prescribed adhesive force (dhfield.analysis.bem_spring.bem_loading_cycle; exit 3 if no state "
                   "converges, 4 if a jump is not resolved on the branch)")
    p.add_argument("--machine-stiffness", type=float, default=None, metavar="K",
                   help="machine stiffness, >= 0: N/m with physical inputs, K* (paper's units) with --beta0/--mu; "
                   "0 is load control; default: a rigid machine (displacement control)")
    p.add_argument("--n", type=int, default=None,
                   help="--model bem: cells per axis (even, >= 8; default: chosen from the Dugdale zone width "
                   "and memory, as 'dhfield solve')")
    p.add_argument("--threads", type=int, default=None,
                   help="--model bem: FFTW threads (default $DHFIELD_THREADS, else the CPUs available, at most 4)")
    p.add_argument("--json", action="store_true", help="print one JSON object (with a 'units' entry)")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="draw force against approach with both jumps and the energy lost shaded")
    add_physical_arguments(p)
    p.set_defaults(func=run)


def _print_record(rec, as_json) -> None:
    """The cycle record as one JSON object with its units, or one ``key value unit`` line per entry."""
    import math

    from ..analysis import spring
    from ..io.cycle import round_to_uncertainty

    units = {k: _BEM_UNITS.get(k, spring.CYCLE_UNITS.get(k, "1")) for k in rec
             if k not in ("model", "geometry", "jump_in_rule", "warning")}
    if as_json:
        print_json({**rec, "units": units})
        return
    for k, v in rec.items():
        if k == "warning":
            continue
        if k in _ROUNDED and isinstance(v, float):
            text = round_to_uncertainty(v, rec.get(_ROUNDED[k], float("nan")))
        elif k in _ROUNDED.values() or k in _UNCERTAINTY_PARTS:
            text = f"{v:.2g}" if isinstance(v, float) and math.isfinite(v) else str(v)
        else:
            text = f"{v:.10g}" if isinstance(v, float) and math.isfinite(v) else str(v)
        u = units.get(k, "1")
        print(f"{k:28s} {text:24s} {'' if u == '1' else u}".rstrip())


#: Entries the text output rounds to the digits their uncertainty supports: key -> key of that uncertainty
#: (the quadrature error plus, for a model without a force out of contact, the spread between the two
#: jump-in conventions; dhfield.analysis.spring).
_ROUNDED = {"energy_lost_star": "energy_lost_uncertainty_star", "energy_lost": "energy_lost_uncertainty"}
#: The parts of those uncertainties, printed to two significant digits.
_UNCERTAINTY_PARTS = ("energy_lost_error_star", "energy_lost_convention_star", "energy_lost_error",
                      "energy_lost_convention")


def run(args) -> int:
    from ..analysis import spring
    from ..io import validate_output_path

    if args.plot is not None:
        validate_output_path(args.plot, (".png",), "plot")
        from ..io.figures import figure_paths

        figure_paths(args.plot)  # the .svg and .pdf beside it checked before computing
    if args.machine_stiffness is not None:
        spring.check_machine_stiffness("machine-stiffness", args.machine_stiffness)
    params = contact_parameters_from_args(args)
    if args.model == "bem":
        return _run_bem(args, params)
    if args.n is not None or args.threads is not None:
        raise UsageError("--n and --threads go with --model bem")
    if params is None:
        rec = spring.loading_cycle(args.model, mu=args.mu, beta0=args.beta0, machine_stiffness=args.machine_stiffness)
        k_star, mu, beta0 = args.machine_stiffness, args.mu, args.beta0
    else:
        rec = spring.loading_cycle_si(params, args.machine_stiffness, model=args.model)
        k_star, mu, beta0 = (None if args.machine_stiffness is None else rec["machine_stiffness_star"],
                             params.mu, params.beta0)
    print_warning(rec)
    _print_record(rec, args.json)
    if args.plot is not None:
        from ..io.cycle import write_cycle_plot

        data = spring.cycle_path(args.model, mu=mu, beta0=beta0, machine_stiffness=k_star)
        data["record"].update(rec)
        if params is None:
            write_cycle_plot(data, args.plot)
        else:
            from ..core.units import load_unit

            force = float(load_unit(params.effective_radius, params.work_of_adhesion, rec["sin_skew"]))
            write_cycle_plot(data, args.plot, force_unit=force, approach_unit=float(params.approach_unit))
        if not args.json:   # the JSON stays one object
            print(f"wrote {args.plot}, {args.plot[:-4]}.svg and {args.plot[:-4]}.pdf")
    return 0


# --------------------------------------------------------------------------- --model bem
#: Units of the BEM cycle's keys that :data:`dhfield.analysis.spring.CYCLE_UNITS` does not list.
_BEM_UNITS = {"elapsed": "s", "jump_in_force_error": "N", "jump_out_force_error": "N"}
#: The BEM's jump-in rule (:func:`dhfield.analysis.bem_spring.bem_loading_cycle`).
_BEM_JUMP_IN_RULE = ("Dugdale law: force-free approach until the central gap reaches the range h0 = "
                     "dgamma/sigma0 (delta_s = -h0), then the jump at fixed machine position")


def bem_cycle_record(cyc, k_star, params=None) -> dict:
    """The cycle record of :func:`dhfield.analysis.bem_spring.bem_loading_cycle` (scalar K*), keys in the
    order of :func:`dhfield.analysis.spring.loading_cycle`'s, with the BEM's error estimates, its branch's
    diagnostics and, with ``params``, the SI values of :func:`dhfield.analysis.spring.loading_cycle_si`."""
    import numpy as np

    from ..analysis.spring import cycle_si_values
    from ..core.geometry import sin_skew_angle

    br = cyc["branch"]
    f = {k: float(np.asarray(v)) for k, v in cyc.items() if k not in ("branch", "resolved")}
    rec = {"model": "bem", "geometry": "circle" if br.beta0 == 1.0 else "ellipse", "beta0": br.beta0,
           "mu": br.mu, "sin_skew": float(sin_skew_angle(br.beta0)), "n": br.n,
           "machine_stiffness_star": float("inf") if k_star is None else float(k_star),
           "jump_in_rule": _BEM_JUMP_IN_RULE, "jump_in_start_delta_star": f["jump_in_start_delta_star"],
           "jump_in_W_star": f["jump_in_W_star"], "jump_in_W_star_error": f["jump_in_W_star_error"],
           "jump_in_delta_star": f["jump_in_delta_star"], "jump_out_W_star": f["jump_out_W_star"],
           "jump_out_W_star_error": f["jump_out_W_star_error"], "jump_out_delta_star": f["jump_out_delta_star"],
           "separation_delta_star": f["separation_delta_star"], "energy_lost_star": f["energy_lost_star"],
           "energy_lost_error_star": f["energy_lost_error_star"],
           # the Dugdale law's jump-in is physical: no convention to spread over
           "energy_lost_convention_star": 0.0, "energy_lost_uncertainty_star": f["energy_lost_error_star"],
           "resolved": bool(np.asarray(cyc["resolved"])),
           "branch_states": int(np.size(br.adhesive_force)), "branch_complete": bool(br.complete),
           "failures": int(br.failures), "elapsed": float(br.elapsed)}
    if params is not None:  # inverts Eqs. 33-34 with the contact's scales (its sin(theta_skew): the BEM's)
        force, approach = float(params.load_unit), float(params.approach_unit)
        rec.update({"machine_stiffness": rec["machine_stiffness_star"] * force / approach,
                    **cycle_si_values(rec, force=force, approach=approach)})
    rec["warning"] = ("" if rec["resolved"] else "a jump is not resolved on the sampled branch: the cycle is not "
                      "an answer (increase --n)")
    return rec


def bem_cycle_path(cyc, rec) -> dict:
    """The BEM cycle as the polylines of :func:`dhfield.analysis.spring.cycle_path`, from the branch's samples."""
    import numpy as np

    br = cyc["branch"]
    k = rec["machine_stiffness_star"]
    s = 1.0 if not np.isfinite(k) else k / (1.0 + k)
    x, w, d = np.sqrt(br.adhesive_force), br.W_star, br.delta_star
    x_o = float(np.sqrt(cyc["jump_out_adhesive_force"]))
    ds, dsep = rec["jump_in_start_delta_star"], rec["separation_delta_star"]
    d_o, w_o, d_i, w_i = (rec[key] for key in ("jump_out_delta_star", "jump_out_W_star", "jump_in_delta_star",
                                               "jump_in_W_star"))
    up = np.flatnonzero(x > x_o)
    up = up[np.argsort(x[up])]                                  # loading order, from the jump out up
    between = up[(s * d[up] + (1.0 - s) * w[up]) < s * ds]      # below the machine position of the landing
    loop_d = np.concatenate([[d_o], d[between], [d_i, ds, dsep, d_o]])
    loop_w = np.concatenate([[w_o], w[between], [w_i, 0.0, 0.0, w_o]])
    bd, bw = np.concatenate([[d_o], d[up]]), np.concatenate([[w_o], w[up]])
    lo = min(dsep, ds, float(np.min(bd))) if np.isfinite(dsep) else min(ds, float(np.min(bd)))
    return {"record": rec, "branch": (bd, bw), "approach": (np.array([lo - 0.2, ds]), np.zeros(2)),
            "jump_in": (np.array([ds, d_i]), np.array([0.0, w_i])),
            "jump_out": (np.array([d_o, dsep]), np.array([w_o, 0.0])), "loop": (loop_d, loop_w)}


def _run_bem(args, params) -> int:
    """``cycle --model bem``: the BEM's loading-unloading cycle under the machine spring."""
    import sys

    from ..analysis.bem_start import plan_grid
    from ..analysis.bem_spring import bem_loading_cycle

    mu, beta0 = (args.mu, args.beta0) if params is None else (float(params.mu), float(params.beta0))
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"threads must be an integer >= 1; got {args.threads}")
    args.threads = command_threads(args.threads)
    k = args.machine_stiffness
    if k is not None and k == 0:
        raise ValueError("machine-stiffness of a BEM cycle must be > 0 (0 is load control, which loses an "
                         "infinite energy per cycle); leave it out for a rigid machine")
    if k is not None and params is not None:
        from ..analysis.spring import stiffness_star

        k = float(stiffness_star(k, params.effective_radius, params.reduced_modulus, params.work_of_adhesion,
                                 params.sin_skew))
    from .solve import check_solve_memory

    check_solve_memory(args.n)
    # the cycle samples the unloading branch; its jump out is the displacement-control pull-off for a rigid
    # machine, else the spring's: the analytic value a refusal advises
    plan = plan_grid(mu=mu, beta0=beta0, n=args.n, predicted=False, control="displacement" if k is None else "spring",
                     machine_stiffness=k)
    where = f"beta0={beta0:g}, mu={mu:g}, n={plan.n}"
    if plan.too_coarse or (args.n is None and not plan.affordable):
        print(f"dhfield: cycle refused: {plan.message()}", file=sys.stderr)
        return EXIT_UNRESOLVABLE
    try:
        cyc = bem_loading_cycle(beta0=beta0, mu=mu, n=plan.n, machine_stiffness=k, threads=args.threads)
    except RuntimeError as exc:
        print(f"dhfield: cycle did not converge for {where}: {' '.join(str(exc).split())}", file=sys.stderr)
        return EXIT_UNCONVERGED
    rec = bem_cycle_record(cyc, k, params)
    if params is not None and args.machine_stiffness is not None:
        rec["machine_stiffness"] = float(args.machine_stiffness)   # exactly as given
    print_warning(rec)
    _print_record(rec, args.json)
    if args.plot is not None:
        from ..io.cycle import write_cycle_plot

        data = bem_cycle_path(cyc, rec)
        if params is None:
            write_cycle_plot(data, args.plot)
        else:
            write_cycle_plot(data, args.plot, force_unit=float(params.load_unit),
                             approach_unit=float(params.approach_unit))
        if not args.json:   # the JSON stays one object
            print(f"wrote {args.plot}, {args.plot[:-4]}.svg and {args.plot[:-4]}.pdf")
    if not rec["resolved"]:
        return EXIT_UNRESOLVED
    if rec["failures"]:
        print(f"dhfield: note: {rec['failures']} state(s) of the branch did not converge for {where} (left out "
              "of the samples)", file=sys.stderr)
    return 0
