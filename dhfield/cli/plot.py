"""``dhfield plot SWEEP.nc``: the standard maps of a sweep (PNG + SVG + PDF), optionally in SI units."""
from __future__ import annotations

from pathlib import Path

from ._common import UsageError, add_material_arguments

#: The SI flags of ``plot``: a material and equal crossed cylinders; the sweep supplies the angle and mu.
_SI_FLAGS = {"youngs_modulus": "--youngs-modulus", "poisson_ratio": "--poisson-ratio",
             "youngs_modulus_2": "--youngs-modulus-2", "poisson_ratio_2": "--poisson-ratio-2",
             "cylinder_radius": "--cylinder-radius", "work_of_adhesion": "--work-of-adhesion"}


def add_parser(sub) -> None:
    p = sub.add_parser("plot", help="standard maps of a sweep: W*max per model, errors, ellipticities",
                       description="The standard maps of a sweep: the pull-off of every model, its difference "
                       "from a reference model (model/ref - 1 [%], positive where the model's pull-off is the "
                       "stronger), and the contact ellipticity at pull-off; panels of one figure share one "
                       "colour scale.  Written as PNG, SVG and PDF.  With the SI flags (a material and two "
                       "equal crossed cylinders) the axes are the crossing angle [deg] and sigma0 [Pa] and the "
                       "pull-off is a force [N] (Eqs. 34-35).")
    p.add_argument("sweep", help="netCDF file written by 'dhfield sweep'")
    p.add_argument("--out", default=None, help="output directory, created if needed (default: the sweep "
                   "file's directory)")
    from ..analysis.compare import RECOMMENDED_MODEL

    p.add_argument("--reference", default=None,
                   help="reference model of the error maps (default: the most trusted swept model: "
                   f"bem-adhesive, {RECOMMENDED_MODEL} (the recommended model), dh-elliptic-two-axis, "
                   "jkr-elliptic-energy, jkr-elliptic, then dh-elliptic)")
    g = p.add_argument_group("SI axes (all of --youngs-modulus, --poisson-ratio, --cylinder-radius, "
                             "--work-of-adhesion)")
    add_material_arguments(g)
    g.add_argument("--cylinder-radius", type=float, metavar="RC", help="radius of the two equal crossed "
                   "cylinders [m]")
    g.add_argument("--work-of-adhesion", type=float, metavar="DGAMMA", help="work of adhesion [J/m^2]")
    p.set_defaults(func=run)


def _si(args):
    given = {k: getattr(args, k) for k in _SI_FLAGS if getattr(args, k) is not None}
    if not given:
        return None
    need = [f for k, f in _SI_FLAGS.items() if not k.endswith("_2") and k not in given]
    if need:
        raise UsageError(f"SI maps need {', '.join(need)} (with {', '.join(_SI_FLAGS[k] for k in given)})")
    rename = {"youngs_modulus": "youngs_modulus_1", "poisson_ratio": "poisson_ratio_1"}
    return {rename.get(k, k): v for k, v in given.items()}


def run(args) -> int:
    from ..io import read_netcdf
    from ..io.sweep_maps import standard_maps

    si = _si(args)
    ds = read_netcdf(args.sweep)
    out = Path(args.out) if args.out is not None else (Path(args.sweep).parent or Path("."))
    for path in standard_maps(ds, out, reference=args.reference, stem=Path(args.sweep).stem, si=si):
        print(f"wrote {path}")
    return 0
