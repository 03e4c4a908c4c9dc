"""Dimensional front end: materials and crossed-cylinder geometry in SI units.

The nondimensional model (:mod:`dhfield.model`) is scaled back with

* lengths in the contact plane: c_r = (R^2 dgamma/E*)^(1/3)          (Eq. 33)
* approach: c_r^2/R
* stresses: E* c_r/R = (E*^2 dgamma/R)^(1/3), so sigma0 = mu times it (Eq. 35)
* load: W = 2 pi R dgamma W*/sin(theta_skew)                          (Eq. 34)

Paper note: for equal cylinders R = R_c/sin(theta_skew), so Eq. (34) may also be
written W = 2 pi R_c dgamma W*/sin^2(theta_skew).  dhfield follows Eq. (34) as
printed, consistently with Eq. (36).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _adhesion as units
from . import geometry, model
from ._validation import check_positive

__all__ = ["ContactParameters", "contact_parameters", "load_curve_si", "pull_off_force"]


@dataclass(frozen=True)
class ContactParameters:
    """Derived parameters of a crossed-cylinder adhesive contact (SI).

    Attributes
    ----------
    reduced_modulus : E* [Pa] (Eq. 6)
    r_major, r_minor : R', R'' [m] (Eqs. 3-4)
    effective_radius : R [m] (Eq. 5)
    beta0 : Hertz ellipticity [-] (Eq. 9)
    sin_skew : sin(theta_skew) [-]
    mu : Tabor parameter [-] (Eq. 35)
    length_unit : c_r [m] (Eq. 33)
    approach_unit : c_r^2/R [m]
    load_unit : 2 pi R dgamma / sin(theta_skew) [N] (Eq. 34)
    """
    reduced_modulus: float
    r_major: float
    r_minor: float
    effective_radius: float
    beta0: float
    sin_skew: float
    mu: float
    length_unit: float
    approach_unit: float
    load_unit: float


def contact_parameters(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2, poisson_ratio_2,
                       cylinder_radius, skew_angle, work_of_adhesion, max_adhesive_stress):
    """Nondimensional groups and scales of a crossed-cylinder contact.

    Parameters
    ----------
    youngs_modulus_1, youngs_modulus_2 : float
        Young's moduli E1, E2 [Pa].
    poisson_ratio_1, poisson_ratio_2 : float
        Poisson's ratios in (-1, 0.5] [-].
    cylinder_radius : float
        Radius R_c of both cylinders [m].
    skew_angle : float
        Crossing angle theta_skew in (0, pi/2] [rad].
    work_of_adhesion : float
        Delta gamma > 0 [J m^-2].
    max_adhesive_stress : float
        sigma0 > 0 [Pa].

    Returns
    -------
    ContactParameters
    """
    e_star = float(geometry.reduced_modulus(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2,
                                            poisson_ratio_2))  # Eq. (6)
    r1, r2 = geometry.principal_radii(cylinder_radius, skew_angle)  # Eqs. (3)-(4)
    r = float(geometry.effective_radius(r1, r2))  # Eq. (5)
    beta0 = float(geometry.ellipticity_from_radius_ratio(r1 / r2))
    sin_skew = float(np.sin(skew_angle))
    mu = float(units.tabor_parameter(max_adhesive_stress, r, e_star, work_of_adhesion))  # Eq. (35)
    return ContactParameters(e_star, float(r1), float(r2), r, beta0, sin_skew, mu,
                             float(units.length_unit(r, e_star, work_of_adhesion)),  # Eq. (33)
                             float(units.approach_unit(r, e_star, work_of_adhesion)),
                             float(units.load_unit(r, work_of_adhesion, sin_skew)))  # Eq. (34)


def load_curve_si(params: ContactParameters, semi_major=None, n=200):
    """Dimensional load curve of the elliptical DH model.

    Parameters
    ----------
    params : ContactParameters
        From :func:`contact_parameters`.
    semi_major : array_like, optional
        Contact semi-major axes a [m]; default the nondimensional default grid.

    Returns
    -------
    dict of ndarray
        ``semi_major``, ``semi_minor``, ``adhesive_semi_major``, ``adhesive_semi_minor`` [m],
        ``scaling`` v [-], ``load`` W [N] (positive compressive), ``approach`` delta [m].
    """
    a_star = None if semi_major is None else check_positive("semi_major", semi_major, "m") / params.length_unit
    c = model.load_curve(params.mu, params.beta0, a_star, n=n)
    lu = params.length_unit
    return {
        "semi_major": c.a_star * lu, "semi_minor": c.b_star * lu,  # Eq. (32)
        "adhesive_semi_major": c.c_star * lu, "adhesive_semi_minor": c.d_star * lu,
        "scaling": c.v, "load": c.W_star * params.load_unit,  # Eq. (34)
        "approach": c.delta_star * params.approach_unit,
    }


def pull_off_force(params: ContactParameters, control="load"):
    """Pull-off of the crossed-cylinder contact in SI units.

    Returns
    -------
    dict
        ``force`` [N] (negative: tensile), ``semi_major``, ``adhesive_semi_major`` [m],
        ``approach`` [m], ``scaling`` v [-], and the nondimensional ``mu``, ``beta0``.
    """
    p = model.pull_off(params.mu, params.beta0, control=control)
    return {
        "force": float(p.W_star) * params.load_unit,  # Eq. (34)
        "semi_major": float(p.a_star) * params.length_unit,
        "adhesive_semi_major": float(p.c_star) * params.length_unit,
        "approach": float(p.delta_star) * params.approach_unit,
        "scaling": float(p.v), "mu": params.mu, "beta0": params.beta0,
    }
