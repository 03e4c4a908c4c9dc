"""The estimated error of each model's pull-off against the stored BEM ground truth.

Every pull-off of :mod:`dhfield.analysis.compare` carries ``model_error``, the estimated relative
error of its W* against the adhesive BEM (Dugdale law, load control), and ``bem_verified``,
whether the point lies in the box of the stored BEM cases.  Both come from the 57 cases of
``data/adhesive_ground_truth_extended.nc`` (beta0 0.1-1, mu 0.1-10), with every model's W*
at those cases tabulated once in :mod:`dhfield.analysis._truth_table`
(``python -m verification.model_error_table``).

The error of a model at a stored case is

.. math::

    e = \\frac{|W^*_\\mathrm{model} - W^*_\\mathrm{truth}| + \\epsilon_\\mathrm{truth}}{|W^*_\\mathrm{truth}|},

its deviation from the stored truth plus the truth's own stated error
(``W_star_truth_error``), relative to the truth: the model's W* lies within e of the
grid-converged BEM pull-off, in proportion, at that case.  At a point (beta0, mu) in the
box, :func:`model_error` is the largest e over the bracketing stored cases: on each of the
two stored beta0 lines that bracket beta0 (one where beta0 is stored), the stored cases
nearest in mu at or below and at or above mu (up to four cases).  It is exact at the stored
cases and an estimate, not a bound, in between: held out one at a time, a stored case's error
is at most its neighbours' estimate at 37 of the 57 cases for ``md-elliptic`` (the estimate
short by at most 0.93 percentage points) and at 30 of 45 to 48 of 57 for the other models,
the median estimate 1.0-1.4 times the held-out error
(``python -m verification.model_error_table --leave-one-out``; a held-out case on the edge
of the box is then extrapolated from one side, which the estimate inside the box never is).

:func:`dhfield.analysis.compare.compare` also flags every model whose W* departs from the
recommended model's by more than :data:`dhfield.analysis.validity.WARNING_THRESHOLD` (2 %)
(:func:`departure_warning`).  The threshold exceeds the recommended model's own error
everywhere in the box (at most 1.53 %: ``tests/test_model_error.py``), so such a departure is a
departure from the BEM truth too, not noise of the reference.  A data-derived error cannot
be exceeded at the stored cases themselves (it is the deviation there), which is why the flag
is the departure from the recommended model and not from the model's own error.

Outside the box (beta0 < 0.1, mu < 0.1 or mu > 10), under displacement control (the
stored truth is load control), and where the model refused any of the bracketing cases
(the closures below beta0 = 0.3), the error is NaN and ``bem_verified`` False: no stored
case checks the answer there.
"""
from __future__ import annotations

import numpy as np

from . import _truth_table as _table

__all__ = ["VERIFIED_BETA0", "VERIFIED_MU", "TRUTH_SOURCE", "stored_case_error", "model_error", "bem_verified",
           "with_model_error", "departure_warning"]

_BETA0 = np.asarray(_table.BETA0, float)
_MU = np.asarray(_table.MU, float)
_TRUTH = np.asarray(_table.W_STAR_TRUTH, float)
_TRUTH_ERROR = np.asarray(_table.W_STAR_TRUTH_ERROR, float)

#: (smallest, largest) beta0 of the stored BEM cases [-].
VERIFIED_BETA0 = (float(_BETA0.min()), float(_BETA0.max()))
#: (smallest, largest) mu of the stored BEM cases [-].
VERIFIED_MU = (float(_MU.min()), float(_MU.max()))
#: The file the stored cases come from, and the command that tabulated the models there.
TRUTH_SOURCE = f"{_table.SOURCE} (built {_table.SOURCE_BUILT}; tabulated by {_table.COMMAND})"


def stored_case_error(model):
    """The relative error e of a model at every stored case (module docstring).

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.MODEL_NAMES`.

    Returns
    -------
    beta0 : ndarray
        Hertz ellipticity of each stored case [-].
    mu : ndarray
        Tabor parameter (Eq. 35) of each stored case [-].
    error : ndarray
        The error e at each stored case [-] (NaN where the model refused the case).
    """
    w = _model_values(model)
    with np.errstate(invalid="ignore"):
        e = (np.abs(w - _TRUTH) + _TRUTH_ERROR) / np.abs(_TRUTH)
    return _BETA0.copy(), _MU.copy(), e


def _model_values(model):
    try:
        return np.asarray(_table.W_STAR_MODEL[model], float)
    except KeyError:
        raise ValueError(f"model must be one of {', '.join(_table.W_STAR_MODEL)}; got {model!r}") from None


def bem_verified(beta0, mu, control="load"):
    """Whether points lie in the box of the stored BEM cases (load control).

    Parameters
    ----------
    beta0, mu : array_like
        Hertz ellipticity and Tabor parameter (Eq. 35) [-].
    control : {'load', 'displacement'}
        Loading mode; the stored truth is load control, so 'displacement' is never verified.

    Returns
    -------
    bool or ndarray of bool
        True inside :data:`VERIFIED_BETA0` x :data:`VERIFIED_MU` under load control.
    """
    beta0, mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))
    inside = ((beta0 >= VERIFIED_BETA0[0]) & (beta0 <= VERIFIED_BETA0[1])
              & (mu >= VERIFIED_MU[0]) & (mu <= VERIFIED_MU[1]) & (control == "load"))
    return inside[()] if inside.ndim == 0 else inside


def model_error(model, beta0, mu, control="load"):
    """Estimated relative error of a model's pull-off W* against the BEM ground truth.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.MODEL_NAMES`.
    beta0, mu : array_like
        Hertz ellipticity and Tabor parameter (Eq. 35) [-], broadcast together.
    control : {'load', 'displacement'}
        Loading mode of the pull-off.

    Returns
    -------
    float or ndarray
        The largest error e over the stored cases bracketing each point (module
        docstring), a fraction [-]; NaN outside the verified box, under displacement
        control, and where the model refused any of the bracketing cases.

    Examples
    --------
    At a stored case the error is the model's own deviation plus the truth's error:

    >>> from dhfield.analysis.model_error import model_error
    >>> float(model_error("md-elliptic", 1.0, 0.3)) < 1e-3
    True
    >>> import numpy as np
    >>> bool(np.isnan(model_error("md-elliptic", 0.05, 1.0)))  # beta0 below the stored cases
    True
    """
    _, _, e = stored_case_error(model)
    beta0, mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))
    inside = bem_verified(beta0, mu, control)
    out = np.full(beta0.size, np.nan)
    for i in np.flatnonzero(np.ravel(inside)):
        out[i] = _bracket_max(e, beta0.ravel()[i], mu.ravel()[i])
    out = out.reshape(beta0.shape)
    return out[()] if out.ndim == 0 else out


def _bracket_max(e, b, m, cases_beta0=_BETA0, cases_mu=_MU):
    """The largest e over the cases bracketing (b, m); NaN if the model refused any of them.

    ``cases_beta0``, ``cases_mu``: the cases e belongs to (default the stored ones; the leave-one-out
    check of ``python -m verification.model_error_table --leave-one-out`` passes fewer).
    """
    lines = np.unique(cases_beta0)
    lines = {lines[lines <= b].max(), lines[lines >= b].min()}
    picked = []
    for line in lines:
        on = np.flatnonzero(cases_beta0 == line)
        mus = cases_mu[on]
        below, above = on[mus <= m], on[mus >= m]
        if below.size:
            picked.append(below[np.argmax(cases_mu[below])])
        if above.size:
            picked.append(above[np.argmin(cases_mu[above])])
    values = e[picked]
    return float(values.max()) if values.size and np.all(np.isfinite(values)) else np.nan


def with_model_error(rec):
    """A pull-off record with its trust group filled (:data:`dhfield.core.schema.PULL_OFF_TRUST_KEYS`).

    Parameters
    ----------
    rec : dhfield.core.records.PullOff
        A pull-off of a model of :data:`dhfield.analysis.compare.MODEL_NAMES`.

    Returns
    -------
    dhfield.core.records.PullOff
        ``rec`` with ``model_error`` (:func:`model_error`; NaN also where ``W_star`` is not
        finite: the model gave no answer) and ``bem_verified`` (:func:`bem_verified`).
    """
    from ..core.records import broadcast_field

    shape = np.shape(rec.W_star)
    err = np.where(np.isfinite(rec.W_star), model_error(rec.model, rec.beta0, rec.mu, rec.control), np.nan)
    return rec.replace(model_error=broadcast_field(err, shape),
                       bem_verified=broadcast_field(bem_verified(rec.beta0, rec.mu, rec.control), shape, bool))


def departure_warning(model, w_star, reference_w_star, error=np.nan):
    """The warning of a model whose pull-off departs from the recommended model's by more than 2 %.

    Parameters
    ----------
    model : str
        The model's name.
    w_star, reference_w_star : array_like
        W* (Eq. 34) of the model and of the recommended model
        (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`) [-], broadcast together.
    error : array_like, optional
        The model's ``model_error`` at the same points [-], quoted in the warning (NaN: no
        stored BEM case checks the point).

    Returns
    -------
    str or ndarray of str
        Empty where |W*/W*_recommended - 1| is at most
        :data:`dhfield.analysis.validity.WARNING_THRESHOLD`, or where either W* is not finite.
    """
    from ..models.registry import RECOMMENDED_MODEL
    from .validity import WARNING_THRESHOLD

    w, ref, err = np.broadcast_arrays(np.asarray(w_star, float), np.asarray(reference_w_star, float),
                                      np.asarray(error, float))
    with np.errstate(invalid="ignore", divide="ignore"):
        dev = w / ref - 1.0

    def one(d, e):
        if not abs(d) > WARNING_THRESHOLD:  # also NaN: no answer to compare
            return ""
        trust = (f"its estimated error against the BEM ground truth here is {100 * e:.2g} %" if np.isfinite(e)
                 else "no stored BEM case checks this point")
        return (f"{model} departs from the recommended model {RECOMMENDED_MODEL} by {100 * d:+.1f} % "
                f"(> {100 * WARNING_THRESHOLD:g} %); {trust}")

    out = np.array([one(d, e) for d, e in zip(dev.ravel(), err.ravel())], dtype=object).reshape(dev.shape)
    return out[()] if out.ndim == 0 else out
