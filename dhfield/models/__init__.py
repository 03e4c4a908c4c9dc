"""Every analytic model, one module per model, named as on the command line (``--model``).

* :mod:`dhfield.models.md_elliptic` -- ``md-elliptic``, the recommended model.
* :mod:`dhfield.models.dh_elliptic` -- ``dh-elliptic``, the paper's model (Eqs. 31-36), with
  :mod:`~dhfield.models.dh_elliptic_fields` (Eqs. 16-27), :mod:`~dhfield.models.dh_elliptic_adhesion`
  (Eqs. 28-31), :mod:`~dhfield.models.dh_elliptic_periphery` and :mod:`~dhfield.models.dh_elliptic_rays`
  (every ray theta_p) and :mod:`~dhfield.models.dh_elliptic_closure` (its closures:
  ``dh-elliptic-two-axis``, ``dh-elliptic-ray-average``).
* :mod:`dhfield.models.jkr_elliptic` -- ``jkr-elliptic``, Johnson & Greenwood (2005).
* :mod:`dhfield.models.jkr_elliptic_energy` -- ``jkr-elliptic-energy``, Giudici, Vella & Griffiths (2025).
* :mod:`dhfield.models.maugis_dugdale` -- ``md``, Maugis (1992); :mod:`~dhfield.models.maugis_dugdale_separated`,
  the same sphere out of contact.
* :mod:`dhfield.models.jkr`, :mod:`dhfield.models.dmt`, :mod:`dhfield.models.dh_circular` -- ``jkr``, ``dmt``,
  ``dh-circular`` (Greenwood & Johnson 1998).
* :mod:`dhfield.models.hertz` -- the non-adhesive elliptical Hertz contact (Eqs. 7-15).
* :mod:`dhfield.models.registry` -- every model by its name.

The models build on :mod:`dhfield.core` only.
"""
import importlib as _importlib


def __getattr__(name):
    """Submodules as attributes on first use (``dhfield.models.md_elliptic``)."""
    if not name.startswith("__"):
        try:
            return _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
