"""Shared pieces of the ``dhfield`` command line: parser class, JSON output, common options."""
from __future__ import annotations

import argparse
import contextlib
import json
import math

__all__ = ["OneLineParser", "UsageError", "print_json", "add_model_arguments", "model_names",
           "plain_record", "add_physical_arguments", "contact_parameters_from_args",
           "print_warning", "validity_epilog", "PHYSICAL_FLAGS", "OUTPUT_SUFFIXES", "check_output_argument", "thread_count",
           "max_threads", "termination_signals_as_exceptions"]


class UsageError(Exception):
    """A command-line usage error (reported in one line, exit status 2)."""


class OneLineParser(argparse.ArgumentParser):
    """argparse with usage errors reduced to one line and exit status 2."""

    def error(self, message):
        # main() already prints "dhfield: error: "; keep only the subcommand (if any) of the prog
        where = self.prog.partition(" ")[2]
        raise UsageError(f"{where}: {message}" if where else message)

    def _get_values(self, action, arg_strings):
        # argparse drops a '--' value, so "--beta0=--" (or "--beta0 --" for nargs="+") would give the
        # option an empty list where a number or a list of at least one value is expected
        given = " ".join(arg_strings)
        dashes = "--" in arg_strings
        value = super()._get_values(action, arg_strings)
        if (dashes and isinstance(value, list) and not value and action.option_strings
                and action.nargs not in (0, "*", "?", argparse.REMAINDER)):
            raise argparse.ArgumentError(action, f"expected a value; got {given!r}, which argparse reads as no "
                                                 "value at all")
        return value


def _json_default(obj):
    import numpy as np

    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(type(obj))


def print_json(payload) -> None:
    """Print ``payload`` as one JSON object; non-finite floats become null."""
    def clean(x):
        if isinstance(x, float) and not math.isfinite(x):
            return None
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x

    print(json.dumps(clean(json.loads(json.dumps(payload, default=_json_default))), sort_keys=False))


def add_model_arguments(p, required=True) -> None:
    """The dimensionless model inputs every analytic subcommand takes.

    ``required=False`` where physical inputs (:func:`add_physical_arguments`) may
    replace them; :func:`contact_parameters_from_args` then checks the choice.
    """
    p.add_argument("--beta0", type=float, required=required, help="initial ellipticity b/a in (0, 1]")
    p.add_argument("--mu", type=float, required=required, help="Tabor parameter (Eq. 35), > 0")


def model_names():
    from ..analysis.compare import MODEL_NAMES

    return MODEL_NAMES


def _plain(v):
    import numpy as np

    if isinstance(v, (str, bool, np.bool_)):
        return bool(v) if isinstance(v, np.bool_) else v
    return float(v)


def plain_record(rec) -> dict:
    """A scalar record with numpy scalars turned into str, bool or float (key order kept)."""
    return {k: _plain(v) for k, v in rec.items()}


# --------------------------------------------------------------------------- physical (SI) inputs
#: dest -> flag of every physical input, in the order of the help text.
PHYSICAL_FLAGS = {
    "youngs_modulus": "--youngs-modulus", "poisson_ratio": "--poisson-ratio",
    "youngs_modulus_2": "--youngs-modulus-2", "poisson_ratio_2": "--poisson-ratio-2",
    "cylinder_radius": "--cylinder-radius", "radii": "--radii", "principal_radii": "--principal-radii",
    "skew_angle_deg": "--skew-angle-deg", "work_of_adhesion": "--work-of-adhesion",
    "adhesive_stress": "--adhesive-stress",
}


def add_material_arguments(g) -> None:
    """The elastic constants of both bodies (``--youngs-modulus``, ``--poisson-ratio`` and their ``-2``)."""
    g.add_argument("--youngs-modulus", type=float, metavar="E1", help="Young's modulus of body 1 [Pa]")
    g.add_argument("--poisson-ratio", type=float, metavar="NU1", help="Poisson's ratio of body 1, in (-1, 0.5]")
    g.add_argument("--youngs-modulus-2", type=float, metavar="E2", help="Young's modulus of body 2 [Pa] "
                   "(default: body 1)")
    g.add_argument("--poisson-ratio-2", type=float, metavar="NU2", help="Poisson's ratio of body 2 "
                   "(default: body 1)")


def add_physical_arguments(p) -> None:
    """Physical inputs in SI units, an alternative to ``--beta0/--mu``."""
    g = p.add_argument_group("physical inputs (SI units; instead of --beta0/--mu)")
    add_material_arguments(g)
    g.add_argument("--cylinder-radius", type=float, metavar="RC", help="radius of two equal crossed "
                   "cylinders [m] (with --skew-angle-deg)")
    g.add_argument("--radii", type=float, nargs=2, metavar=("R1", "R2"), help="radii of two unequal "
                   "crossed cylinders [m] (with --skew-angle-deg)")
    g.add_argument("--principal-radii", type=float, nargs=2, metavar=("R'", "R''"),
                   help="principal relative radii of any paraboloidal gap [m]")
    g.add_argument("--skew-angle-deg", type=float, metavar="DEG", help="angle between the cylinder axes, "
                   "in (0, 90] degrees (90: perpendicular)")
    g.add_argument("--work-of-adhesion", type=float, metavar="DGAMMA", help="work of adhesion [J/m^2]")
    g.add_argument("--adhesive-stress", type=float, metavar="SIGMA0", help="maximum adhesive stress "
                   "sigma0 [Pa]")


def contact_parameters_from_args(args):
    """``ContactParameters`` from the physical inputs, or None for ``--beta0/--mu``.

    Raises :class:`UsageError` (one line, exit status 2) for a mixed or incomplete choice.
    """
    import math

    given = [f for d, f in PHYSICAL_FLAGS.items() if getattr(args, d, None) is not None]
    nondim = [f for d, f in (("beta0", "--beta0"), ("mu", "--mu")) if getattr(args, d, None) is not None]
    if given and nondim:
        raise UsageError(f"give either --beta0/--mu or physical inputs, not both; got {' '.join(nondim)} "
                         f"with {' '.join(given)}")
    if not given:
        missing = [f for f in ("--beta0", "--mu") if f not in nondim]
        if missing:
            raise UsageError(f"the following arguments are required: {', '.join(missing)} (or physical "
                             "inputs: --youngs-modulus ... --adhesive-stress)")
        return None
    need = [f for d, f in PHYSICAL_FLAGS.items()
            if d in ("youngs_modulus", "poisson_ratio", "work_of_adhesion", "adhesive_stress")
            and getattr(args, d) is None]
    if need:
        raise UsageError(f"physical inputs need {', '.join(need)}")
    shapes = [f for d, f in PHYSICAL_FLAGS.items() if d in ("cylinder_radius", "radii", "principal_radii")
              and getattr(args, d) is not None]
    if len(shapes) != 1:
        raise UsageError("give exactly one of --cylinder-radius, --radii R1 R2, --principal-radii R' R''; "
                         f"got {', '.join(shapes) or 'none'}")
    from ..analysis import dimensional

    e1, nu1 = args.youngs_modulus, args.poisson_ratio
    e2 = e1 if args.youngs_modulus_2 is None else args.youngs_modulus_2
    nu2 = nu1 if args.poisson_ratio_2 is None else args.poisson_ratio_2
    if args.principal_radii is not None:
        if args.skew_angle_deg is not None:
            raise UsageError("--skew-angle-deg goes with --cylinder-radius or --radii, not --principal-radii")
        r1, r2 = args.principal_radii
    else:
        if args.skew_angle_deg is None:
            raise UsageError(f"{shapes[0]} needs --skew-angle-deg")
        if not 0.0 < args.skew_angle_deg <= 90.0:
            raise ValueError(f"skew-angle-deg must be in (0, 90] degrees; got {args.skew_angle_deg!r}")
        if args.radii is None:  # equal cylinders: the angle alone sets beta0; its bound in the user's degrees
            from ..core.validation import ELLIPTICITY_RANGE
            from ..core.geometry import skew_angle

            low = math.degrees(float(skew_angle(ELLIPTICITY_RANGE[0], checked=False)))
            if args.skew_angle_deg < low:
                raise ValueError(f"skew-angle-deg must be in [{low:.6g}, 90] degrees (below {low:.6g} degrees the "
                                 f"contact is a line contact, beta0 < {ELLIPTICITY_RANGE[0]:g}); got "
                                 f"{args.skew_angle_deg!r}")
        theta = math.radians(args.skew_angle_deg)
        if args.radii is not None:
            r1, r2 = dimensional.crossed_cylinder_radii(args.radii[0], args.radii[1], theta)
        else:
            return dimensional.contact_parameters(e1, nu1, e2, nu2, args.cylinder_radius, theta,
                                                  args.work_of_adhesion, args.adhesive_stress)
    return dimensional.contact_parameters_from_principal_radii(e1, nu1, e2, nu2, r1, r2, args.work_of_adhesion,
                                                               args.adhesive_stress)


def validity_epilog() -> str:
    """The ``--help`` epilog: each model's validated range (outside it, results carry a warning)."""
    from ..analysis.validity import validity_table

    return ("validated ranges (outside them the result is computed and a warning printed):\n"
            + validity_table())


def print_warning(rec) -> None:
    """One line on stderr if the record carries a non-empty warning (:func:`print_warning_line`)."""
    text = rec.get("warning")
    if isinstance(text, str) and text:
        print_warning_line(text)


#: Warnings already printed by this process, so that a record's warning that was also raised as a
#: Python warning (:class:`dhfield.analysis.validity.DhfieldWarning`) is printed once.
_PRINTED_WARNINGS: set = set()


def print_warning_line(text: str) -> None:
    """``dhfield: warning: TEXT`` on stderr, once per distinct non-empty text."""
    import sys

    text = " ".join(str(text).split())
    if text and text not in _PRINTED_WARNINGS:
        _PRINTED_WARNINGS.add(text)
        print(f"dhfield: warning: {text}", file=sys.stderr)


# --------------------------------------------------------------------------- hardening (paths, threads, signals)
#: Output suffixes of the subcommands whose ``--out`` is one file.  A subcommand may
#: instead declare its own with ``parser.set_defaults(out_suffixes=(".nc",))``; the
#: ``--out`` of any other subcommand (possibly a directory) gets the generic checks only.
OUTPUT_SUFFIXES = {"curve": (".nc", ".csv"), "compare": (".nc",), "periphery": (".nc",), "field": (".nc",),
                   "solve": (".nc",)}


def check_output_argument(args) -> None:
    """Validate ``args.out`` before anything is computed (called by :func:`dhfield.cli.main`).

    A file output (see :data:`OUTPUT_SUFFIXES`) goes through
    :func:`dhfield.io.validate_output_path`.  Any other ``--out`` must be non-empty
    and, if it exists and is not a directory, a writable regular file (no
    symbolic link, device, FIFO or socket).
    """
    import os
    import stat

    from ..io import validate_output_path

    out = getattr(args, "out", None)
    if out is None:
        return
    suffixes = getattr(args, "out_suffixes", None) or OUTPUT_SUFFIXES.get(getattr(args, "command", None))
    if suffixes:
        validate_output_path(out, suffixes, "out")
        return
    if not str(out).strip():
        raise ValueError(f"out (output path) must be a non-empty path; got {out!r}")
    try:
        st = os.stat(out)
    except OSError:
        return
    if not stat.S_ISDIR(st.st_mode):
        validate_output_path(out, None, "out")


def max_threads() -> int:
    """Largest accepted thread count: 4 x the CPUs (see :func:`dhfield.bem.operator.max_threads`)."""
    from ..bem.operator import max_threads as _max

    return _max()


#: Most FFTW threads the BEM commands take by default (beyond a few, a 2-D transform of the sizes solved
#: here gains little).
CLI_DEFAULT_MAX_THREADS = 4


def command_threads(requested=None) -> int:
    """FFTW threads of a BEM command: ``--threads``, else ``$DHFIELD_THREADS``, else the CPUs this process
    may use that other work is not using (:func:`dhfield.bem.operator.free_cpu_count`: the CPUs less the
    one-minute load average, at least 1), at most :data:`CLI_DEFAULT_MAX_THREADS`.

    The library's own default stays 1 thread (:func:`dhfield.bem.operator.default_threads`: results
    reproducible bit for bit from one machine to another); a command run by a person uses the machine.
    Two threads on two free cores take ~0.84x the wall time of one (``dhfield solve --beta0 0.4826
    --mu 10``); threads beyond the free cores only compete with the work already running.
    """
    import os

    from ..bem.operator import default_threads, free_cpu_count

    if requested is not None:
        return int(requested)
    if os.environ.get("DHFIELD_THREADS", "").strip():
        return default_threads()
    return max(1, min(free_cpu_count(), CLI_DEFAULT_MAX_THREADS))


def thread_count(text: str) -> int:
    """argparse type of ``--threads``: an integer in ``1 .. max_threads()``."""
    try:
        n = int(text)
    except (TypeError, ValueError):
        raise argparse.ArgumentTypeError(f"must be an integer in 1..{max_threads()}; got {text!r}") from None
    if not 1 <= n <= max_threads():
        raise argparse.ArgumentTypeError(f"must be an integer in 1..{max_threads()} (at most 4 threads per CPU; "
                                         f"more only slows FFTW down); got {n}")
    return n


@contextlib.contextmanager
def termination_signals_as_exceptions():
    """Within the block, SIGTERM and SIGHUP raise :class:`dhfield.io.SignalExit`.

    SIGINT keeps Python's ``KeyboardInterrupt`` (or stays ignored, e.g. in a
    background job).  Signals already ignored stay ignored.  Previous handlers
    are restored on exit.  Only in the main thread; elsewhere it does nothing.
    """
    import signal
    import threading

    previous = {}
    if threading.current_thread() is threading.main_thread():
        for name in ("SIGTERM", "SIGHUP"):
            s = getattr(signal, name, None)
            if s is None or signal.getsignal(s) is signal.SIG_IGN:
                continue
            previous[s] = signal.signal(s, _raise_signal_exit)
    try:
        yield
    finally:
        for s, prev in previous.items():
            signal.signal(s, prev)


def _raise_signal_exit(signum, frame):  # noqa: ARG001 - signal handler signature
    from ..io import SignalExit

    raise SignalExit(signum)
