"""Ray geometry of the adhesive annulus, shared by :mod:`dhfield.models.dh_elliptic_periphery` and :mod:`dhfield.analysis.eq30`.

A ray theta_p (0 on the major axis) crosses the contact ellipse (a, b) at r_ab
(Eq. A1) and the adhesive ellipse (c, d) at r_cd (Eq. A2).  Along it, the gap and
the stress are integrated in the ellipsoidal coordinate of the contact ellipse,
``l = l_cd sin^2 t``, with the graded Gauss rule of :func:`dhfield.models.dh_elliptic_adhesion.graded_rule`
(exact for the square-root end-point behaviour at both edges).

The functions are unchecked array cores: their callers validate the inputs, and arrays
broadcast.  Lengths are in any one unit (metres in the signatures, c_r in the model).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import hertz
from .dh_elliptic_adhesion import graded_rule

__all__ = ["RayGeometry", "RayNodes", "edge_radius", "ray_geometry", "ray_nodes"]


class RayGeometry(NamedTuple):
    """The geometry of the rays theta_p across the adhesive annulus, with a trailing ray axis.

    Parameters
    ----------
    a, b : numpy.ndarray
        Semi-major and semi-minor axes of the contact ellipse, with a trailing axis of length 1 [m].
    c, d : numpy.ndarray
        Semi-major and semi-minor axes of the adhesive ellipse, with a trailing axis of length 1 [m].
    theta : numpy.ndarray
        Ray angles theta_p, 0 on the major axis [rad].
    cos2, sin2 : numpy.ndarray
        Squared cosine and sine of ``theta`` [-].
    r_ab : numpy.ndarray
        Radius of the contact ellipse along each ray, Eq. (A1) [m].
    r_cd : numpy.ndarray
        Radius of the adhesive ellipse along each ray, Eq. (A2) [m].
    """

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
    """Quadrature nodes along each ray, from the contact edge (l = 0) to the adhesive edge (l = l_cd).

    The node arrays have the shape of the rays followed by a trailing node axis.

    Parameters
    ----------
    t : numpy.ndarray
        Graded Gauss nodes in t, where l = l_cd sin^2 t [rad].
    w : numpy.ndarray
        Their weights [rad].
    l : numpy.ndarray
        Ellipsoidal coordinate of the contact ellipse at the nodes, l = l_cd sin^2 t [m^2].
    r2 : numpy.ndarray
        Squared radius along the ray of the confocal ellipse l,
        r^2 = 1/(cos^2/(a^2 + l) + sin^2/(b^2 + l)) [m^2].
    dr2_dl : numpy.ndarray
        Derivative d(r^2)/dl [-].
    dl_dt : numpy.ndarray
        Derivative dl/dt = 2 l_cd sin t cos t [m^2 rad^-1].
    l_cd : numpy.ndarray
        Ellipsoidal coordinate of the adhesive edge on each ray (no node axis) [m^2].
    """

    t: np.ndarray
    w: np.ndarray
    l: np.ndarray
    r2: np.ndarray
    dr2_dl: np.ndarray
    dl_dt: np.ndarray
    l_cd: np.ndarray


def edge_radius(major, minor, cos2, sin2):
    """Return the radius of an ellipse along a ray from its centre.

    Parameters
    ----------
    major, minor : array_like
        Semi-major and semi-minor axes of the ellipse [m].
    cos2, sin2 : array_like
        Squared cosine and sine of the ray angle theta_p, 0 on the major axis [-].

    Returns
    -------
    numpy.ndarray
        The radius r where the ray crosses the ellipse [m].

    Notes
    -----
    .. math:: r = ab/\\sqrt{b^2\\cos^2\\theta_p + a^2\\sin^2\\theta_p}  \\quad (Eqs.\\ A1, A2)
    """
    return major * minor / np.sqrt(minor**2 * cos2 + major**2 * sin2)  # Eqs. (A1), (A2)


def ray_geometry(a, b, c, d, theta) -> RayGeometry:
    """Return the geometry of the rays theta_p across the annulus between two ellipses.

    Parameters
    ----------
    a, b : array_like
        Semi-major and semi-minor axes of the contact ellipse [m].
    c, d : array_like
        Semi-major and semi-minor axes of the adhesive ellipse [m].
    theta : array_like
        Ray angles theta_p, 0 on the major axis, appended as the last axis [rad].

    Returns
    -------
    RayGeometry
        The semi-axes with a trailing axis, the angles, cos^2 and sin^2, and the edge radii
        r_ab (Eq. A1) and r_cd (Eq. A2) on each ray.
    """
    ex = (lambda q: np.asarray(q, float)[..., None])
    a, b, c, d = ex(a), ex(b), ex(c), ex(d)
    theta = np.asarray(theta, float)
    cos2, sin2 = np.cos(theta) ** 2, np.sin(theta) ** 2
    r_ab = edge_radius(a, b, cos2, sin2)  # Eq. (A1)
    r_cd = edge_radius(c, d, cos2, sin2)  # Eq. (A2)
    return RayGeometry(a, b, c, d, theta, cos2, sin2, r_ab, r_cd)


def ray_nodes(a, b, r_cd, theta, cos2, sin2, nodes=None) -> RayNodes:
    """Return graded quadrature nodes along each ray, from the contact edge to the adhesive edge.

    Parameters
    ----------
    a, b : array_like
        Semi-major and semi-minor axes of the contact ellipse, broadcast with the rays [m].
    r_cd : array_like
        Radius of the adhesive edge along each ray, Eq. (A2) [m].
    theta : array_like
        Ray angles theta_p, 0 on the major axis [rad].
    cos2, sin2 : array_like
        Squared cosine and sine of ``theta`` [-].
    nodes : int, optional
        Gauss-Legendre nodes per panel of :func:`~dhfield.models.dh_elliptic_adhesion.graded_rule`
        (default: its own).

    Returns
    -------
    RayNodes
        The nodes t and weights w, with l = l_cd sin^2 t, r^2(l), dr^2/dl and dl/dt at each node
        and l_cd on each ray.
    """
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
