"""Self-consistent adhesive normal contact (DC-FFT BEM): the public names in one place.

The solver is split by concept:

* :mod:`dhfield.bem.solver` -- one state: the Polonsky-Keer inner problem, the
  Anderson-accelerated outer fixed point on the cohesive zone, the sub-cell
  zone edge (:func:`solve_adhesive`).
* :mod:`dhfield.bem.path` -- displacement-controlled loading and unloading
  paths, the load-control pull-off and the displacement-control fold
  (:func:`unloading_path`, :func:`fold_of_branch`).
* :mod:`dhfield.bem.continuation` -- states at a prescribed adhesive force (the
  approach an unknown): the branch through its fold, the displacement-control
  pull-off (:func:`fold_by_adhesive_force`).
* :mod:`dhfield.bem.pull_off` -- the pull-off in the paper's units
  (R = E* = Delta gamma = 1): bracket search, nested warm starts, coarse to
  fine, Richardson extrapolation (:func:`adhesive_pull_off`,
  :func:`refine_pull_off`).

This module re-exports their public names, so ``from dhfield.bem.adhesive
import adhesive_pull_off`` keeps working.
"""
from .continuation import (FoldSearch, adhesive_force, fit_fold, fold_by_adhesive_force,  # noqa: F401
                           solve_at_adhesive_force)
from .path import Fold, PathProgress, UnloadingPath, fold_of_branch, unloading_path  # noqa: F401
from .pull_off import (DEFAULT_STEPS, DISPLACEMENT_CONTROL_NOTE, DOMAIN_MARGIN, SEARCHES,  # noqa: F401
                       AdhesivePullOff, NestedWarmStart, NondimensionalProblem, adhesive_pull_off,
                       interpolate_state, nondimensional_problem, refine_pull_off,
                       richardson_extrapolation)
from .solver import (DEFAULT_MAX_ITER, DEFAULT_TOL, ContactPressureSolution, solve_adhesive,  # noqa: F401
                     solve_contact_pressure)

__all__ = ["solve_adhesive", "unloading_path", "adhesive_pull_off", "richardson_extrapolation",
           "nondimensional_problem", "UnloadingPath", "AdhesivePullOff", "NondimensionalProblem",
           "refine_pull_off", "interpolate_state", "NestedWarmStart", "fold_of_branch", "Fold",
           "DISPLACEMENT_CONTROL_NOTE", "DEFAULT_TOL", "DEFAULT_MAX_ITER", "DOMAIN_MARGIN",
           "DEFAULT_STEPS", "SEARCHES", "solve_at_adhesive_force", "adhesive_force", "fold_by_adhesive_force",
           "fit_fold", "FoldSearch", "solve_contact_pressure", "ContactPressureSolution"]
