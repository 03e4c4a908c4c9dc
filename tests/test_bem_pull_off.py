"""dhfield.bem.pull_off: the paper's problem (nondimensional_problem) and coarse to fine (refine_pull_off).

The solver and the paths are tested in tests/test_bem_adhesive.py; here the set-up
of the paper's problem and the input checks of the pull-off entry points.
"""
import pytest

from dhfield.bem import adhesive_pull_off, refine_pull_off
from dhfield.bem.pull_off import nondimensional_problem


@pytest.fixture(scope="module")
def coarse():
    # the cheapest load-control pull-off there is (16 x 16 cells, 4 steps): only its type matters
    return adhesive_pull_off(1.0, 1.0, 16, progress=False, n_steps=4, refine_levels=0)


@pytest.mark.parametrize("kwargs, name", [
    (dict(n="64"), "n"), (dict(n=64.5), "n"), (dict(n=True), "n"), (dict(n=6), "n"), (dict(n=62 + 1), "n"),
    (dict(n=64, n_steps="20"), "n_steps"), (dict(n=64, n_steps=3), "n_steps"),
])
def test_nondimensional_problem_names_a_bad_count(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} must be an (even )?integer"):
        nondimensional_problem(1.0, 0.8, **kwargs)


@pytest.mark.parametrize("kwargs, name", [
    (dict(n="32"), "n"), (dict(n=32.5), "n"), (dict(n=16), "n"),
    (dict(n=32, window="3"), "window"), (dict(n=32, window=0), "window"),
    (dict(n=32, refine_levels=None), "refine_levels"), (dict(n=32, refine_factor=1), "refine_factor"),
])
def test_refine_pull_off_names_a_bad_count(coarse, kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} must be an integer"):
        refine_pull_off(coarse, **kwargs)


#: The start is copied from the closure's pull-off record: only round-off can differ.
RTOL_SAME_NUMBER = 1e-12


def test_cold_start_of_the_bracket_search_is_the_two_axis_pull_off():
    """The fix of beta0 = 0.5, mu = 5 (issue 8): the bracket search cold-starts from the two-axis
    closure's pull-off state, whose adhesive ellipse is rounder than beta0 (like the BEM's), not
    from the paper's zone d = beta0 c (48 cells short along y at N = 512: no convergence)."""
    from dhfield import compare, model

    nd = nondimensional_problem(5.0, 0.5, 16)
    ref = compare.pull_off("dh-elliptic-two-axis", 5.0, 0.5, "load")
    c, d = nd.pull_off_zone
    assert nd.pull_off_approach == pytest.approx(float(ref["delta_star"]), rel=RTOL_SAME_NUMBER)
    assert (c, d) == pytest.approx((float(ref["c_star"]), float(ref["d_star"])), rel=RTOL_SAME_NUMBER)
    assert d / c > 0.5 + 0.05                      # rounder than beta0 (two-axis: 0.596)
    # the circle: the DH model itself (the two-axis closure reduces to it), not computed twice
    sphere = nondimensional_problem(5.0, 1.0, 16)
    po = model.pull_off(5.0, 1.0)
    assert sphere.pull_off_approach == float(po.delta_star)
    assert sphere.pull_off_zone[0] == sphere.pull_off_zone[1]
