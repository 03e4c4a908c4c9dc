"""The engine under every pull-off route (dhfield.bem.branch): the states of one problem along the approach.

Identities only: the Branch's minimum is the sampled minimum of its own records
(:func:`dhfield.core.pull_off_search.refine_sampled_minimum`, tested there), the search
extends the samples until that minimum is interior, and the path it writes holds
the records it solved.  The accuracy of the routes built on it is tested in
tests/test_bem_adhesive.py, test_bem_path.py and test_bem_pull_off.py.
"""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.core import transition
from dhfield.bem import nondimensional_problem
from dhfield.bem.branch import Branch
from dhfield.bem.solver import DEFAULT_MAX_ITER, DEFAULT_TOL
from dhfield.core.pull_off_search import refine_sampled_minimum


@pytest.fixture(scope="module")
def sphere():
    # lambda = 1 on 32 x 32 cells: each state solves in milliseconds
    nd = nondimensional_problem(mu=float(transition.tabor_from_maugis(1.0)), beta0=1.0, n=32)
    return nd, nd.adhesive_problem()


def _branch(prob, **kw):
    return Branch(prob, DEFAULT_TOL, DEFAULT_MAX_ITER, progress=False, **kw)


def test_extension_stops_when_the_load_minimum_is_interior(sphere):
    nd, prob = sphere
    b = _branch(prob, keep_states=True)
    step = nd.approach_step
    # one state well above the expected pull-off: the search must walk down to the minimum
    k, st = b.solve(nd.pull_off_approach + 3 * step, None, "unloading")
    assert st.converged and st.in_contact
    outcome, order = b.extend_until_interior([k], lambda i, up: b.approach(i) + (step if up else -step), 50)
    assert outcome == "interior"
    order2, sm = b.minimum(order)
    assert order2 == order and not sm.at_boundary
    loads = [b.records[i]["load"] for i in order]
    assert 0 < int(np.argmin(loads)) < len(order) - 1          # usable samples on both sides
    # every added sample is one step below the previous one (the minimum was below the start)
    np.testing.assert_allclose(-np.diff([b.approach(i) for i in order]), step, rtol=1e-9)


def test_minimum_is_the_sampled_minimum_of_the_usable_records(sphere):
    nd, prob = sphere
    b = _branch(prob, keep_states=True)
    step = nd.approach_step
    idx = [b.solve(nd.pull_off_approach + j * step, None, "unloading")[0] for j in (-1, 0, 1)]
    jump = b.solve(nd.pull_off_approach - 5 * step, None, "jump")[0]          # off the branch: left out
    order, sm = b.minimum(idx + [jump])
    assert jump not in order and order == sorted(idx, key=lambda i: -b.approach(i))
    ref = refine_sampled_minimum(np.array([b.approach(i) for i in order]),
                                 np.array([b.records[i]["load"] for i in order]), first=False)
    assert (sm.x, sm.y, sm.index, sm.at_boundary) == (ref.x, ref.y, ref.index, ref.at_boundary)


def test_path_holds_the_records_in_the_order_asked(sphere):
    nd, prob = sphere
    b = _branch(prob, keep_states=True)
    for j in (1, -1, 0):
        b.solve(nd.pull_off_approach + j * nd.approach_step, None, "refine")
    order, sm = b.minimum(range(3))
    path = b.to_path(control="load", load=sm.y, approach=sm.x, pull_off_index=order[sm.index], converged=True,
                     order=order)
    assert path.n_steps == 3 and np.all(np.diff(path.approach) < 0)           # by decreasing approach
    assert [s.approach for s in path.states] == list(path.approach)
    assert path.pull_off_state is b.states[order[sm.index]]
    assert path.pull_off_load == sm.y and path.resolved == prob.resolved


def test_warm_start_of_another_grid_is_not_used(sphere):
    nd, prob = sphere
    other = nondimensional_problem(mu=nd.mu, beta0=1.0, n=16).adhesive_problem()
    foreign = _branch(other).solve(nd.pull_off_approach, None, "unloading")[1]
    b = _branch(prob, warm_start=lambda d: foreign)
    assert b.external(nd.pull_off_approach) is None
    own = b.solve(nd.pull_off_approach, None, "unloading")[1]
    same = _branch(prob, warm_start=lambda d: own)
    assert same.external(nd.pull_off_approach) is own

