"""The foundations every layer builds on: input validation, the paper's units, the variable table, the
result records, elliptic integrals, the crossed-cylinder geometry and the one pull-off search.

* :mod:`dhfield.core.validation` -- input checks shared by every public function.
* :mod:`dhfield.core.memory` -- memory estimates checked before large allocations.
* :mod:`dhfield.core.units` -- the paper's nondimensional units (Eqs. 32-35) and the SI plumbing of the models.
* :mod:`dhfield.core.schema` -- one table of variable metadata (name, units, long_name) for every writer.
* :mod:`dhfield.core.records` -- the pull-off and load-curve records every model answers with.
* :mod:`dhfield.core.elliptic` -- complete elliptic integrals in the forms the Hertz problem needs.
* :mod:`dhfield.core.geometry` -- two equal cylinders crossed at an angle (Eqs. 2-6).
* :mod:`dhfield.core.pull_off_search` -- the one place where a pull-off point is located.
* :mod:`dhfield.core.transition` -- the paper's mu (Eq. 35) and Maugis' lambda.
* :mod:`dhfield.core.refinement` -- observed orders of convergence between grids.
* :mod:`dhfield.core.progress` -- one progress line per state of a long solve, and its time limit.

It imports nothing else of dhfield, and no xarray or matplotlib.
"""
import importlib as _importlib


def __getattr__(name):
    """Submodules as attributes on first use (``dhfield.core.schema``)."""
    if not name.startswith("__"):
        try:
            return _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
