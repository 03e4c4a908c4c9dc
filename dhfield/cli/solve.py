"""``dhfield solve``: the self-consistent adhesive BEM pull-off of one (beta0, mu) case."""
from __future__ import annotations

import contextlib
import math
import sys

from ..core.progress import SolveProgress, SolveTimeLimit
from ._common import (add_model_arguments, add_physical_arguments, command_threads, contact_parameters_from_args,
                      print_json)

#: Exit status when a state of the path did not converge (the result is still printed/written, flagged).
EXIT_UNCONVERGED = 3
#: Exit status when the path converged but the grid does not resolve the cohesive zone
#: (``resolved = false``: the pull-off is not an answer; refine --n).
EXIT_UNRESOLVED = 4
#: Exit status when the case cannot be resolved within the memory or time available (or the given
#: --n is far too coarse for it): one line, before solving, with the N it needs and the analytic value.
EXIT_UNRESOLVABLE = 5
#: Exit status when the solve ran past --max-seconds and was stopped: one line with what was reached
#: (states, time, the lowest load on the answer's grid, not a pull-off) and the analytic value.
EXIT_TIME_LIMIT = 6

def check_solve_memory(n) -> None:
    """Refuse an N x N adhesive BEM solve that would not fit in memory, before anything is computed.

    The library's own check (:func:`dhfield.analysis.bem_start.check_grid_memory`, which every BEM
    route also makes before it allocates), made first so that a bad ``--n`` fails at once.
    Raises ValueError naming ``n``, the estimate and the limit.
    """
    from ..analysis.bem_start import check_grid_memory

    if isinstance(n, int) and not isinstance(n, bool) and n > 0:
        check_grid_memory(n)


_EPILOG = (f"exit status: 0 success, converged and resolved (a note on stderr if states beyond the pull-off "
           f"did not converge); 2 invalid input (one line on stderr); {EXIT_UNCONVERGED} a state of the path "
           "up to the pull-off did not converge; "
           f"{EXIT_UNRESOLVED} converged but unresolved: the grid is too coarse for the cohesive zone, the "
           "pull-off is not an answer (increase --n).  In cases 3 and 4 one line on stderr names the "
           "parameters, and the result is still printed and written with converged / resolved = false.  "
           f"{EXIT_UNRESOLVABLE} the case cannot be resolved within the memory or time available, or --n is "
           "far too coarse for it (one line, before solving: the n it needs, its estimated memory and time, "
           "and the analytic W* to use instead, and in N for SI input); "
           f"{EXIT_TIME_LIMIT} stopped at --max-seconds (one line: what was reached, not an answer, and the "
           "analytic value).  Progress: one line per state on stderr, starting 'dhfield: progress:', on a "
           "terminal or not (--quiet: none).")


def add_parser(sub) -> None:
    p = sub.add_parser("solve", help="self-consistent adhesive BEM (Dugdale) pull-off of the elliptical contact",
                       description="Pull-off of the adhesive elliptical contact (beta0, mu) from the self-"
                                   "consistent boundary-element solver: under load control (the default) the "
                                   "minimum of the force along the unloading path, under --control displacement "
                                   "the jump.  Free-boundary DC-FFT grid of N x N cells "
                                   "(dhfield.bem.adhesive_pull_off); W* in the normalisation of Eq. (34), "
                                   "semi-axes in c_r (Eq. 32) from the second moments of the contact and "
                                   "adhesive masks.  The result says whether the path converged and whether the "
                                   "grid resolves the cohesive zone; one progress line per state goes to "
                                   "stderr (with its load in the result's units, W* or N, the elapsed time and "
                                   "an ETA), on a terminal or not.  Inputs: --beta0 and --mu, or the physical inputs in SI units of "
                                   "'dhfield pulloff' (converted with dhfield.analysis.dimensional.contact_parameters); "
                                   "these add the force [N], the semi-axes and the approach [m] beside W*, a*, "
                                   "b*, c*, d*, delta*.  With --machine-stiffness: the pull-off under a "
                                   "machine spring, from the unloading branch sampled at prescribed adhesive "
                                   "force (dhfield.analysis.bem_spring).",
                       epilog=_EPILOG)
    add_model_arguments(p, required=False)   # or the SI inputs of add_physical_arguments (below)
    p.add_argument("--n", type=int, default=None,
                   help="cells per axis (even, >= 8; default: chosen from the Dugdale zone width and memory)")
    p.add_argument("--law", default="dugdale", choices=("dugdale", "exponential"),
                   help="traction law, sigma0 = mu and dgamma = 1 (default dugdale)")
    p.add_argument("--control", default="load", choices=("load", "displacement"),
                   help="load: minimum of the unloading force; displacement: the jump (default load)")
    p.add_argument("--machine-stiffness", type=float, default=None, metavar="K",
                   help="pull-off under a machine spring (control 'spring'), as in 'dhfield pulloff': K >= 0 in "
                        "N/m with physical inputs, K* (paper's units, dhfield.analysis.spring.stiffness_star) with "
                        "--beta0/--mu; 0 is load control.  The BEM's unloading branch is sampled at prescribed "
                        "adhesive force and the jump is the first minimum of the machine position on it "
                        "(dhfield.analysis.bem_spring); the same branch on a coarser grid gives the grid's error; "
                        "--out then holds the branch, --search does not apply")
    p.add_argument("--search", default=None, choices=("located", "bracket", "march", "predicted", "newton"),
                   help="load control: how the force minimum is found -- newton: the semismooth Newton solve "
                        "on the answer's grid and a check grid, the stated error from the two (the default of the "
                        "Dugdale law without --n); located: on coarser grids first, then 3-4 states on this one "
                        "(the default otherwise); bracket: from the analytic pull-off on this grid; march: unload "
                        "in uniform steps (slowest); predicted: lattice samples around GVG's pull-off on its own "
                        "domain (located's route at mu >= 7.5 on an automatic grid; with --n, that route refined)")
    p.add_argument("--max-seconds", type=float, default=None, metavar="S",
                   help="stop after the first state that ends past S seconds, say what was reached and exit "
                        f"{EXIT_TIME_LIMIT} (default: no limit).  Above the planner's own allowance "
                        "(dhfield.analysis.bem_start.DEFAULT_MAX_SECONDS) it also lets the automatic grid take a case "
                        "estimated to need that long")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.add_argument("--threads", type=int, default=None,
                   help="FFTW threads (default $DHFIELD_THREADS, else the CPUs available, at most 4)")
    p.add_argument("--out", default=None, help="netCDF file for the pull-off fields and the path")
    p.add_argument("--json", action="store_true", help="print one JSON object (with a 'units' entry)")
    p.add_argument("--plot", metavar="FILE.png", default=None,
                   help="figure of the pull-off: contact and adhesive-zone map with the fitted ellipses, the "
                        "pressure, the load-approach path (PNG, with an .svg and a .pdf beside it); SI axes "
                        "with physical inputs")
    add_physical_arguments(p)
    p.set_defaults(func=run)


def _record(res) -> dict:
    """The solve record: the BEM's pull-off record, JSON-ready (the keys of the one pull-off record)."""
    from ..bem.pull_off import pull_off_summary

    return pull_off_summary(res)


#: Units of the solve record's keys that :mod:`dhfield.core.schema` does not list.
_LOCAL_UNITS = {"n": "1", "W_star_error": "1", "residual": "1", "elapsed": "s", "resolved": "1", "n_steps": "1",
                "iterations": "1", "converged": "1", "half_width_x": "1", "half_width_y": "1"}


def _units(rec, si_keys=()) -> dict:
    """key -> unit string of every numeric entry of the record ("1": dimensionless, paper's units;
    the keys ``si_keys`` in their SI unit of :mod:`dhfield.core.schema`)."""
    from ..core.schema import units

    out = {}
    for k, v in rec.items():
        if isinstance(v, (bool, int, float)) and not isinstance(v, str):
            local = _LOCAL_UNITS.get(k, _SPRING_UNITS.get(k))
            out[k] = local if local is not None else units(k, nondimensional=k not in si_keys)
    return out


# --------------------------------------------------------------------------- --machine-stiffness
#: Units of the keys of the spring record that :func:`_units` cannot take from the schema.
_SPRING_UNITS = {"machine_stiffness_star": "1", "separation_delta_star": "1", "in_contact": "1",
                 "branch_states": "1", "branch_complete": "1", "failures": "1"}


def _check_spring_arguments(args, params) -> None:
    """Refuse what does not go with --machine-stiffness (one line, exit 2), before solving."""
    from ..analysis.spring import check_machine_stiffness

    check_machine_stiffness("machine-stiffness", args.machine_stiffness)
    if args.control != "load":
        raise ValueError("control goes with no machine spring; --machine-stiffness sets the machine itself")
    if args.search is not None:
        raise ValueError("search applies to the load-control pull-off; with --machine-stiffness the whole "
                         "unloading branch is sampled (leave --search out)")
    if args.plot is not None:
        raise ValueError("plot draws the fields of a pull-off state; with --machine-stiffness use "
                         "'dhfield cycle --model bem --plot' for the branch and both jumps")


def _stiffness_star(args, params) -> float:
    """K* in the paper's units: --machine-stiffness itself, or from N/m with the contact's scales."""
    if params is None:
        return float(args.machine_stiffness)
    from ..analysis.spring import stiffness_star

    # the BEM's load normalisation is that of beta0 (Eq. 34): the contact's own sin(theta_skew)
    return float(stiffness_star(args.machine_stiffness, params.effective_radius, params.reduced_modulus,
                                params.work_of_adhesion, params.sin_skew))


def spring_record(branch, k_star, params=None, coarse=None) -> dict:
    """The solve record of the BEM pull-off under a spring of stiffness K* (paper's units; SI with params).

    ``coarse``: the same branch on a coarser grid (:func:`dhfield.analysis.bem_spring.coarse_branch`),
    for the grid's error; None: no estimate (not resolved).  Keys: beta0, mu, n, law, control
    ('spring'), machine_stiffness_star, W_star, W_star_error (the fit's error plus the grid's,
    :func:`dhfield.analysis.bem_spring.spring_pull_off`; inf when not resolved), delta_star,
    separation_delta_star (the force-free approach the contact jumps to, delta* + W*/K*), in_contact
    (the jump starts from a contact state), converged (no state failed among the samples the jump is
    fitted on), resolved, note, branch_states, branch_complete, failures, elapsed (both branches); with
    ``params``, the SI values (machine_stiffness [N/m], force [N], approach and separation_approach
    [m]) and the SI inputs.
    """
    import numpy as np

    from ..analysis.bem_spring import spring_pull_off

    po = spring_pull_off(branch, k_star, coarse)     # the BEM's PullOff, spring group filled, route-checked
    w, d = float(po.W_star), float(po.delta_star)
    sep = float(po.separation_delta_star)  # Delta* = delta* + W*/K*
    rec = {"beta0": branch.beta0, "mu": branch.mu, "n": branch.n, "law": po.law, "control": "spring",
           "machine_stiffness_star": float(k_star), "W_star": w, "W_star_error": float(po.W_star_error),
           "delta_star": d, "separation_delta_star": sep, "in_contact": not bool(po.on_separated_branch),
           "converged": bool(po.converged), "resolved": bool(po.resolved), "note": str(po.note),
           "branch_states": int(np.size(branch.adhesive_force)),
           "branch_complete": bool(branch.complete), "failures": int(branch.failures),
           "elapsed": float(branch.elapsed) + (0.0 if coarse is None else float(coarse.elapsed))}
    if params is not None:
        from ..io.solution import SI_INPUT_KEYS

        au = float(params.approach_unit)
        rec.update(machine_stiffness=float(k_star * float(params.load_unit) / au),  # the inverse of K*
                   force=w * float(params.load_unit), approach=d * au, separation_approach=sep * au)
        rec.update({k: float(getattr(params, k)) for k in SI_INPUT_KEYS})
    return rec


def _spring_dataset(branch, rec, params):
    """netCDF Dataset of the spring pull-off: the branch per state, the jump, the spring (attributes)."""
    import numpy as np
    import xarray as xr

    from ..io import cf, provenance_attrs
    from ..io.solution import SI_INPUT_KEYS

    k = rec["machine_stiffness_star"]
    dims = ("step",)
    q = "per state of the unloading branch (prescribed adhesive force)"
    w, d = np.asarray(branch.W_star, float), np.asarray(branch.delta_star, float)
    data = {"W_star_branch": cf.variable("W_star", dims, w, nondimensional=True, qualifier=q),
            "delta_star_branch": cf.variable("delta_star", dims, d, nondimensional=True, qualifier=q),
            "in_contact_branch": (dims, np.asarray(branch.in_contact, dtype=np.int8),
                                  {"long_name": "state has contact cells, " + q,
                                   "flag_values": np.arange(2, dtype=np.int8), "flag_meanings": "false true"})}
    if k > 0:
        data["machine_displacement_branch"] = cf.variable("machine_displacement", dims, d + w / k,
                                                          nondimensional=True, qualifier=q)
    at = "BEM at the jump out under the machine spring"
    data["W_star_pull_off"] = cf.variable("W_star", (), rec["W_star"], nondimensional=True, qualifier=at)
    data["W_star_error_pull_off"] = ((), float(rec["W_star_error"]),
                                     {"long_name": "error estimate of W* at the jump out (the fit's plus the grid's, "
                                                   "from a coarser grid)", "units": "1"})
    data["delta_star_pull_off"] = cf.variable("delta_star", (), rec["delta_star"], nondimensional=True,
                                              qualifier=at)
    data["machine_stiffness"] = cf.variable("machine_stiffness", (), k, nondimensional=True)
    data["resolved"] = ((), np.int8(rec["resolved"]),
                        {"long_name": "the jump out is bracketed, fitted and resolved by the grid (false: not an "
                                      "answer)",
                         "flag_values": np.arange(2, dtype=np.int8), "flag_meanings": "false true"})
    if params is not None:
        data["force_pull_off"] = cf.variable("force", (), rec["force"], qualifier=at)
        data["approach_pull_off"] = cf.variable("approach", (), rec["approach"], qualifier=at)
        data["separation_approach"] = cf.variable("separation_approach", (), rec["separation_approach"])
        data["machine_stiffness_si"] = cf.variable("machine_stiffness", (), rec["machine_stiffness"],
                                                   quantity="machine_stiffness")
        data["force_branch"] = cf.variable("force", dims, w * float(params.load_unit), qualifier=q)
        data["approach_branch"] = cf.variable("approach", dims, d * float(params.approach_unit), qualifier=q)
        for key in SI_INPUT_KEYS:
            data[key] = cf.variable(key, (), rec[key])
    ds = xr.Dataset(data, coords={"step": ("step", np.arange(w.size, dtype=np.int32),
                                           {"long_name": "state of the branch, in unloading order", "units": "1"})})
    ds.attrs.update(provenance_attrs(
        "dhfield: BEM pull-off of the adhesive elliptical contact under a machine spring (DC-FFT, free boundary)",
        beta0=rec["beta0"], mu=rec["mu"], n=rec["n"], law=rec["law"], control="spring",
        machine_stiffness_star=k, machine_stiffness=rec.get("machine_stiffness")))
    ds.attrs.update({"resolved": int(rec["resolved"]), "converged": int(rec["converged"]),
                     "branch_complete": int(rec["branch_complete"]),
                     "n_failures": rec["failures"], "elapsed_seconds": rec["elapsed"]})
    if params is not None:
        ds.attrs.update({"length_unit_m": float(params.length_unit), "approach_unit_m": float(params.approach_unit),
                         "load_unit_N": float(params.load_unit)})
    return cf.finalize(ds)


def _run_spring(args, params, plan, where, progress) -> int:
    """``solve --machine-stiffness``: the BEM's unloading branch and the jump under the spring."""
    from ..analysis.bem_spring import bem_pull_off_under_spring, bem_unloading_branch, coarse_branch

    if args.n is None and not plan.affordable:
        print(f"dhfield: solve refused: {plan.message()}{_in_newtons(plan.analytic_W_star, params)}",
              file=sys.stderr)
        return EXIT_UNRESOLVABLE
    k_star = plan.machine_stiffness_star
    if progress:
        print(f"dhfield: solving {where} (the unloading branch at prescribed adhesive force, K* = {k_star:.4g})",
              file=sys.stderr, flush=True)
    try:
        branch = bem_unloading_branch(beta0=args.beta0, mu=args.mu, n=plan.n, law=args.law, threads=args.threads)
    except RuntimeError as exc:  # no converged state to start from
        print(f"dhfield: solve did not converge for {where}: {' '.join(str(exc).split())}", file=sys.stderr)
        return EXIT_UNCONVERGED
    if progress:
        print(f"dhfield: solving {where} on a coarser grid (the grid's error)", file=sys.stderr, flush=True)
    fit = bem_pull_off_under_spring(branch, k_star)   # the jump on this grid alone: not bracketed, no answer
    coarse = coarse_branch(branch, threads=args.threads) if bool(fit.resolved) else None
    rec = spring_record(branch, k_star, params, coarse)
    rec["law"] = args.law
    if args.out is not None:
        from ..io import write_netcdf

        write_netcdf(_spring_dataset(branch, rec, params), args.out)
    if args.json:
        si_keys = tuple(k for k in ("machine_stiffness", "force", "approach", "separation_approach",
                                    *_si_input_keys()) if k in rec)
        print_json({**rec, "units": _units(rec, si_keys=si_keys)})
    else:
        err = (f" (stated error {rec['W_star_error']:.2g})"
               if math.isfinite(rec["W_star_error"]) else " (no error bound: not resolved)")
        print(f"beta0 = {rec['beta0']:g}, mu = {rec['mu']:g}, N = {rec['n']}, {args.law}, machine spring "
              f"K* = {k_star:.6g}")
        print(f"W* = {rec['W_star']:.6f}{err}  delta* = {rec['delta_star']:.5f}  after the jump: delta* = "
              f"{rec['separation_delta_star']:.5f}, W* = 0  (jump {'from contact' if rec['in_contact'] else 'from the separated branch'})")
        print(f"converged = {rec['converged']}  resolved = {rec['resolved']}  branch states = "
              f"{rec['branch_states']}  complete = "
              f"{rec['branch_complete']}  unconverged = {rec['failures']}  ({rec['elapsed']:.1f} s)")
        if params is not None:
            print(f"force = {rec['force']:.6g} N  approach = {rec['approach']:.5g} m  after the jump: approach = "
                  f"{rec['separation_approach']:.5g} m  (K = {rec['machine_stiffness']:.6g} N/m)")
        if args.out is not None:
            print(f"wrote {args.out}")
    if not rec["converged"]:
        print(f"dhfield: solve did not converge for {where}: {rec['failures']} state(s) of the branch did not "
              "converge, some among the samples the jump out is fitted on (converged = false)", file=sys.stderr)
        return EXIT_UNCONVERGED
    if not rec["resolved"]:
        why = rec["note"].split("unresolved: ", 1)[-1]
        print(f"dhfield: solve is unresolved for {where}: {why} (resolved = false), so W* is not an answer; "
              "increase --n", file=sys.stderr)
        return EXIT_UNRESOLVED
    if rec["failures"]:
        print(f"dhfield: note: {rec['failures']} state(s) of the branch away from the jump out did not converge "
              f"for {where} (left out of the samples; the jump's fit does not use them)", file=sys.stderr)
    return 0


def _si_input_keys():
    from ..io.solution import SI_INPUT_KEYS

    return SI_INPUT_KEYS


# --------------------------------------------------------------------------- SI inputs and outputs, --plot
def _physical_inputs(args):
    """ContactParameters of the SI flags (beta0, mu then set on ``args``), or None for --beta0/--mu."""
    params = contact_parameters_from_args(args)
    if params is not None:
        args.beta0, args.mu = float(params.beta0), float(params.mu)
    return params


def _check_plot(args) -> None:
    """Refuse a bad --plot path (and its .svg/.pdf) before solving."""
    if getattr(args, "plot", None) is None:
        return
    from pathlib import Path

    from ..io import check_writable, validate_output_path

    validate_output_path(args.plot, (".png",), "plot")
    for suffix in (".svg", ".pdf"):
        check_writable(Path(args.plot).with_suffix(suffix), "plot")


def _print_si(si) -> None:
    """The SI line(s) of the text output."""
    print(f"force = {si['force']:.6g} N  a = {si['semi_major']:.5g} m  b = {si['semi_minor']:.5g} m  "
          f"c = {si['adhesive_semi_major']:.5g} m  d = {si['adhesive_semi_minor']:.5g} m  "
          f"approach = {si['approach']:.5g} m")
    print(f"(E* = {si['reduced_modulus']:.6g} Pa, R' = {si['r_major']:.6g} m, R'' = {si['r_minor']:.6g} m, "
          f"R = {si['effective_radius']:.6g} m, dgamma = {si['work_of_adhesion']:.6g} J/m^2, "
          f"sigma0 = {si['max_adhesive_stress']:.6g} Pa)")


class _NoLines:
    """A stream that drops what is written (--quiet: the time limit without the lines)."""

    def write(self, text):
        return len(text)

    def flush(self):
        pass


def _progress(args, params, plan, route, header, answer=None):
    """The reporter of every state (:class:`dhfield.core.progress.SolveProgress`), in W* or N."""
    from ..core.geometry import sin_skew_angle

    # a state's load is in R = E* = dgamma = 1: W* = load sin(theta_skew)/(2 pi) (Eq. 34), times the load unit in N
    scale = float(sin_skew_angle(args.beta0)) / (2.0 * math.pi)
    if params is not None:
        scale *= float(params.load_unit)
    return SolveProgress(scale, "W*" if params is None else "N", (plan.n, plan.ny) if answer is None else answer, route,
                         max_seconds=args.max_seconds, stream=_NoLines() if args.quiet else None, header=header)


def _planner_allowance(max_seconds):
    """The time the grid planner may allow: --max-seconds where above its default, else None (the default).

    The planner's estimate is an upper one (the sphere at mu = 1: ~24 s estimated, 0.5 s taken), so a
    shorter limit stops the solve when reached instead of refusing it on the estimate.
    """
    from ..analysis.bem_start import DEFAULT_MAX_SECONDS

    if max_seconds is None:
        return None
    if not (math.isfinite(max_seconds) and max_seconds > 0):
        raise ValueError(f"max-seconds must be a positive number of seconds; got {max_seconds!r}")
    return float(max_seconds) if max_seconds > DEFAULT_MAX_SECONDS else None


def _in_newtons(w_star, params) -> str:
    """The analytic W* of a refusal in newtons, for SI input (Eq. 34); '' otherwise."""
    if params is None or not math.isfinite(w_star):
        return ""
    return (f"; for these SI inputs that is a force of {w_star * float(params.load_unit):.6g} N "
            "(W = W* 2 pi R dgamma/sin theta_skew, Eq. 34)")


@contextlib.contextmanager
def _time_limit(seconds, reporter):
    """Raise :class:`dhfield.core.progress.SolveTimeLimit` ``seconds`` from now, also within a state.

    The reporter stops the solve after a state that ends past the limit; where the platform has
    SIGALRM (and this is the main thread) an interval timer stops it within a state too.
    """
    import signal
    import threading

    if seconds is None or not hasattr(signal, "setitimer") or threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum, frame):  # noqa: ARG001 - signal handler signature
        raise SolveTimeLimit(reporter.reached())

    old = signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, float(seconds))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, old)


def run(args) -> int:
    from ..bem import adhesive_pull_off
    from ..io import check_writable

    params = _physical_inputs(args)
    if args.out is not None:
        check_writable(args.out)
    _check_plot(args)
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"threads must be an integer >= 1; got {args.threads}")
    args.threads = command_threads(args.threads)
    from ..analysis.bem_start import (AdhesiveOptions, UnresolvableCaseError, plan_grid, takes_newton_route,
                                      takes_predicted_route)
    from ..bem.branch import state_reporter

    check_solve_memory(args.n)
    k_star = None
    if args.machine_stiffness is not None:
        _check_spring_arguments(args, params)
        k_star = _stiffness_star(args, params)
    # the route: the Newton route by default where it applies (takes_newton_route), else the path routes
    search = args.search or ("newton" if args.machine_stiffness is None and takes_newton_route(
        law=args.law, control=args.control, n=args.n) else "located")
    # the plan of the domain the solve uses: the spring samples the unloading branch, never the predicted route
    predicted = args.machine_stiffness is None and takes_predicted_route(
        beta0=args.beta0, mu=args.mu, n=args.n, law=args.law, control=args.control, search=search)
    allowance = _planner_allowance(args.max_seconds)
    plan = plan_grid(mu=args.mu, beta0=args.beta0, n=args.n, law=args.law,
                     predicted=None if search == "newton" else predicted,    # (the Newton route's own plan)
                     control=args.control if k_star is None else "spring", machine_stiffness=k_star,
                     **({} if allowance is None else {"max_seconds": allowance}))
    if args.n is not None and plan.too_coarse:   # far too coarse: refused before minutes of unconverged states
        print(f"dhfield: solve refused: {plan.message()}{_in_newtons(plan.analytic_W_star, params)}",
              file=sys.stderr)
        return EXIT_UNRESOLVABLE
    cells = f"{plan.n}" + (f" x {plan.ny}" if plan.ny != plan.n else "")    # nx x ny: slender automatic grids
    control = args.control if args.machine_stiffness is None else "spring"
    where = f"beta0={args.beta0:g}, mu={args.mu:g}, n={cells}, law={args.law}, control={control}"
    route = ("spring" if args.machine_stiffness is not None else "displacement" if args.control == "displacement"
             else "predicted" if predicted else search)
    if args.n is None and not plan.affordable:   # the automatic grid exceeds the memory or the time allowed
        print(f"dhfield: solve refused: {plan.message()}{_in_newtons(plan.analytic_W_star, params)}",
              file=sys.stderr)
        return EXIT_UNRESOLVABLE
    answer = (plan.n, plan.ny)
    if route == "newton":     # the route's own grids: the check grid, then the answer's (before any refinement)
        from ..analysis.bem_start import newton_grids, newton_problem

        _, answer = newton_grids(newton_problem(beta0=args.beta0, mu=args.mu, n=plan.n, ny=plan.ny))
    answer_cells = f"{answer[0]}" + (f" x {answer[1]}" if answer[1] != answer[0] else "")
    reporter = _progress(args, params, plan, route, f"solving {where} (states of coarser grids first where the "
                         f"route has them, then the answer's {answer_cells} grid)", answer)
    try:
        with state_reporter(reporter), _time_limit(args.max_seconds, reporter):
            if args.machine_stiffness is not None:
                return _run_spring(args, params, plan, where, False)
            extra = {} if allowance is None else {"options": AdhesiveOptions(max_seconds=allowance)}
            res = adhesive_pull_off(mu=args.mu, beta0=args.beta0, n=args.n, law=args.law, control=args.control,
                                    threads=args.threads, progress=False, search=search, **extra)
    except SolveTimeLimit as exc:
        print(f"dhfield: solve stopped at --max-seconds {args.max_seconds:g} s for {where}: {exc.reached} (not a "
              f"pull-off: the solve had not finished; nothing written); {plan.advice()}"
              f"{_in_newtons(plan.analytic_W_star, params)}", file=sys.stderr)
        return EXIT_TIME_LIMIT
    except UnresolvableCaseError as exc:
        print(f"dhfield: solve refused: {exc}{_in_newtons(exc.analytic_W_star, params)}", file=sys.stderr)
        return EXIT_UNRESOLVABLE
    except RuntimeError as exc:  # the solver found no converged state to report
        print(f"dhfield: solve did not converge for {where}: {' '.join(str(exc).split())}", file=sys.stderr)
        return EXIT_UNCONVERGED
    rec = _record(res)
    # the answer's grid: the planned one, or finer where the route refined it (the Newton route)
    grid = res.path.pull_off_state.grid if res.path is not None else None
    solved = cells if grid is None else f"{grid.nx}" + (f" x {grid.ny}" if grid.ny != grid.nx else "")
    where = where.replace(f"n={cells},", f"n={solved},")
    si = {}
    if params is not None:
        from ..io.solution import pull_off_si

        si = pull_off_si(res, params)
    from ..io import atomic_files

    with atomic_files():   # --out and --plot's three files as one set: all moved into place, or none
        if args.out is not None:
            from ..io.solution import write_solution

            write_solution(res, args.out, params=params)
        if args.plot is not None:
            from ..io.solve_plot import write_solve_plot

            write_solve_plot(res, args.plot, params=params)
    if args.json:
        rec = {**rec, **si}
        print_json({**rec, "units": _units(rec, si_keys=tuple(si))})
    else:
        print(f"beta0 = {res.beta0:g}, mu = {res.mu:g}, N = {solved}, {res.law}, {res.control} control")
        # the stated error: the search's (load control) or the fold fit's (displacement control) plus the
        # grid's (W_star_error); infinite when the answer is not resolved
        err = (f" (stated error {res.W_star_error:.2g})" if math.isfinite(res.W_star_error)
               else " (no error bound: not resolved)")
        print(f"W* = {res.W_star:.6f}{err}  a* = {res.a_star:.5f}  b* = {res.b_star:.5f}  c* = {res.c_star:.5f}  "
              f"d* = {res.d_star:.5f}")
        print(f"b/a = {res.ellipticity:.5f}  d/c = {res.adhesive_ellipticity:.5f}  delta* = {res.delta_star:.5f}")
        print(f"converged = {res.converged}  resolved = {rec['resolved']}  states = {res.n_steps}  "
              f"GMRES iterations = {res.iterations}  search = {res.search}  ({res.elapsed:.1f} s)")
        if si:
            _print_si(si)
        if args.out is not None:
            print(f"wrote {args.out}")
        if args.plot is not None:
            print(f"wrote {args.plot}, {args.plot[:-4]}.svg and {args.plot[:-4]}.pdf")
    if not res.converged:
        unconverged = f"{len(res.failures)} unconverged state(s), worst residual {res.worst_residual:.3g}"
        why = "; ".join(filter(None, (unconverged if res.failures else "", res.note)))
        print(f"dhfield: solve did not converge for {where}: {why}", file=sys.stderr)
        return EXIT_UNCONVERGED
    if not rec["resolved"]:
        print(f"dhfield: solve is unresolved for {where}: the grid does not resolve the cohesive zone "
              "(resolved = false), so W* is not an answer; increase --n", file=sys.stderr)
        return EXIT_UNRESOLVED
    if res.note:
        print(f"dhfield: note: {where}: {res.note}", file=sys.stderr)
    if res.failures:
        print(f"dhfield: note: {len(res.failures)} state(s) beyond the pull-off did not converge for {where} "
              "(the pull-off is not affected; listed under failures)", file=sys.stderr)
    return 0
