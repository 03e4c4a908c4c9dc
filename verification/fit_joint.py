"""Joint fit over crossing angles (dhfield.analysis.fit.fit_joint, ``dhfield fit --data`` with an angle column).

Synthetic pull-off forces of the PDMS contact of issue 40 (E = 1.8 MPa, nu = 0.49, two
cylinders of R = 3 mm, dgamma = 45 mJ/m^2, sigma0 = 0.3 MPa), computed with the recommended
model (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`) at 4 crossing angles (20, 40, 60 and 90 deg)
x 5 replicates, each multiplied by 1 + 0.03 z with z standard normal (numpy seed 40): 3 %
noise.  The CSV (``skew_angle_deg``, ``force [mN]``) goes through ``dhfield fit --data ...
--adhesive-stress 3e5 --plot``, which fits dgamma at the known sigma0; printed: the recovered
dgamma, its standard error, the 95 % interval, and the departure from the truth in standard
errors.  With ``--seeds N`` the same is repeated on N other seeds (library call) and the
fraction of fits within 2 standard errors of the truth is printed (about 94 % expected:
Student t with 19 degrees of freedom).

Run: ``.venv/bin/python -m verification.fit_joint [--out out/fit_joint] [--seeds 40]``.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import time
import warnings
from pathlib import Path

import numpy as np

from dhfield.analysis import compare
from dhfield.analysis import dimensional as dim
from dhfield.analysis.fit import fit_joint

MATERIAL = dict(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, youngs_modulus_2=1.8e6, poisson_ratio_2=0.49,
                cylinder_radius=3e-3)
WORK, STRESS = 0.045, 3e5
ANGLES_DEG = (20.0, 40.0, 60.0, 90.0)
REPLICATES = 5
NOISE = 0.03
SEED = 40
CLI_INPUTS = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3",
              "--adhesive-stress", "3e5"]


def contact_at(angle_deg):
    """The PDMS contact at one crossing angle [deg], at the true dgamma and sigma0."""
    return dim.contact_parameters(**MATERIAL, skew_angle=math.radians(angle_deg), work_of_adhesion=WORK,
                                  max_adhesive_stress=STRESS)


def synthetic_forces(seed):
    """(angles [deg], pull-off forces [N]): the recommended model times 1 + NOISE z."""
    angles = np.repeat(ANGLES_DEG, REPLICATES)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exact = {a: float(dim.pull_off_force(contact_at(a), compare.RECOMMENDED_MODEL)["force"]) for a in ANGLES_DEG}
    rng = np.random.default_rng(seed)
    return angles, np.array([exact[a] for a in angles]) * (1.0 + NOISE * rng.standard_normal(angles.size))


def write_csv(path, angles, forces):
    lines = ["skew_angle_deg,force [mN]"] + [f"{a:g},{f * 1e3:.9g}" for a, f in zip(angles, forces)]
    Path(path).write_text("\n".join(lines) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/fit_joint", help="folder of the CSV and the plot (default out/fit_joint)")
    ap.add_argument("--seeds", type=int, default=0, help="other seeds for the coverage count (default 0)")
    args = ap.parse_args(argv)
    from dhfield.cli import main as cli

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    angles, forces = synthetic_forces(SEED)
    csv, png = out / "pull_off_by_angle.csv", out / "fit_joint.png"
    write_csv(csv, angles, forces)
    argv_cli = ["fit", "--data", str(csv), *CLI_INPUTS, "--plot", str(png), "--json"]
    print("dhfield " + " ".join(argv_cli))
    buf = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(buf):
        code = cli(argv_cli)
    wall = time.perf_counter() - t0
    rec = json.loads(buf.getvalue())
    w, se, (lo, hi) = rec["work_of_adhesion"], rec["work_of_adhesion_stderr"], rec["work_of_adhesion_ci95"]
    print(f"exit status {code}, {wall:.1f} s, model {rec['model']}, {rec['n_points']} rows at "
          f"{rec['skew_angles_deg']} deg, mu {[round(m, 2) for m in rec['mu']]}")
    print(f"truth      dgamma = {WORK * 1e3:.4f} mJ/m^2 (sigma0 = {STRESS:g} Pa held fixed)")
    print(f"recovered  dgamma = {w * 1e3:.4f} mJ/m^2, standard error {se * 1e3:.4f} mJ/m^2, "
          f"95 % interval [{lo * 1e3:.4f}, {hi * 1e3:.4f}] mJ/m^2")
    print(f"departure  {(w - WORK) / se:+.2f} standard errors ({'within' if abs(w - WORK) <= 2 * se else 'OUTSIDE'} 2); "
          f"relative noise of the residuals {rec['relative_noise']:.4f}")
    print(f"wrote {csv}, {png} (.svg, .pdf)")
    if args.seeds > 0:
        inside, t0 = 0, time.perf_counter()
        for seed in range(SEED + 1, SEED + 1 + args.seeds):
            a, f = synthetic_forces(seed)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = fit_joint(f, a, contact_at, max_adhesive_stress=STRESS)
            inside += abs(r.work_of_adhesion - WORK) <= 2 * r.work_of_adhesion_stderr
        print(f"coverage   {inside}/{args.seeds} seeds ({SEED + 1}..{SEED + args.seeds}) within 2 standard errors "
              f"({time.perf_counter() - t0:.0f} s)")
    return 0 if code == 0 and abs(w - WORK) <= 2 * se else 1


if __name__ == "__main__":
    raise SystemExit(main())
