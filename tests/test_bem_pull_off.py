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
