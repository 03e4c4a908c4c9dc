"""``dhfield field``."""
from __future__ import annotations

import sys

from ._common import add_model_arguments, command_threads, thread_count


def add_parser(sub) -> None:
    p = sub.add_parser("field", help="full-field BEM cross-check of one DH case, written to netCDF",
                       description="Full-field cross-check of the analytic double-Hertz model at one state "
                       "(beta0, mu, contact size a*): the DH pressure (Eqs. 7, 16, 22; cell averages) is put "
                       "on an N x N grid, the surface displacement computed from it by the DC-FFT boundary "
                       "elements (dhfield.analysis.fields) and compared with the analytic displacement (Eqs. 13-15, "
                       "21, 26) and gap (Eq. 27) in the contact, the adhesive annulus and outside.  Writes "
                       "one netCDF file (dhfield.io.field): pressure, analytic and numerical displacement "
                       "and gap and their differences on (y, x), a region flag, the same resampled on a "
                       "polar (r, theta_p) grid with the annulus-identity error per ray, the error summary "
                       "as error_* attributes and every input as param_*; paper's units (Eqs. 32-35).  "
                       "Nothing is solved for: the pressure is the model's (the self-consistent BEM is "
                       "'dhfield solve').")
    add_model_arguments(p)
    p.add_argument("--a-star", type=float, required=True, help="contact semi-major axis a* (> 0)")
    p.add_argument("--n", type=int, default=512,
                   help="cells per axis (>= 8, default 512; refused if the case would not fit in memory)")
    p.add_argument("--threads", type=thread_count, default=None,
                   help="FFTW threads, 1..4 per CPU (default $DHFIELD_THREADS, else the CPUs available, at most 4)")
    p.add_argument("--out", required=True, help="output netCDF file (.nc)")
    p.set_defaults(func=run, out_suffixes=(".nc",))


def run(args) -> int:
    from ..analysis.fields import check_case_memory, model_case
    from ..io import validate_output_path
    from ..io.field import write_field

    # everything that can be checked is checked before the computation
    validate_output_path(args.out, (".nc",), "out")
    threads = command_threads(args.threads)
    check_case_memory(args.n)
    if sys.stderr.isatty():  # progress only for a person watching
        print(f"dhfield field: computing the {args.n} x {args.n} case and writing {args.out} ...", file=sys.stderr)
    case = model_case(args.n, args.beta0, args.mu, args.a_star, threads=threads)
    path = write_field(case, args.out)
    print(f"wrote {path}")
    return 0
