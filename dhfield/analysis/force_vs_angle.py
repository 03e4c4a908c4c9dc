"""Pull-off force of two equal crossed cylinders against their crossing angle, for one material.

For a material (E, nu), two equal cylinders of radius R_c, a work of adhesion Delta gamma and a
peak adhesive stress sigma0, every crossing angle theta_skew has its own Hertz ellipticity
beta0 (Eqs. 3-4, 9) and its own Tabor parameter mu (Eq. 35: R = R_c/sin theta_skew grows as the
angle closes, and mu, proportional to R^(1/3), rises).  :func:`pull_off_force_vs_angle` tabulates the pull-off force [N]
of every model of :data:`dhfield.analysis.compare.MODEL_NAMES` along that path, the recommended model's
estimated error (:mod:`dhfield.analysis.model_error`), and the stored BEM ground truth that lies on the
path.

The stored BEM cases
--------------------
The stored truth is the grid of 57 load-control cases of ``data/adhesive_ground_truth_extended.nc``
(beta0 0.1-1, mu 0.1-10), tabulated in :mod:`dhfield.analysis._truth_table`; the 12 slender cases of
``data/adhesive_ground_truth_slender.nc`` (beta0 0.1, 0.1806, 0.3) are among them with the same
W* (``tests/test_force_vs_angle.py`` checks it).  A stored case is a point (beta0_s, mu_s); the
material passes through beta0_s at exactly one angle, theta_s = theta_skew(beta0_s), where its
Tabor parameter is mu(theta_s).  The case is *on the path*, and converted to newtons with the
load unit of Eq. (34) at theta_s, only where mu(theta_s) is within :data:`MU_MATCH_TOLERANCE`
of mu_s.  Elsewhere a stored W* is the pull-off of another contact, and converting it would draw
a force this material does not have; the figure shows all stored cases instead on a second,
nondimensional panel (mu against the angle), beside the material's path.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _truth_table, compare
from ..core import geometry
from .dimensional import contact_parameters, pull_off_record_si
from ..core.validation import check_count, check_interval
from .model_error import model_error

__all__ = ["MU_MATCH_TOLERANCE", "DEFAULT_ANGLES_DEG", "DEFAULT_POINTS", "CLOSURE_MODELS", "CLOSURE_POINTS",
           "StoredCases", "ForceVsAngle",
           "stored_bem_cases", "pull_off_force_vs_angle"]

#: A stored BEM case lies on the material's path where the material's mu at the case's angle is within
#: this relative tolerance of the case's mu [-].  |d ln W*/d ln mu| is at most 0.13 between neighbouring
#: stored cases (0.14 for the recommended model's local slope at beta0 = 0.1), so a 1 % mismatch moves W* by
#: at most ~0.14 %, less than the recommended model's own departure from the stored truth (up to 0.46 %).
MU_MATCH_TOLERANCE = 0.01
#: Default range of crossing angles, (smallest, largest) [deg].
DEFAULT_ANGLES_DEG = (10.0, 90.0)
#: Default number of angles, evenly spaced (1 deg apart over the default range) [-].
DEFAULT_POINTS = 81
#: Models solved point by point with a root finder, 0.2-2 s per point (:mod:`dhfield.models.dh_elliptic_closure`): evaluated
#: at :data:`CLOSURE_POINTS` of the angles only (81 points of the two-axis closure take minutes).
CLOSURE_MODELS = ("dh-elliptic-two-axis", "dh-elliptic-ray-average")
#: Angles at which :data:`CLOSURE_MODELS` are evaluated, evenly picked among the angles, ends included [-].
CLOSURE_POINTS = 9


@dataclass(frozen=True)
class StoredCases:
    """Stored BEM ground-truth cases (load control), as points of a crossed-cylinder path.

    Parameters
    ----------
    beta0 : ndarray
        Hertz ellipticity of each case [-] (Eq. 9).
    mu : ndarray
        Tabor parameter of each case [-] (Eq. 35).
    skew_angle_deg : ndarray
        The crossing angle of equal cylinders with that beta0 [deg] (Eqs. 3-4, 9).
    W_star : ndarray
        The stored pull-off W* (Eq. 34) [-].
    W_star_error : ndarray
        Its stated error [-].
    material_mu : ndarray
        The material's Tabor parameter at ``skew_angle_deg`` [-] (NaN for the whole stored set).
    force : ndarray
        W* in newtons at ``skew_angle_deg``, W* 2 pi R Delta gamma/sin theta_skew [N] (NaN for the
        whole stored set).
    force_error : ndarray
        ``W_star_error`` in newtons [N].
    """
    beta0: np.ndarray
    mu: np.ndarray
    skew_angle_deg: np.ndarray
    W_star: np.ndarray
    W_star_error: np.ndarray
    material_mu: np.ndarray = field(default=None)
    force: np.ndarray = field(default=None)
    force_error: np.ndarray = field(default=None)

    def __len__(self):
        return int(np.size(self.beta0))


def stored_bem_cases() -> StoredCases:
    """Every stored BEM ground-truth case (module docstring), with the angle of its beta0.

    Returns
    -------
    StoredCases
        The 57 cases of :mod:`dhfield.analysis._truth_table`; ``material_mu``, ``force`` and
        ``force_error`` NaN.
    """
    beta0 = np.asarray(_truth_table.BETA0, float)
    nan = np.full(beta0.shape, np.nan)
    return StoredCases(beta0=beta0, mu=np.asarray(_truth_table.MU, float),
                       skew_angle_deg=np.rad2deg(np.asarray(geometry.skew_angle(beta0), float)),  # Eqs. (3)-(4), (9)
                       W_star=np.asarray(_truth_table.W_STAR_TRUTH, float),
                       W_star_error=np.asarray(_truth_table.W_STAR_TRUTH_ERROR, float),
                       material_mu=nan, force=nan, force_error=nan)


@dataclass(frozen=True)
class ForceVsAngle:
    """The pull-off force of every model against the crossing angle, for one material.

    Parameters
    ----------
    skew_angle_deg : ndarray
        Crossing angles theta_skew [deg], increasing.
    beta0 : ndarray
        Hertz ellipticity at each angle [-] (Eq. 9).
    mu : ndarray
        Tabor parameter at each angle [-] (Eq. 35).
    load_unit : ndarray
        2 pi R Delta gamma/sin theta_skew at each angle [N] (Eq. 34).
    models : tuple of str
        The models, the recommended one (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`) first.
    force : dict
        Model -> pull-off force at each angle [N] (negative: tensile); NaN where the model gave no
        answer or was not evaluated.
    evaluated : dict
        Model -> bool at each angle: the model was evaluated there (all angles, except for
        :data:`CLOSURE_MODELS`, evaluated at ``closure_points`` of them).
    reason : dict
        Model -> why it gave no answer at some evaluated angles (its first such warning), '' where
        it answered at every angle it was evaluated at.
    recommended_error : ndarray
        The recommended model's estimated relative error against the BEM ground truth at each angle
        (:func:`dhfield.analysis.model_error.model_error`) [-]; NaN where no stored case checks the point.
    bem : StoredCases
        The stored BEM cases on the material's path (:data:`MU_MATCH_TOLERANCE`), in newtons.
    stored : StoredCases
        Every stored BEM case (nondimensional).
    inputs : dict
        The SI inputs: ``youngs_modulus_1``, ``poisson_ratio_1``, ``youngs_modulus_2``,
        ``poisson_ratio_2`` [Pa, -], ``cylinder_radius`` [m], ``work_of_adhesion`` [J m^-2],
        ``max_adhesive_stress`` [Pa].
    """
    skew_angle_deg: np.ndarray
    beta0: np.ndarray
    mu: np.ndarray
    load_unit: np.ndarray
    models: tuple
    force: dict
    evaluated: dict
    reason: dict
    recommended_error: np.ndarray
    bem: StoredCases
    stored: StoredCases
    inputs: dict

    @property
    def recommended_model(self) -> str:
        """The recommended model's name (the first of :attr:`models`)."""
        return self.models[0]


def _check_models(models):
    if models is None:
        names = list(compare.MODEL_NAMES)
    else:
        if isinstance(models, str):
            models = [models]
        names = list(dict.fromkeys(models))
        bad = [m for m in names if m not in compare.MODELS]
        if bad or not names:
            raise ValueError(f"models must be names of {', '.join(compare.MODEL_NAMES)}; got "
                             f"{', '.join(map(repr, bad)) if bad else 'none'}")
    rec = compare.RECOMMENDED_MODEL
    return (rec,) + tuple(m for m in names if m != rec)  # the recommended model always, first


def _on_path(stored, angle_range, inputs, tolerance):
    """The stored cases whose (beta0, mu) the material passes through, in newtons."""
    lo, hi = angle_range
    # a stored angle may sit a rounding error above 90 deg (beta0 = 1)
    theta_deg = np.minimum(stored.skew_angle_deg, 90.0)
    inside = (theta_deg >= lo - 1e-9) & (theta_deg <= hi + 1e-9)
    if not np.any(inside):
        return _subset(stored, inside, np.array([]), np.array([]))
    p = contact_parameters(inputs["youngs_modulus_1"], inputs["poisson_ratio_1"], inputs["youngs_modulus_2"],
                           inputs["poisson_ratio_2"], inputs["cylinder_radius"], np.deg2rad(theta_deg[inside]),
                           inputs["work_of_adhesion"], inputs["max_adhesive_stress"])
    material_mu = np.full(theta_deg.shape, np.nan)
    unit = np.full(theta_deg.shape, np.nan)
    material_mu[inside] = p.mu
    unit[inside] = p.load_unit  # Eq. (34) at the case's angle
    with np.errstate(invalid="ignore"):
        match = inside & (np.abs(material_mu / stored.mu - 1.0) <= tolerance)
    return _subset(stored, match, material_mu[match], unit[match])


def _subset(stored, mask, material_mu, unit):
    w, e = stored.W_star[mask], stored.W_star_error[mask]
    return StoredCases(beta0=stored.beta0[mask], mu=stored.mu[mask], skew_angle_deg=stored.skew_angle_deg[mask],
                       W_star=w, W_star_error=e, material_mu=np.asarray(material_mu, float),
                       force=w * unit, force_error=e * unit)  # Eq. (34)


def _sub_params(params, mask):
    """The ContactParameters of ``params`` (arrays over the angles) at the angles of ``mask``."""
    from dataclasses import fields, replace

    return replace(params, **{f.name: np.asarray(getattr(params, f.name))[mask] for f in fields(params)
                              if np.ndim(getattr(params, f.name)) == 1})


def pull_off_force_vs_angle(youngs_modulus, poisson_ratio, cylinder_radius, work_of_adhesion, max_adhesive_stress,
                            *, angles_deg=DEFAULT_ANGLES_DEG, points=DEFAULT_POINTS, models=None,
                            youngs_modulus_2=None, poisson_ratio_2=None, mu_tolerance=MU_MATCH_TOLERANCE,
                            closure_points=CLOSURE_POINTS):
    """Tabulate the pull-off force of every model against the crossing angle of two equal cylinders.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E of the cylinders (body 1) [Pa].
    poisson_ratio : float
        Poisson's ratio nu of body 1, in (-1, 0.5] [-].
    cylinder_radius : float
        Radius R_c of both cylinders [m].
    work_of_adhesion : float
        Delta gamma [J m^-2].
    max_adhesive_stress : float
        Peak adhesive stress sigma0 [Pa].
    angles_deg : (float, float), default DEFAULT_ANGLES_DEG
        Smallest and largest crossing angle, in (0, 90] [deg].
    points : int, default DEFAULT_POINTS
        Number of angles, evenly spaced, 2 to 2001 [-].
    models : sequence of str, optional
        Names of :data:`dhfield.analysis.compare.MODEL_NAMES`; default all.  The recommended model is
        always included, first.
    youngs_modulus_2, poisson_ratio_2 : float, optional
        Body 2 (default: body 1) [Pa, -].
    mu_tolerance : float, default MU_MATCH_TOLERANCE
        Relative tolerance on mu of a stored BEM case on the path (module docstring) [-].
    closure_points : int or None, default CLOSURE_POINTS
        Number of the angles (evenly picked, ends included) at which the slow
        :data:`CLOSURE_MODELS` are evaluated, >= 2; None: every angle.

    Returns
    -------
    ForceVsAngle
        The angles, beta0, mu and load unit at each, every model's force [N], the recommended
        model's estimated error, and the stored BEM cases on the path in newtons.

    Raises
    ------
    ValueError
        Naming the input out of its range (a material or geometry parameter, the angles, the
        number of points, a model name), or a sigma0 that puts mu outside the models' domain at
        some angle.

    Warns
    -----
    dhfield.analysis.validity.ImplausibleInputWarning
        Where an SI input is far outside the range of real contacts (a unit slip).

    Notes
    -----
    At each angle, Eqs. (3)-(6), (9) and (35) give beta0 and mu
    (:func:`dhfield.analysis.dimensional.contact_parameters`), every model's W* follows
    (:func:`dhfield.analysis.compare.compare`) and Eq. (34) turns it into newtons, with
    sin theta_skew of beta0 for the elliptical models and 1 for the circular ones
    (:func:`dhfield.analysis.dimensional.pull_off_record_si`).

    Examples
    --------
    A sphere-like contact at 90 deg: every model at beta0 = 1.

    >>> from dhfield.analysis.force_vs_angle import pull_off_force_vs_angle
    >>> t = pull_off_force_vs_angle(1.8e6, 0.49, 3e-3, 0.045, 0.3e6, angles_deg=(80, 90), points=2,
    ...                             models=["jkr"])
    >>> t.models
    ('md-elliptic', 'jkr')
    >>> round(float(t.beta0[-1]), 12)
    1.0
    """
    e2 = youngs_modulus if youngs_modulus_2 is None else youngs_modulus_2
    nu2 = poisson_ratio if poisson_ratio_2 is None else poisson_ratio_2
    names = _check_models(models)
    try:
        lo, hi = (float(a) for a in angles_deg)
    except (TypeError, ValueError):
        raise ValueError(f"angles_deg must be two numbers (smallest, largest crossing angle, deg); "
                         f"got {angles_deg!r}") from None
    check_interval("angles_deg", np.array([lo, hi]), 0.0, 90.0, what="deg")
    if not lo < hi:
        raise ValueError(f"angles_deg must be increasing (smallest, largest); got ({lo:g}, {hi:g})")
    n = check_count("points", points, 2, 2001, "angles")
    tol = float(check_interval("mu_tolerance", mu_tolerance, 0.0, 1.0, what="relative"))
    theta_deg = np.linspace(lo, hi, n)
    inputs = {"youngs_modulus_1": float(youngs_modulus), "poisson_ratio_1": float(poisson_ratio),
              "youngs_modulus_2": float(e2), "poisson_ratio_2": float(nu2),
              "cylinder_radius": float(cylinder_radius), "work_of_adhesion": float(work_of_adhesion),
              "max_adhesive_stress": float(max_adhesive_stress)}
    params = contact_parameters(youngs_modulus, poisson_ratio, e2, nu2, cylinder_radius, np.deg2rad(theta_deg),
                                work_of_adhesion, max_adhesive_stress)  # Eqs. (3)-(6), (9), (33)-(35)
    beta0, mu = np.asarray(params.beta0, float), np.asarray(params.mu, float)
    sparse = np.ones(n, bool)
    if closure_points is not None:
        k = check_count("closure_points", closure_points, 2, 2001, "angles of the closure models")
        sparse = np.zeros(n, bool)
        sparse[np.unique(np.round(np.linspace(0, n - 1, min(k, n))).astype(int))] = True
    fast = [m for m in names if m not in CLOSURE_MODELS]
    records = compare.compare(beta0=beta0, mu=mu, models=fast)
    force, evaluated, reason = {}, {}, {}
    for name in names:
        at = sparse if name in CLOSURE_MODELS else np.ones(n, bool)
        if name in CLOSURE_MODELS:
            rec = compare.compare(beta0=beta0[at], mu=mu[at], models=[name])[name]
            sub = _sub_params(params, at)
        else:
            rec, sub = records[name], params
        f = np.full(n, np.nan)
        f[at] = np.asarray(pull_off_record_si(rec, sub)["force"], float)  # Eq. (34)
        force[name], evaluated[name] = f, at
        missing = ~np.isfinite(f[at])
        said = [str(w) for w in np.ravel(rec.warning)[missing] if str(w)]
        reason[name] = said[0] if said else ("no answer at some angles" if np.any(missing) else "")
    error = np.asarray(model_error(names[0], beta0, mu), float)
    stored = stored_bem_cases()
    return ForceVsAngle(skew_angle_deg=theta_deg, beta0=beta0, mu=mu, load_unit=np.asarray(params.load_unit, float),
                        models=names, force=force, evaluated=evaluated, reason=reason, recommended_error=error,
                        bem=_on_path(stored, (lo, hi), inputs, tol), stored=stored, inputs=inputs)
