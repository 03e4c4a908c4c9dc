"""Shared plumbing of the comparison models (JKR, DMT, MD, DH circular, elliptical JKR).

Units
-----
Every comparison model has a private nondimensional core in the units of the
paper (Eqs. 32-35): with the equivalent radius R, the reduced modulus E* and the
work of adhesion dgamma,

* lengths in ``c_r = (R^2 dgamma/E*)^(1/3)`` (Eq. 33): ``a* = a/c_r``;
* approaches in ``c_r^2/R = (R dgamma^2/E*^2)^(1/3)``: ``delta* = delta R/c_r^2``
  (the Hertz approach a^2/R becomes a*^2);
* loads in ``2 pi R dgamma / sin(theta_skew)`` (Eq. 34): ``W* = W sin(theta_skew)/(2 pi R dgamma)``,
  with sin(theta_skew) = 1 for the circle;
* the transition parameter ``mu = sigma0 (R/(E*^2 dgamma))^(1/3)`` (Eq. 35).

With R = E* = dgamma = 1 the nondimensional lengths are the dimensional ones.
The dimensional public wrappers convert with :func:`length_unit`,
:func:`approach_unit` and :func:`load_unit`.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._validation import check_interval, check_positive


class LoadCurve(NamedTuple):
    """Equilibrium states along a load curve (dimensional or nondimensional)."""

    load: np.ndarray
    contact_radius: np.ndarray
    approach: np.ndarray


class PullOff(NamedTuple):
    """The state at pull-off (dimensional or nondimensional)."""

    load: np.ndarray
    contact_radius: np.ndarray
    approach: np.ndarray


def check_material(effective_radius, reduced_modulus, work_of_adhesion):
    """Validate R [m], E* [Pa], dgamma [J/m^2]; return them as float arrays."""
    r = check_positive("effective_radius", effective_radius, "m")
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J/m^2")
    return r, e, w


def check_contact_size(name, value):
    """Validate a (nondimensional or SI) contact radius: finite and >= 0."""
    return check_interval(name, value, 0.0, np.inf, low_open=False, high_open=True,
                          what="contact radius, >= 0")


def length_unit(effective_radius, reduced_modulus, work_of_adhesion):
    """c_r = (R^2 dgamma/E*)^(1/3), Eq. (33) [m]."""
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    return np.cbrt(r * r * w / e)  # Eq. (33)


def approach_unit(effective_radius, reduced_modulus, work_of_adhesion):
    """c_r^2/R = (R dgamma^2/E*^2)^(1/3) [m], the unit of delta*."""
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    return np.cbrt(r * w * w / (e * e))


def load_unit(effective_radius, work_of_adhesion, sin_skew=1.0):
    """2 pi R dgamma / sin(theta_skew), Eq. (34) [N]; sin_skew = 1 for the circle."""
    r = check_positive("effective_radius", effective_radius, "m")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J/m^2")
    return 2.0 * np.pi * r * w / np.asarray(sin_skew, dtype=float)  # Eq. (34)


def tabor_parameter(max_adhesive_stress, effective_radius, reduced_modulus, work_of_adhesion):
    """mu = sigma0 (R/(E*^2 dgamma))^(1/3), Eq. (35) [-]."""
    s = check_positive("max_adhesive_stress", max_adhesive_stress, "Pa")
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        # extreme but finite inputs give 0 or inf here; the caller's range check names the input
        return s * np.cbrt(r / (e * e * w))  # Eq. (35)


def scalar_or_array(x):
    """Return a 0-d array as a Python-float-like numpy scalar, otherwise the array."""
    x = np.asarray(x, dtype=float)
    return x[()] if x.ndim == 0 else x
