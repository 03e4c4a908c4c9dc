"""dhfield: the extended double-Hertz model of an adhesive elliptical contact.

Zini, de Rooij, Bazr Afshan Fadafan, Ismail & Schipper, Tribology Letters 66 (2018) 30,
doi:10.1007/s11249-017-0976-8, verified against a DC-FFT boundary-element solver.

Quick start (nondimensional units of Eqs. 32-35), with the recommended model
(``dhfield.analysis.compare.RECOMMENDED_MODEL``; the paper's model is ``model="dh-elliptic"``)::

    >>> import dhfield
    >>> p = dhfield.pull_off(mu=1.0, beta0=0.9)
    >>> p.model, round(float(p.W_star), 4)
    ('md-elliptic', -0.7901)
    >>> round(float(dhfield.pull_off("dh-elliptic", mu=1.0, beta0=0.9).W_star), 4)
    -0.7714

Package map, bottom up: one folder a layer.  A layer imports only the layers before it
(and itself); ``tests/test_layout.py`` reads the folders and checks this against the import
statements::

    folder      holds                                                     may import
    ----------  --------------------------------------------------------  ------------------------
    core/       validation, the paper's units, the variable table,        nothing of dhfield
                records, elliptic integrals, geometry (Eqs. 2-6), the
                one pull-off search, mu and lambda, progress lines
    models/     one module per model, named as on the command line        core
                (md_elliptic, dh_elliptic and its closures, jkr_elliptic,
                jkr_elliptic_energy, maugis_dugdale, jkr, dmt,
                dh_circular, hertz) and the registry of their names
    bem/        DC-FFT boundary elements: operator, laws, solver, paths,  core (+ one lazy forward
                pull-off; it imports no model                             of analysis.bem_start)
    analysis/   compare, validity and model error, the SI front end,      core, models, bem
                fits, the spring, the BEM started from the models,
                fields and Eq. 30, the adhesion map, force vs angle
    io/         files (xarray, netCDF, pandas) and figures (matplotlib)   all of the above
    sweep/      dask sweeps                                               all of the above, io
    cli/        the ``dhfield`` command                                   everything

Every model, the BEM included, answers with the two records of :mod:`dhfield.core.records`:
``PullOff`` (nondimensional; with an SI group for physical inputs, a spring group under a
machine spring and a solver group for the BEM) and ``LoadCurve`` (nondimensional or SI).

The core (every layer but the edges) is numpy/scipy only: it imports no xarray, matplotlib,
pandas, netCDF4 or dask, and no edge module.
"""
__version__ = "0.1.0"
PAPER_DOI = "10.1007/s11249-017-0976-8"

import importlib as _importlib  # noqa: E402

#: Public names and the module each comes from.  They are imported on first use, so that
#: ``import dhfield.cli`` stays light: a Ctrl-C while the CLI starts then reaches its
#: one-line handler instead of printing a traceback from inside scipy's import.
_LAZY = {"LoadCurve": "core.records", "PullOff": "core.records", "load_curve": "analysis.compare",
         "pull_off": "analysis.compare", "solve_adhesive_axis": "models.dh_elliptic",
         "MODEL_NAMES": "models.registry", "RECOMMENDED_MODEL": "models.registry",
         "DhfieldWarning": "analysis.validity", "OutsideVerifiedDomainWarning": "analysis.validity",
         "ImplausibleInputWarning": "analysis.validity", "contact_parameters": "analysis.dimensional",
         "contact_parameters_from_principal_radii": "analysis.dimensional",
         "crossed_cylinder_radii": "analysis.dimensional", "load_curve_si": "analysis.dimensional",
         "pull_off_force": "analysis.dimensional",
         # the inverse problem pulls in every model
         "fit_work_of_adhesion": "analysis.fit", "fit_curve": "analysis.fit"}

#: Where the modules that sat flat in ``dhfield/`` before the layers had folders now live
#: (``import dhfield.model`` still works, with a DeprecationWarning; see :class:`_MovedModules`).
MOVED_MODULES = {
    "_validation": "core.validation", "_memory": "core.memory", "schema": "core.schema",
    "records": "core.records", "elliptic": "core.elliptic", "geometry": "core.geometry",
    "pull_off_search": "core.pull_off_search", "transition": "core.transition",
    "refinement": "core.refinement", "solve_progress": "core.progress", "_adhesion": "core.units",
    "hertz": "models.hertz", "model": "models.dh_elliptic", "double_hertz": "models.dh_elliptic_fields",
    "adhesion": "models.dh_elliptic_adhesion", "closure": "models.dh_elliptic_closure",
    "periphery": "models.dh_elliptic_periphery", "_rays": "models.dh_elliptic_rays",
    "jkr": "models.jkr", "dmt": "models.dmt", "dh_circular": "models.dh_circular",
    "maugis_dugdale": "models.maugis_dugdale", "dugdale_separation": "models.maugis_dugdale_separated",
    "jkr_elliptic": "models.jkr_elliptic", "jkr_elliptic_energy": "models.jkr_elliptic_energy",
    "elliptic_transition": "models.md_elliptic",
    "compare": "analysis.compare", "validity": "analysis.validity", "model_error": "analysis.model_error",
    "_truth_table": "analysis._truth_table", "dimensional": "analysis.dimensional", "fit": "analysis.fit",
    "compliance": "analysis.spring", "bem_compliance": "analysis.bem_spring",
    "adhesive_start": "analysis.bem_start", "adhesion_map": "analysis.adhesion_map",
    "force_vs_angle": "analysis.force_vs_angle", "fields": "analysis.fields",
    "field_sampling": "analysis.field_sampling", "field_metrics": "analysis.field_metrics",
    "polar": "analysis.polar", "eq30": "analysis.eq30", "plotting": "io.sweep_maps",
}

__all__ = ["__version__", "PAPER_DOI", "load_curve", "pull_off", "solve_adhesive_axis", "LoadCurve",
           "PullOff", "MODEL_NAMES", "RECOMMENDED_MODEL", "DhfieldWarning", "OutsideVerifiedDomainWarning",
           "ImplausibleInputWarning", "contact_parameters", "contact_parameters_from_principal_radii",
           "crossed_cylinder_radii", "pull_off_force", "load_curve_si", "fit_work_of_adhesion", "fit_curve"]


class _MovedModules:
    """Import hook: ``dhfield.<old flat name>`` is the module at its new place (the same object)."""

    @staticmethod
    def find_spec(fullname, path=None, target=None):
        prefix = __name__ + "."
        if not fullname.startswith(prefix) or fullname[len(prefix):] not in MOVED_MODULES:
            return None
        import importlib.util

        return importlib.util.spec_from_loader(fullname, _MovedModules)

    @staticmethod
    def create_module(spec):
        import warnings

        new = f"{__name__}.{MOVED_MODULES[spec.name[len(__name__) + 1:]]}"
        warnings.warn(f"{spec.name} has moved to {new}; import it from there", DeprecationWarning, stacklevel=3)
        return _importlib.import_module(new)

    @staticmethod
    def exec_module(module):
        """The module was executed at its new place."""


import sys as _sys  # noqa: E402

if not any(f is _MovedModules or getattr(f, "__qualname__", "") == "_MovedModules" for f in _sys.meta_path):
    _sys.meta_path.append(_MovedModules)


def __getattr__(name):
    if name in _LAZY:
        return getattr(_importlib.import_module(f".{_LAZY[name]}", __name__), name)
    if not name.startswith("__"):
        try:  # submodules as attributes (dhfield.models.dh_elliptic, dhfield.bem, ...), as when they were imported eagerly
            return _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module 'dhfield' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
