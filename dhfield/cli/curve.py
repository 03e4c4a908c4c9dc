"""``dhfield curve``."""
from __future__ import annotations

from ._common import add_model_arguments


def add_parser(sub) -> None:
    p = sub.add_parser("curve", help="load curve of the elliptical DH model (nondimensional, Eqs. 32-36)")
    add_model_arguments(p)
    p.add_argument("--ellipticity", type=float, default=None,
                   help="ellipticity of both ellipses if different from beta0")
    p.add_argument("--a-min", type=float, default=None, help="smallest contact semi-major axis a* (> 0)")
    p.add_argument("--a-max", type=float, default=None, help="largest contact semi-major axis a*")
    p.add_argument("--n", type=int, default=200, help="number of points (default 200)")
    p.add_argument("--out", default=None, help="write FILE.nc (netCDF) or FILE.csv; default: print a table")
    p.set_defaults(func=run)


def run(args) -> int:
    import numpy as np

    from ..io.curves import CURVE_VARIABLES, write_load_curve
    from ..model import DEFAULT_A_STAR, load_curve

    a_star = None
    if args.a_min is not None or args.a_max is not None:
        lo = DEFAULT_A_STAR[0] if args.a_min is None else args.a_min
        hi = DEFAULT_A_STAR[1] if args.a_max is None else args.a_max
        if not hi > lo:
            raise ValueError(f"a-max must be greater than a-min; got a-min={lo!r}, a-max={hi!r}")
        if args.n < 2:
            raise ValueError(f"n must be an integer >= 2; got {args.n!r}")
        a_star = np.linspace(lo, hi, args.n)
    curve = load_curve(args.mu, args.beta0, a_star, ellipticity=args.ellipticity, n=args.n)
    if args.out:
        path = write_load_curve(curve, args.out)
        print(f"wrote {path}")
        return 0
    names = list(CURVE_VARIABLES)
    print("\t".join(names))
    for row in zip(*(getattr(curve, n) for n in names)):
        print("\t".join(f"{x:.10g}" for x in row))
    return 0
