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
