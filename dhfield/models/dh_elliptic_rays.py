"""Ray geometry of the adhesive annulus, shared by :mod:`dhfield.models.dh_elliptic_periphery` and :mod:`dhfield.analysis.eq30`.

A ray theta_p (0 on the major axis) crosses the contact ellipse (a, b) at r_ab
(Eq. A1) and the adhesive ellipse (c, d) at r_cd (Eq. A2).  Along it, the gap and
the stress are integrated in the ellipsoidal coordinate of the contact ellipse,
``l = l_cd sin^2 t``, with the graded Gauss rule of :func:`dhfield.models.dh_elliptic_adhesion.graded_rule`
(exact for the square-root end-point behaviour at both edges).

Internal module: unchecked array cores (callers validate), arrays broadcast.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import hertz
from .dh_elliptic_adhesion import graded_rule

__all__ = ["RayGeometry", "RayNodes", "edge_radius", "ray_geometry", "ray_nodes"]


class RayGeometry(NamedTuple):
    """Semi-axes with a trailing ray axis, the ray angles, cos^2 and sin^2, and the edge radii [m]."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    theta: np.ndarray
    cos2: np.ndarray
    sin2: np.ndarray
    r_ab: np.ndarray
    r_cd: np.ndarray


class RayNodes(NamedTuple):
    """Graded nodes t and weights w on each ray, l = l_cd sin^2 t there, r^2(l), dr^2/dl, dl/dt, l_cd."""

    t: np.ndarray
    w: np.ndarray
    l: np.ndarray
    r2: np.ndarray
    dr2_dl: np.ndarray
    dl_dt: np.ndarray
    l_cd: np.ndarray


def edge_radius(major, minor, cos2, sin2):
    """Radius of the ellipse (major, minor) along the ray with cos^2 and sin^2 of its angle [m].

    .. math:: r = ab/\\sqrt{b^2\\cos^2\\theta_p + a^2\\sin^2\\theta_p}  \\quad (Eqs.\\ A1, A2)
    """
    return major * minor / np.sqrt(minor**2 * cos2 + major**2 * sin2)  # Eqs. (A1), (A2)


def ray_geometry(a, b, c, d, theta) -> RayGeometry:
    """Common ray geometry; theta is appended as the last axis of a, b, c, d."""
    ex = (lambda q: np.asarray(q, float)[..., None])
    a, b, c, d = ex(a), ex(b), ex(c), ex(d)
    theta = np.asarray(theta, float)
    cos2, sin2 = np.cos(theta) ** 2, np.sin(theta) ** 2
    r_ab = edge_radius(a, b, cos2, sin2)  # Eq. (A1)
    r_cd = edge_radius(c, d, cos2, sin2)  # Eq. (A2)
    return RayGeometry(a, b, c, d, theta, cos2, sin2, r_ab, r_cd)


def ray_nodes(a, b, r_cd, theta, cos2, sin2, nodes=None) -> RayNodes:
    """Graded nodes t on each ray from the contact edge to r_cd and the quantities of l = l_cd sin^2 t."""
    l_cd = hertz.ellipse_root(r_cd * np.cos(theta), r_cd * np.sin(theta), a, b)
    t1 = np.arcsin(np.minimum(1.0, b / np.sqrt(np.maximum(l_cd, 1e-300))))
    kw = {} if nodes is None else dict(nodes=nodes)
    t, w = graded_rule(t1, **kw)
    ex = (lambda q: np.broadcast_to(q, l_cd.shape)[..., None])
    l = ex(l_cd) * np.sin(t) ** 2
    a2l, b2l = ex(a) ** 2 + l, ex(b) ** 2 + l
    c2, s2 = ex(cos2), ex(sin2)
    r2 = 1.0 / (c2 / a2l + s2 / b2l)
    dr2_dl = r2**2 * (c2 / a2l**2 + s2 / b2l**2)
    dl_dt = 2.0 * ex(l_cd) * np.sin(t) * np.cos(t)
    return RayNodes(t, w, l, r2, dr2_dl, dl_dt, l_cd)
