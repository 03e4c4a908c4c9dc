"""Pressures sampled on a BEM grid (dhfield.analysis.field_sampling): closed-form cell averages against quadrature, loads, Eq. (7)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from dhfield import bem
from dhfield.models import dh_elliptic_fields as double_hertz, hertz
from dhfield.analysis import field_sampling

#: hemisphere_volume vs scipy dblquad asked for 1e-13 absolute.
ATOL_VOLUME = 1e-12
#: V(1, 1) = pi/6 exactly in the closed form: a few rounding errors of O(1) terms.
ATOL_QUARTER = 1e-15
#: Sums of exact cell averages: rounding of O(N^2) corner differences of O(1) volumes.
RTOL_LOAD = 1e-11
#: Cell average vs dblquad (asked for 1e-13 absolute) divided by a cell area of ~0.014.
ATOL_CELL_AVERAGE = 1e-10


@pytest.mark.parametrize("x, y", [(0.3, 0.4), (0.9, 0.8), (1.0, 1.0), (0.2, 1.3), (-0.5, 0.7), (0.99, -0.1),
                                  (2.0, 0.05)])
def test_hemisphere_volume_matches_quadrature(x, y):
    f = lambda t, s: math.sqrt(max(1.0 - s * s - t * t, 0.0))  # noqa: E731
    sx, sy = math.copysign(1.0, x), math.copysign(1.0, y)
    ref = sx * sy * integrate.dblquad(f, 0.0, abs(x), 0.0, abs(y), epsabs=1e-13, epsrel=1e-13)[0]
    assert field_sampling.hemisphere_volume(x, y) == pytest.approx(ref, abs=ATOL_VOLUME)


def test_hemisphere_volume_quarter_is_pi_over_6():
    assert field_sampling.hemisphere_volume(1.0, 1.0) == pytest.approx(math.pi / 6.0, abs=ATOL_QUARTER)
    assert field_sampling.hemisphere_volume(5.0, 3.0) == pytest.approx(math.pi / 6.0, abs=ATOL_QUARTER)


def test_cell_averages_carry_the_hertz_load():
    # sum of cell means x cell area = 2/3 pi a b Po (Eq. 10) when the grid covers the ellipse
    a, beta = 1.0, 0.6
    grid = bem.Grid.centered(50, 1.3, ny=36, half_width_y=0.9)
    p = field_sampling.hertz_pressure(grid, a, beta)
    load = p.sum() * grid.dx * grid.dy
    assert load == pytest.approx(float(hertz.load(a, beta)), rel=RTOL_LOAD)


def test_cell_averages_carry_the_dh_load():
    a, c, beta, v = 1.2, 1.9, 0.9, 1.1
    grid = bem.Grid.centered(64, 1.05 * c)
    p = field_sampling.dh_pressure(grid, a, c, beta, v)
    load = p.sum() * grid.dx * grid.dy
    assert load == pytest.approx(float(double_hertz.load(a, c, beta, v)), rel=RTOL_LOAD)  # Eq. (25)


def test_cell_average_of_an_edge_cell_matches_quadrature():
    a, b, po = 1.0, 0.7, 2.0
    grid = bem.Grid(10, 10, 0.13, 0.11)
    avg = field_sampling.ellipsoid_cell_average(grid, a, b, po)
    xe, ye = grid.x_edges, grid.y_edges
    f = lambda y, x: po * math.sqrt(max(1 - (x / a) ** 2 - (y / b) ** 2, 0.0))  # noqa: E731
    for i, j in [(8, 5), (9, 7), (5, 5), (7, 8)]:
        ref = integrate.dblquad(f, xe[i], xe[i + 1], ye[j], ye[j + 1], epsabs=1e-13)[0] / (grid.dx * grid.dy)
        assert avg[i, j] == pytest.approx(ref, abs=ATOL_CELL_AVERAGE)


def test_centre_sampling_is_eq7_and_dh_is_the_superposition():
    grid = bem.Grid.centered(32, 2.5)
    x, y = grid.mesh()
    p = field_sampling.dh_pressure(grid, 1.0, 1.8, 0.8, 0.7, sampling="centre")
    assert np.array_equal(p, double_hertz.pressure(x, y, 1.0, 1.8, 0.8, 0.7))
    with pytest.raises(ValueError, match="sampling"):
        field_sampling.hertz_pressure(grid, 1.0, 0.8, sampling="midpoint")
