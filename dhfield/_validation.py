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
]


def _describe(value) -> str:
    arr = np.asarray(value)
    if arr.ndim == 0:
        return repr(arr.item())
    return f"array of shape {arr.shape}"


def check_finite(name: str, value, what: str = "") -> np.ndarray:
    """Return ``value`` as a float array; raise if any element is NaN or infinite."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a finite real number{_what(what)}; got {value!r}") from None
    if not np.all(np.isfinite(arr)):
        bad = float(arr[~np.isfinite(arr)].flat[0])
        raise ValueError(f"{name} must be finite{_what(what)}; got {bad!r}")
    return arr


def _what(what: str) -> str:
    return f" ({what})" if what else ""


def check_interval(name: str, value, low: float, high: float, *, low_open: bool = True,
                   high_open: bool = False, what: str = "") -> np.ndarray:
    """Check ``low < value <= high`` (openness selectable) element-wise."""
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
    """Check ``value > 0`` (or ``>= 0``) and finite, element-wise."""
    return check_interval(name, value, 0.0, math.inf, low_open=not allow_zero, high_open=True,
                          what=what)


def check_ellipticity(name: str, value) -> np.ndarray:
    """Check an ellipticity ratio beta = b/a in (0, 1]."""
    return check_interval(name, value, 0.0, 1.0, what="ellipticity ratio b/a, dimensionless")
