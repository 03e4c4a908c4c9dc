"""Compliant loading and cycles (dhfield.analysis.spring): figures against closed forms, and a table.

Run: ``PYTHONPATH=. python verification/cycle_check.py``.  Prints

* the JKR pull-off under a spring against the root of the quintic
  4 t^5 + 4 pi K t^3 - 3 c t^2 - pi K c = 0 (t = sqrt(a*), c = sqrt(2 pi); derived in
  dhfield.analysis.spring), and the rigid-machine cycle against its closed forms;
* the jump-out load W* against the machine stiffness K* for every circular model and
  elliptical JKR at mu = 1 (beta0 = 0.8 for the ellipse), with the energy lost.
"""
import math

import numpy as np

from dhfield.analysis import spring as compliance

C = math.sqrt(2 * math.pi)


def jkr_quintic(k):
    r = np.roots([4.0, 0.0, 4 * np.pi * k, -3 * C, 0.0, -np.pi * k * C])
    t = r[(abs(r.imag) < 1e-9) & (r.real > 0)].real.max()
    return (4 / 3 * t**6 - 2 * C * t**3) / (2 * np.pi)


def main():
    ks = np.array([0.0, 0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0, 1e4])
    po = compliance.pull_off_under_spring("jkr", mu=10.0, beta0=1.0, machine_stiffness=ks)
    dev = max(abs(w - jkr_quintic(k)) for k, w in zip(ks, po["W_star"]))
    print(f"JKR pull-off under a spring vs quintic root, K* in {ks.min():g}..{ks.max():g}: max |dW*| = {dev:.2e}")
    cyc = compliance.loading_cycle("jkr", mu=10.0, beta0=1.0, machine_stiffness=None)
    t1, t2 = (np.pi / 8) ** (1 / 6), (2 * np.pi) ** (1 / 6)
    prim = lambda t: (8 / 15 * t**10 - 4 / 3 * C * t**7 + C**2 / 2 * t**4) / (2 * np.pi)  # noqa: E731
    print(f"JKR rigid machine: jump out W* {cyc['jump_out_W_star']:.12f} (-5/12 = {-5 / 12:.12f}), "
          f"jump in W* {cyc['jump_in_W_star']:.12f} (-2/3), energy {cyc['energy_lost_star']:.12f} "
          f"(closed form {prim(t1) - prim(t2):.12f})")
    print()
    print(f"{'model':14s} " + " ".join(f"K*={k:<8g}" for k in (0.0, 0.1, 1.0, 10.0)) + "  rigid     | U* at K*=1, rigid")
    for model, beta0 in (("jkr", 1.0), ("md", 1.0), ("dh-circular", 1.0), ("dmt", 1.0), ("jkr-elliptic", 0.8)):
        r = compliance.loading_cycle(model, mu=1.0, beta0=beta0, machine_stiffness=[0.0, 0.1, 1.0, 10.0])
        rr = compliance.loading_cycle(model, mu=1.0, beta0=beta0, machine_stiffness=None)
        print(f"{model:14s} " + " ".join(f"{w:<10.5f}" for w in r["jump_out_W_star"])
              + f"  {rr['jump_out_W_star']:<9.5f} | {r['energy_lost_star'][2]:.5f}, {rr['energy_lost_star']:.5f}")


if __name__ == "__main__":
    main()
