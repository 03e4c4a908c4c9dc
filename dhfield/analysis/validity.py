"""Where each analytic model is validated, and the warnings its pull-off records carry.

The policy behind the ``warning`` field of every pull-off record of :mod:`dhfield.analysis.compare`:

* :data:`VALIDITY_RANGES`: the (beta0, mu) box where each model was validated (provenance
  below); outside it a result is still computed and says so (:func:`validity_message`);
* for the paper's model, the departure of its pull-off from the recommended model
  ``md-elliptic`` (:mod:`dhfield.models.md_elliptic`, within 0.46 % of the stored BEM
  ground truth), warned above :data:`WARNING_THRESHOLD` (:func:`departure_warning`; about
  1 ms per point); :func:`closure_departure` gives the departure from the two-axis closure
  on request (about 200 ms per point, refusing beta0 < 0.3 and mu > 30).

The recommended model answers over the whole accepted domain; its entry in
:data:`VALIDITY_RANGES` is the box the stored boundary-element ground truth covers
(:data:`BEM_VERIFIED_BETA0`, :data:`BEM_VERIFIED_MU`), and outside it its records say that
the point is an unverified extrapolation.  The table of departures these thresholds come
from is in :mod:`dhfield.analysis.compare`.

Warnings
--------
A non-empty ``warning`` is also raised as a Python warning by :func:`dhfield.analysis.compare.pull_off`
(category :class:`OutsideVerifiedDomainWarning`), and implausible SI inputs are warned by
:mod:`dhfield.analysis.dimensional` (:class:`ImplausibleInputWarning`); both derive from
:class:`DhfieldWarning`, so that ``warnings.simplefilter("error", dhfield.DhfieldWarning)``
turns every one of them into an exception, and ``"ignore"`` silences them.
"""
from __future__ import annotations

import numpy as np

from ..models import dh_elliptic_closure, md_elliptic
from ..models import dh_elliptic
from ..core.validation import check_grid_point

__all__ = ["VALIDITY_RANGES", "WARNING_THRESHOLD", "JKR_PROXY_MU", "validity_message", "validity_table",
           "join_warnings", "departure_warning", "closure_departure", "BEM_VERIFIED_BETA0", "BEM_VERIFIED_MU",
           "DhfieldWarning", "OutsideVerifiedDomainWarning", "ImplausibleInputWarning", "warn_record"]


class DhfieldWarning(UserWarning):
    """Base category of every warning dhfield raises about its results or inputs."""


class OutsideVerifiedDomainWarning(DhfieldWarning):
    """A pull-off outside its model's validated domain, or off the recommended model.

    Raised as a Python warning with the ``warning`` of a record: outside the domain where its model is
    validated (:data:`VALIDITY_RANGES`) or, for the paper's model, departing from the recommended model
    by more than :data:`WARNING_THRESHOLD`.
    """


class ImplausibleInputWarning(DhfieldWarning):
    """An SI input far outside the physical range of its quantity, most likely given in the wrong unit."""


_NAN = float("nan")
#: Relative departure of the paper's pull-off force from the recommended model above which the
#: paper's model carries a warning ("more than 2 %").
WARNING_THRESHOLD = 0.02


_INF = float("inf")
#: Hertz ellipticity beta0 [-] and Tabor parameter mu [-] (Eq. 35) spanned by the stored boundary-element
#: ground truth, ``data/adhesive_ground_truth_extended.nc`` (the smallest and largest beta0 and mu with a
#: finite ``W_star_truth``; ``tests/test_one_default.py`` reads them back from the file): the box where the
#: recommended model is verified against the BEM (within 0.46 % of every stored case).
BEM_VERIFIED_BETA0 = (0.1, 1.0)
BEM_VERIFIED_MU = (0.1, 10.0)
#: Largest mu of the closures: the grid of the table above, capped by the closures' own accepted domain.
_CLOSURE_MU_MAX = min(30.0, dh_elliptic_closure.CLOSURE_MU_RANGE[1])
#: name -> ((beta0_min, beta0_max), (mu_min, mu_max)) where each model is validated; outside, its
#: results are still computed and carry a ``warning``.  Provenance:
#:
#: * md-elliptic (the recommended model): the box of the stored BEM ground truth, :data:`BEM_VERIFIED_BETA0`
#:   x :data:`BEM_VERIFIED_MU`, within 0.46 % of every stored case (``python -m
#:   verification.elliptic_transition``).  It answers the whole accepted domain, exact at its three
#:   limits, DMT (mu -> 0), the energy-minimising elliptical JKR of GVG (mu -> infinity) and MD on the
#:   sphere (beta0 = 1), smooth in between (:mod:`dhfield.models.md_elliptic`); outside the box that is
#:   an extrapolation no BEM case checked, and its records say so;
#: * dh-elliptic, dh-elliptic-jkr-beta: the paper's own range, "beta0 ranging from 0.8 to 0.99" and
#:   "0.5 <= mu <= 5" (Zini et al. 2018, Sec. 1); beta0 = 1 is the circular DH model;
#: * the closures: the grid of the table above (beta0 = 0.3-1, mu = 0.1-30), where they were solved
#:   and compared with elliptical JKR (mu -> infinity) and the circular DH model (beta0 = 1), capped
#:   by the domain :mod:`dhfield.models.dh_elliptic_closure` accepts (``CLOSURE_MU_RANGE``);
#: * jkr-elliptic and jkr: the JKR side of the adhesion map, mu >= 10 for the ellipse (within 0.3 %
#:   of the two-axis closure, table above) and lambda = 1.1272 mu >= 5 for the circle (Johnson &
#:   Greenwood 1997, doi:10.1006/jcis.1997.4984); dmt: lambda <= 0.1 (same map);
#: * the circular models at beta0 = 1 only (elsewhere they are the circle of R = sqrt(R'R'')).
VALIDITY_RANGES = {
    "md-elliptic": (BEM_VERIFIED_BETA0, BEM_VERIFIED_MU),
    "dh-elliptic": ((0.8, 1.0), (0.5, 5.0)),
    "dh-elliptic-two-axis": ((0.3, 1.0), (0.1, _CLOSURE_MU_MAX)),
    "dh-elliptic-ray-average": ((0.3, 1.0), (0.1, _CLOSURE_MU_MAX)),
    "dh-elliptic-jkr-beta": ((0.8, 1.0), (0.5, 5.0)),
    "dh-circular": ((1.0, 1.0), (0.0, _INF)),
    "jkr": ((1.0, 1.0), (4.4, _INF)),
    "dmt": ((1.0, 1.0), (0.0, 0.09)),
    "md": ((1.0, 1.0), (0.0, _INF)),
    "jkr-elliptic": ((0.0, 1.0), (10.0, _INF)),
    # the JKR limit like jkr-elliptic: BEM at mu = 5 is within 0.4 % of it (beta0 0.5-1, verification/jkr_limit.py)
    "jkr-elliptic-energy": ((0.0, 1.0), (10.0, _INF)),
}


def validity_table() -> str:
    """Tabulate each model's validated beta0 and mu (for ``--help`` and the README).

    Returns
    -------
    str
        One line per model.
    """
    return "\n".join(f"  {name:24s} beta0 {_interval(*b):14s} mu {_interval(*m)}"
                     for name, (b, m) in VALIDITY_RANGES.items())


def _interval(lo, hi):
    if lo == 0.0 and hi == _INF:
        return "any"
    if lo == hi:
        return f"= {lo:g}"
    if hi == _INF:
        return f">= {lo:g}"
    if lo == 0.0:
        return f"<= {hi:g}"
    return f"in [{lo:g}, {hi:g}]"


def validity_message(model, mu, beta0):
    """The validated range of a model and where (mu, beta0) leaves it ("" inside).

    Parameters
    ----------
    model : str
        One of :data:`MODEL_NAMES`.
    mu, beta0 : array_like
        Tabor parameter (Eq. 35) and Hertz ellipticity [-].

    Returns
    -------
    str or ndarray of str
        Empty where (mu, beta0) lies in :data:`VALIDITY_RANGES`.
    """
    (b_lo, b_hi), (m_lo, m_hi) = VALIDITY_RANGES[_known(model)]
    mu, beta0 = np.broadcast_arrays(np.asarray(mu, float), np.asarray(beta0, float))

    def one(m, b):
        if b_lo <= b <= b_hi and m_lo <= m <= m_hi:
            return ""
        if model == _REFERENCE:
            return (f"{model}: beta0 = {b:.4g}, mu = {m:.4g} is outside the BEM-verified box (beta0 "
                    f"{_interval(b_lo, b_hi)}, mu {_interval(m_lo, m_hi)}, the stored ground truth): an "
                    "extrapolation no boundary-element case checked")
        return (f"{model} is validated for beta0 {_interval(b_lo, b_hi)} and mu {_interval(m_lo, m_hi)}; "
                f"got beta0 = {b:.4g}, mu = {m:.4g}")

    out = np.array([one(m, b) for m, b in zip(mu.ravel(), beta0.ravel())], dtype=object).reshape(mu.shape)
    return out[()] if out.ndim == 0 else out


def join_warnings(*messages):
    """Join warning strings (or object arrays of them, broadcast) with '; ', skipping empty ones.

    Parameters
    ----------
    *messages : str or array_like of str
        The warnings, broadcast together.

    Returns
    -------
    str or ndarray of str
        The joined warnings, with the broadcast shape.
    """
    parts = np.broadcast_arrays(*(np.asarray(m, dtype=object) for m in messages))
    out = np.array(["; ".join(p for p in ps if p) for ps in zip(*(q.ravel() for q in parts))],
                   dtype=object).reshape(parts[0].shape)
    return out[()] if out.ndim == 0 else out


#: Kept for compatibility (unused by the warnings, whose reference is the recommended model): the
#: smallest mu at which elliptical JKR stands in for the two-axis closure.
JKR_PROXY_MU = 10.0
_REFERENCE = md_elliptic.MODEL_NAME


def _departure_warning(w_paper, w_ref, reason=""):
    w_paper, w_ref = np.broadcast_arrays(np.asarray(w_paper, float), np.asarray(w_ref, float))
    dep = w_paper / w_ref - 1.0

    def one(x):
        if np.isnan(x):
            return f"dh-elliptic could not be checked against {_REFERENCE}{reason}"
        if not abs(x) > WARNING_THRESHOLD:
            return ""
        return (f"dh-elliptic pull-off departs from the recommended model {_REFERENCE} by {100 * x:+.1f} % "
                f"(> {100 * WARNING_THRESHOLD:g} %): prefer the model {_REFERENCE}")

    out = np.array([one(x) for x in dep.ravel()], dtype=object).reshape(dep.shape)
    return out[()] if out.ndim == 0 else out


def closure_departure(mu, beta0, control="load"):
    """Relative departure of the paper's pull-off from the two-axis closure (about 200 ms per point).

    The measure of the table in :mod:`dhfield.analysis.compare`; the warning uses the
    recommended model instead (:func:`departure_warning`).

    Parameters
    ----------
    mu : array_like
        Tabor parameter of Eq. (35), > 0 [-].
    beta0 : array_like
        Hertz ellipticity b/a of the geometry, in (0, 1] [-].
    control : {'load', 'displacement'}

    Returns
    -------
    ndarray or float
        W*_paper / W*_two-axis - 1 at pull-off [-]; negative where the paper's
        model predicts less adhesion.  0 at beta0 = 1, where both are the circle.
    """

    beta0, mu = check_grid_point(beta0, mu, control)
    w = dh_elliptic.pull_off_nondimensional(beta0, mu, control=control).W_star
    ref = dh_elliptic_closure.pull_off_two_axis(beta0, mu, control=control).W_star
    out = np.asarray(w, float) / np.asarray(ref, float) - 1.0
    return out[()] if out.ndim == 0 else out


def departure_warning(w_paper, mu, beta0, control, reference_w_star=None):
    """The warning of the paper's model: its departure from the recommended model.

    Parameters
    ----------
    w_paper : ndarray
        Pull-off W* of ``dh-elliptic`` (Eq. 34) [-].
    mu, beta0 : ndarray
        Tabor parameter (Eq. 35) and Hertz ellipticity [-], already validated.
    control : {'load', 'displacement'}
        Loading mode of both pull-offs.
    reference_w_star : ndarray, optional
        W* of the recommended model ``md-elliptic`` where the caller has it; else it is
        computed here (:func:`dhfield.models.md_elliptic.pull_off_nondimensional`, about
        1 ms per point).

    Returns
    -------
    str or ndarray of str
        Empty where the departure W*_paper/W*_md-elliptic - 1 is at most
        :data:`WARNING_THRESHOLD` in magnitude.
    """
    reason = ""
    if reference_w_star is None:
        try:
            reference_w_star = md_elliptic.pull_off_nondimensional(beta0, mu, control=control).W_star
        except (ValueError, RuntimeError) as exc:  # never take the paper's result down with the check
            reference_w_star, reason = np.nan, f" ({exc})"
    return _departure_warning(w_paper, np.broadcast_to(reference_w_star, np.shape(w_paper)), reason)


def warn_record(rec, stacklevel=2):
    """Raise a record's non-empty ``warning`` as a Python warning (:class:`OutsideVerifiedDomainWarning`).

    One warning per call: the message itself for a scalar record; for an array, how many
    points warn and the first distinct messages.

    Parameters
    ----------
    rec : dhfield.core.records.PullOff or mapping
        A pull-off record with a ``warning`` field (str or object array of str).
    stacklevel : int
        As for :func:`warnings.warn`, counted from the caller of this function.
    """
    import warnings

    msgs = np.asarray(rec["warning"], dtype=object).ravel()
    said = [str(m) for m in msgs if m]
    if not said:
        return
    if msgs.size == 1:
        text = said[0]
    else:
        distinct = list(dict.fromkeys(said))
        text = (f"{len(said)} of {msgs.size} points warn: " + "; ".join(distinct[:2])
                + (f"; and {len(distinct) - 2} other messages" if len(distinct) > 2 else ""))
    warnings.warn(text, OutsideVerifiedDomainWarning, stacklevel=stacklevel + 1)


def _known(model):
    if model not in VALIDITY_RANGES:
        raise ValueError(f"model must be one of {', '.join(VALIDITY_RANGES)}; got {model!r}")
    return model
