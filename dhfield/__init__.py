"""dhfield: the extended double-Hertz model of an adhesive elliptical contact.

Zini, de Rooij, Bazr Afshan Fadafan, Ismail & Schipper, Tribology Letters 66 (2018) 30,
doi:10.1007/s11249-017-0976-8, verified against a DC-FFT boundary-element solver.

Quick start (nondimensional units of Eqs. 32-35), with the recommended model
(``dhfield.compare.RECOMMENDED_MODEL``; the paper's model is ``model="dh-elliptic"``)::

    >>> import dhfield
    >>> p = dhfield.pull_off(mu=1.0, beta0=0.9)
    >>> p.model, round(float(p.W_star), 4)
    ('md-elliptic', -0.7901)
    >>> round(float(dhfield.pull_off("dh-elliptic", mu=1.0, beta0=0.9).W_star), 4)
    -0.7714

Package map, bottom up.  A layer imports only the layers named in its last column (and
itself); ``tests/test_layout.py`` checks this against the import statements::

    layer        modules                                   holds                          may import
    -----------  ----------------------------------------  -----------------------------  -------------------
    foundations  _validation _memory schema records        input checks, the variable     one another
                 elliptic geometry pull_off_search         table, result records,
                 _adhesion transition dugdale_separation   elliptic integrals, Eqs. 2-6,
                                                           the one pull-off search
    analytic     hertz double_hertz adhesion model _rays   the paper's model, Eqs. 7-36;  foundations
                 periphery eq30 closure                    theta_p, Eq. 30, closures
    comparison   jkr dmt dh_circular maugis_dugdale        JKR, DMT, GJ98, MD, elliptical foundations
                 jkr_elliptic jkr_elliptic_energy          JKR, the MD-to-JKR transition
                 elliptic_transition
    front        compare validity model_error              model registry, validity,      the three above
                 _truth_table dimensional compliance fit   error against the BEM truth,
                 adhesion_map force_vs_angle               SI front end, fitting, the
                                                           pull-off force against the
                                                           crossing angle
    bem          bem/                                      DC-FFT boundary elements:      foundations (+ one
                                                           operator, laws, solver, paths, lazy forward of
                                                           pull-off                       adhesive_start)
    bridge       adhesive_start fields field_sampling      BEM start from the analytic    all of the above
                 field_metrics polar refinement            models; analytic-vs-BEM
                 bem_compliance solve_progress             fields (grid sampling, error
                                                           metrics, polar resampling,
                                                           refinement studies); the BEM
                                                           under a spring; a BEM solve's
                                                           progress and time limit
    edges        io/ plotting sweep/ cli/                  files (xarray, netCDF,         io: the core;
                                                           pandas), figures (matplotlib), plotting: io; sweep:
                                                           dask sweeps, the command       core + io; cli: all

Every model, the BEM included, answers with the two records of :mod:`dhfield.records`:
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
_LAZY = {"LoadCurve": "records", "PullOff": "model", "load_curve": "compare", "pull_off": "compare",
         "solve_adhesive_axis": "model", "MODEL_NAMES": "compare", "RECOMMENDED_MODEL": "compare",
         "DhfieldWarning": "validity", "OutsideVerifiedDomainWarning": "validity",
         "ImplausibleInputWarning": "validity", "contact_parameters": "dimensional",
         "contact_parameters_from_principal_radii": "dimensional", "crossed_cylinder_radii": "dimensional",
         "load_curve_si": "dimensional", "pull_off_force": "dimensional",
         # the inverse problem pulls in every model
         "fit_work_of_adhesion": "fit", "fit_curve": "fit"}

__all__ = ["__version__", "PAPER_DOI", "load_curve", "pull_off", "solve_adhesive_axis", "LoadCurve",
           "PullOff", "MODEL_NAMES", "RECOMMENDED_MODEL", "DhfieldWarning", "OutsideVerifiedDomainWarning",
           "ImplausibleInputWarning", "contact_parameters", "contact_parameters_from_principal_radii",
           "crossed_cylinder_radii", "pull_off_force", "load_curve_si", "fit_work_of_adhesion", "fit_curve"]


def __getattr__(name):
    if name in _LAZY:
        return getattr(_importlib.import_module(f".{_LAZY[name]}", __name__), name)
    if not name.startswith("__"):
        try:  # submodules as attributes (dhfield.model, dhfield.bem, ...), as when they were imported eagerly
            return _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module 'dhfield' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
