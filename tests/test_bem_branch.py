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


def test_race_tries_the_starts_in_turn_until_one_converges(sphere):
    # a start of None is skipped; a failed try (a CG cap of 1 iteration from a cold start) is kept,
    # marked 'discarded'; the first converged state is returned and the later starts are never called
    from dhfield.bem.solver import Prediction

    nd, prob = sphere
    d = nd.pull_off_approach
    cold = Prediction(np.zeros_like(prob.z), np.zeros_like(prob.z))       # no contact, no zone
    b = _branch(prob)
    called = []

    def start(name, cap, guess):
        def make():
            called.append(name)
            b.max_iter = cap
            return guess
        return make

    k, st = b.race(d, [start("none", DEFAULT_MAX_ITER, None), start("capped", 1, cold),
                       start("full", DEFAULT_MAX_ITER, cold), start("never", DEFAULT_MAX_ITER, cold)], "unloading")
    assert called == ["none", "capped", "full"]
    assert st.converged and k == 1 and b.kept() == [1]
    assert b.records[0]["phase"] == "discarded" and not b.records[0]["converged"]
    assert b.race(d, [start("none", DEFAULT_MAX_ITER, None)], "unloading") is None and len(b.records) == 2
    # every start fails: the last try is returned, kept, unconverged; every start but the last
    # listed may be given up early, the last has the solver's full budget
    gave = []
    solve = b._solve_from
    b._solve_from = lambda *args: gave.append(args[3]) or solve(*args)
    k, st = b.race(d, [start("capped", 1, cold), start("capped", 1, cold)], "unloading", give_up_after=40)
    assert not st.converged and b.records[k]["phase"] == "unloading" and b.records[k - 1]["phase"] == "discarded"
    assert gave == [40, None]
    # give_up_last: the last start is given up early too (Branch.solve's neighbour/external race)
    gave.clear()
    b.race(d, [start("capped", 1, cold), start("capped", 1, cold)], "unloading", give_up_after=40,
           give_up_last=True)
    assert gave == [40, 40]
    # a try given up early (here: reported stopped at its window of 40 outer iterations, unconverged)
    # whose later start gives None goes on from its best iterate with the full budget
    import dataclasses

    gave.clear()
    resumed = []

    def given_up_once(approach, start, phase, window):
        gave.append(window)
        resumed.append(start)
        if len(gave) > 1:
            return solve(approach, start, phase, window)
        st = dataclasses.replace(solve(approach, start, phase, window)[1], converged=False, outer_iterations=40)
        b.states[len(b.records) - 1] = st
        return len(b.records) - 1, st

    b._solve_from = given_up_once
    k, st = b.race(d, [start("full", DEFAULT_MAX_ITER, cold), start("none", DEFAULT_MAX_ITER, None)],
                   "unloading", give_up_after=40)
    assert gave == [40, None] and resumed[0] is cold and resumed[1] is b.states[k - 1]
    assert st.converged and b.records[k - 1]["phase"] == "discarded" and b.records[k]["phase"] == "unloading"
    # two tries given up, the first closer (residual 2e-4) than the second (2e-3), and the last start gives
    # None: the closer one is resumed, from its own best iterate
    gave.clear()
    resumed.clear()
    residuals = iter((2e-4, 2e-3))

    def given_up_twice(approach, start, phase, window):
        gave.append(window)
        resumed.append(start)
        if window is None:
            return solve(approach, start, phase, window)
        st = dataclasses.replace(solve(approach, start, phase, window)[1], converged=False, outer_iterations=40,
                                 residual=next(residuals))
        b.states[len(b.records) - 1] = st
        return len(b.records) - 1, st

    b._solve_from = given_up_twice
    n0 = len(b.records)
    k, st = b.race(d, [start("full", DEFAULT_MAX_ITER, cold), start("full", DEFAULT_MAX_ITER, cold),
                       start("none", DEFAULT_MAX_ITER, None)], "unloading", give_up_after=40)
    assert gave == [40, 40, None] and resumed[2] is b.states[n0] and resumed[2].residual == 2e-4
    assert st.converged and [r["phase"] for r in b.records[n0:]] == ["discarded", "discarded", "unloading"]
    # a try given up at 2e-4 and the last start, with the full budget, ending unconverged farther off (2e-3):
    # the given-up try is resumed from its best iterate; ending closer (5e-5, still unconverged) it is not
    for last_residual, resumes in ((2e-3, True), (5e-5, False)):
        gave.clear()
        resumed.clear()

        def closer_given_up(approach, start, phase, window, last_residual=last_residual):
            gave.append(window)
            resumed.append(start)
            if len(gave) == 3:
                return solve(approach, start, phase, window)
            st = dataclasses.replace(solve(approach, start, phase, window)[1], converged=False,
                                     outer_iterations=40 if window else 300,
                                     residual=2e-4 if window else last_residual)
            b.states[len(b.records) - 1] = st
            return len(b.records) - 1, st

        b._solve_from = closer_given_up
        n0 = len(b.records)
        k, st = b.race(d, [start("full", DEFAULT_MAX_ITER, cold), start("full", DEFAULT_MAX_ITER, cold)],
                       "unloading", give_up_after=40)
        if resumes:
            assert gave == [40, None, None] and resumed[2] is b.states[n0] and st.converged
            assert [r["phase"] for r in b.records[n0:]] == ["discarded", "discarded", "unloading"]
        else:
            assert gave == [40, None] and not st.converged and st.residual == 5e-5 and k == n0 + 1
    # a try stopped by its CG budget (max_iter 1), not given up, is not resumed
    gave.clear()
    b._solve_from = lambda *args: gave.append(args[3]) or solve(*args)
    b.race(d, [start("capped", 1, cold), start("none", 1, None)], "unloading", give_up_after=40)
    assert gave == [40]


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


@pytest.mark.parametrize("option", ["stretch_every", "anderson_memory"])
@pytest.mark.parametrize("bad", [0, -30, 2.5, True, "30"])
def test_integer_options_are_positive_integers_or_none(sphere, option, bad):
    _, prob = sphere
    assert getattr(_branch(prob, **{option: 30}), option) == 30 and getattr(_branch(prob), option) is None
    with pytest.raises(ValueError, match=f"{option} must be None or an integer >= 1"):
        _branch(prob, **{option: bad})



def test_external_fallback_starts_from_neighbours_and_falls_back_on_the_external_start(sphere):
    nd, prob = sphere
    d0, d1 = nd.pull_off_approach, nd.pull_off_approach - nd.approach_step
    own = {d: _branch(prob).solve(d, None, "unloading")[1] for d in (d0, d1)}   # converged references
    asked = []

    def external(d):
        asked.append(d)
        return own[d]

    b = _branch(prob, warm_start=external, external_fallback=True)
    assert b.guess(d0, None) is own[d0] and asked == [d0]          # no neighbour: the external start
    k0, st0 = b.solve(d0, own[d0], "unloading")
    assert st0.converged and not b.guess(d1, k0) is own[d1] and asked == [d0]   # a neighbour: not asked
    # a neighbour's start that fails (a CG cap of 1 iteration) is solved again from the external start
    b.max_iter = 1
    k1, st1 = b.solve(d1, b.guess(d1, k0), "unloading")
    assert asked == [d0, d1] and b.records[k1 - 1]["phase"] == "discarded" and b.records[k1]["phase"] == "unloading"
    assert len(b.records) == 3 and not b.records[k1 - 1]["converged"]
    assert b.kept() == [k0, k1]                                     # the discarded record is not kept
    # both tries of that race get the caller's give_up_after
    gave = []
    solve = b._solve_from
    b._solve_from = lambda *args: gave.append(args[3]) or solve(*args)
    b.solve(d1, b.guess(d1, k0), "unloading", give_up_after=25)
    assert gave == [25, 25] and asked == [d0, d1, d1]
    # without the fallback the external start is asked first, and a failure is left as it is
    plain = _branch(prob, warm_start=external)
    assert plain.guess(d1, b.states[k0]) is own[d1]
    plain.max_iter = 1
    k, st = plain.solve(d1, b.states[k0], "unloading")
    assert not st.converged and len(plain.records) == 1 and plain.records[k]["phase"] == "unloading"


def test_widest_edge_guess_is_a_converged_start_of_this_grid_and_not_recorded():
    # mu = 2 on 128^2: the grid's own edge (0.58 h0) is narrower than the widest (2 h0)
    from dhfield.analysis import bem_start as adhesive_start
    from dhfield.bem.solver import Prediction

    nd = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    prob = nd.adhesive_problem(1)
    b = _branch(prob)
    d = nd.pull_off_approach
    cold = nd.path_start(prob).stress
    assert b.widest_edge_guess(d, None) is None and b._widest is None      # no start: nothing solved
    g = b.widest_edge_guess(d, Prediction(np.zeros_like(cold), cold.copy()))
    assert g.converged and g.grid == prob.grid and b.records == []          # a start, not a record
    assert b._widest.widest_edge and b._widest.min_spread > prob.min_spread
    k, st = b.solve(d, g, "unloading")
    ref = _branch(prob).solve(d, Prediction(np.zeros_like(cold), cold.copy()), "unloading")[1]
    assert st.converged and st.load == pytest.approx(ref.load, rel=1e-5)    # DEFAULT_TOL 1e-6 on both
    # a grid whose edge is at its widest already (mu = 7 on cells of 0.05: the cap 2 h0) gets no
    # wide start, and nothing is solved
    from dhfield.bem import DugdaleLaw, Grid
    from dhfield.bem.solver import AdhesiveProblem

    grid = Grid(64, 64, 0.05, 0.05)
    x, y = grid.mesh()
    capped = AdhesiveProblem(x * x / 2.0 + y * y / 2.0, grid, DugdaleLaw(7.0, 1.0 / 7.0), None, 1, 1.0)
    assert capped.with_widest_edge().min_spread == capped.min_spread == pytest.approx(2.0 / 7.0)
    bc = _branch(capped)
    assert bc.widest_edge_guess(0.1, Prediction(np.zeros_like(capped.z), np.zeros_like(capped.z))) is None
    assert bc._widest is None                                               # nor built
