"""Independent reference computations shared by tests and report sections.

Kept outside the library on purpose: these are oracles, not models.
"""
import numpy as np
from scipy import special


def boussinesq_displacement(x0, y0, a, b, alpha, n_t=40, n_phi=256):
    """Surface displacement (E* = 1) of p = (al0 + al1 X^2 + al2 Y^2)/sqrt(1-X^2-Y^2) at (x0, y0),
    by quadrature in polar coordinates about the point; rho = rho_e (1 - t^2) removes the edge."""
    al0, al1, al2 = alpha
    phi = 2 * np.pi * np.arange(n_phi) / n_phi  # periodic: trapezoid is spectral
    t, w = special.roots_legendre(n_t)
    t, w = 0.5 * (t + 1), 0.5 * w
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    q2 = (c / a) ** 2 + (s / b) ** 2
    q1 = -2 * (x0 * c / a**2 + y0 * s / b**2)
    q0 = 1 - (x0 / a) ** 2 - (y0 / b) ** 2
    rho_e = (q1 + np.sqrt(q1 * q1 + 4 * q2 * q0)) / (2 * q2)  # Q = q0 + q1 rho - q2 rho^2
    rho_m = q0 / (q2 * rho_e)  # the other root is -rho_m
    rho = rho_e * (1 - t * t)
    x, y = x0 + rho * c, y0 + rho * s
    num = al0 + al1 * (x / a) ** 2 + al2 * (y / b) ** 2
    f = num * 2 * rho_e / np.sqrt(q2 * rho_e * (rho + rho_m))
    return (f @ w).sum() * (2 * np.pi / n_phi) / np.pi
