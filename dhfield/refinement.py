"""Grid-refinement studies: observed orders of convergence between successive grids.

Used by the BEM convergence checks (``verification/convergence_bem.py``, the report's
field section): an error measured on grids of decreasing cell size h, and the order
log(e_i/e_(i+1))/log(h_i/h_(i+1)) it converges at.
"""
from __future__ import annotations

import numpy as np

__all__ = ["observed_orders", "refinement_study"]


def observed_orders(h, err):
    """Compute the observed orders ``log(e_i/e_{i+1})/log(h_i/h_{i+1})`` between successive grids.

    Parameters
    ----------
    h : array_like
        Cell sizes of the grids [m].
    err : array_like
        Errors on those grids (any consistent unit).

    Returns
    -------
    ndarray
        The ``len(h) - 1`` observed orders [-].
    """
    h = np.asarray(h, dtype=float)
    e = np.asarray(err, dtype=float)
    return np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])


def refinement_study(error_of_n, ns):
    """Run a grid-refinement study.

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
    orders = np.concatenate([[np.nan], observed_orders(hs, errs)])
    fitted = float(np.polyfit(np.log(hs), np.log(errs), 1)[0]) if len(ns) > 1 else float("nan")
    return {"n": np.asarray(ns), "h": hs, "error": errs, "order": orders, "fitted_order": fitted}
