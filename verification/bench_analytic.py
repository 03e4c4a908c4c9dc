"""Speed of the analytic elliptical DH model (issue 2).

Run:  .venv/bin/python -m verification.bench_analytic

Prints the median wall time of
  * a 200-point load curve                     (target <= 50 ms)
  * one pull-off under load control            (target <= 30 ms)
  * one pull-off under displacement control    (reported)
  * the Fig. 9a dataset: 60 mu in [0.05, 20] x beta0 in {0.8, 0.9, 0.99}, vectorised (target <= 2 s)
"""
from __future__ import annotations

import sys

import numpy as np

from dhfield.models import dh_elliptic as model
from verification._bench import run_cases


def main() -> int:
    mu60 = np.geomspace(0.05, 20.0, 60)
    beta3 = np.array([0.8, 0.9, 0.99])
    cases = [
        ("load curve, 200 points (mu=1, beta0=0.9)", lambda: model.load_curve(mu=1.0, beta0=0.9, n=200), 0.050, 20),
        ("pull-off, load control (mu=1, beta0=0.9)", lambda: model.pull_off(mu=1.0, beta0=0.9), 0.030, 20),
        ("pull-off, displacement control (mu=1, beta0=0.9)",
         lambda: model.pull_off(mu=1.0, beta0=0.9, control="displacement"), None, 20),
        ("Fig. 9a dataset: 60 mu x 3 beta0 pull-offs", lambda: model.pull_off(mu=mu60[:, None], beta0=beta3[None, :]),
         2.0, 5),
    ]
    return run_cases("dhfield analytic benchmark", cases, width=52)


if __name__ == "__main__":
    sys.exit(main())
