"""Tests of dhfield.models.dh_elliptic_periphery: the DH fields along every ray theta_p."""
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy import integrate

from dhfield.models import (dh_elliptic_adhesion as adhesion, dh_elliptic_fields as double_hertz, hertz,
                            dh_elliptic as model, dh_elliptic_periphery as periphery)

#: Ray quadrature is exponentially convergent (graded Gauss rule): ~1e-13 relative.
QUAD_RTOL = 1e-11
#: scipy.integrate.quad oracle on a smooth integrand, epsrel 1e-12.
ORACLE_RTOL = 1e-9
#: Closed forms evaluated from Carlson integrals: a few ulp, with cancellation in g.
CLOSED_RTOL = 1e-12
#: Bicubic interpolation of a gap sampled on a 512^2 grid (256^2 quadrant) at the mu = 1,
#: beta0 = 0.8 pull-off: the s^(3/2) kinks at both zone edges give O(dx^1.5);
#: measured 2.2e-4 (4.5e-4 at N = 256, 7e-5 at N = 1024).
GRID_RTOL_512 = 5e-4
#: With the analytic gap as interpolation trend only a 1e-6 relative perturbation is
#: interpolated; the reconstruction is then exact to ~1e-6 times that.
TREND_RTOL = 1e-9

STATES = [  # a, c, beta, v: wide, narrow, tiny contact, nearly circular, strongly elliptical
    (1.3, 2.0, 0.8, 1.1),
    (1.0, 1.02, 0.9, 25.0),
    (1e-3, 1.5, 0.7, 0.3),
    (1.2, 1.9, 0.99, 1.0),
    (0.8, 1.6, 0.3, 0.7),
]
THETA = np.array([0.0, 0.1, 0.4, np.pi / 4, 1.2, np.pi / 2])


def gj98(a, c, v):
    """Greenwood & Johnson (1998) DH circular work of adhesion, R = E* = 1."""
    return v * (1 + v) * 2.0 / (3.0 * np.pi) * (c - a) ** 2 * (c + 2 * a)


@pytest.mark.parametrize("state", STATES)
def test_work_matches_adhesion_module(state):
    prof = periphery.periphery(*state, theta=THETA)
    ref = adhesion.work_of_adhesion(*state, theta=THETA)
    assert_allclose(prof.work_of_adhesion, ref, rtol=QUAD_RTOL)


@pytest.mark.parametrize("theta", [0.0, 0.7, np.pi / 2])
def test_work_against_quad_oracle(theta):
    # Independent: quad of sigma * dh/dr with the Cartesian displacement gradient of Eq. (13),
    # on r = r_ab + (r_cd - r_ab) sin^2 t (smooth integrand).
    a, c, beta, v = 1.3, 2.0, 0.8, 1.1
    b, d = beta * a, beta * c
    r_ab = periphery.contact_edge_radius(a, beta, theta)
    r_cd = periphery.adhesive_edge_radius(c, beta, theta)
    po_ab, po_cd = hertz.max_pressure(a, beta), hertz.max_pressure(c, beta)
    r1, r2 = hertz.principal_radii_from_ellipticity(beta)

    def f(t):
        r = r_ab + (r_cd - r_ab) * np.sin(t) ** 2
        x, y = r * np.cos(theta), r * np.sin(theta)
        gx, gy = hertz.surface_displacement_gradient(x, y, a, b, po_ab)
        hx, hy = x / r1 + gx, y / r2 + gy  # Hertz gap gradient, Eq. (2) + Eq. (13)
        dh = (1 + v) * (hx * np.cos(theta) + hy * np.sin(theta))
        sigma = v * hertz.pressure(x, y, c, d, po_cd)
        return sigma * dh * 2 * (r_cd - r_ab) * np.sin(t) * np.cos(t)

    ref, _ = integrate.quad(f, 0, np.pi / 2, epsabs=0, epsrel=1e-12, limit=200)
    got = periphery.periphery(a, c, beta, v, theta=[theta]).work_of_adhesion[0]
    assert_allclose(got, ref, rtol=ORACLE_RTOL)


def test_circle_everything_independent_of_theta_and_gj98():
    a, c, v = np.array([0.5, 1.2, 2.0]), np.array([1.5, 1.9, 2.05]), np.array([0.4, 1.0, 9.0])
    prof = periphery.periphery(a[:, None], c[:, None], 1.0, v[:, None], theta=THETA)
    assert prof.work_of_adhesion.shape == (3, 1, THETA.size)
    w = prof.work_of_adhesion[:, 0]
    assert_allclose(w, np.broadcast_to(gj98(a, c, v)[:, None], w.shape), rtol=1e-12)
    for q in (prof.max_adhesive_stress, prof.zone_width, prof.edge_separation):
        q = q[:, 0]
        assert_allclose(q, np.broadcast_to(q[:, :1], q.shape), rtol=CLOSED_RTOL)
    # GJ98 peak stress sigma0 = (2 v/pi) sqrt(c^2 - a^2) (R = E* = 1)
    assert_allclose(prof.max_adhesive_stress[:, 0, 0], 2 * v / np.pi * np.sqrt(c**2 - a**2), rtol=CLOSED_RTOL)


@pytest.mark.parametrize("state", STATES)
def test_sigma0_constant_with_equal_beta(state):
    prof = periphery.periphery(*state, theta=THETA)
    assert_allclose(prof.max_adhesive_stress, double_hertz.max_adhesive_stress(*state), rtol=CLOSED_RTOL)


@pytest.mark.parametrize("state", STATES)
def test_edge_values_and_law_match_double_hertz_fields(state):
    a, c, beta, v = state
    prof = periphery.periphery(*state, theta=THETA)
    r_cd = prof.adhesive_radius
    h_ref = double_hertz.gap(r_cd * np.cos(THETA), r_cd * np.sin(THETA), *state)
    assert_allclose(prof.edge_separation, h_ref, rtol=1e-10, atol=1e-14)
    assert_allclose(prof.zone_width, r_cd - prof.contact_radius, rtol=0)
    law = periphery.cohesive_law(*state, theta=THETA, n_points=9)
    x, y = law.radius * np.cos(THETA)[:, None], law.radius * np.sin(THETA)[:, None]
    scale = np.max(np.abs(prof.edge_separation))
    assert_allclose(law.separation, double_hertz.gap(x, y, *state), rtol=1e-9, atol=1e-12 * scale)
    # interior samples (at the contact edge double_hertz reports the contact side, 0;
    # at the adhesive edge sqrt(rounding) ~ 1e-8)
    assert_allclose(law.stress[:, 1:-1], double_hertz.adhesive_stress(x[:, 1:-1], y[:, 1:-1], *state),
                    rtol=1e-10)
    assert_allclose(law.stress[:, 0], prof.max_adhesive_stress, rtol=CLOSED_RTOL)
    assert_allclose(law.stress[:, -1], 0.0, atol=1e-15)
    assert_allclose(law.separation[:, -1], prof.edge_separation, rtol=1e-12)
    # the law is a function: sigma decreasing, h increasing along the ray
    assert np.all(np.diff(law.stress, axis=-1) < 0)
    assert np.all(np.diff(law.separation, axis=-1) > 0)


def test_work_is_area_under_sampled_law():
    # Trapezoid area under a finely sampled sigma-h curve converges to Delta gamma(theta_p).
    state = (1.3, 2.0, 0.8, 1.1)
    law = periphery.cohesive_law(*state, theta=THETA, n_points=4001)
    area = np.trapezoid(law.stress, law.separation, axis=-1)
    assert_allclose(area, periphery.periphery(*state, theta=THETA).work_of_adhesion, rtol=1e-6)


def test_unit_neutrality():
    # E* -> k E*: pressures x k, gap unchanged; lengths and R -> lam: Delta gamma x k lam.
    a, c, beta, v, k, lam = 1.3, 2.0, 0.8, 1.1, 7.0e9, 3.0e-4
    ref = periphery.periphery(a, c, beta, v, THETA)
    dim = periphery.periphery(lam * a, lam * c, beta, v, THETA, effective_radius=lam, reduced_modulus=k)
    assert_allclose(dim.work_of_adhesion, k * lam * ref.work_of_adhesion, rtol=1e-12)
    assert_allclose(dim.edge_separation, lam * ref.edge_separation, rtol=1e-12)
    assert_allclose(dim.max_adhesive_stress, k * ref.max_adhesive_stress, rtol=1e-12)


def test_elliptical_work_decreases_towards_minor_axis():
    # Finding recorded in the report: with equal beta < 1, Delta gamma(theta_p) falls
    # monotonically from the major to the minor axis (not a closed form; a property).
    prof = periphery.periphery(1.3, 2.0, 0.8, 1.1, theta=np.linspace(0, np.pi / 2, 31))
    assert np.all(np.diff(prof.work_of_adhesion) < 0)
    assert prof.work_of_adhesion[-1] / prof.work_of_adhesion[0] < 0.95


def test_pull_off_periphery_imposes_eq31_and_eq24():
    mu = np.array([0.5, 1.0, 5.0])
    beta0 = np.array([[0.8], [0.99]])
    po = model.pull_off(mu=mu, beta0=beta0)
    prof = periphery.periphery_at_pull_off(po, theta=THETA)
    assert prof.work_of_adhesion.shape == (2, 3, THETA.size)
    assert_allclose(prof.work_of_adhesion[..., 0], 1.0, rtol=1e-12)  # Eq. (31), Delta gamma = 1
    assert_allclose(prof.max_adhesive_stress, np.broadcast_to(mu[:, None], (2, 3, THETA.size)),
                    rtol=1e-12)  # Eq. (35): sigma0 = mu on every ray
    assert_allclose(prof.zone_width[..., 0], po.c_star - po.a_star, rtol=1e-12)


def test_periphery_along_curve():
    """The periphery of the paper's model's one load-curve record (issue 16); the registry's curve of
    the same model (ellipses of beta0) gives the same profile."""
    from dhfield.analysis import compare

    curve = model.load_curve(beta0=0.9, mu=1.0, a_star=[0.3, 1.0, 2.0])
    prof = periphery.periphery_along_curve(curve, THETA)
    again = periphery.periphery_along_curve(compare.load_curve("dh-elliptic", beta0=0.9, mu=1.0,
                                                               a_star=[0.3, 1.0, 2.0]), THETA)
    assert_allclose(again.work_of_adhesion, prof.work_of_adhesion, rtol=0)  # same arrays, same computation
    assert prof.work_of_adhesion.shape == (3, THETA.size)
    assert_allclose(prof.work_of_adhesion[:, 0], 1.0, rtol=1e-12)
    assert np.all(prof.work_of_adhesion[:, -1] < 1.0)


def test_ray_average():
    th = np.linspace(0, np.pi / 2, 91)
    r_ab = periphery.contact_edge_radius(1.0, 0.6, th)
    assert_allclose(periphery.ray_average(np.full_like(th, 3.0), th, r_ab), 3.0, rtol=1e-15)
    # area weighting: int r_ab^2 d theta over a quarter = 2 * (quarter-ellipse area) = pi a b / 2
    assert_allclose(np.trapezoid(r_ab**2, th), np.pi * 0.6 / 2, rtol=1e-12)
    assert_allclose(periphery.ray_average(np.cos(th) ** 2, th, weight="angle"), 0.5, rtol=1e-12)
    with pytest.raises(ValueError, match="weight"):
        periphery.ray_average(th, th, weight="arc")
    with pytest.raises(ValueError, match="contact_radius"):
        periphery.ray_average(th, th)


def _grid(n, a, c, beta, v, quadrant=True):
    half = 1.25 * c
    dx = 2 * half / n
    x = (np.arange(n) - (n - 1) / 2) * dx
    if quadrant:
        x = x[n // 2:]
    xx, yy = np.meshgrid(x, x, indexing="ij")
    return x, double_hertz.gap(xx, yy, a, c, beta, v), xx


def test_gap_grid_direct_interpolation():
    state = (float(v) for v in (1.3145422487447191, 2.0576511066101677, 0.8, 1.104254789816939))
    a, c, beta, v = state
    x, g, _ = _grid(512, a, c, beta, v)
    ref = periphery.periphery(a, c, beta, v, THETA)
    for method in ("parts", "slope"):
        got = periphery.periphery_from_gap_grid(x, x, g, (a, c, beta, v), THETA, method=method)
        assert_allclose(got.work_of_adhesion, ref.work_of_adhesion, rtol=GRID_RTOL_512)
        assert_allclose(got.edge_separation, ref.edge_separation, rtol=GRID_RTOL_512)
        assert np.max(np.abs(got.contact_edge_gap)) < 1e-3 * np.max(ref.edge_separation)


def test_gap_grid_full_equals_quadrant_and_trend():
    a, c, beta, v = 1.3, 2.0, 0.8, 1.1
    xq, gq, xxq = _grid(128, a, c, beta, v)
    xf, gf, _ = _grid(128, a, c, beta, v, quadrant=False)
    pq = periphery.periphery_from_gap_grid(xq, xq, gq, (a, c, beta, v), THETA)
    pf = periphery.periphery_from_gap_grid(xf, xf, gf, (a, c, beta, v), THETA)
    assert_allclose(pq.work_of_adhesion, pf.work_of_adhesion, rtol=1e-6)
    ref = periphery.periphery(a, c, beta, v, THETA)

    def trend(x, y):
        return double_hertz.gap(x, y, a, c, beta, v)

    noisy = gq * (1 + 1e-6 * np.sin(3 * xxq))
    for method in ("parts", "slope"):
        got = periphery.periphery_from_gap_grid(xq, xq, noisy, (a, c, beta, v), THETA, method=method,
                                                trend=trend)
        assert_allclose(got.work_of_adhesion, ref.work_of_adhesion, rtol=2e-6)
        exact = periphery.periphery_from_gap_grid(xq, xq, gq, (a, c, beta, v), THETA, method=method,
                                                  trend=trend)
        assert_allclose(exact.work_of_adhesion, ref.work_of_adhesion, rtol=TREND_RTOL)


@pytest.mark.parametrize("call, match", [
    (lambda: periphery.periphery(1.0, 0.5, 0.8, 1.0), "adhesive_semi_major"),
    (lambda: periphery.periphery(1.0, 2.0, 1.2, 1.0), "beta"),
    (lambda: periphery.periphery(1.0, 2.0, 0.8, -1.0), "scaling"),
    (lambda: periphery.periphery(1.0, 2.0, 0.8, 1.0, theta=[0.0, 2.0]), "theta"),
    (lambda: periphery.periphery(1.0, 2.0, 0.8, 1.0, theta=[[0.0]]), "theta"),
    (lambda: periphery.cohesive_law(1.0, 2.0, 0.8, 1.0, n_points=1), "n_points"),
    (lambda: periphery.contact_edge_radius(-1.0, 0.8, 0.0), "semi_major"),
    (lambda: periphery.periphery_from_gap_grid([0, 1, 2, 3], [0, 1, 2, 3], np.zeros((3, 4)), (1, 2, 0.8, 1)),
     "shape"),
    (lambda: periphery.periphery_from_gap_grid(np.arange(5.0), np.arange(5.0), np.zeros((5, 5)), (1, 2, 0.8, 1),
                                               method="fd"), "method"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_gap_grid_state_is_one_tuple():
    """The DH state travels as one tuple (4 entries, or 6 with R and E*); anything else is named."""
    a, c, beta, v = 1.3, 2.0, 0.8, 1.1
    x, g, _ = _grid(64, a, c, beta, v)
    four = periphery.periphery_from_gap_grid(x, x, g, (a, c, beta, v), THETA)
    six = periphery.periphery_from_gap_grid(x, x, g, (a, c, beta, v, 1.0, 1.0), THETA)
    assert np.array_equal(four.work_of_adhesion, six.work_of_adhesion)  # R = E* = 1 are the defaults
    for bad in ((a, c, beta), [a, c, beta, v]):
        with pytest.raises(ValueError, match="^state must be a tuple"):
            periphery.periphery_from_gap_grid(x, x, g, bad, THETA)


def test_periphery_along_curve_takes_the_paper_models_curve_only():
    """The ray formulas are the elliptical DH model's: another model's curve, or an SI one, is refused."""
    from dhfield.analysis import compare

    with pytest.raises(ValueError, match="dh-elliptic"):
        periphery.periphery_along_curve(compare.load_curve("md", beta0=0.9, mu=1.0, n=3), THETA)


def test_datasets_round_trip(tmp_path):
    from dhfield.models import dh_elliptic_closure as closure
    from dhfield.analysis import eq30
    from dhfield.io import read_netcdf
    from dhfield.io import periphery as iop

    mu, beta0 = np.array([1.0, 5.0]), np.array([0.8, 0.99])
    th = np.linspace(0, np.pi / 2, 5)
    po = model.pull_off(mu=mu[None, :], beta0=beta0[:, None])
    prof = periphery.periphery_at_pull_off(po, th)
    law = periphery.cohesive_law(po.a_star, po.c_star, po.ellipticity, po.v, theta=[0.0, np.pi / 2], n_points=7)
    ds = iop.pull_off_periphery_dataset(po, prof, law, beta0=beta0, mu=mu)
    p = iop.write_dataset(ds, tmp_path / "periphery.nc")
    back = read_netcdf(p)
    assert_allclose(back["work_of_adhesion"].values, prof.work_of_adhesion, rtol=0)
    assert back["work_of_adhesion"].attrs["units"] == "1"
    assert back["theta"].attrs["units"] == "rad"
    for name in back.variables:
        assert "long_name" in back[name].attrs, name
    assert back.attrs["references"].endswith("10.1007/s11249-017-0976-8")
    assert_allclose(back.attrs["param_mu"], mu)

    spread = closure.equal_beta_spread(beta0=beta0[:, None], mu=mu[None, :])
    paper = closure.state_at_pull_off(beta0=beta0[:, None], mu=mu[None, :], closure="paper")
    ds2 = iop.equal_beta_dataset(spread, {"paper": paper, "paper2": paper}, beta0=beta0, mu=mu)
    back2 = read_netcdf(iop.write_dataset(ds2, tmp_path / "equal_beta.nc"))
    assert list(back2["closure"].values) == ["paper", "paper2"]
    assert_allclose(back2["closure_W_star"].values[0], paper.W_star, rtol=0)

    area = eq30.eq30_area(po.a_star, po.c_star, po.ellipticity, po.v)
    ds3 = iop.eq30_dataset(area, area, prof.work_of_adhesion[..., 0], prof.work_of_adhesion[..., -1], area,
                           beta0=beta0, mu=mu)
    back3 = read_netcdf(iop.write_dataset(ds3, tmp_path / "eq30.nc"))
    assert_allclose(back3["eq30_area"].values, area, rtol=0)
    with pytest.raises(ValueError, match="directory"):
        iop.write_dataset(ds3, tmp_path / "missing" / "x.nc")


def test_load_curve_dataset(tmp_path):
    from dhfield.io import read_netcdf
    from dhfield.io import periphery as iop

    curves, profs = {}, {}
    for b in (0.8, 0.9):
        lc = model.load_curve(beta0=b, mu=1.0, a_star=[0.5, 1.0, 2.0])
        curves[(b, 1.0)], profs[(b, 1.0)] = lc, periphery.periphery_along_curve(lc, THETA)
    ds = iop.load_curve_periphery_dataset(curves, profs, beta0=[0.8, 0.9], mu=[1.0])
    back = read_netcdf(iop.write_dataset(ds, tmp_path / "lc.nc"))
    assert back["work_of_adhesion"].shape == (2, 1, 3, THETA.size)
    assert_allclose(back["work_of_adhesion"].values[1, 0], profs[(0.9, 1.0)].work_of_adhesion, rtol=0)
    assert_allclose(back["W_star"].values[0, 0], curves[(0.8, 1.0)].W_star, rtol=0)


# --------------------------------------------------------------------------- BEM states
def _radial_dugdale_state(n, a=1.0, c=1.5, h0=0.4, sigma0=2.5, half_width=2.0):
    """A synthetic full-grid ContactState with a known Dugdale zone (closed form).

    Contact r < a (gap 0), gap h = h0 (r^2 - a^2)/(c^2 - a^2) outside it, so h(c) = h0;
    traction sigma0 on cells with centre r < c (piecewise constant, as a BEM applies it).
    Every ray's work of adhesion is sigma0 h0 up to where the staircase of cells leaves
    the zone, at most one cell diagonal from r = c.
    """
    from dhfield.bem import ContactState, DugdaleLaw, Grid

    grid = Grid.centered(n, half_width)
    x, y = grid.mesh()
    r2 = x * x + y * y
    gap = np.where(r2 < a * a, 0.0, h0 * (r2 - a * a) / (c * c - a * a))
    contact = r2 < a * a
    zone = (r2 < c * c) & ~contact
    pressure = np.where(zone, -sigma0, 0.0) + np.where(contact, 1.0, 0.0)
    state = ContactState(grid, pressure, gap, 0.0, float(pressure.sum() * grid.dx * grid.dy), contact,
                         zone.astype(float), DugdaleLaw(sigma0, h0), True, 0, 0.0)
    slope = 2.0 * h0 * c / (c * c - a * a)  # dh/dr at r = c
    return state, sigma0 * h0, slope * np.hypot(grid.dx, grid.dy) / h0


#: Staircase bound of the synthetic state, relative: one cell diagonal times max dh/dr at the
#: zone edge (in h0), plus 20 % for the spline across the contact-edge kink of the gap.
STATE_STAIRCASE_FACTOR = 1.2


@pytest.mark.parametrize("n", [64, 256])
def test_periphery_from_state_dugdale_closed_form(n):
    state, work, rel_bound = _radial_dugdale_state(n)
    prof = periphery.periphery_from_state(state, THETA)
    assert np.all(np.abs(prof.work_of_adhesion / work - 1.0) <= STATE_STAIRCASE_FACTOR * rel_bound)
    cell = np.hypot(state.grid.dx, state.grid.dy)
    assert np.all(np.abs(prof.contact_radius - 1.0) <= cell)
    assert np.all(np.abs(prof.adhesive_radius - 1.5) <= cell)
    assert_allclose(prof.max_adhesive_stress, 2.5, rtol=0)


def test_periphery_from_state_converges():
    """The staircase error falls at least like the cell size (4x finer grid: >= 2x smaller)."""
    errs = []
    for n in (64, 256):
        state, work, _ = _radial_dugdale_state(n)
        errs.append(np.max(np.abs(periphery.periphery_from_state(state, THETA).work_of_adhesion / work - 1.0)))
    assert errs[1] <= 0.5 * errs[0]


def test_adhesive_traction_without_repulsive_part():
    state, _, _ = _radial_dugdale_state(32)
    t = periphery.adhesive_traction(state)
    assert_allclose(t[np.asarray(state.contact)], 2.5, rtol=0)  # sigma0 continued over the contact (Maugis)
    assert np.all(t[~np.asarray(state.contact) & (state.cohesive == 0)] == 0.0)
    with pytest.raises(ValueError, match="n_samples"):
        periphery.periphery_from_state(state, THETA, n_samples=3)
