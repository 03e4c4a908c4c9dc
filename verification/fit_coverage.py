"""Coverage of the pull-off fit's standard error: replicate forces and uncertain inputs (issue 17).

The issue's PDMS contact (E = 1.8 MPa, nu = 0.49, two cylinders of R = 3 mm crossed
at 60 degrees, sigma0 = 0.3 MPa) with a known work of adhesion (the truth).  For each
of ``--sets`` seeded replicate sets:

A. replicates only: ``--replicates`` pull-off forces, each the model's force of the
   truth times (1 + e), e ~ N(0, ``--noise``); ``dhfield.analysis.fit.fit_work_of_adhesion``;
B. replicates and uncertain inputs: as A, but the fit is given a sigma0 and a
   cylinder radius each drawn from N(truth, std) -- what a user's measured inputs
   are -- with those standard deviations, propagated by
   ``dhfield.analysis.fit.propagate_input_uncertainty``.

Prints, per scenario, how many sets put the truth within 2 reported standard
errors (about 95 % if the standard errors are right; 40 sets: 38 +- 1.4), and
the count with the plain
s/sqrt(n) standard error (82 % expected for three replicates: why the reported one
is t-adjusted).  The model is dh-elliptic (the fit's default); the statistics do
not depend on it.

Run: ``.venv/bin/python -m verification.fit_coverage [--sets 40] [--replicates 3] [--noise 0.03]``
(about 30 s).  Measured (2026-11-26): 40 sets -- A 38/40, B 37/40 (plain s/sqrt(n): 34/40, 37/40);
200 sets -- A 190/200, B 187/200 (plain: 173/200, 186/200).  The plain standard error falls short
in A, where the replicates' 2 degrees of freedom dominate, and not in B, where the inputs'
(known) standard deviations do.  Exit status 1 if a scenario covers fewer than 85 % of the sets.
"""
from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

from dhfield.analysis import dimensional as dim
from dhfield.analysis.fit import fit_work_of_adhesion, propagate_input_uncertainty

PDMS = dict(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, youngs_modulus_2=1.8e6, poisson_ratio_2=0.49,
            skew_angle=math.pi / 3)
RADIUS, STRESS = 3e-3, 3e5
#: The truth: dgamma [J m^-2] (mu ~ 9.7 with sigma0 = 0.3 MPa; forces about -0.8 mN, as in the issue).
WORK = 0.074
#: Standard deviations of the uncertain inputs of scenario B [Pa], [m].
STRESS_STD, RADIUS_STD = 0.5e5, 0.1e-3
MODEL = "dh-elliptic"


def build(cylinder_radius, max_adhesive_stress):
    return dim.contact_parameters(**PDMS, cylinder_radius=cylinder_radius, work_of_adhesion=WORK,
                                  max_adhesive_stress=max_adhesive_stress)


def one_set(rng, n, noise, uncertain_inputs):
    force = float(dim.pull_off_force(build(RADIUS, STRESS), MODEL, check_closure=False)["force"])
    forces = force * (1.0 + rng.normal(0.0, noise, n))
    if not uncertain_inputs:
        res = fit_work_of_adhesion(forces, build(RADIUS, STRESS), model=MODEL, check_closure=False)
    else:
        inputs = {"cylinder_radius": RADIUS + rng.normal(0.0, RADIUS_STD),
                  "max_adhesive_stress": STRESS + rng.normal(0.0, STRESS_STD)}
        res = fit_work_of_adhesion(forces, build(**inputs), model=MODEL, check_closure=False)
        res = propagate_input_uncertainty(res, build, inputs, {"cylinder_radius": RADIUS_STD,
                                                               "max_adhesive_stress": STRESS_STD})
    return res


def scenario(label, sets, n, noise, uncertain_inputs, seed0):
    t = time.perf_counter()
    z, z_plain = [], []
    for k in range(sets):
        res = one_set(np.random.default_rng(seed0 + k), n, noise, uncertain_inputs)
        z.append((res.work_of_adhesion - WORK) / res.work_of_adhesion_stderr)
        plain = math.hypot(res.replicate_stderr, res.input_stderr)
        z_plain.append((res.work_of_adhesion - WORK) / plain)
    z, z_plain = np.array(z), np.array(z_plain)
    inside = int(np.sum(np.abs(z) < 2.0))
    print(f"{label}: truth within 2 standard errors in {inside}/{sets} sets ({100 * inside / sets:.0f} %); "
          f"with the plain s/sqrt(n) "
          f"{int(np.sum(np.abs(z_plain) < 2.0))}/{sets}  [{time.perf_counter() - t:.1f} s]")
    return inside


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sets", type=int, default=40)
    p.add_argument("--replicates", type=int, default=3)
    p.add_argument("--noise", type=float, default=0.03, help="relative standard deviation of a force")
    args = p.parse_args(argv)
    print(f"truth dgamma = {WORK} J/m^2, {args.replicates} replicates per set, force noise "
          f"{100 * args.noise:g} %, model {MODEL}")
    a = scenario("A replicates only        ", args.sets, args.replicates, args.noise, False, 1000)
    b = scenario(f"B + sigma0 +-{STRESS_STD:.0e} Pa, R +-{RADIUS_STD:.0e} m", args.sets, args.replicates,
                 args.noise, True, 2000)
    # 95 % of 40 is 38; a binomial count below 34 (p < 0.01 for a true 95 %) means the errors are too small
    low = math.floor(0.85 * args.sets)
    return 0 if min(a, b) >= low else 1


if __name__ == "__main__":
    sys.exit(main())
