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
from scipy.optimize import elementwise

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


def grid_minimum(func, lo, hi, args=(), n=64, xatol=1e-13, first=False, grid=None,
                 complex_step=False):
    """Vectorised grid-then-local minimisation of ``func(t, *args)`` on [lo, hi].

    ``func`` must broadcast: it is first evaluated on an ``n``-point grid (a
    trailing axis) to locate the basin of the minimum, then refined with
    :func:`scipy.optimize.elementwise.find_minimum` from the bracket around the
    best grid point.  A minimum on the grid's end point is returned as is (the
    minimiser sits on the boundary of the admissible range).

    With ``first=True`` the basin is the *first* discrete local minimum met from
    ``lo`` (callers put the high-load end of a curve at ``lo``, so this is the
    end of the stable branch reached on unloading); otherwise the global one.

    ``grid`` (shape ``(..., n)``, increasing along the last axis) replaces the
    even grid on [lo, hi] when the parameter is badly graded.

    With ``complex_step=True`` (``func`` analytic and complex-safe) the local
    refinement finds the root of the complex-step derivative
    ``Im f(t + ih)/h`` instead of minimising ``f``: the minimiser is then
    accurate to ~1e-15 rather than ~sqrt(eps).

    Returns
    -------
    t, f : ndarray
        Minimiser and minimum, with the broadcast shape of ``lo``, ``hi`` and ``args``.
    """
    args = tuple(np.asarray(a, dtype=float) for a in args)
    shape = np.broadcast_shapes(np.shape(lo), np.shape(hi), *(a.shape for a in args))
    lo = np.broadcast_to(np.asarray(lo, dtype=float), shape)
    hi = np.broadcast_to(np.asarray(hi, dtype=float), shape)
    args = tuple(np.broadcast_to(a, shape) for a in args)
    if grid is None:
        s = np.linspace(0.0, 1.0, n)
        grid = lo[..., None] + (hi - lo)[..., None] * s
    else:
        grid = np.broadcast_to(grid, shape + np.shape(grid)[-1:])
        n = grid.shape[-1]
    vals = func(grid, *(a[..., None] for a in args))
    vals = np.where(np.isfinite(vals), vals, np.inf)
    i = np.argmin(vals, axis=-1)
    if first:
        loc = np.zeros(vals.shape, dtype=bool)
        loc[..., 1:-1] = (vals[..., 1:-1] <= vals[..., :-2]) & (vals[..., 1:-1] < vals[..., 2:])
        loc[..., -1] = vals[..., -1] <= vals[..., -2]
        i = np.where(loc.any(axis=-1), np.argmax(loc, axis=-1), i)
    t = np.take_along_axis(grid, i[..., None], -1)[..., 0]
    f = np.take_along_axis(vals, i[..., None], -1)[..., 0]
    inner = (i > 0) & (i < n - 1)
    if np.any(inner):
        il = np.clip(i - 1, 0, n - 1)
        ir = np.clip(i + 1, 0, n - 1)
        xl = np.take_along_axis(grid, il[..., None], -1)[..., 0][inner]
        xr = np.take_along_axis(grid, ir[..., None], -1)[..., 0][inner]
        xm = t[inner]
        sub_args = tuple(a[inner] for a in args)
        if complex_step:
            def dfunc(x, *a):
                return np.imag(func(x + 1e-30j, *a)) / 1e-30

            res = elementwise.find_root(dfunc, (xl, xr), args=sub_args,
                                        tolerances=dict(xatol=xatol, xrtol=1e-15))
            fx = func(res.x, *sub_args)
        else:
            res = elementwise.find_minimum(func, (xl, xm, xr), args=sub_args,
                                           tolerances=dict(xatol=xatol, xrtol=1e-14, fatol=0.0,
                                                           frtol=0.0))
            fx = res.f_x
        better = np.isfinite(fx) & (fx <= f[inner] + 1e-14 * np.abs(f[inner]))
        t_in = np.where(better, res.x, xm)
        f_in = np.where(better, fx, f[inner])
        t = t.copy()
        f = f.copy()
        t[inner] = t_in
        f[inner] = f_in
    return t, f
