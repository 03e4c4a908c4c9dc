"""Tests of the ray geometry shared by dhfield.models.dh_elliptic_periphery and dhfield.analysis.eq30 (closed forms)."""
from __future__ import annotations

import numpy as np

from dhfield.models import dh_elliptic_rays as _rays

#: Closed-form identities evaluated in floating point (a few ulp of O(1) quantities).
RTOL_IDENTITY = 1e-12


def test_edge_radius_lies_on_its_ellipse():
    theta = np.linspace(0.0, 0.5 * np.pi, 7)
    r = _rays.edge_radius(2.0, 0.6, np.cos(theta) ** 2, np.sin(theta) ** 2)   # Eqs. (A1), (A2)
    x, y = r * np.cos(theta), r * np.sin(theta)
    np.testing.assert_allclose(x**2 / 4.0 + y**2 / 0.36, 1.0, rtol=RTOL_IDENTITY)
    np.testing.assert_allclose(r[[0, -1]], [2.0, 0.6], rtol=RTOL_IDENTITY)


def test_ray_nodes_lie_on_confocal_ellipses():
    """Each node l is an ellipsoidal coordinate of the contact ellipse: 1/r^2 = cos^2/(a^2 + l) + sin^2/(b^2 + l)."""
    geo = _rays.ray_geometry(1.0, 0.7, 1.4, 0.98, np.array([0.0, 0.6, 1.2]))
    nodes = _rays.ray_nodes(geo.a, geo.b, geo.r_cd, geo.theta, geo.cos2, geo.sin2)
    # on the major axis the outer edge (r_cd, 0) has l_cd = r_cd^2 - a^2
    np.testing.assert_allclose(nodes.l_cd[0], 1.4**2 - 1.0, rtol=RTOL_IDENTITY)
    c2, s2 = geo.cos2[:, None], geo.sin2[:, None]
    np.testing.assert_allclose(1.0 / nodes.r2, c2 / (1.0 + nodes.l) + s2 / (0.49 + nodes.l), rtol=RTOL_IDENTITY)
    assert np.all((nodes.l >= 0) & (nodes.l <= nodes.l_cd[:, None] * (1 + RTOL_IDENTITY)))
