"""Shared numpydoc parameter text, filled into docstrings at import.

The parameters that many functions share (the material inputs R, E*, dgamma, the loading
mode, the state of the double-Hertz (DH) field, the Hertz contact) are described once, in
:data:`DOCDICT`, and named in a docstring by a placeholder line, in the manner of scipy's
``doccer``, matplotlib's ``_docstring.interpd`` and MNE's ``fill_doc``::

    @fill_doc
    def example(semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
                reduced_modulus=1.0):
        '''One line on what the function computes [unit].

        Parameters
        ----------
        %(dh_parameters)s
        '''

A placeholder ``%(name)s`` stands alone on its line; :func:`fill_doc` replaces that line by
the entry ``DOCDICT[name]``, every line of it indented as the placeholder was.  An entry is
one or more complete numpydoc items: the ``name : type`` line, then its description indented
by four spaces, with units in brackets.  The docstring is filled once, when the decorator
runs at import, so ``help()``, numpydoc validation and sphinx autodoc all read the filled
text; a placeholder that names no entry raises :class:`KeyError` at import, naming the
function and the placeholder.

Only text that means the same in every function that uses it belongs here: a parameter
whose meaning or valid range differs between models (the Dugdale stress of Maugis-Dugdale
against the peak stress of the double-Hertz field, say) keeps its own text.
"""
from __future__ import annotations

import re
import textwrap

__all__ = ["DOCDICT", "fill_doc", "fill_docstring"]


def _entry(text: str) -> str:
    """An entry as written below, dedented and without its surrounding blank lines."""
    return textwrap.dedent(text).strip("\n")


# --------------------------------------------------------------------------- material (SI)
_EFFECTIVE_RADIUS = _entry("""
    effective_radius : array_like
        Equivalent radius R = sqrt(R'R''), Eq. (5), finite and > 0 [m].
""")
_REDUCED_MODULUS = _entry("""
    reduced_modulus : array_like
        Reduced modulus E*, Eq. (6), finite and > 0 [Pa].
""")
_WORK_OF_ADHESION = _entry("""
    work_of_adhesion : array_like
        Work of adhesion dgamma, finite and > 0 [J/m^2].
""")
_EFFECTIVE_RADIUS_DEFAULT = _entry("""
    effective_radius : array_like, default 1
        Equivalent radius R = sqrt(R'R''), Eq. (5), finite and > 0 [m].
""")
_REDUCED_MODULUS_DEFAULT = _entry("""
    reduced_modulus : array_like, default 1
        Reduced modulus E*, Eq. (6), finite and > 0 [Pa].
""")

# --------------------------------------------------------------------------- the DH state (Eqs. 16-27)
_DH_STATE = _entry("""
    semi_major : array_like
        Contact semi-major axis a > 0 [m].
    adhesive_semi_major : array_like
        Adhesive semi-major axis c >= a [m].
    beta : array_like
        Common ellipticity beta = b/a = d/c in (0, 1] (Eq. 17) [-].
    scaling : array_like
        DH scaling factor v >= 0 [-].
""")

#: The shared parameter entries, by placeholder name.  Each value is one or more complete
#: numpydoc items without indentation (the placeholder's indentation is added when filled).
DOCDICT: dict[str, str] = {
    # ---- the SI material inputs of every analytic model
    "effective_radius": _EFFECTIVE_RADIUS,
    "reduced_modulus": _REDUCED_MODULUS,
    "work_of_adhesion": _WORK_OF_ADHESION,
    "material": _entry("""
        effective_radius, reduced_modulus, work_of_adhesion : array_like
            Equivalent radius R = sqrt(R'R'') (Eq. 5) [m], reduced modulus E* (Eq. 6) [Pa]
            and work of adhesion dgamma [J/m^2], each finite and > 0.
    """),
    "material_units_checked": _entry("""
        checked : bool, optional
            Validate the inputs (:func:`dhfield.core.units.check_material`); False on inputs
            validated already.
    """),
    "contact_radius": _entry("""
        contact_radius : array_like
            Contact radius a >= 0 [m].
    """),
    "elliptic_geometry": _entry("""
        radius_ratio, beta0 : array_like, optional
            R'/R'' >= 1, or its Hertz ellipticity beta0 in (0, 1] (give one) [-].
    """),
    # ---- the pull-off
    "control": _entry("""
        control : {'load', 'displacement'}
            Loading mode of the pull-off.
    """),
    "circle_beta0_mu": _entry("""
        beta0, mu : array_like
            Hertz ellipticity and Tabor parameter (Eq. 35) [-]; the circle of R = sqrt(R'R'')
            depends on mu only; the record has their broadcast shape.
    """),
    "circle_beta0_mu_unused": _entry("""
        beta0, mu : array_like
            Hertz ellipticity and Tabor parameter (Eq. 35) [-]: the model depends on neither;
            the record has their broadcast shape (the circle of R = sqrt(R'R'')).
    """),
    "pull_off_nondimensional_returns": _entry("""
        dhfield.core.records.PullOff
            The pull-off point, nondimensional (Eqs. 32-35).
    """),
    "pull_off_force_returns": _entry("""
        ndarray
            The pull-off force W [N] (:func:`pull_off`'s ``force``).
    """),
    # ---- the DH field (Eqs. 16-27) and the Hertz contact (Eqs. 7-15)
    "dh_state": _DH_STATE,
    "dh_material": _EFFECTIVE_RADIUS_DEFAULT + "\n" + _REDUCED_MODULUS_DEFAULT,
    "dh_parameters": _DH_STATE + "\n" + _EFFECTIVE_RADIUS_DEFAULT + "\n" + _REDUCED_MODULUS_DEFAULT,
    "effective_radius_default": _EFFECTIVE_RADIUS_DEFAULT,
    "reduced_modulus_default": _REDUCED_MODULUS_DEFAULT,
    "surface_xy": _entry("""
        x, y : array_like
            Surface coordinates, x along the major axis [m].
    """),
    "ellipticity": _entry("""
        beta : array_like
            Ellipticity ratio b/a in (0, 1] [-].
    """),
    "hertz_contact": _entry("""
        semi_major : array_like
            Semi-major axis a > 0 of the contact ellipse [m].
        beta : array_like
            Ellipticity ratio b/a in (0, 1] [-].
    """) + "\n" + _EFFECTIVE_RADIUS_DEFAULT + "\n" + _REDUCED_MODULUS_DEFAULT,
    "loaded_ellipse": _entry("""
        semi_major, semi_minor : array_like
            Semi-axes a >= b of the loaded ellipse [m].
        peak_pressure : array_like
            Po [Pa].
    """),
    "ellipsoid_lower_limit": _entry("""
        l : array_like
            Lower limit of integration, the root of Eq. (12) outside the ellipse and
            0 inside it [m^2].
    """),
    "ellipsoid_integrals_returns": _entry("""
        I1 : ndarray
            Integral of Eq. (B1) [m^-1].
        I2 : ndarray
            Integral of Eq. (B2) [m^-3].
        I3 : ndarray
            Integral of Eq. (B3) [m^-3].
    """),
}

_PLACEHOLDER = re.compile(r"%\((\w+)\)s")
_PLACEHOLDER_LINE = re.compile(r"^([ \t]*)%\((\w+)\)s[ \t]*$")


def fill_docstring(doc: str, docdict: dict[str, str] | None = None, *, where: str = "docstring") -> str:
    """Replace every placeholder line ``%(name)s`` of ``doc`` by its entry, indented as the placeholder.

    Parameters
    ----------
    doc : str
        The docstring to fill.
    docdict : dict of str to str, optional
        The entries by name; default :data:`DOCDICT`.
    where : str, optional
        What the docstring belongs to (a function's qualified name); it starts the error messages.

    Returns
    -------
    str
        ``doc`` with every placeholder line replaced; the other lines unchanged.

    Raises
    ------
    KeyError
        If a placeholder names no entry of ``docdict``; the message names ``where`` and the placeholder.
    ValueError
        If a placeholder does not stand alone on its line.
    """
    docdict = DOCDICT if docdict is None else docdict
    out = []
    for line in doc.split("\n"):
        m = _PLACEHOLDER_LINE.match(line)
        if m is None:
            if _PLACEHOLDER.search(line):
                raise ValueError(f"{where}: a docstring placeholder must stand alone on its line; got {line.strip()!r}")
            out.append(line)
            continue
        indent, name = m.groups()
        if name not in docdict:
            raise KeyError(f"{where}: unknown docstring placeholder %({name})s "
                           f"(the entries are those of dhfield.core._docstrings.DOCDICT)")
        out.extend(indent + row if row.strip() else "" for row in docdict[name].split("\n"))
    return "\n".join(out)


def fill_doc(obj):
    """Fill the placeholders of a function's or class's docstring from :data:`DOCDICT` (a decorator).

    Parameters
    ----------
    obj : function or class
        The object whose ``__doc__`` holds placeholder lines ``%(name)s``.

    Returns
    -------
    function or class
        ``obj`` itself, its ``__doc__`` filled (left as it is when docstrings are stripped, ``python -OO``).

    Raises
    ------
    KeyError
        If a placeholder names no entry; the message names the object and the placeholder.
    """
    if obj.__doc__ is not None:
        where = f"{getattr(obj, '__module__', '?')}.{getattr(obj, '__qualname__', repr(obj))}"
        obj.__doc__ = fill_docstring(obj.__doc__, where=where)
    return obj
