"""``dhfield force-vs-angle``: the pull-off force of every model against the crossing angle, one material."""
from __future__ import annotations

import numpy as np

from ._common import UsageError, add_material_arguments, print_json

#: The SI flags every run needs (body 2 defaults to body 1).
_REQUIRED = {"youngs_modulus": "--youngs-modulus", "poisson_ratio": "--poisson-ratio",
             "cylinder_radius": "--cylinder-radius", "work_of_adhesion": "--work-of-adhesion",
             "adhesive_stress": "--adhesive-stress"}


def add_parser(sub) -> None:
    from ..analysis.compare import MODEL_NAMES, RECOMMENDED_MODEL
    from ..analysis.force_vs_angle import CLOSURE_MODELS, CLOSURE_POINTS, DEFAULT_ANGLES_DEG, DEFAULT_POINTS

    p = sub.add_parser("force-vs-angle", help="pull-off force [N] of every model against the crossing angle of "
                       "two equal cylinders, for one material (figure)",
                       description="The pull-off force [N] of two equal crossed cylinders of one material "
                       "against their crossing angle: beta0 and the Tabor parameter mu change with the angle "
                       "(Eqs. 3-4, 9, 35).  Every model on the same axes, the recommended model "
                       f"({RECOMMENDED_MODEL}) first and on top with its estimated error band where a stored "
                       "BEM case checks it, and the stored BEM pull-offs that lie on the material's path (its "
                       "mu within 1 % of a stored case's at that case's angle), in newtons; a second panel "
                       "shows the path in (angle, mu) over every stored BEM case.  Prints the forces at a few "
                       f"angles (--json: every angle); --out writes the figure (PNG, with an .svg and a .pdf "
                       f"beside it).  {', '.join(CLOSURE_MODELS)} are evaluated at {CLOSURE_POINTS} of the "
                       "angles only (a root solve per point).")
    g = p.add_argument_group("material and geometry (SI units, all required but body 2)")
    add_material_arguments(g)
    g.add_argument("--cylinder-radius", type=float, metavar="RC", help="radius of the two equal crossed cylinders [m]")
    g.add_argument("--work-of-adhesion", type=float, metavar="DGAMMA", help="work of adhesion [J/m^2]")
    g.add_argument("--adhesive-stress", type=float, metavar="SIGMA0", help="maximum adhesive stress sigma0 [Pa]")
    p.add_argument("--angles-deg", type=float, nargs=2, metavar=("LO", "HI"), default=DEFAULT_ANGLES_DEG,
                   help=f"smallest and largest crossing angle, in (0, 90] deg (default {DEFAULT_ANGLES_DEG[0]:g} "
                        f"{DEFAULT_ANGLES_DEG[1]:g})")
    p.add_argument("--points", type=int, default=DEFAULT_POINTS,
                   help=f"number of angles, evenly spaced, 2-2001 (default {DEFAULT_POINTS})")
    p.add_argument("--models", nargs="+", default=None, metavar="MODEL",
                   help=f"models to draw (default all: {', '.join(MODEL_NAMES)}); the recommended one always")
    p.add_argument("--out", default=None, metavar="FILE.png", help="write the figure (and FILE.svg, FILE.pdf)")
    p.add_argument("--json", action="store_true", help="print the whole table as one JSON object")
    p.set_defaults(func=run, out_suffixes=(".png",))


def _check_arguments(args) -> None:
    missing = [flag for key, flag in _REQUIRED.items() if getattr(args, key) is None]
    if missing:
        raise UsageError(f"force-vs-angle needs {', '.join(missing)} (SI units)")


def run(args) -> int:
    from ..analysis.force_vs_angle import pull_off_force_vs_angle
    from ..io.figures import figure_paths, model_label, si_prefix

    _check_arguments(args)
    if args.out is not None:
        figure_paths(args.out)  # all three files checked writable before anything is computed
    table = pull_off_force_vs_angle(args.youngs_modulus, args.poisson_ratio, args.cylinder_radius,
                                    args.work_of_adhesion, args.adhesive_stress, angles_deg=args.angles_deg,
                                    points=args.points, models=args.models, youngs_modulus_2=args.youngs_modulus_2,
                                    poisson_ratio_2=args.poisson_ratio_2)
    paths = ()
    if args.out is not None:
        from ..io.force_vs_angle_plot import write_force_vs_angle_plot

        paths = write_force_vs_angle_plot(table, args.out)
    if args.json:
        print_json({"skew_angle_deg": table.skew_angle_deg, "beta0": table.beta0, "mu": table.mu,
                    "load_unit": table.load_unit, "recommended_model": table.recommended_model,
                    "force": table.force, "reason": table.reason,
                    "recommended_model_error": table.recommended_error,
                    "bem_on_path": {"skew_angle_deg": table.bem.skew_angle_deg, "beta0": table.bem.beta0,
                                    "mu": table.bem.mu, "material_mu": table.bem.material_mu,
                                    "W_star": table.bem.W_star, "force": table.bem.force,
                                    "force_error": table.bem.force_error},
                    "inputs": table.inputs, "written": [str(p) for p in paths],
                    "units": {"skew_angle_deg": "deg", "beta0": "1", "mu": "1", "load_unit": "N", "force": "N",
                              "recommended_model_error": "1", "W_star": "1", "force_error": "N"}})
        return 0
    th = table.skew_angle_deg
    show = np.unique(np.round(np.linspace(0, th.size - 1, min(th.size, 9))).astype(int))
    finite = np.concatenate([np.abs(f[np.isfinite(f)]) for f in table.force.values()] + [np.zeros(0)])
    scale, unit = si_prefix(np.median(finite) if finite.size else 1.0, "N")
    width = max(len(model_label(m)) for m in table.models) + 2
    print(f"pull-off force W [{unit}] (negative: tensile) against the crossing angle; mu "
          f"{np.nanmin(table.mu):.3g}-{np.nanmax(table.mu):.3g}, beta0 {np.nanmin(table.beta0):.3g}-"
          f"{np.nanmax(table.beta0):.3g}")
    print(f"{'angle [deg]':<{width}s}" + "".join(f"{t:>10.4g}" for t in th[show]))
    for m in table.models:
        mark = "* " if m == table.recommended_model else "  "
        print(f"{mark + model_label(m):<{width}s}" + "".join(f"{v:>10.4g}" for v in table.force[m][show] / scale))
    err = table.recommended_error
    print(f"* recommended; its estimated error against the BEM: "
          + (f"{100 * np.nanmin(err):.2g}-{100 * np.nanmax(err):.2g} % where checked"
             if np.any(np.isfinite(err)) else "none here (no stored BEM case checks these points)"))
    print(f"stored BEM cases on this path: {len(table.bem)}"
          + "".join(f"; {t:.4g} deg (beta0 {b:g}, mu {mu:g}): {f / scale:.4g} +- {e / scale:.2g} {unit}"
                    for t, b, mu, f, e in zip(table.bem.skew_angle_deg, table.bem.beta0, table.bem.mu,
                                              table.bem.force, table.bem.force_error)))
    for m in table.models:
        if table.reason[m]:
            print(f"no answer from {m} at some angles: {table.reason[m]}")
    for path in paths:
        print(f"wrote {path}")
    return 0
