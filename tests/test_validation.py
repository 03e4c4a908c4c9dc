"""Input validation helpers (dhfield.core.validation): names, ranges, masked/empty arrays, counts, the interval's ends, NaN, the loading mode and (beta0, mu)."""
import re

import numpy as np
import pytest

from dhfield.core import validation as v


def test_interval_message_names_parameter_range_and_value():
    with pytest.raises(ValueError, match=r"^mu must be in \[1e-06, 1e\+12\] \(Tabor parameter of Eq\. \(35\), "
                                         r"dimensionless\); got 1e\+308$"):
        v.check_tabor("mu", 1e308)
    with pytest.raises(ValueError, match=r"^beta0 must be in \[0\.0001, 1\]"):
        v.check_model_ellipticity("beta0", 1e-308)
    with pytest.raises(ValueError, match=r"^a_star must be finite"):
        v.check_contact_size_star("a_star", [1.0, np.inf])


def test_domain_edges_are_accepted():
    assert v.check_tabor("mu", v.TABOR_RANGE[0]) == v.TABOR_RANGE[0]
    assert v.check_model_ellipticity("beta0", 1.0) == 1.0
    assert v.check_contact_size_star("a_star", v.CONTACT_SIZE_RANGE[1]) == v.CONTACT_SIZE_RANGE[1]


def test_masked_arrays_are_rejected_by_name():
    with pytest.raises(ValueError, match="^x must not be a masked array"):
        v.check_finite("x", np.ma.masked_array([1.0, 2.0], mask=[True, False]))


@pytest.mark.parametrize("good, expect", [(3, 3), (np.int64(4), 4), (5.0, 5)])
def test_count_accepts_integers(good, expect):
    assert v.check_count("n", good, 2, 10) == expect


@pytest.mark.parametrize("bad", [2.5, True, "3", 1, 11, None, float("nan")])
def test_count_rejects_non_integers_and_out_of_range(bad):
    with pytest.raises(ValueError, match=r"^n must be an integer in \[2, 10\]"):
        v.check_count("n", bad, 2, 10)


@pytest.mark.parametrize("good, expect", [(None, None), (1, 1), (np.int64(30), 30)])
def test_optional_count_accepts_none_and_positive_integers(good, expect):
    assert v.check_optional_count("m", good) == expect


@pytest.mark.parametrize("bad", [0, -1, 2.5, 3.0, True, "3", float("nan")])
def test_optional_count_rejects_the_rest_by_name(bad):
    with pytest.raises(ValueError, match=r"^m must be None or an integer >= 1 \(what it is\); got"):
        v.check_optional_count("m", bad, "what it is")


def test_as_circle_is_the_one_near_circle_decision():
    """Within sqrt(eps) of 1 an ellipticity is exactly the circle (issue 18, item 2); outside it is kept."""
    eps = np.finfo(float).eps
    assert v.CIRCLE_TOLERANCE == np.sqrt(eps)
    assert v.as_circle(1.0 - 2.0**-53) == 1.0 and v.as_circle(1.0 - 1e-8) == 1.0
    assert v.as_circle(1.0 - 1e-7) == 1.0 - 1e-7 and v.as_circle(0.3) == 0.3
    np.testing.assert_array_equal(v.check_model_ellipticity("beta0", [0.5, 1 - 3 * 2.0**-53]), [0.5, 1.0])


def test_issue18_item4_complex_arrays_are_rejected_by_name():
    """Complex arrays were cut to their real part with only a ComplexWarning (complex scalars were
    already refused): every public entry point now names the parameter."""
    import warnings

    import dhfield
    from dhfield.analysis import compare

    params = dhfield.contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, 1.0, 0.05, 2e5)
    calls = [
        (lambda: dhfield.pull_off(mu=np.array([1 + 5j]), beta0=0.9), "mu"),
        (lambda: dhfield.pull_off(mu=1.0, beta0=np.array([0.9 + 0j])), "beta0"),
        (lambda: compare.pull_off("jkr", mu=[1 + 1j], beta0=0.9), "mu"),
        (lambda: dhfield.load_curve(mu=1.0, beta0=0.9, a_star=np.array([1 + 0j])), "a_star"),
        (lambda: dhfield.contact_parameters(np.array([1e6 + 0j]), 0.5, 1e6, 0.5, 0.01, 1.0, 0.05, 2e5),
         "youngs_modulus_1"),
        (lambda: dhfield.fit_curve(np.array([1e-3 + 1j, 2e-3, 3e-3]), np.array([1e-4, 2e-4, 3e-4]), params),
         "load"),
        (lambda: v.check_sequence("x", [1.0, 2j]), "x"),
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no ComplexWarning on the way
        for call, name in calls:
            with pytest.raises(ValueError, match=rf"^{name} must be real"):
                call()


@pytest.mark.parametrize("value", [np.datetime64("2020-01-01"), np.timedelta64(1, "s"),
                                   np.array(["2020-01-01"], dtype="datetime64[D]")])
def test_dates_and_durations_are_refused_by_name(value):
    """Issue 18 (hostile run): model.pull_off(mu=datetime64) was accepted as a count of time units."""
    from dhfield.models import dh_elliptic as model

    with pytest.raises(ValueError, match="mu must be a real number.*date/time"):
        model.pull_off(mu=value, beta0=0.9)


# --------------------------------------------------------------------------- the interval's ends
@pytest.mark.parametrize("low_open, high_open, brackets", [(True, False, "(1, 2]"), (False, True, "[1, 2)"),
                                                          (True, True, "(1, 2)"), (False, False, "[1, 2]")])
def test_interval_ends_open_or_closed(low_open, high_open, brackets):
    """An end is in the interval exactly when it is closed; the message writes the brackets."""
    kw = dict(low_open=low_open, high_open=high_open, what="a length [m]")
    for end, is_open in ((1.0, low_open), (2.0, high_open)):
        if is_open:
            with pytest.raises(ValueError, match=rf"^x must be in {re.escape(brackets)} \(a length \[m\]\); "
                                                 rf"got {end!r}$"):
                v.check_interval("x", end, 1.0, 2.0, **kw)
        else:
            assert v.check_interval("x", end, 1.0, 2.0, **kw) == end
    assert v.check_interval("x", 1.5, 1.0, 2.0, **kw) == 1.5
    for outside in (np.nextafter(1.0, 0.0), np.nextafter(2.0, 3.0)):
        with pytest.raises(ValueError, match=r"^x must be in"):
            v.check_interval("x", outside, 1.0, 2.0, **kw)


def test_interval_names_the_first_offending_element_of_an_array():
    with pytest.raises(ValueError, match=r"^x must be in \(0, inf\); got -2\.0$"):
        v.check_interval("x", [1.0, -2.0, -3.0], 0.0, np.inf, high_open=True)
    np.testing.assert_array_equal(v.check_interval("x", [[0.5], [1.0]], 0.0, 1.0), [[0.5], [1.0]])


def test_positive_with_and_without_zero():
    assert v.check_positive("x", 0.0, allow_zero=True) == 0.0
    with pytest.raises(ValueError, match=r"^x must be in \(0, inf\)"):
        v.check_positive("x", 0.0)
    with pytest.raises(ValueError, match=r"^x must be in \[0, inf\)"):
        v.check_positive("x", -1e-300, allow_zero=True)
    with pytest.raises(ValueError, match=r"^x must be finite"):
        v.check_positive("x", np.inf)


def test_ellipticity_is_the_half_open_unit_interval():
    assert v.check_ellipticity("beta", 1.0) == 1.0
    for bad in (0.0, 1.0 + 1e-15):
        with pytest.raises(ValueError, match=r"^beta must be in \(0, 1\] \(ellipticity ratio b/a"):
            v.check_ellipticity("beta", bad)


# --------------------------------------------------------------------------- NaN and empty input
@pytest.mark.parametrize("check", [
    lambda x: v.check_finite("x", x),
    lambda x: v.check_interval("x", x, 0.0, 1.0),
    lambda x: v.check_positive("x", x),
    lambda x: v.check_ellipticity("x", x),
    lambda x: v.check_tabor("x", x),
    lambda x: v.check_model_ellipticity("x", x),
    lambda x: v.check_contact_size_star("x", x),
])
@pytest.mark.parametrize("value", [float("nan"), [0.5, float("nan")], np.array([[np.nan]])])
def test_nan_is_refused_with_the_parameter_name(check, value):
    with pytest.raises(ValueError, match=r"^x must be finite.*; got nan$"):
        check(value)


def test_empty_arrays_are_refused_by_name():
    with pytest.raises(ValueError, match="^x must contain at least one value; got an empty array$"):
        v.check_array_input("x", np.array([]))
    v.check_array_input("x", np.array([1.0]))   # one value: accepted


# --------------------------------------------------------------------------- control and (beta0, mu)
def test_control_is_one_of_the_two_loading_modes():
    for control in v.CONTROLS:
        assert v.check_control(control) == control
    for bad in ("Load", "spring", None, 1):
        with pytest.raises(ValueError, match=r"^control must be one of \('load', 'displacement'\)"):
            v.check_control(bad)


def test_grid_point_broadcasts_and_names_the_bad_input():
    beta0, mu = v.check_grid_point([0.5, 1.0], [[1.0], [2.0], [3.0]])
    assert beta0.shape == mu.shape == (3, 2)
    assert beta0[0, 1] == 1.0 and mu[2, 0] == 3.0
    # the near circle is the circle (as_circle)
    assert v.check_grid_point(1.0 - 2.0**-53, 1.0)[0] == 1.0
    with pytest.raises(ValueError, match="^mu must be"):   # mu is checked first
        v.check_grid_point(2.0, float("nan"))
    with pytest.raises(ValueError, match="^beta0 must be in"):
        v.check_grid_point(0.0, 1.0)
    with pytest.raises(ValueError, match="^beta0 must contain at least one value"):
        v.check_grid_point([], 1.0)
    with pytest.raises(ValueError, match="^control must be one of"):
        v.check_grid_point(0.5, 1.0, control="force")


def test_sequence_allows_nan_but_not_two_dimensions():
    np.testing.assert_array_equal(v.check_sequence("x", [1.0, np.nan]), [1.0, np.nan])
    with pytest.raises(ValueError, match=r"^x must be a 1-d sequence of numbers; got shape \(1, 2\)$"):
        v.check_sequence("x", [[1.0, 2.0]])
