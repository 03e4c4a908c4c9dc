"""Grid-refinement studies: observed orders of convergence between successive grids.

Used by the BEM convergence checks (``verification/convergence_bem.py``, the report's
field section): an error computed on grids of decreasing cell size h, and the order
log(e_i/e_(i+1))/log(h_i/h_(i+1)) it converges at.
"""
from __future__ import annotations

import numpy as np

__all__ = ["observed_orders"]


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
