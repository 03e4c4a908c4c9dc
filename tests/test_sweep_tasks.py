"""The computations of a sweep at its grid points (:mod:`dhfield.sweep.tasks`)."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.core.records import LoadCurve
from dhfield.sweep import config, tasks


@pytest.mark.parametrize("call", [lambda: tasks.pull_off_block("md", "load", 1.0, 0.9),
                                  lambda: tasks.load_curve_case("md", 0.9, 1.0, [1.0])])
def test_beta0_and_mu_are_keyword_only(call):
    """The old orders were (control, mu, beta0) and (beta0, mu): a positional call would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        call()


def test_pull_off_block_is_the_vectorised_record_with_its_warnings():
    """One records.PullOff per block (issue 16); values and warnings are those of compare.pull_off's records, point by point (issue 17: md at
    beta0 = 0.5 and jkr-elliptic at mu = 0.3 are outside their validated ranges, dhfield.analysis.validity)."""
    from dhfield.analysis import compare

    beta0 = np.array([[0.5], [1.0]])
    mu = np.array([[0.3, 20.0]])
    for model in ("md", "jkr-elliptic"):
        rec = tasks.pull_off_block(model, beta0=beta0, mu=mu)
        values, warnings = tasks.block_values(rec), rec.warning
        assert values.shape == (2, 2, len(tasks.PULL_OFF_FIELDS)) and warnings.shape == (2, 2)
        for i in range(2):
            for j in range(2):
                rec = compare.pull_off(model, beta0=beta0[i, 0], mu=mu[0, j], check_closure=False)
                np.testing.assert_array_equal(values[i, j], [rec[k] for k in tasks.PULL_OFF_FIELDS])
                assert warnings[i, j] == rec["warning"]
    md = tasks.pull_off_block("md", beta0=beta0, mu=mu).warning
    assert "md is validated for beta0 = 1" in md[0, 0] and md[1, 1] == ""
    je = tasks.pull_off_block("jkr-elliptic", beta0=beta0, mu=mu).warning
    assert "jkr-elliptic is validated" in je[0, 0] and "mu = 0.3" in je[1, 0] and je[1, 1] == ""


@pytest.mark.parametrize("kw, name", [({"beta0": np.empty((0, 3)), "mu": 1.0}, "mu"),
                                      ({"beta0": 0.9, "mu": np.empty(0)}, "mu")])
def test_empty_block_is_refused_by_name(kw, name):
    """A block is the record of compare.pull_off, which refuses a pull-off of no points by name (issue 42
    finding 11).  A sweep never builds one: its axes are refused empty (sweep.config) and the dask kernel
    is given its output dtype, so dask does not probe it with an empty block."""
    with pytest.raises(ValueError, match=f"^{name} must contain at least one value"):
        tasks.pull_off_block("md", **kw)


def test_cost_model_orders_what_is_dearer():
    """More cells, a larger mu (narrower zone: more CG iterations) and beta0 < 1 cost more."""
    cost = tasks.expected_seconds
    assert cost("adhesive", {"mu": 1.0, "beta0": 1.0, "n": 256}) > cost("adhesive", {"mu": 1.0, "beta0": 1.0,
                                                                                      "n": 128})
    assert cost("adhesive", {"mu": 2.0, "beta0": 1.0, "n": 128}) > cost("adhesive", {"mu": 0.5, "beta0": 1.0,
                                                                                      "n": 128})
    assert cost("adhesive", {"mu": 1.0, "beta0": 0.8, "n": 128}) > cost("adhesive", {"mu": 1.0, "beta0": 1.0,
                                                                                      "n": 128})
    assert cost("bem_field", {"n": 512}) > cost("bem_field", {"n": 256})
    assert cost("load_curve", {"a_star": np.ones(20)}) > cost("load_curve", {"a_star": np.ones(10)})
    with pytest.raises(ValueError, match="quantity"):
        cost("pull_off", {})


def test_load_curve_case_is_compare_load_curve():
    from dhfield.analysis import compare

    a = np.linspace(0.1, 2.0, 7)
    got = tasks.load_curve_case("md", beta0=0.8, mu=0.5, a_star=a)
    ref = compare.load_curve("md", mu=0.5, beta0=0.8, a_star=a)
    assert type(got) is LoadCurve and set(tasks.CURVE_FIELDS) <= set(got)   # the one load-curve type (issue 16)
    for k in tasks.CURVE_FIELDS:
        np.testing.assert_array_equal(got[k], np.asarray(ref[k], dtype=float), err_msg=k)


def test_adhesive_case_reads_any_result_and_explains_a_failed_path(monkeypatch):
    """The record of an adhesive case: the solver's fields (NaN where it has none), converged,
    resolved, and a message naming the unconverged states when the solver gives none."""
    from types import SimpleNamespace

    seen = {}

    def solver(*, beta0, mu, n, law, control, threads):
        seen.update(beta0=beta0, mu=mu, n=n, law=law, control=control, threads=threads)
        return SimpleNamespace(W_star=-0.7, a_star=1.0, c_star=1.4, beta_ab=0.9, delta_star=-0.2, iterations=40,
                               b_star=0.9, d_star=1.3, beta_cd=0.93, converged=False, resolved=True, message="",
                               failures=[{}, {}], residual=0.25)

    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": solver)
    rec = tasks.adhesive_case(0.9, 1.0, 32, "dugdale")
    assert seen == dict(beta0=0.9, mu=1.0, n=32, law="dugdale", control="load", threads=1)
    assert rec["W_star"] == -0.7 and rec["ellipticity"] == 0.9 and rec["beta_cd"] == 0.93
    assert rec["converged"] is False and rec["resolved"] is True
    assert rec["message"] == "2 state(s) of the load path did not converge; largest residual 0.25"
    assert set(tasks.ADHESIVE_FIELDS + tasks.ADHESIVE_BEM_FIELDS) <= set(rec)


def test_solver_and_law_names():
    from dhfield.analysis.bem_start import adhesive_pull_off
    from dhfield.bem.laws import LAWS

    assert tasks.adhesive_solver() is adhesive_pull_off
    with pytest.raises(ValueError, match="adhesive solver"):
        tasks.adhesive_solver("other")
    assert config.cohesive_laws() == tuple(LAWS)
