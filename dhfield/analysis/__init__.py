"""What is built on the models and the BEM together: comparison, errors, the SI front end, fits, the spring,
fields and their cross-check, the adhesion map.

* :mod:`dhfield.analysis.compare` -- every model behind one interface (``pull_off``, ``compare``, ``load_curve``).
* :mod:`dhfield.analysis.validity`, :mod:`dhfield.analysis.model_error` -- where each model is validated, and
  its error against the stored BEM ground truth.
* :mod:`dhfield.analysis.dimensional` -- materials and contact geometry in SI units.
* :mod:`dhfield.analysis.fit` -- the inverse problem: work of adhesion and adhesive stress from measurements.
* :mod:`dhfield.analysis.spring` -- the analytic contact in series with a machine spring.
* :mod:`dhfield.analysis.bem_start`, :mod:`dhfield.analysis.bem_spring` -- the BEM pull-off started from the
  analytic models, free and under a spring.
* :mod:`dhfield.analysis.fields`, :mod:`~dhfield.analysis.field_sampling`, :mod:`~dhfield.analysis.field_metrics`,
  :mod:`~dhfield.analysis.polar` -- analytic and BEM fields on one grid, and their comparison.
* :mod:`dhfield.analysis.eq30` -- Eq. (30) as printed and what it measures.
* :mod:`dhfield.analysis.adhesion_map`, :mod:`dhfield.analysis.force_vs_angle` -- where each model agrees with
  the ground truth; the pull-off force against the crossing angle.

It builds on :mod:`dhfield.core`, :mod:`dhfield.models` and :mod:`dhfield.bem`; it imports no xarray or
matplotlib.
"""
import importlib as _importlib


def __getattr__(name):
    """Submodules as attributes on first use (``dhfield.analysis.compare``)."""
    if not name.startswith("__"):
        try:
            return _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
