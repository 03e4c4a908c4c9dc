"""The computations of a sweep at its grid points (:mod:`dhfield.sweep.tasks`)."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.sweep import tasks


@pytest.mark.parametrize("call", [lambda: tasks.pull_off_block("md", "load", 1.0, 0.9),
                                  lambda: tasks.load_curve_case("md", 0.9, 1.0, [1.0])])
def test_beta0_and_mu_are_keyword_only(call):
    """The old orders were (control, mu, beta0) and (beta0, mu): a positional call would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        call()


def test_pull_off_block_is_the_vectorised_record_with_its_warnings():
    """Values and warnings are those of compare.pull_off's records, point by point (issue 17: md at
    beta0 = 0.5 and jkr-elliptic at mu = 0.3 are outside their validated ranges, dhfield.validity)."""
    from dhfield import compare

    beta0 = np.array([[0.5], [1.0]])
    mu = np.array([[0.3, 20.0]])
    for model in ("md", "jkr-elliptic"):
        values, warnings = tasks.pull_off_block(model, beta0=beta0, mu=mu)
        assert values.shape == (2, 2, len(tasks.PULL_OFF_FIELDS)) and warnings.shape == (2, 2)
        for i in range(2):
            for j in range(2):
                rec = compare.pull_off(model, beta0=beta0[i, 0], mu=mu[0, j], check_closure=False)
                np.testing.assert_array_equal(values[i, j], [rec[k] for k in tasks.PULL_OFF_FIELDS])
                assert warnings[i, j] == rec["warning"]
    _, md = tasks.pull_off_block("md", beta0=beta0, mu=mu)
    assert "md is validated for beta0 = 1" in md[0, 0] and md[1, 1] == ""
    _, je = tasks.pull_off_block("jkr-elliptic", beta0=beta0, mu=mu)
    assert "jkr-elliptic is validated" in je[0, 0] and "mu = 0.3" in je[1, 0] and je[1, 1] == ""


def test_empty_block():
    values, warnings = tasks.pull_off_block("md", beta0=np.empty((0, 3)), mu=1.0)
    assert values.shape == (0, 3, len(tasks.PULL_OFF_FIELDS)) and warnings.shape == (0, 3)
