"""Boundary-element (DC-FFT) solvers on the elastic half-space.

* :mod:`dhfield.bem.operator` -- the forward operator: Love's influence
  coefficients, DC-FFT convolution on pyfftw, cached plans, symmetry mode.
* :mod:`dhfield.bem.laws` -- traction-separation laws (Dugdale, exponential).
* :mod:`dhfield.bem.state` -- :class:`ContactState`, the one typed BEM solution.
* :mod:`dhfield.bem.solver` -- the self-consistent adhesive contact solver (one state).
* :mod:`dhfield.bem.path` -- loading-unloading paths, the pull-off and the fold.
* :mod:`dhfield.bem.pull_off` -- the pull-off in the paper's units, coarse to fine.
* :mod:`dhfield.bem.adhesive` -- the public names of the three, in one place.

The public names of :mod:`dhfield.bem.operator` are re-exported here, so
``from dhfield import bem; bem.get_operator(...)`` keeps working.
"""
from .operator import *  # noqa: F401,F403
from .operator import __all__ as _operator_all
from .laws import DugdaleLaw, ExponentialLaw, cell_fraction_below  # noqa: E402
from .state import ContactState, mask_semi_axes  # noqa: E402
from .adhesive import (AdhesivePullOff, UnloadingPath, adhesive_pull_off,  # noqa: E402
                       refine_pull_off, richardson_extrapolation, solve_adhesive, unloading_path)

__all__ = list(_operator_all) + ["DugdaleLaw", "ExponentialLaw", "cell_fraction_below", "ContactState",
                                 "mask_semi_axes", "AdhesivePullOff", "UnloadingPath", "adhesive_pull_off",
                                 "refine_pull_off", "richardson_extrapolation", "solve_adhesive", "unloading_path"]
