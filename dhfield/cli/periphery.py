"""``dhfield periphery``."""
from __future__ import annotations

from ._common import add_model_arguments, print_json

#: Most rays accepted: 1e5 rays resolve theta_p to 1.6e-5 rad, far below anything the smooth ray
#: quantities need, and cost about 3 kB each (0.3 GB); 1e7 would need ~30 GB.
MAX_RAYS = 100_000


def add_parser(sub) -> None:
    p = sub.add_parser("periphery", help="sigma0, zone width, edge separation and work of adhesion along "
                       "every ray theta_p at pull-off (the equal-beta test)")
    add_model_arguments(p)
    p.add_argument("--control", choices=("load", "displacement"), default="load",
                   help="pull-off under load control (default) or displacement control")
    p.add_argument("--n-theta", type=int, default=10, help=f"rays in [0, pi/2] (default 10, 2..{MAX_RAYS})")
    p.add_argument("--out", default=None, help="also write FILE.nc (netCDF)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run, out_suffixes=(".nc",))


def run(args) -> int:
    import numpy as np

    from ..io.periphery import pull_off_periphery_dataset, write_dataset
    from ..models.dh_elliptic import pull_off
    from ..models.dh_elliptic_periphery import periphery_at_pull_off

    from ..io import validate_output_path

    if not 2 <= args.n_theta <= MAX_RAYS:
        raise ValueError(f"n-theta must be an integer in 2..{MAX_RAYS} (number of rays); got {args.n_theta!r}")
    if args.out is not None:
        validate_output_path(args.out, (".nc",), "out")
    theta = np.linspace(0.0, 0.5 * np.pi, args.n_theta)
    beta0, mu = np.array([[args.beta0]]), np.array([[args.mu]])
    po = pull_off(mu=mu, beta0=beta0, control=args.control)
    prof = periphery_at_pull_off(po, theta)
    if args.out is not None:
        ds = pull_off_periphery_dataset(po, prof, beta0=beta0[:, 0], mu=mu[0], control=args.control)
        write_dataset(ds, args.out)
    cols = ("theta", "contact_radius", "adhesive_radius", "zone_width", "max_adhesive_stress",
            "edge_separation", "work_of_adhesion")
    rows = {c: np.asarray(getattr(prof, c))[0, 0] for c in cols}
    if args.json:
        from ..core.schema import units_of

        scalars = ("beta0", "mu", "W_star", "a_star", "c_star", "v")
        print_json({"beta0": args.beta0, "mu": args.mu, "control": args.control,
                     "W_star": float(po.W_star[0, 0]), "a_star": float(po.a_star[0, 0]),
                     "c_star": float(po.c_star[0, 0]), "v": float(po.v[0, 0]), "rays": rows,
                     "units": units_of(scalars + cols, nondimensional=True)})
        return 0
    print(f"pull-off ({args.control} control): W* = {float(po.W_star[0, 0]):.6g}, "
          f"a* = {float(po.a_star[0, 0]):.6g}, c* = {float(po.c_star[0, 0]):.6g}, v = {float(po.v[0, 0]):.6g}")
    print("".join(f"{c:>20s}" for c in cols))
    for i in range(theta.size):
        print("".join(f"{rows[c][i]:20.10g}" for c in cols))
    if args.out:
        print(f"wrote {args.out}")
    return 0
