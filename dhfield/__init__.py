"""dhfield: the extended double-Hertz model of an adhesive elliptical contact.

Zini, de Rooij, Bazr Afshan Fadafan, Ismail & Schipper, Tribology Letters 66 (2018) 30,
doi:10.1007/s11249-017-0976-8, verified against a DC-FFT boundary-element solver.

Quick start (nondimensional units of Eqs. 32-35)::

    >>> import dhfield
    >>> p = dhfield.pull_off(mu=1.0, beta0=0.9)
    >>> round(float(p.W_star), 4)
    -0.7714
"""
__version__ = "0.1.0"
PAPER_DOI = "10.1007/s11249-017-0976-8"

from .model import LoadCurve, PullOff, load_curve, pull_off, solve_adhesive_axis  # noqa: E402
from .compare import MODEL_NAMES  # noqa: E402
from .dimensional import (contact_parameters, contact_parameters_from_principal_radii,  # noqa: E402
                          crossed_cylinder_radii, load_curve_si, pull_off_force)

__all__ = ["__version__", "PAPER_DOI", "load_curve", "pull_off", "solve_adhesive_axis", "LoadCurve",
           "PullOff", "MODEL_NAMES", "contact_parameters", "contact_parameters_from_principal_radii",
           "crossed_cylinder_radii", "pull_off_force", "load_curve_si", "fit_work_of_adhesion", "fit_curve"]


def __getattr__(name):
    # the inverse problem (dhfield.fit) is imported on first use: it pulls in every model
    if name in ("fit_work_of_adhesion", "fit_curve"):
        from . import fit

        return getattr(fit, name)
    raise AttributeError(f"module 'dhfield' has no attribute {name!r}")
