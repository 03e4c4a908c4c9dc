"""Adhesion map for elliptical contacts: where each pull-off model agrees with the reference.

For equal cylinders crossed at an angle theta_skew (10-90 deg by default) and a Tabor
parameter mu (0.01-100 by default, Eq. 35), the load-control pull-off force of every
comparison model is set beside that of a reference model and the relative deviation is
mapped.  Johnson & Greenwood's (1997) adhesion map is for spheres; this is its elliptical
counterpart on the axes a practitioner uses (crossing angle, mu).

The reference, and how far it can be trusted
---------------------------------------------
The reference is the recommended DMT-to-JKR model, MD elliptical (:mod:`dhfield.models.md_elliptic`,
``md-elliptic``, :data:`dhfield.analysis.compare.DEFAULT_MODEL`), evaluated through :func:`recommended_pull_off` (the one place
that names it): exact at mu -> 0 (DMT of the paraboloid), at mu -> infinity (the
energy-minimising elliptical JKR of Giudici, Vella & Griffiths 2025) and on the circle
(Maugis-Dugdale).  It is **validated against the BEM only
where the stored ground truth exists**: the 57 cases of
``data/adhesive_ground_truth_extended.nc`` (every case of ``data/adhesive_ground_truth.nc`` and
``data/adhesive_ground_truth_slender.nc``, plus mu = 10 and the extended study) span beta0 in
[0.1, 1] (crossing angles of about 19-90 deg) and mu in [0.1, 10], the box of
:func:`dhfield.analysis.model_error.bem_verified`; the recommended model's largest deviation from them is
:data:`REFERENCE_TRUTH_DEVIATION`.  Elsewhere a deviation on this map is a deviation from the
recommended model, not from the truth.
:attr:`AdhesionMap.validated` marks the validated region (:data:`VALIDATED_BETA0`,
:data:`VALIDATED_MU`, read from the stored ground truth, or the ranges the caller passes).

Quantities
----------
* Every model is evaluated through :func:`dhfield.analysis.compare.pull_off` (load control), except
  the reference, evaluated by :func:`recommended_pull_off`.  ``dh-elliptic`` is evaluated with
  ``check_closure=False`` (the paper's model alone, ~1 ms per point; the two-axis check
  costs ~200 ms per point).
* ``force``: the pull-off force W/(pi R dgamma), R = sqrt(R'R'') (Eq. 5); from a record,
  ``2 W*/sin_skew`` (Eq. 34 inverted with the record's own ``sin_skew``: sin(theta_skew)
  for the elliptical models, 1 for the circular ones, which are the sphere of radius R).
  -2 is DMT, -1.5 the JKR sphere; negative is tensile.
* ``deviation``: force/force_reference - 1; positive where the model predicts more
  adhesion than the reference.
* ``status`` per point: :data:`STATUS_MEANINGS`.  A model that raises ``ValueError`` or
  ``RuntimeError`` for some inputs (e.g. the closures below beta0 = 0.3) is *refused* there:
  NaN, no answer, no exception.  A model that answers with a non-empty ``warning``
  (outside its own :data:`dhfield.analysis.compare.VALIDITY_RANGES`) or a Python warning is
  ``answered_with_warning``: the value is kept.

Crossing angle and beta0
------------------------
beta0 = :func:`dhfield.core.geometry.ellipticity_from_skew_angle` of the crossing angle (equal
cylinders, Eqs. 3-4 and the Hertz ratio of Eq. 8): 10 deg -> 0.0470, 30 deg -> 0.1806,
60 deg -> 0.4826, 90 deg -> 1.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _truth_table, compare, model_error
from ..models import md_elliptic
from ..core.validation import TABOR_RANGE, check_count, check_interval, check_tabor
from ..core.geometry import ellipticity_from_skew_angle, sin_skew_angle

__all__ = ["AdhesionMap", "adhesion_map", "map_grid", "recommended_pull_off", "REFERENCE_MODEL", "MAP_MODEL_NAMES",
           "MODEL_LABELS", "STATUS_MEANINGS", "VALIDATED_BETA0", "VALIDATED_MU",
           "DEFAULT_CROSSING_ANGLE_DEG", "DEFAULT_MU", "MAX_AXIS_POINTS", "REFERENCE_NOTE"]

#: Name of the reference model, the recommended one (:mod:`dhfield.models.md_elliptic`), read from
#: the registry, :data:`dhfield.analysis.compare.RECOMMENDED_MODEL`.
REFERENCE_MODEL = compare.RECOMMENDED_MODEL
#: The models of the map, reference first.
MAP_MODEL_NAMES = (REFERENCE_MODEL, "dh-elliptic", "jkr-elliptic", "jkr-elliptic-energy", "md", "dmt")
#: Readable names of the models (figures, tables).
MODEL_LABELS = {
    REFERENCE_MODEL: "MD elliptical (recommended)",
    "dh-elliptic": "Elliptical double-Hertz (Zini 2018)",
    "dh-elliptic-two-axis": "Double-Hertz, two-axis closure",
    "dh-elliptic-ray-average": "Double-Hertz, ray-average closure",
    "jkr-elliptic": "Elliptical JKR (Johnson-Greenwood 2005)",
    "jkr-elliptic-energy": "Elliptical JKR, energy (Giudici 2025)",
    "md": "Maugis-Dugdale, equivalent sphere",
    "dmt": "DMT",
    "jkr": "JKR, equivalent sphere",
    "dh-circular": "Double-Hertz, equivalent sphere",
}
#: Codes of :attr:`AdhesionMap.status`; codes 2 and 3 are 'no answer' (NaN).
STATUS_MEANINGS = ("answered", "answered_with_warning", "refused", "not_finite")
#: Extent of the stored BEM ground truth, load control, where the reference is validated: the box of
#: the stored cases (:data:`dhfield.analysis.model_error.VERIFIED_BETA0`, read from the stored ground truth).
VALIDATED_BETA0 = model_error.VERIFIED_BETA0
#: mu extent of the stored cases (:data:`dhfield.analysis.model_error.VERIFIED_MU`) [-].
VALIDATED_MU = model_error.VERIFIED_MU
#: The reference's largest relative deviation from the stored BEM cases, max |W*/W*_BEM - 1| [-]
#: (without the BEM's own stated error, which :func:`dhfield.analysis.model_error.model_error` adds).
REFERENCE_TRUTH_DEVIATION = float(np.max(np.abs(
    np.asarray(_truth_table.W_STAR_MODEL[compare.RECOMMENDED_MODEL]) / np.asarray(_truth_table.W_STAR_TRUTH) - 1.0)))
#: Default axes: crossing angle 10-90 deg [deg] and mu 0.01-100 [-].
DEFAULT_CROSSING_ANGLE_DEG = (10.0, 90.0)
DEFAULT_MU = (0.01, 100.0)
#: Largest number of points on one axis of :func:`map_grid` (a 2000 x 2000 map: ~1 min per model).
MAX_AXIS_POINTS = 2000
#: The one sentence every output of the map carries about its reference.
REFERENCE_NOTE = ("Reference: the recommended model md-elliptic (MD elliptical, dhfield.models.md_elliptic), not "
                  "the BEM. It is validated against the BEM only where the stored ground truth exists "
                  "(beta0 {b}, mu {m}: within " f"{100 * REFERENCE_TRUTH_DEVIATION:.2f}" " % of every case); "
                  "elsewhere a deviation is from the recommended model, not from the truth.")

_NAN = float("nan")


def _note(validated_beta0, validated_mu):
    return REFERENCE_NOTE.format(b=f"in [{validated_beta0[0]:g}, {validated_beta0[1]:g}]",
                                 m=f"in [{validated_mu[0]:g}, {validated_mu[1]:g}]")


@dataclass(frozen=True)
class AdhesionMap:
    """Pull-off of several models on a (crossing angle, mu) grid, against a reference.

    Parameters
    ----------
    crossing_angle_deg : ndarray, shape (n_angle,)
        Crossing angle theta_skew of the equal cylinders [deg].
    mu : ndarray, shape (n_mu,)
        Tabor parameter of Eq. (35) with R = sqrt(R'R'') [-].
    beta0 : ndarray, shape (n_angle,)
        Hertz ellipticity of each crossing angle [-].
    models : tuple of str
        Model names (the reference first).
    force : ndarray, shape (n_model, n_angle, n_mu)
        Load-control pull-off force W/(pi R dgamma), R = sqrt(R'R'') [-]; NaN where no answer.
    deviation : ndarray, shape (n_model, n_angle, n_mu)
        Relative deviation force/reference_force - 1 [-]; NaN where no answer.
    status : ndarray of int8, shape (n_model, n_angle, n_mu)
        Codes of :data:`STATUS_MEANINGS`.
    reference_force : ndarray, shape (n_angle, n_mu)
        The reference's W/(pi R dgamma) [-].
    validated : ndarray of bool, shape (n_angle, n_mu)
        Inside the extent of the BEM ground truth, where the reference is validated.
    validated_beta0, validated_mu : tuple of float
        That extent.
    notes : dict, optional
        Model -> one line on its warnings and refusals over the grid ("" if none).
    reference : str, default REFERENCE_MODEL
        :data:`REFERENCE_MODEL`.
    reference_note : str, default ""
        Where the reference is validated (:data:`REFERENCE_NOTE`).
    """

    crossing_angle_deg: np.ndarray
    mu: np.ndarray
    beta0: np.ndarray
    models: tuple
    force: np.ndarray
    deviation: np.ndarray
    status: np.ndarray
    reference_force: np.ndarray
    validated: np.ndarray
    validated_beta0: tuple
    validated_mu: tuple
    notes: dict = field(default_factory=dict)
    reference: str = REFERENCE_MODEL
    reference_note: str = ""

    def index(self, model: str) -> int:
        """Return the position of ``model`` on the first axis of the model arrays.

        Parameters
        ----------
        model : str
            One of :attr:`models`.

        Returns
        -------
        int
            The index.

        Raises
        ------
        ValueError
            If ``model`` is not on the map.
        """
        if model not in self.models:
            raise ValueError(f"model must be one of {', '.join(self.models)}; got {model!r}")
        return self.models.index(model)

    def within(self, tolerance: float) -> np.ndarray:
        """Mark where a model answered within ``tolerance`` of the reference.

        Parameters
        ----------
        tolerance : float
            Relative deviation, > 0 [-].

        Returns
        -------
        ndarray of bool, shape (n_model, n_angle, n_mu)
            False where the model gave no answer.
        """
        tol = float(check_interval("tolerance", tolerance, 0.0, np.inf, what="relative deviation"))
        with np.errstate(invalid="ignore"):
            return np.abs(self.deviation) <= tol

    def fraction_within(self, tolerance: float) -> dict:
        """Compute each model's fraction of the map within ``tolerance`` of the reference.

        The grid is uniform in angle and log mu, so this is a fraction of the map's
        area; a point without answer counts as outside.

        Parameters
        ----------
        tolerance : float
            Relative deviation, > 0 [-].

        Returns
        -------
        dict
            Model -> fraction [-].
        """
        w = self.within(tolerance)
        return {m: float(w[i].mean()) for i, m in enumerate(self.models)}

    def fraction_answered(self) -> dict:
        """Compute each model's fraction of the grid where it gave a finite answer (status 0 or 1).

        Returns
        -------
        dict
            Model -> fraction [-].
        """
        return {m: float((self.status[i] <= 1).mean()) for i, m in enumerate(self.models)}


def map_grid(n_angle: int = 81, n_mu: int = 81, *, crossing_angle_deg=DEFAULT_CROSSING_ANGLE_DEG,
             mu=DEFAULT_MU):
    """Build the map's axes: ``n_angle`` crossing angles evenly spaced, ``n_mu`` mu log-spaced.

    Parameters
    ----------
    n_angle, n_mu : int
        Number of points, >= 2 [-].
    crossing_angle_deg : (float, float)
        First and last crossing angle, in (0, 90] [deg].
    mu : (float, float)
        First and last mu, in :data:`dhfield.core.validation.TABOR_RANGE` [-].

    Returns
    -------
    angles : ndarray
        Crossing angles [deg].
    mus : ndarray
        Tabor parameters [-].
    """
    n_angle = check_count("n_angle", n_angle, 2, MAX_AXIS_POINTS, "number of crossing angles")
    n_mu = check_count("n_mu", n_mu, 2, MAX_AXIS_POINTS, "number of values of mu")
    a0, a1 = (float(x) for x in _check_angles(np.asarray(crossing_angle_deg, float)))
    m0, m1 = (float(x) for x in check_tabor("mu", np.asarray(mu, float)))
    return np.linspace(a0, a1, int(n_angle)), np.geomspace(m0, m1, int(n_mu))


def _check_angles(angles):
    return check_interval("crossing_angle_deg", angles, 0.0, 90.0, what="crossing angle of the cylinders, deg")


def _axis(name, values, check):
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or arr.size < 1:
        raise ValueError(f"{name} must be a 1-D array with at least one value; got shape {arr.shape}")
    arr = np.asarray(check(arr), dtype=float)
    if arr.size > 1 and not np.all(np.diff(arr) > 0):
        raise ValueError(f"{name} must be strictly increasing; got {values!r}")
    return arr


def _range(name, value, lo, hi):
    v = tuple(float(x) for x in np.ravel(value))
    if len(v) != 2 or not (lo <= v[0] <= v[1] <= hi):
        raise ValueError(f"{name} must be (low, high) with {lo:g} <= low <= high <= {hi:g}; got {value!r}")
    return v


def recommended_pull_off(beta0, mu):
    """W* of the recommended model, load control: the one place that names it.

    Parameters
    ----------
    beta0, mu : array_like
        Hertz ellipticity in (0, 1] and Tabor parameter of Eq. (35) [-]; broadcast.

    Returns
    -------
    ndarray
        W* = W sin(theta_skew)/(2 pi R dgamma) (Eq. 34) of :mod:`dhfield.models.md_elliptic`.

    Notes
    -----
    By keyword, so that the call holds for the module's ``(mu, beta0, control)`` and for a
    ``(beta0, mu, *, control)`` signature, and ``["W_star"]`` reads a dict or a
    :class:`dhfield.core.records.PullOff` alike.
    """
    return np.asarray(md_elliptic.pull_off_nondimensional(beta0=beta0, mu=mu, control="load")["W_star"],
                      dtype=float)


def _force(rec):
    """W/(pi R dgamma) from a pull-off record: 2 W*/sin_skew (Eq. 34 inverted)."""
    return 2.0 * np.asarray(rec["W_star"], float) / np.asarray(rec["sin_skew"], float)  # Eq. (34)


def _evaluate(model, mu, beta0):
    """(force, warned) of one model on broadcast arrays; raises what the model raises.

    Over arrays :func:`dhfield.analysis.compare.pull_off` answers a point the model refuses with NaN and
    ``"<model> failed: <reason>"`` in its warning: the first such point's reason is raised here as
    the model raised it, so that :func:`_model_on_grid` finds the refused points as before.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if model == REFERENCE_MODEL:
            force = 2.0 * recommended_pull_off(beta0=beta0, mu=mu) / sin_skew_angle(beta0)  # Eq. (34)
            warned = np.zeros(np.shape(force), bool)
        else:
            kw = {"check_closure": False} if model == "dh-elliptic" else {}
            rec = compare.pull_off(model, beta0=beta0, mu=mu, control="load", warn=False, **kw)
            failed = [str(w) for w in np.ravel(np.asarray(rec["warning"], dtype=object))
                      if str(w).startswith(f"{model} failed: ")]
            if failed:
                raise ValueError(failed[0][len(f"{model} failed: "):])
            force = _force(rec)
            warned = np.asarray(rec["warning"], dtype=object) != ""
    force = np.broadcast_to(force, np.shape(mu)).astype(float)
    warned = np.broadcast_to(warned, np.shape(mu)) | bool(caught)
    first = next((str(w.message) for w in caught), "")
    return force, warned, first


def _model_on_grid(model, mu, beta0):
    """force, status and a one-line note of ``model`` on the (angle, mu) grid; never raises for
    inputs the model refuses (those points are NaN, status 'refused')."""
    shape = mu.shape
    force = np.full(shape, _NAN)
    status = np.zeros(shape, np.int8)
    warned = np.zeros(shape, bool)
    refusal = warning = ""
    try:
        force[...], warned[...], warning = _evaluate(model, mu, beta0)
    except (ValueError, RuntimeError):
        # some points refused: find which, one crossing angle (beta0) at a time, then point by point
        for i in range(shape[0]):
            try:
                force[i], warned[i], w = _evaluate(model, mu[i], beta0[i])
                warning = warning or w
                continue
            except (ValueError, RuntimeError):
                pass
            for j in range(shape[1]):
                try:
                    f, wd, w = _evaluate(model, mu[i, j], beta0[i, j])
                    force[i, j], warned[i, j] = float(f), bool(wd)
                    warning = warning or w
                except (ValueError, RuntimeError) as exc:
                    status[i, j] = 2
                    refusal = refusal or " ".join(str(exc).split())
    status[(status == 0) & warned] = 1
    status[(status < 2) & ~np.isfinite(force)] = 3
    force[status >= 2] = _NAN
    if model != REFERENCE_MODEL and np.any(status == 1) and not warning:
        # the record's own warning (its validated range), reproduced for one point
        i, j = np.argwhere(status == 1)[0]
        warning = str(compare.validity_message(model, mu=mu[i, j], beta0=beta0[i, j])) or "warning in the record"
    parts = []
    n = status.size
    if np.any(status == 1):
        parts.append(f"answered with a warning at {int(np.sum(status == 1))} of {n} points (e.g. {warning})")
    if np.any(status == 2):
        parts.append(f"refused {int(np.sum(status == 2))} of {n} points (e.g. {refusal})")
    if np.any(status == 3):
        parts.append(f"non-finite at {int(np.sum(status == 3))} of {n} points")
    return force, status, "; ".join(parts)


def adhesion_map(crossing_angle_deg=None, mu=None, models=MAP_MODEL_NAMES, *,
                 validated_beta0=VALIDATED_BETA0, validated_mu=VALIDATED_MU) -> AdhesionMap:
    """Map each model's load-control pull-off over (crossing angle, mu) against the reference.

    Parameters
    ----------
    crossing_angle_deg : array_like, optional
        Strictly increasing crossing angles of the equal cylinders, in (0, 90] [deg];
        default :func:`map_grid`'s 81 angles over 10-90 deg.
    mu : array_like, optional
        Strictly increasing Tabor parameters of Eq. (35), in
        :data:`dhfield.core.validation.TABOR_RANGE` [-]; default 81 log-spaced over 0.01-100.
    models : sequence of str
        :data:`REFERENCE_MODEL` and/or names of :data:`dhfield.analysis.compare.MODEL_NAMES`; the
        reference is always evaluated, and put first.
    validated_beta0, validated_mu : (float, float)
        Extent of the BEM ground truth where the reference is validated (marks
        :attr:`AdhesionMap.validated`) [-].

    Returns
    -------
    AdhesionMap
        Forces, deviations and statuses of every model on the grid.

    Notes
    -----
    beta0 = :func:`dhfield.core.geometry.ellipticity_from_skew_angle` (Eqs. 3-4, 8).  The force
    is :math:`W/(\\pi R \\Delta\\gamma) = 2 W^*/\\sin\\theta` (Eq. 34), with the record's own
    sin(theta) (1 for the circular models: the sphere of R = sqrt(R'R'')), and the deviation
    :math:`W_{model}/W_{ref} - 1`.  The reference is validated against the BEM only inside
    ``validated_beta0`` x ``validated_mu`` (module docstring).
    """
    default_a, default_m = map_grid()
    angles = _axis("crossing_angle_deg", default_a if crossing_angle_deg is None else crossing_angle_deg,
                   _check_angles)
    mus = _axis("mu", default_m if mu is None else mu, lambda x: check_tabor("mu", x))
    if isinstance(models, str):
        models = (models,)
    models = tuple(models)
    if not models:
        raise ValueError("models must name at least one model; got none")
    known = tuple(dict.fromkeys((REFERENCE_MODEL,) + compare.MODEL_NAMES))  # the reference is registered too
    for m in models:
        if m not in known:
            raise ValueError(f"models must be among {', '.join(known)}; got {m!r}")
    models = (REFERENCE_MODEL,) + tuple(dict.fromkeys(m for m in models if m != REFERENCE_MODEL))
    vb = _range("validated_beta0", validated_beta0, 0.0, 1.0)
    vm = _range("validated_mu", validated_mu, *TABOR_RANGE)

    beta0 = np.asarray(ellipticity_from_skew_angle(np.radians(angles)), float).reshape(angles.shape)
    beta0[angles == 90.0] = 1.0  # cos(radians(90)) is 6e-17, not 0: the circle exactly, as the models' ranges say
    b_grid, m_grid = np.meshgrid(beta0, mus, indexing="ij")
    forces, statuses, notes = [], [], {}
    for m in models:
        f, s, note = _model_on_grid(m, m_grid, b_grid)
        forces.append(f)
        statuses.append(s)
        notes[m] = note
    force = np.stack(forces)
    ref = force[0]
    with np.errstate(invalid="ignore", divide="ignore"):
        deviation = force / ref - 1.0
    validated = (b_grid >= vb[0]) & (b_grid <= vb[1]) & (m_grid >= vm[0]) & (m_grid <= vm[1])
    return AdhesionMap(crossing_angle_deg=angles, mu=mus, beta0=beta0, models=models, force=force,
                       deviation=deviation, status=np.stack(statuses), reference_force=ref,
                       validated=validated, validated_beta0=vb, validated_mu=vm, notes=notes,
                       reference_note=_note(vb, vm))
