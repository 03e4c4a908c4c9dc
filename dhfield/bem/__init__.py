"""Boundary-element (DC-FFT) solvers on the elastic half-space: the one BEM facade.

* :mod:`dhfield.bem.operator` -- the forward operator: Love's influence
  coefficients, DC-FFT convolution on pyfftw, cached plans, symmetry mode.
* :mod:`dhfield.bem.backend` -- where the solver's arrays live: pyfftw (default), numpy with
  ``scipy.fft``, or CuPy on a GPU (``$DHFIELD_BEM_BACKEND``); states are returned on the host.
* :mod:`dhfield.bem.laws` -- traction-separation laws (Dugdale, exponential).
* :mod:`dhfield.bem.state` -- :class:`ContactState`, the one typed BEM solution.
* :mod:`dhfield.bem.solver` -- the self-consistent adhesive contact solver (one state).
* :mod:`dhfield.bem.branch` -- :class:`~dhfield.bem.branch.Branch`, the states of one
  problem along the approach: the engine under every pull-off route.
* :mod:`dhfield.bem.continuation` -- states at a prescribed adhesive force (the fold).
* :mod:`dhfield.bem.path` -- loading-unloading paths: the bracket search, the
  marching path, the continuation (:func:`unloading_path` dispatches).
* :mod:`dhfield.bem.pull_off` -- the pull-off in the paper's units from a given
  start (:class:`UnloadingStart`): located, bracket, march, continuation, coarse to fine,
  each answering with the one pull-off record :class:`dhfield.core.records.PullOff`.

This package imports no analytic model: the start of the paper's problem is chosen
from the models by :mod:`dhfield.analysis.bem_start`, whose :func:`adhesive_pull_off`,
:func:`refine_pull_off` and :func:`nondimensional_problem` are forwarded here on
first use (``from dhfield.bem import adhesive_pull_off`` keeps working).  The public
names of :mod:`dhfield.bem.operator` are re-exported here, so
``from dhfield import bem; bem.get_operator(...)`` keeps working.
"""
from .operator import *  # noqa: F401,F403
from .operator import __all__ as _operator_all
from ._wisdom import save_wisdom  # noqa: F401  (not public: verification/bench_bem saves its own plans)
from .laws import DugdaleLaw, ExponentialLaw, cell_fraction_below  # noqa: E402
from .state import ContactState, mask_semi_axes  # noqa: E402
from .solver import (DEFAULT_MAX_ITER, DEFAULT_TOL, ContactPressureSolution, solve_adhesive,  # noqa: E402
                     solve_contact_pressure)
from .continuation import (FoldSearch, adhesive_force, fit_fold, fold_by_adhesive_force,  # noqa: E402
                           solve_at_adhesive_force)
from .branch import UnloadingPath  # noqa: E402
from .path import Fold, PathOptions, fold_of_branch, unloading_path  # noqa: E402
from .pull_off import (DEFAULT_STEPS, DISPLACEMENT_CONTROL_NOTE, DOMAIN_MARGIN, SEARCHES,  # noqa: E402
                       NestedWarmStart, NondimensionalProblem, UnloadingStart, interpolate_state, pull_off_summary,
                       paper_problem, richardson_extrapolation, solve_pull_off)

#: Names of :mod:`dhfield.analysis.bem_start` forwarded on first use (it imports the analytic models).
_FROM_START = ("adhesive_pull_off", "refine_pull_off", "nondimensional_problem", "unloading_start")

__all__ = list(_operator_all) + [
    "DugdaleLaw", "ExponentialLaw", "cell_fraction_below", "ContactState", "mask_semi_axes",
    "DEFAULT_MAX_ITER", "DEFAULT_TOL", "ContactPressureSolution", "solve_adhesive", "solve_contact_pressure",
    "FoldSearch", "adhesive_force", "fit_fold", "fold_by_adhesive_force", "solve_at_adhesive_force",
    "UnloadingPath", "Fold", "PathOptions", "fold_of_branch", "unloading_path",
    "DEFAULT_STEPS", "DISPLACEMENT_CONTROL_NOTE", "DOMAIN_MARGIN", "SEARCHES", "pull_off_summary",
    "NestedWarmStart", "NondimensionalProblem", "UnloadingStart", "interpolate_state", "paper_problem",
    "solve_pull_off", "richardson_extrapolation", *_FROM_START]


def __getattr__(name):
    if name in _FROM_START:
        from ..analysis import bem_start

        return getattr(bem_start, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
