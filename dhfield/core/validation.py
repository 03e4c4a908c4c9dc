"""Input validation shared by every public function.

Every check raises :class:`ValueError` whose message names the parameter,
states its valid range and repeats the offending value, e.g.::

    beta0 must be in (0, 1] (ellipticity ratio b/a, dimensionless); got 1.2

The CLI turns these messages into a one-line error and exit status 2.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = [
    "check_finite",
    "check_interval",
    "check_positive",
    "check_ellipticity",
    "check_array_input",
    "check_count",
    "check_tabor",
    "check_model_ellipticity",
    "as_circle",
    "CIRCLE_TOLERANCE",
    "check_contact_size_star",
    "check_control",
    "check_grid_point",
    "CONTROLS",
    "TABOR_RANGE",
    "ELLIPTICITY_RANGE",
    "CONTACT_SIZE_RANGE",
]

#: Accepted Tabor parameter mu of Eq. (35) for every nondimensional model.  Below
#: 1e-6 every model is at its DMT limit to < 1e-3 relative and above 1e12 at its
#: JKR limit to < 1e-6; outside, the adhesive zone (~mu^-1/2 wide on the DMT side,
#: ~mu^-2 on the JKR side) is no longer resolved in double precision.
TABOR_RANGE = (1e-6, 1e12)
#: Accepted Hertz ellipticity beta0 = b/a of the nondimensional models: below 1e-4
#: R'/R'' > 3e3 (a line contact) and the elliptic integrals of Eq. (8) lose accuracy.
ELLIPTICITY_RANGE = (1e-4, 1.0)
#: Accepted nondimensional contact size a* = a/c_r (Eq. 32): below 1e-6 the state
#: equals the zero-contact limit to ~1e-6; above 1e6 the load W* ~ a*^3 nears 1e18
#: and the adhesive correction is below rounding.
CONTACT_SIZE_RANGE = (1e-6, 1e6)


def check_array_input(name: str, value) -> None:
    """Reject numpy masked arrays (their mask would be silently dropped) and empty arrays.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The input to check.

    Raises
    ------
    ValueError
        If ``value`` is a :class:`numpy.ma.MaskedArray` or has no element.
    """
    if isinstance(value, np.ma.MaskedArray):
        raise ValueError(f"{name} must not be a masked array (the mask would be ignored); "
                         f"pass {name}.compressed() or fill the masked values")
    if np.size(value) == 0:
        raise ValueError(f"{name} must contain at least one value; got an empty array")


def _describe(value) -> str:
    arr = np.asarray(value)
    if arr.ndim == 0:
        return repr(arr.item())
    return f"array of shape {arr.shape}"


def check_finite(name: str, value, what: str = "") -> np.ndarray:
    """Check that every element of ``value`` is a finite real number.

    Masked arrays are rejected: their mask would be silently dropped.  So are complex numbers and
    dates or durations, which numpy would convert to a float without an error.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The input to check.
    what : str, optional
        What the parameter is and its units, added to the message in parentheses.

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape (0-d for a scalar).

    Raises
    ------
    ValueError
        If an element is NaN or infinite, or ``value`` is not real numbers; the message names
        ``name`` and the first offending value.
    """
    if isinstance(value, np.ma.MaskedArray):
        check_array_input(name, value)
    _check_real(name, value, what)
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a finite real number{_what(what)}; got {value!r}") from None
    if not np.all(np.isfinite(arr)):
        bad = float(arr[~np.isfinite(arr)].flat[0])
        raise ValueError(f"{name} must be finite{_what(what)}; got {bad!r}")
    return arr


def _check_real(name: str, value, what: str = "") -> None:
    """Reject complex and date/time input by name (numpy would keep the real part of a complex with
    only a ComplexWarning, and turn a datetime64 or timedelta64 into its count of time units)."""
    try:
        complex_ = np.iscomplexobj(value)
        kind = np.asarray(value).dtype.kind
    except Exception:  # noqa: BLE001 - objects numpy cannot inspect: the float conversion names them
        return
    if complex_:
        raise ValueError(f"{name} must be real{_what(what)}; got complex {_describe(value)}")
    if kind in "mM":
        raise ValueError(f"{name} must be a real number{_what(what)}; got a date/time {_describe(value)}")


def _what(what: str) -> str:
    return f" ({what})" if what else ""


def check_interval(name: str, value, low: float, high: float, *, low_open: bool = True,
                   high_open: bool = False, what: str = "") -> np.ndarray:
    """Check that every element of ``value`` lies in an interval, by default ``(low, high]``.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The input to check; it must be finite (:func:`check_finite`).
    low, high : float
        The interval's ends, in the units of ``value``; ``high`` may be ``math.inf``.
    low_open : bool, optional
        Exclude ``low`` from the interval (default) or include it.
    high_open : bool, optional
        Exclude ``high`` from the interval, or include it (default).
    what : str, optional
        What the parameter is and its units, added to the message in parentheses.

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape.

    Raises
    ------
    ValueError
        If an element is not finite or lies outside the interval; the message names ``name``,
        writes the interval with its brackets, e.g. ``(0, 1]``, and repeats the first offending
        value.
    """
    arr = check_finite(name, value, what)
    lo_ok = arr > low if low_open else arr >= low
    hi_ok = arr < high if high_open else arr <= high
    if not np.all(lo_ok & hi_ok):
        bad = float(arr[~(lo_ok & hi_ok)].flat[0])
        lb = "(" if low_open else "["
        hb = ")" if high_open else "]"
        hs = "inf" if math.isinf(high) else f"{high:g}"
        raise ValueError(f"{name} must be in {lb}{low:g}, {hs}{hb}{_what(what)}; got {bad!r}")
    return arr


def check_positive(name: str, value, what: str = "", *, allow_zero: bool = False) -> np.ndarray:
    """Check that every element of ``value`` is finite and positive (or zero, if allowed).

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The input to check.
    what : str, optional
        What the parameter is and its units, added to the message in parentheses.
    allow_zero : bool, optional
        Accept zero, the interval ``[0, inf)`` instead of ``(0, inf)``.

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape.

    Raises
    ------
    ValueError
        If an element is not finite, negative, or zero where zero is not allowed.
    """
    return check_interval(name, value, 0.0, math.inf, low_open=not allow_zero, high_open=True,
                          what=what)


def check_ellipticity(name: str, value) -> np.ndarray:
    """Check an ellipticity ratio beta = b/a in (0, 1].

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        Ratio of the minor to the major semi-axis [-].

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape [-].

    Raises
    ------
    ValueError
        If an element is not finite or outside (0, 1].
    """
    return check_interval(name, value, 0.0, 1.0, what="ellipticity ratio b/a, dimensionless")


def check_count(name: str, value, low: int, high: int, what: str = "") -> int:
    """Check an integer count ``low <= value <= high``.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : int
        The count.  A float is accepted only if it has no fraction (``5.0``); a bool, a string,
        None and NaN are refused.
    low, high : int
        The smallest and the largest count accepted (both included).
    what : str, optional
        What the count is, added to the message in parentheses.

    Returns
    -------
    int
        ``value`` as a Python int.

    Raises
    ------
    ValueError
        If ``value`` is not an integer or lies outside ``[low, high]``.
    """
    ok = isinstance(value, (int, np.integer)) and not isinstance(value, bool)
    if not ok and isinstance(value, (float, np.floating)) and float(value).is_integer():
        ok = True
    if not ok or not (low <= int(value) <= high):
        raise ValueError(f"{name} must be an integer in [{low}, {high}]{_what(what)}; got {value!r}")
    return int(value)


def check_optional_count(name: str, value, what: str = ""):
    """Check ``value`` is None or an integer >= 1 (no bools, no floats); return it (an int) or None."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be None or an integer >= 1{_what(what)}; got {value!r}")
    return int(value)


def check_tabor(name: str, value) -> np.ndarray:
    """Check a Tabor parameter mu (Eq. 35) against :data:`TABOR_RANGE` (both ends included).

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The Tabor parameter mu of Eq. (35) [-].

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape [-].

    Raises
    ------
    ValueError
        If an element is not finite or outside :data:`TABOR_RANGE`.
    """
    return check_interval(name, value, *TABOR_RANGE, low_open=False,
                          what="Tabor parameter of Eq. (35), dimensionless")


#: Ellipticities within this of 1 are the circle, exactly (:func:`as_circle`): 1 - beta0 <= sqrt(eps)
#: = 1.49e-8.  Where beta0 -> 1 the elliptical forms lose digits like eps/(1 - beta0) (the Hertz
#: integrals' modulus k^2 = 1 - beta^2 and elliptical JKR's path u = (beta - beta0)/(1 - beta0)
#: carry 1 - beta0: elliptical JKR's pull-off contact is off by 3e-5 at 1 - beta0 = 1e-12 and by
#: 3e-4 at 1e-13), while every model departs from its circle linearly, by about 0.4 (1 - beta0)
#: relative (the slopes of W* and a* of dh-elliptic at beta0 = 1).  The two errors balance at 1 - beta0 ~ sqrt(eps):
#: closer to 1, the circle is the more accurate answer, and 90 deg from SI input (beta0 =
#: 1 - 2^-53) is the sphere.
CIRCLE_TOLERANCE = math.sqrt(float(np.finfo(float).eps))


def as_circle(beta):
    """Set the ellipticities within :data:`CIRCLE_TOLERANCE` of 1 to exactly 1 (the circle).

    The one place where dhfield decides that an ellipticity is the circle; applied where a
    model's ellipticity is validated (:func:`check_model_ellipticity`).

    Parameters
    ----------
    beta : array_like
        Ellipticity ratios b/a [-].

    Returns
    -------
    numpy.ndarray
        ``beta`` as a float array, with every element ``>= 1 - CIRCLE_TOLERANCE`` replaced by 1 [-].
    """
    beta = np.asarray(beta, dtype=float)
    return np.where(beta >= 1.0 - CIRCLE_TOLERANCE, 1.0, beta)


def check_model_ellipticity(name: str, value) -> np.ndarray:
    """Check a model's Hertz ellipticity beta0 against :data:`ELLIPTICITY_RANGE`.

    Both ends are included; values within :data:`CIRCLE_TOLERANCE` of 1 become exactly 1, the
    circle (:func:`as_circle`).

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The Hertz ellipticity ratio beta0 = b/a [-].

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape, the near-circle set to 1 [-].

    Raises
    ------
    ValueError
        If an element is not finite or outside :data:`ELLIPTICITY_RANGE`.
    """
    return as_circle(check_interval(name, value, *ELLIPTICITY_RANGE, low_open=False,
                                    what="ellipticity ratio b/a, dimensionless"))


def check_contact_size_star(name: str, value) -> np.ndarray:
    """Check a nondimensional contact size a* against :data:`CONTACT_SIZE_RANGE` (ends included).

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts every message.
    value : array_like
        The contact semi-axis a* = a/c_r of Eq. (32) [-].

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array of the same shape [-].

    Raises
    ------
    ValueError
        If an element is not finite or outside :data:`CONTACT_SIZE_RANGE`.
    """
    return check_interval(name, value, *CONTACT_SIZE_RANGE, low_open=False,
                          what="contact semi-axis in units of c_r, Eq. (32)")


#: Loading modes of every pull-off: the minimum of the load (load control) or of the approach
#: (displacement control) along the unloading path.
CONTROLS = ("load", "displacement")


def check_control(control) -> str:
    """Check a loading mode, one of :data:`CONTROLS` (the one check of ``control`` in dhfield).

    Parameters
    ----------
    control : str
        ``"load"`` or ``"displacement"``.

    Returns
    -------
    str
        ``control``, unchanged.

    Raises
    ------
    ValueError
        If ``control`` is not one of :data:`CONTROLS`.
    """
    if not isinstance(control, str) or control not in CONTROLS:
        raise ValueError(f"control must be one of {CONTROLS} (loading mode); got {control!r}")
    return control


def check_grid_point(beta0, mu, control="load"):
    """Check the inputs of a nondimensional model's pull-off and broadcast them together.

    ``mu`` is checked first, so its message wins where both ``mu`` and ``beta0`` are bad.  An empty
    ``beta0`` or ``mu`` is refused by name: a pull-off needs at least one point.

    Parameters
    ----------
    beta0 : array_like
        Hertz ellipticity ratio b/a, checked by :func:`check_model_ellipticity` [-].
    mu : array_like
        Tabor parameter of Eq. (35), checked by :func:`check_tabor` [-].
    control : str, optional
        Loading mode, checked by :func:`check_control`.

    Returns
    -------
    beta0 : numpy.ndarray
        The checked ellipticity, broadcast with ``mu`` [-].
    mu : numpy.ndarray
        The checked Tabor parameter, broadcast with ``beta0`` [-].

    Raises
    ------
    ValueError
        If an input is empty, not finite, out of its range, or ``control`` is unknown.
    """
    for name, value in (("mu", mu), ("beta0", beta0)):
        if not isinstance(value, np.ma.MaskedArray) and np.size(value) == 0:
            raise ValueError(f"{name} must contain at least one value; got an empty array")
    mu = check_tabor("mu", mu)
    beta0 = check_model_ellipticity("beta0", beta0)
    check_control(control)
    beta0, mu = np.broadcast_arrays(beta0, mu)
    return beta0, mu


def check_sequence(name: str, value, what: str = "") -> np.ndarray:
    """Check a 1-d sequence of numbers (NaN allowed) and return it as a float array."""
    _check_real(name, value, what)
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a sequence of numbers{_what(what)}; got {value!r}") from None
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a 1-d sequence of numbers{_what(what)}; got shape {arr.shape}")
    return arr
