"""Boundary-element (DC-FFT) solvers on the elastic half-space.

* :mod:`dhfield.bem.operator` -- the forward operator: Love's influence
  coefficients, DC-FFT convolution on pyfftw, cached plans, symmetry mode.

The public names of :mod:`dhfield.bem.operator` are re-exported here, so
``from dhfield import bem; bem.get_operator(...)`` keeps working.
"""
from .operator import *  # noqa: F401,F403
from .operator import __all__ as _operator_all
from .operator import _save_wisdom  # noqa: F401  (used by verification/bench_bem.py)

__all__ = list(_operator_all)
