"""``dhfield field``."""
from __future__ import annotations

from ._common import add_model_arguments


def add_parser(sub) -> None:
    p = sub.add_parser("field", help="full-field BEM cross-check of one DH case, written to netCDF")
    add_model_arguments(p)
    p.add_argument("--a-star", type=float, required=True, help="contact semi-major axis a* (> 0)")
    p.add_argument("--n", type=int, default=512, help="cells per axis (>= 8, default 512)")
    p.add_argument("--threads", type=int, default=None, help="FFTW threads (default $DHFIELD_THREADS or 1)")
    p.add_argument("--out", required=True, help="output netCDF file")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..io.field import compute_and_write_case

    path = compute_and_write_case(args.beta0, args.mu, args.a_star, args.n, args.out, threads=args.threads)
    print(f"wrote {path}")
    return 0
