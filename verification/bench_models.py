"""Speed of the comparison models (issue 3).

Run:  .venv/bin/python -m verification.bench_models

Prints the median wall time (over repeats, after a warm-up) of
  * one Maugis-Dugdale pull-off (load control, lambda ~ 1)    (target <= 20 ms)
  * one elliptical-JKR pull-off (load control, beta0 = 0.9)     (target <= 50 ms)
and, for information, the displacement-controlled variants, a vectorised MD
pull-off over 100 lambda in [0.01, 100], the circular DH pull-off and a full
``dhfield.analysis.compare.compare`` row.  Exits 1 if a target is missed.
"""
from __future__ import annotations

import sys

import numpy as np

from dhfield.analysis import compare
from dhfield.models import dh_circular, jkr_elliptic, maugis_dugdale
from dhfield.core.transition import tabor_from_maugis
from verification._bench import run_cases

# SI inputs of the public wrappers: R = 1 mm, E* = 1 GPa, dgamma = 0.1 J/m^2 (any values do).
R, E, W = 1e-3, 1e9, 0.1
SIGMA_LAM1 = 1.0 / 1.1272 * (E**2 * W / R) ** (1 / 3)  # sigma0 giving lambda ~ 1 (mu ~ 0.89)


def main() -> int:
    lam100 = np.geomspace(0.01, 100.0, 100)
    cases = [
        ("MD pull-off, load control (lambda ~ 1)",
         lambda: maugis_dugdale.pull_off(R, E, W, SIGMA_LAM1), 0.020, 30),
        ("MD pull-off, displacement control (lambda ~ 1)",
         lambda: maugis_dugdale.pull_off(R, E, W, SIGMA_LAM1, control="displacement"), None, 30),
        ("MD pull-off, 100 lambda in [0.01, 100], vectorised", lambda: maugis_dugdale.pull_off_nondimensional(1.0, tabor_from_maugis(lam100)),
         None, 10),
        ("elliptical JKR pull-off, load control (beta0 = 0.9)",
         lambda: jkr_elliptic.pull_off(R, E, W, beta0=0.9), 0.050, 30),
        ("elliptical JKR pull-off, displacement control (beta0 = 0.9)",
         lambda: jkr_elliptic.pull_off(R, E, W, beta0=0.9, control="displacement"), None, 30),
        ("circular DH pull-off, load control (mu ~ 0.89)",
         lambda: dh_circular.pull_off(R, E, W, SIGMA_LAM1), None, 30),
        ("compare(mu = 5, beta0 = 0.9): all 7 models", lambda: compare.compare(mu=5.0, beta0=0.9), None, 10),
    ]
    return run_cases("dhfield comparison-model benchmark", cases, width=62)


if __name__ == "__main__":
    sys.exit(main())
