"""The start of the adhesive BEM chosen from the analytic models (dhfield.adhesive_start).

The start itself is judged by the BEM states it leads to (tests/test_bem_pull_off.py);
here: that it is the analytic models' numbers, and that a domain too small for the
contact is refused before anything is solved.
"""
from __future__ import annotations

import pytest

from dhfield import adhesive_start, compare, model

#: The start is copied from the closure's pull-off record: only round-off can differ.
RTOL_SAME_NUMBER = 1e-12


def test_cold_start_is_the_two_axis_pull_off_for_an_ellipse_and_the_dh_one_for_the_sphere():
    """The fix of beta0 = 0.5, mu = 5 (issue 8): the bracket search cold-starts from the two-axis
    closure's pull-off state, whose adhesive ellipse is rounder than beta0 (like the BEM's), not
    from the paper's zone d = beta0 c (48 cells short along y at N = 512: no convergence)."""
    start = adhesive_start.pull_off_start(5.0, 0.5)
    ref = compare.pull_off("dh-elliptic-two-axis", 5.0, 0.5, "load")
    c, d = start.zone
    assert start.approach == pytest.approx(float(ref["delta_star"]), rel=RTOL_SAME_NUMBER)
    assert (c, d) == pytest.approx((float(ref["c_star"]), float(ref["d_star"])), rel=RTOL_SAME_NUMBER)
    assert d / c > 0.5 + 0.05                      # rounder than beta0 (two-axis: 0.596)
    sphere = adhesive_start.pull_off_start(5.0, 1.0)
    assert sphere.approach == float(model.pull_off(5.0, 1.0).delta_star)
    assert sphere.zone[0] == sphere.zone[1]


@pytest.mark.parametrize("margin", [0.1, 0.3, 1.0])
def test_domain_too_small_for_the_contact_is_refused_before_solving(margin):
    # issue 18: margin = 0.3 gave W* = -0.261 and 0.1 gave -0.029 (about -0.79): the domain cut the zone
    with pytest.raises(ValueError, match=r"^margin must be > 1"):
        adhesive_start.adhesive_pull_off(1.0, 0.9, 64, margin=margin)
    with pytest.raises(ValueError, match=r"^margin must be > 1"):
        adhesive_start.pull_off_start(1.0, 0.9, margin=margin)


def test_the_bem_facade_forwards_the_convenience_functions():
    from dhfield import bem

    assert bem.adhesive_pull_off is adhesive_start.adhesive_pull_off
    assert bem.refine_pull_off is adhesive_start.refine_pull_off
    assert bem.nondimensional_problem is adhesive_start.nondimensional_problem
