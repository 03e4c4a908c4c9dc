"""The shared pull-off search (dhfield.core.pull_off_search) on functions with known minima."""
import numpy as np
import pytest

from dhfield.core.pull_off_search import refine_sampled_minimum, stable_branch_end

#: A parabola is reproduced exactly by the three-point vertex: rounding only.
EXACT_RTOL = 1e-12
#: Chandrupatla's tolerance is 1e-13 in x; roots of O(1) to a few ulps more.
ROOT_ATOL = 1e-12


def test_parabola_vertex_is_exact_on_nonuniform_samples():
    x = np.array([0.0, 0.1, 0.25, 0.5, 0.9, 1.4])
    y = 2.0 * (x - 0.31) ** 2 - 1.5
    m = refine_sampled_minimum(x, y)
    assert not m.at_boundary and m.index == 2
    assert m.x == pytest.approx(0.31, rel=EXACT_RTOL)
    assert m.y == pytest.approx(-1.5, rel=EXACT_RTOL)


def test_sampled_minimum_converges_at_least_cubically_in_value():
    # y = -cos(x - 0.3137) (vertex off the grid): the error of the refined value is O(h^3)
    # (the interpolation error of a parabola); quartering h must gain more than 4^3 / 2.
    errs = []
    for n in (11, 41, 161):
        x = np.linspace(-1.0, 1.0, n)
        m = refine_sampled_minimum(x, -np.cos(x - 0.3137))
        errs.append(abs(m.y + 1.0))
    assert errs[1] < errs[0] / 32 and errs[2] < errs[1] / 32


def test_first_local_minimum_from_the_start_vs_global():
    x = np.linspace(0.0, 4.0, 81)
    y = np.cos(2 * np.pi * x) - 0.1 * x  # minima near x = 0.5, 1.5, 2.5, 3.5 (deepest last)
    first = refine_sampled_minimum(x, y)
    glob = refine_sampled_minimum(x, y, first=False)
    assert abs(first.x - 0.5) < 0.02 and abs(glob.x - 3.5) < 0.02


def test_boundary_minimum_and_failed_samples():
    x = np.arange(6.0)
    m = refine_sampled_minimum(x, x.copy())  # increasing: minimum at the first sample
    assert m.at_boundary and m.index == 0 and m.x == 0.0
    m = refine_sampled_minimum(x[::-1], x[::-1].copy())  # decreasing x is allowed
    assert m.at_boundary
    y = (x - 2.0) ** 2
    y[2] = np.nan  # the failed state at the minimum is skipped, not reported
    m = refine_sampled_minimum(x, y)
    assert np.isfinite(m.y) and m.index in (1, 3)


def test_bad_samples_are_rejected_with_names():
    with pytest.raises(ValueError, match="x and y"):
        refine_sampled_minimum([0, 1, 2], [0, 1])
    with pytest.raises(ValueError, match="finite sample"):
        refine_sampled_minimum([0, 1], [np.nan, np.nan])
    with pytest.raises(ValueError, match="monotone"):
        refine_sampled_minimum([0, 2, 1], [1, 0, 1])


def test_stable_branch_end_finds_largest_crossing_per_problem():
    # d(a) = (a - r1)(a - r2)(a - r3) with r1 < r2 < r3: crossings neg -> pos at r1 and r3;
    # the stable branch (from large a) ends at r3.
    r3 = np.array([0.7, 1.3, 2.9])

    def deriv(a, r):
        return (a - 0.1) * (a - 0.4) * (a - r)

    scan = np.geomspace(1e-3, 4.0, 60)
    end = stable_branch_end(deriv, scan, (r3,))
    assert end.found.all()
    np.testing.assert_allclose(end.x, r3, atol=ROOT_ATOL)


def test_stable_branch_end_chunks_and_extends_the_scan():
    rng = np.random.default_rng(7)
    r = rng.uniform(0.5, 3.0, 50)
    r[::7] = 10.0  # beyond the scan top 4: the scan of those rows is extended (x 8)

    def deriv(a, r_):
        return a - r_

    scan = np.broadcast_to(np.linspace(0.01, 4.0, 30), (50, 30))
    one = stable_branch_end(deriv, scan, (r,))
    many = stable_branch_end(deriv, scan, (r,), chunk_bytes=1, bytes_per_state=1)
    assert one.found.all()
    np.testing.assert_array_equal(one.x, many.x)
    np.testing.assert_allclose(one.x, r, atol=ROOT_ATOL)
    with pytest.raises(RuntimeError, match="still negative"):
        stable_branch_end(deriv, scan, (np.array([1e9]),), max_extend=2)


def test_noise_floor_hides_rounding_minima_but_not_real_ones():
    # d = a - 1 plus +-1e-12 noise near a -> 0 on an otherwise positive derivative.
    scan = np.geomspace(1e-6, 4.0, 80)

    def noisy(a, s):
        return s * np.where(a < 1e-4, 1e-12 * np.cos(1e7 * a), 1.0)

    end = stable_branch_end(noisy, scan, (np.array([1.0]),), floor=1e-9)
    assert not end.found[0]
    end = stable_branch_end(noisy, scan, (np.array([1.0]),), floor=0.0)
    assert end.found[0]  # without the floor the noise makes a spurious minimum


def test_walk_down_the_scan_gives_the_whole_scan_bracket_with_fewer_evaluations():
    # Issue 11: the scan is walked from the top, `block` points at a time.  Any block size gives
    # the bracket (hence the root) of evaluating the whole scan at once (block = n), bit for bit;
    # a crossing near the top costs a few scan points, not the whole scan.
    r3 = np.array([0.7, 1.3, 2.9, 3.9])
    scan_points = []

    def deriv(a, r):
        if np.ndim(a) == 2:  # scan blocks are 2-d; the top point and the root finder's are 1-d
            scan_points.append(np.size(a))
        return (a - 0.1) * (a - 0.4) * (a - r)

    scan = np.geomspace(1e-3, 4.0, 60)
    whole = stable_branch_end(deriv, scan, (r3,), block=60)
    for block in (1, 3, 8, 59):
        end = stable_branch_end(deriv, scan, (r3,), block=block)
        np.testing.assert_array_equal(end.x, whole.x)
    scan_points.clear()
    end = stable_branch_end(deriv, scan, (np.array([3.9]),), block=3)
    assert scan_points == [3]  # the first block below the top holds a negative point: done
    np.testing.assert_allclose(end.x, 3.9, atol=ROOT_ATOL)


def test_last_local_minimum_is_the_one_nearest_the_top_whatever_the_block():
    # f = cos(2 pi x / p) - 0.05 x: minima near x = p/2 + k p; the one nearest the top of the scan
    # [0.05, 3] is refined to find_minimum's tolerance.  A rising f has none (zero-contact side).
    from dhfield.core.pull_off_search import last_local_minimum
    from scipy.optimize import minimize_scalar

    period = np.array([0.9, 1.3, 2.2])

    def f(x, p):
        return np.cos(2 * np.pi * x / p) - 0.05 * x

    scan = np.geomspace(0.05, 3.0, 40)
    whole = last_local_minimum(f, scan, (period,), block=40)
    for block in (1, 4, 8):
        end = last_local_minimum(f, scan, (period,), block=block)
        np.testing.assert_array_equal(end.x, whole.x)
    for p, x in zip(period, whole.x):
        k = np.floor((3.0 - p / 2) / p)  # last minimum below the top
        ref = minimize_scalar(lambda t: f(t, p), bounds=(p / 2 + k * p - 0.2, p / 2 + k * p + 0.2), method="bounded",
                              options=dict(xatol=1e-12))
        assert x == pytest.approx(ref.x, abs=1e-7)
    rising = last_local_minimum(lambda x, s: s * x, scan, (np.array([1.0]),))
    assert not rising.found[0] and np.isnan(rising.x[0])


@pytest.mark.parametrize("values, index", [
    ([5.0, 3.0, 1.0, 4.0], 2),             # one interior minimum
    ([5.0, 2.0, 2.0, 2.0, 6.0], 3),        # a plateau is walked down to its last sample before the rise
    ([5.0, 1.0, 3.0, 0.0, 2.0], 1),        # the minimum nearest the high-load end, not the global one
    ([5.0, 4.0, 3.0], 2),                  # still falling: the low-load end point
    ([5.0, 4.0, 4.0], 2),                  # a tie at the end counts as falling
    ([1.0, 2.0, 3.0], 0),                  # rising strictly from the high-load end: that end
    ([5.0, 5.0], 1),                       # two equal samples: the tie goes to the lower-load one
])
def test_stable_minimum_index_one_rule(values, index):
    """The one local-minimum and tie rule (issue 16), checked by hand on sequences."""
    from dhfield.core.pull_off_search import stable_minimum_index

    assert int(stable_minimum_index(np.array(values))) == index


def test_every_sampled_search_takes_the_same_sample_on_a_plateau():
    """refine_sampled_minimum and last_local_minimum follow stable_minimum_index on a path whose
    minimum is an exact plateau: the tie rule, not the refinement, decides (issue 16)."""
    from dhfield.core.pull_off_search import last_local_minimum, stable_minimum_index

    x = np.arange(9.0)  # high-load end first
    y = np.array([8.0, 6.0, 4.0, 2.0, 2.0, 2.0, 3.0, 5.0, 7.0])
    i = int(stable_minimum_index(y))
    assert i == 5 and refine_sampled_minimum(x, y).index == i
    # last_local_minimum scans a = 8 - x upwards (its top is the high-load end): sample i is a = 3,
    # refined on the bracket (2, 4); the plateau's other end (a = 5, bracket (4, 6)) is not taken
    end = last_local_minimum(lambda a, s: s * np.interp(a, x, y[::-1]), x, (np.array([1.0]),))
    assert end.found[0] and 2.0 <= end.x[0] <= 4.0


def test_global_minimum_and_slopes_follow_the_same_tie_rule():
    """first=False (the global minimum) and the slope form (analytic or fitted slopes) apply the
    same rule: equal minima go to the lower-load sample, a zero slope (or one within the floor)
    is not a rise (issue 16: one local-minimum rule, one tie rule)."""
    from dhfield.core.pull_off_search import stable_minimum_index

    assert int(stable_minimum_index(np.array([3.0, 1.0, 2.0, 1.0, 4.0]), first=False)) == 3
    assert int(stable_minimum_index(slopes=np.array([-2.0, -1.0, 0.0, 0.5, 1.0]))) == 3
    assert int(stable_minimum_index(slopes=np.array([-2.0, -1.0, 0.0, 0.5, 1.0]), floor=0.7)) == 4
    assert int(stable_minimum_index(slopes=np.array([-2.0, np.nan, -1.0]))) == 3  # never rises


def test_fitted_slopes_are_exact_on_a_quadratic():
    """A least-squares quadratic reproduces a quadratic path: its slope is the derivative (closed form)."""
    from dhfield.core.pull_off_search import fitted_slopes

    x = np.linspace(2.0, 0.0, 9)  # decreasing along the path, like sqrt(F_a) on unloading
    f = (x - 0.8) ** 2  # along unloading u = x[i] - x: d f/du = -d f/dx = -2 (x - 0.8)
    s = fitted_slopes(x, f, 2)
    assert np.allclose(s, -2.0 * (x - 0.8), atol=1e-12)  # rounding of the least-squares solve
    assert np.all(np.isfinite(fitted_slopes(x, f, 1)[1:-1])) and np.isnan(fitted_slopes(x, f, 1)[0])
