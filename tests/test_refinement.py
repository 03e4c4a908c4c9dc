"""Grid-refinement studies (dhfield.core.refinement) on the Hertz field case: observed orders."""
from __future__ import annotations

import numpy as np

from dhfield.analysis import fields
from dhfield.core import refinement

#: Refinement 64 -> 128 -> 256 (Hertz ellipse, cell averages), the issue's order target; the
#: RMS and off-edge orders measured here are 1.85-1.95 (second order in the smooth interior).
MIN_ORDER = 1.5
#: The whole-grid L-inf order is capped at 1.5 by the square-root edge (see the field_sampling docstring);
#: measured 1.38-1.46 between 128 and 2048 cells; this only guards against a regression.
MIN_ORDER_LINF = 1.25


def _refinement_study(error_of_n, ns):
    """Run a grid-refinement study (test harness, moved here from dhfield.core.refinement: only these tests used it).

    Parameters
    ----------
    error_of_n : callable
        ``error_of_n(n) -> (h, error)`` for ``n`` cells per axis.
    ns : sequence of int
        Increasing resolutions.

    Returns
    -------
    dict
        ``n``, ``h``, ``error`` (arrays), ``order`` (between successive grids,
        NaN-padded in front) and ``fitted_order`` (least-squares slope of
        log error against log h).
    """
    ns = [int(n) for n in ns]
    hs, errs = zip(*(error_of_n(n) for n in ns))
    hs = np.asarray(hs, dtype=float)
    errs = np.asarray(errs, dtype=float)
    orders = np.concatenate([[np.nan], refinement.observed_orders(hs, errs)])
    fitted = float(np.polyfit(np.log(hs), np.log(errs), 1)[0]) if len(ns) > 1 else float("nan")
    return {"n": np.asarray(ns), "h": hs, "error": errs, "order": orders, "fitted_order": fitted}


def test_refinement_order():
    def err(n):
        case = fields.hertz_case(n, 1.0, 0.7)
        e = case.displacement_numerical - case.displacement_analytic
        return case.grid.dx, np.sqrt(np.mean(e**2)) / np.abs(case.displacement_analytic).max()

    study = _refinement_study(err, [64, 128, 256])
    assert np.all(study["order"][1:] >= MIN_ORDER)
    assert study["fitted_order"] >= MIN_ORDER

    def err_linf(n):
        case = fields.hertz_case(n, 1.0, 0.7)
        e = case.displacement_errors()
        return case.grid.dx, e["all"]["rel_max"]

    linf = _refinement_study(err_linf, [128, 256])
    assert linf["fitted_order"] >= MIN_ORDER_LINF


def test_off_edge_order():
    out = []
    for n in (64, 128, 256):
        case = fields.hertz_case(n, 1.0, 0.7)
        x, y = case.grid.mesh()
        keep = np.abs(np.hypot(x, y / 0.7) - 1.0) > 0.1
        e = np.abs(case.displacement_numerical - case.displacement_analytic)[keep].max()
        out.append((case.grid.dx, e))
    h, e = np.array(out).T
    assert np.all(refinement.observed_orders(h, e) >= MIN_ORDER)
